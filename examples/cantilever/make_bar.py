#!/usr/bin/env python3
"""Writes bar.stl: the cantilever of the paper (section VIII-A, Fig. 8 top), 100 mm long,
15 mm x 15 mm, along +x from the origin, centred on the x axis.
Standard library only: python3 make_bar.py [--spacing 3.75] [--out bar.stl]"""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
from box_stl import box_script  # noqa: E402

if __name__ == "__main__":
    box_script(__doc__, (0.0, -7.5, -7.5), (100.0, 7.5, 7.5), 3.75, "fibermold cantilever 100x15x15 mm")
