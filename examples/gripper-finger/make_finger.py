#!/usr/bin/env python3
"""Writes a pneumatic-gripper finger of the kind a user exports from CAD: finger.obj, 115 mm along
+x from the origin, 30 mm wide (y, centred) and 20 mm tall (z from the flat palm at z = 0), with
six slots 5 mm wide cut 12 mm deep into its back (the z = 20 face), so that a muscle along the palm
curls it toward -z. Like a CAD export it has few, large triangles (one quad per face of the
rectilinear cells through the shape's edges, none split): the mesh stage splits them to the
asked edge length. Standard library only:
  python3 make_finger.py [--out finger.obj]"""

import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from cell_surface import boundary, grid_lines, solid_cells, write_obj  # noqa: E402

LENGTH, HALF_WIDTH, HEIGHT = 115.0, 15.0, 20.0     # mm
SLOTS = [(20.0 + 14.0 * k, 25.0 + 14.0 * k) for k in range(6)]  # x intervals of the slots
SLOT_FLOOR = 8.0                                    # z: the slots cut from the back down to here


def is_solid(centre):
    x, _, z = centre
    return not (z > SLOT_FLOOR and any(a < x < b for a, b in SLOTS))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", default="finger.obj")
    args = parser.parse_args()
    no_split = 1e9  # a CAD export: the grid only through the shape's edges
    xs = sorted({0.0, LENGTH} | {x for slot in SLOTS for x in slot})
    lines = [grid_lines(xs, no_split), grid_lines([-HALF_WIDTH, HALF_WIDTH], no_split),
             grid_lines([0.0, SLOT_FLOOR, HEIGHT], no_split)]
    vertices, quads = boundary(lines, solid_cells(lines, is_solid))
    write_obj(args.out, vertices, quads, "fibermold gripper finger: 115 x 30 x 20 mm, six slots in its back")
    print(f"{args.out}: {len(vertices)} vertices, {2 * len(quads)} triangles")


if __name__ == "__main__":
    main()
