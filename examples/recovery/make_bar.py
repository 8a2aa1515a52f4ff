#!/usr/bin/env python3
"""Writes bar.stl: the recovery bar of the paper (section VIII-B, Fig. 8 bottom), 100 mm long,
16 mm x 16 mm (the paper gives only the length), along +x from the origin, centred on the x axis.
Standard library only: python3 make_bar.py [--spacing 4.0] [--out bar.stl]"""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from box_stl import box_script  # noqa: E402

if __name__ == "__main__":
    box_script(__doc__, (0.0, -8.0, -8.0), (100.0, 8.0, 8.0), 4.0, "fibermold recovery bar 100x16x16 mm")
