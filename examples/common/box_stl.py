"""Box-shaped bodies as binary STL, for the examples' geometry scripts. Each face is a regular grid
of right triangles at about a given spacing, so that the tetrahedral mesh keeps good elements at
the skin. Standard library only."""

import argparse
import struct


def box_triangles(lo, hi, counts):
    """Outward-oriented triangles of the box [lo, hi] with `counts` grid cells along x, y, z."""
    tris = []
    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        for side, coord in ((-1, lo[axis]), (1, hi[axis])):
            nu, nv = counts[u], counts[v]
            def point(i, j):
                p = [0.0, 0.0, 0.0]
                p[axis] = coord
                p[u] = lo[u] + (hi[u] - lo[u]) * i / nu
                p[v] = lo[v] + (hi[v] - lo[v]) * j / nv
                return tuple(p)
            for i in range(nu):
                for j in range(nv):
                    a, b, c, d = point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)
                    # (u, v, axis) is right-handed, so a→b→c turns about +axis.
                    if side > 0:
                        tris += [(a, b, c), (a, c, d)]
                    else:
                        tris += [(a, c, b), (a, d, c)]
    return tris


def write_binary_stl(path, tris, name):
    with open(path, "wb") as f:
        f.write(name.encode().ljust(80, b" ")[:80])
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", 0.0, 0.0, 0.0))
            for p in t:
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")


def write_box(path, lo, hi, spacing, name):
    """Writes the box [lo, hi] (mm) gridded at about `spacing` mm; returns the triangle count and grid."""
    counts = [max(1, round((h - l) / spacing)) for l, h in zip(lo, hi)]
    tris = box_triangles(lo, hi, counts)
    write_binary_stl(path, tris, name)
    return len(tris), counts


def box_script(doc, lo, hi, spacing, name):
    """The command line of a make_bar.py: [--spacing MM] [--out FILE], then writes the box."""
    parser = argparse.ArgumentParser(description=doc)
    parser.add_argument("--spacing", type=float, default=spacing, help="target grid spacing, mm")
    parser.add_argument("--out", default="bar.stl")
    args = parser.parse_args()
    count, grid = write_box(args.out, lo, hi, args.spacing, name)
    print(f"{args.out}: {count} triangles, grid {grid}")
