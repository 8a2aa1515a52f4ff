"""Round, straight bodies along +x (cylinders, tapered arms) as closed triangle surfaces, and their
deformation along a spatial curve of prescribed bending curvature, for the examples' geometry
scripts. Every deformed copy keeps the vertices and their order, as a `kind = "surface"` target
needs. Standard library only."""

import math


def tube(length, radius, spacing, around):
    """Vertices and outward triangles of the body x in [0, length] whose cross-section at x is a
    polygon with `around` vertices on the circle of radius(x), a flat side down, rings about `spacing` mm apart, and flat end
    caps (rings at half the radius and a centre vertex)."""
    rings = max(1, math.ceil(length / spacing - 1e-9))
    xs = [length * i / rings for i in range(rings + 1)]
    vertices, triangles = [], []

    def ring(x, r):
        start = len(vertices)
        for k in range(around):
            a = 2 * math.pi * (k + 0.5) / around  # a flat face, not a ridge, at the bottom
            vertices.append((x, r * math.cos(a), r * math.sin(a)))
        return start

    def band(a, b, flip):
        """Quads between rings a and b: facing away from the axis when b lies at larger x, toward
        −x when both lie in one plane and b is the outer ring; `flip` reverses them."""
        for k in range(around):
            k1 = (k + 1) % around
            q = (a + k, a + k1, b + k1, b + k)
            triangles.extend([(q[0], q[2], q[1]), (q[0], q[3], q[2])] if flip else [(q[0], q[1], q[2]), (q[0], q[2], q[3])])

    def fan(centre, a, outward):
        for k in range(around):
            k1 = (k + 1) % around
            triangles.append((centre, a + k, a + k1) if outward else (centre, a + k1, a + k))

    shell = [ring(x, radius(x)) for x in xs]
    for a, b in zip(shell, shell[1:]):
        band(a, b, False)
    for x, outer, toward_plus_x in ((0.0, shell[0], False), (length, shell[-1], True)):
        inner = ring(x, radius(x) / 2)
        band(inner, outer, toward_plus_x)
        vertices.append((x, 0.0, 0.0))
        fan(len(vertices) - 1, inner, toward_plus_x)
    return vertices, triangles


def rotate(v, axis, angle):
    """v rotated about the unit `axis` by `angle` (Rodrigues)."""
    c, s = math.cos(angle), math.sin(angle)
    d = sum(a * b for a, b in zip(axis, v))
    cross = (axis[1] * v[2] - axis[2] * v[1], axis[2] * v[0] - axis[0] * v[2], axis[0] * v[1] - axis[1] * v[0])
    return tuple(v[i] * c + cross[i] * s + axis[i] * d * (1 - c) for i in range(3))


class BentCentreline:
    """The x axis, from x = 0 (held: position and frame unchanged) to `length`, bent with the
    curvatures ky(s) toward +y and kz(s) toward +z (1/mm) of a rotation-minimizing frame, s the arc
    length. The centreline shortens uniformly by the fraction `contraction` (0: it does not stretch):
    a point (x, y, z) of the straight body goes to c(s) + y U(s) + z V(s), s = (1 − contraction) x,
    where the curvatures are ky(x) and kz(x). The cross-sections keep their shape."""

    def __init__(self, length, ky, kz, step=0.05, contraction=0.0):
        self.step = step
        self.scale = 1.0 - contraction
        length *= self.scale
        T, U, V, c = (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (0.0, 0.0, 0.0)
        self.frames = [(c, T, U, V)]
        for i in range(math.ceil(length / step)):
            x = (i + 0.5) * step / self.scale
            # dT/ds = ky U + kz V: an angular velocity ky V − kz U, applied to the whole frame.
            w = tuple(ky(x) * V[j] - kz(x) * U[j] for j in range(3))
            angle = math.sqrt(sum(a * a for a in w)) * step
            T1, U1, V1 = T, U, V
            if angle > 0:
                axis = tuple(a * step / angle for a in w)
                T1, U1, V1 = (rotate(v, axis, angle) for v in (T, U, V))
            c = tuple(c[j] + step * (T[j] + T1[j]) / 2 for j in range(3))
            T, U, V = T1, U1, V1
            self.frames.append((c, T, U, V))

    def frame(self, x):
        i = min(max(int(x / self.step), 0), len(self.frames) - 2)
        t = x / self.step - i
        a, b = self.frames[i], self.frames[i + 1]
        return [tuple((1 - t) * p + t * q for p, q in zip(u, v)) for u, v in zip(a, b)]

    def __call__(self, p):
        c, _, U, V = self.frame(self.scale * p[0])
        return tuple(c[j] + p[1] * U[j] + p[2] * V[j] for j in range(3))


def write_obj(path, vertices, triangles, comment):
    with open(path, "w") as f:
        f.write(f"# {comment}\n# units: mm\n")
        for v in vertices:
            f.write("v {:.6f} {:.6f} {:.6f}\n".format(*v))
        for a, b, c in triangles:
            f.write(f"f {a + 1} {b + 1} {c + 1}\n")


def write_body_and_target(body_path, body_comment, target_comment, vertices, triangles, bend, length):
    """Writes the straight body and its copy moved by `bend` (target.obj), and says where the tip went."""
    write_obj(body_path, vertices, triangles, body_comment)
    write_obj("target.obj", [bend(v) for v in vertices], triangles, target_comment)
    tip = bend((length, 0.0, 0.0))
    print(f"{body_path}, target.obj: {len(vertices)} vertices, {len(triangles)} triangles; "
          f"tip at ({tip[0]:.1f}, {tip[1]:.1f}, {tip[2]:.1f}) mm")
