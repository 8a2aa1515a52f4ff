"""Closed surfaces of bodies made of axis-aligned cells, for the examples' geometry scripts: a
rectilinear grid through every edge of the shape, each interval split to at most a spacing, and the
outward quads between solid and empty cells, written as OBJ triangles. Standard library only."""

import math


def grid_lines(breaks, spacing):
    """The grid coordinates through `breaks`, each interval split into pieces of at most `spacing`."""
    lines = [breaks[0]]
    for a, b in zip(breaks, breaks[1:]):
        n = max(1, math.ceil((b - a) / spacing - 1e-9))
        lines += [a + (b - a) * i / n for i in range(1, n + 1)]
    return lines


def solid_cells(lines, is_solid):
    """The cells (i, j, k) of the grid whose centre `is_solid`."""
    solid = set()
    for i in range(len(lines[0]) - 1):
        for j in range(len(lines[1]) - 1):
            for k in range(len(lines[2]) - 1):
                centre = tuple((lines[a][c] + lines[a][c + 1]) / 2 for a, c in zip(range(3), (i, j, k)))
                if is_solid(centre):
                    solid.add((i, j, k))
    return solid


def boundary(lines, solid):
    """Outward quads between solid and empty cells, as vertex-index quadruples, and the vertices."""
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


def write_obj(path, vertices, quads, comment):
    """Two triangles per quad, vertices in mm."""
    with open(path, "w") as f:
        f.write(f"# {comment}\n# units: mm\n")
        for v in vertices:
            f.write("v {:.6f} {:.6f} {:.6f}\n".format(*v))
        for q in quads:
            a, b, c, d = (i + 1 for i in q)
            f.write(f"f {a} {b} {c}\nf {a} {c} {d}\n")
