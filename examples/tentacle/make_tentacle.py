#!/usr/bin/env python3
"""Writes the tentacle of the paper (section VIII-E, Fig. 13) and its target pose:
  tentacle.obj  a round arm 298 mm long along +x from the origin, tapering linearly from 28 mm
                across at its base (x = 0) to 6 mm at its tip, 12 vertices per ring, rings about
                8 mm apart;
  target.obj    the same surface curled in space: its centreline, held at the base, curls toward
                +y with a curvature growing from 0 at the base to 1/125 mm at the tip (an octopus
                arm curls most near its tip) and swings sideways, toward +z then -z, with a
                curvature of amplitude 1/250 mm (one sine period over the length). The centreline
                does not stretch and the cross-sections stay round: no muscle can do exactly this.
The paper's arm and target are not published (only the length and the 6 mm tip are); this one has
their kind. Standard library only: python3 make_tentacle.py [--curvature 0.008]"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from tube import BentCentreline, tube, write_body_and_target  # noqa: E402

LENGTH, BASE_RADIUS, TIP_RADIUS = 298.0, 14.0, 3.0


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--curvature", type=float, default=0.008, help="curl curvature at the tip, 1/mm")
    args = parser.parse_args()
    k = args.curvature
    vertices, triangles = tube(LENGTH, lambda x: BASE_RADIUS + (TIP_RADIUS - BASE_RADIUS) * x / LENGTH, 8.0, 12)
    curl = BentCentreline(LENGTH, lambda s: k * s / LENGTH, lambda s: k / 2 * math.sin(2 * math.pi * s / LENGTH))
    write_body_and_target("tentacle.obj", "fibermold tentacle: 298 mm, 28 mm to 6 mm across", f"tentacle curled, curvature up to {k}/mm", vertices, triangles, curl, LENGTH)


if __name__ == "__main__":
    main()
