#!/usr/bin/env python3
"""Writes bar.stl: the cantilever of the paper (section VIII-A, Fig. 8 top), 100 mm long,
15 mm x 15 mm, along +x from the origin, centred on the x axis.
Standard library only: python3 make_bar.py [--spacing 3.75] [--out bar.stl]"""

import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from box_stl import write_box  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--spacing", type=float, default=3.75, help="target grid spacing, mm")
    parser.add_argument("--out", default="bar.stl")
    args = parser.parse_args()
    count, grid = write_box(args.out, (0.0, -7.5, -7.5), (100.0, 7.5, 7.5), args.spacing, "fibermold cantilever 100x15x15 mm")
    print(f"{args.out}: {count} triangles, grid {grid}")


if __name__ == "__main__":
    main()
