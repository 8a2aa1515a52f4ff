#!/usr/bin/env python3
"""Writes the walking robot of the paper (section VIII-F, Fig. 15-16) and its two target poses:
  robot.obj  the body, 42 x 20 x 14 mm along +x from the origin (centred on the x axis), with four
             legs 6 x 6 x 8 mm under it, as one closed surface gridded at about 4.5 mm;
  bend.obj   the same surface bent about the y axis with constant curvature, the rear end (x = 0)
             held and the front end turned 20 degrees downward: the robot steps forward;
  twist.obj  the same surface twisted about the x axis, the front end turned 15 degrees: the robot
             swaps which legs touch the ground.
The targets keep every vertex and its order. The paper's mesh is not published; this one matches
its stated body length. Standard library only: python3 make_robot.py [--bend 20] [--twist 15]"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from cell_surface import boundary, grid_lines, solid_cells, write_obj  # noqa: E402

LENGTH = 42.0
# The body x [0, 42] y [-10, 10] z [-7, 7] mm; legs 6 x 6 x 8 mm under its corners. The surface is
# cut on a rectilinear grid through every edge of the shape, each interval split to at most SPACING.
BREAKS = ([0, 4, 10, 32, 38, 42], [-10, -4, 4, 10], [-15, -7, 7])
SPACING = 4.5  # mm


def is_solid(centre):
    x, y, z = centre
    if -7 < z < 7:
        return True
    leg_x = 4 < x < 10 or 32 < x < 38
    leg_y = -10 < y < -4 or 4 < y < 10
    return -15 < z < -7 and leg_x and leg_y


def bend(p, degrees):
    """Constant curvature in the x-z plane, centre of curvature below: x = 0 stays, the front dips."""
    x, y, z = p
    if degrees == 0:
        return p
    radius = LENGTH / math.radians(degrees)
    angle = x / radius
    return ((radius + z) * math.sin(angle), y, (radius + z) * math.cos(angle) - radius)


def twist(p, degrees):
    x, y, z = p
    angle = math.radians(degrees) * x / LENGTH
    c, s = math.cos(angle), math.sin(angle)
    return (x, c * y - s * z, s * y + c * z)


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--bend", type=float, default=20.0, help="front-end bend, degrees")
    parser.add_argument("--twist", type=float, default=15.0, help="front-end twist, degrees")
    args = parser.parse_args()
    lines = [grid_lines(b, SPACING) for b in BREAKS]
    vertices, quads = boundary(lines, solid_cells(lines, is_solid))
    write_obj("robot.obj", vertices, quads, "fibermold walking robot: 42 mm body with four legs")
    write_obj("bend.obj", [bend(v, args.bend) for v in vertices], quads, f"walking robot bent {args.bend} degrees")
    write_obj("twist.obj", [twist(v, args.twist) for v in vertices], quads, f"walking robot twisted {args.twist} degrees")
    print(f"robot.obj, bend.obj, twist.obj: {len(vertices)} vertices, {2 * len(quads)} triangles")


if __name__ == "__main__":
    main()
