#!/usr/bin/env python3
"""Writes bar.stl: the recovery bar of the paper (section VIII-B, Fig. 8 bottom), 100 mm long,
16 mm x 16 mm (the paper gives only the length), along +x from the origin, centred on the x axis.
Standard library only: python3 make_bar.py [--spacing 4.0] [--out bar.stl]"""

import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from box_stl import write_box  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--spacing", type=float, default=4.0, help="target grid spacing, mm")
    parser.add_argument("--out", default="bar.stl")
    args = parser.parse_args()
    count, grid = write_box(args.out, (0.0, -8.0, -8.0), (100.0, 8.0, 8.0), args.spacing, "fibermold recovery bar 100x16x16 mm")
    print(f"{args.out}: {count} triangles, grid {grid}")


if __name__ == "__main__":
    main()
