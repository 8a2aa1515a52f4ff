#!/usr/bin/env python3
"""Writes a notched finger, the kind of body a user brings (after the SOFA SoftRobots tutorials'
finger): finger.obj, 100 mm along +x from the origin, a 12 x 12 mm section centred on the x axis,
three phalanges parted by two notches 4 mm wide cut 4 mm deep into its back (the -y face), so
that it curls toward +y about z. One closed surface on a rectilinear grid through every edge of
the shape, each interval split to at most SPACING. Standard library only:
  python3 make_finger.py [--spacing 3]"""

import argparse
import math

LENGTH, HALF = 100.0, 6.0                   # mm
NOTCHES = [(31.0, 35.0), (64.0, 68.0)]      # x intervals of the notches
NOTCH_FLOOR = -2.0                          # y: the notches cut from y = -6 up to here


def grid_lines(breaks, spacing):
    lines = [breaks[0]]
    for a, b in zip(breaks, breaks[1:]):
        n = max(1, math.ceil((b - a) / spacing - 1e-9))
        lines += [a + (b - a) * i / n for i in range(1, n + 1)]
    return lines


def is_solid(centre):
    x, y, _ = centre
    return not (y < NOTCH_FLOOR and any(a < x < b for a, b in NOTCHES))


def boundary(lines):
    """Outward quads between solid and empty cells (vertex-index quadruples), and the vertices."""
    counts = [len(l) - 1 for l in lines]
    solid = set()
    for i in range(counts[0]):
        for j in range(counts[1]):
            for k in range(counts[2]):
                c = ((lines[0][i] + lines[0][i + 1]) / 2, (lines[1][j] + lines[1][j + 1]) / 2, (lines[2][k] + lines[2][k + 1]) / 2)
                if is_solid(c):
                    solid.add((i, j, k))
    index, vertices, quads = {}, [], []

    def vertex(c):
        if c not in index:
            index[c] = len(vertices)
            vertices.append(tuple(float(lines[a][c[a]]) for a in range(3)))
        return index[c]

    for v in sorted(solid):
        for axis in range(3):
            for side in (-1, 1):
                n = list(v)
                n[axis] += side
                if tuple(n) in solid:
                    continue
                u, w = (axis + 1) % 3, (axis + 2) % 3
                base = list(v)
                base[axis] += 1 if side > 0 else 0
                corners = []
                for du, dw in ((0, 0), (1, 0), (1, 1), (0, 1)):
                    c = list(base)
                    c[u] += du
                    c[w] += dw
                    corners.append(vertex(tuple(c)))
                quads.append(corners if side > 0 else corners[::-1])  # (u, w, axis) is right-handed
    return vertices, quads


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--spacing", type=float, default=3.0, help="largest grid interval, mm")
    parser.add_argument("--out", default="finger.obj")
    args = parser.parse_args()
    xs = sorted({0.0, LENGTH} | {x for notch in NOTCHES for x in notch})
    lines = [grid_lines(xs, args.spacing), grid_lines([-HALF, NOTCH_FLOOR, HALF], args.spacing),
             grid_lines([-HALF, HALF], args.spacing)]
    vertices, quads = boundary(lines)
    with open(args.out, "w") as f:
        f.write("# fibermold notched finger: 100 mm, 12 x 12 mm, two notches in its back\n# units: mm\n")
        for v in vertices:
            f.write("v {:.6f} {:.6f} {:.6f}\n".format(*v))
        for q in quads:
            a, b, c, d = (i + 1 for i in q)
            f.write(f"f {a} {b} {c}\nf {a} {c} {d}\n")
    print(f"{args.out}: {len(vertices)} vertices, {2 * len(quads)} triangles")


if __name__ == "__main__":
    main()
