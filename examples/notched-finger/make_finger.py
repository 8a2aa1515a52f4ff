#!/usr/bin/env python3
"""Writes a notched finger, the kind of body a user brings (after the SOFA SoftRobots tutorials'
finger): finger.obj, 100 mm along +x from the origin, a 12 x 12 mm section centred on the x axis,
three phalanges parted by two notches 4 mm wide cut 4 mm deep into its back (the -y face), so
that it curls toward +y about z. One closed surface on a rectilinear grid through every edge of
the shape, each interval split to at most SPACING. Standard library only:
  python3 make_finger.py [--spacing 3]"""

import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from cell_surface import boundary, grid_lines, solid_cells, write_obj  # noqa: E402

LENGTH, HALF = 100.0, 6.0                   # mm
NOTCHES = [(31.0, 35.0), (64.0, 68.0)]      # x intervals of the notches
NOTCH_FLOOR = -2.0                          # y: the notches cut from y = -6 up to here


def is_solid(centre):
    x, y, _ = centre
    return not (y < NOTCH_FLOOR and any(a < x < b for a, b in NOTCHES))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--spacing", type=float, default=3.0, help="largest grid interval, mm")
    parser.add_argument("--out", default="finger.obj")
    args = parser.parse_args()
    xs = sorted({0.0, LENGTH} | {x for notch in NOTCHES for x in notch})
    lines = [grid_lines(xs, args.spacing), grid_lines([-HALF, NOTCH_FLOOR, HALF], args.spacing),
             grid_lines([-HALF, HALF], args.spacing)]
    vertices, quads = boundary(lines, solid_cells(lines, is_solid))
    write_obj(args.out, vertices, quads, "fibermold notched finger: 100 mm, 12 x 12 mm, two notches in its back")
    print(f"{args.out}: {len(vertices)} vertices, {2 * len(quads)} triangles")


if __name__ == "__main__":
    main()
