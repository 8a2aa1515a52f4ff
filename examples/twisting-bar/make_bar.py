#!/usr/bin/env python3
"""Writes bar.stl: the twisting bar of the paper (section VIII-C), 129 mm long, 20 mm x 20 mm,
along +x from the origin, centred on the x axis.
Standard library only: python3 make_bar.py [--spacing 7] [--out bar.stl]"""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from box_stl import box_script  # noqa: E402

if __name__ == "__main__":
    box_script(__doc__, (0.0, -10.0, -10.0), (129.0, 10.0, 10.0), 7.0, "fibermold twisting bar 129x20x20 mm")
