#!/usr/bin/env python3
"""Writes configs/sortfirst/fleet_heavy_db.yaml: a structure database file
with heavy instancing (issue 37 point 3) for the sortfirst workload.

Twelve cars on the circle of radius 6 that configs/scenes/bronco.yaml's
camera orbits (placed as the vehicle generator places its copies), all
executing one `car` structure; a car executes one `wheel` four times and
each wheel one `lug` five times, so a lug's chunk has 240 instances, a
wheel's 48 and the body's 12.  Faces are wound outward (back-face
culling).  Run: python3 scripts/gen-fleet-db.py > configs/sortfirst/fleet_heavy_db.yaml
"""
import math


def fmt(x):
    s = "%.4f" % x
    s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def tri_out(a, b, c, centre):
    """(a, b, c) wound so that its normal points away from centre."""
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
         u[0] * v[1] - u[1] * v[0]]
    m = [(a[i] + b[i] + c[i]) / 3 - centre[i] for i in range(3)]
    return (a, b, c) if sum(n[i] * m[i] for i in range(3)) > 0 else (a, c, b)


def box(lo, hi, k):
    """Triangles of box [lo, hi]'s six faces, each a k x k grid."""
    centre = [(lo[i] + hi[i]) / 2 for i in range(3)]
    out = []
    for axis in range(3):
        for side in (lo[axis], hi[axis]):
            u, v = [i for i in range(3) if i != axis]
            for i in range(k):
                for j in range(k):
                    def p(a, b):
                        q = [0, 0, 0]
                        q[axis] = side
                        q[u] = lo[u] + (hi[u] - lo[u]) * a / k
                        q[v] = lo[v] + (hi[v] - lo[v]) * b / k
                        return q
                    a, b, c, d = p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)
                    out.append(tri_out(a, b, c, centre))
                    out.append(tri_out(a, c, d, centre))
    return out


def cylinder(r, half, n):
    """A closed cylinder about the z axis, n sides."""
    out = []
    for i in range(n):
        a0, a1 = 2 * math.pi * i / n, 2 * math.pi * (i + 1) / n
        p = [(r * math.cos(a), r * math.sin(a)) for a in (a0, a1)]
        f0 = [p[0][0], p[0][1], -half]
        f1 = [p[1][0], p[1][1], -half]
        b0 = [p[0][0], p[0][1], half]
        b1 = [p[1][0], p[1][1], half]
        mid = [(p[0][0] + p[1][0]) / 4, (p[0][1] + p[1][1]) / 4, 0]
        out.append(tri_out(f0, f1, b1, mid))
        out.append(tri_out(f0, b1, b0, mid))
        out.append(tri_out([0, 0, half], b0, b1, [0, 0, 0]))
        out.append(tri_out([0, 0, -half], f0, f1, [0, 0, 0]))
    return out


def matrix(m, mode=None):
    s = "      - matrix: [%s]" % ", ".join(fmt(x) for row in m for x in row)
    return s + ("\n        mode: %s" % mode if mode else "")


def translate(x, y, z):
    return [[1, 0, 0, x], [0, 1, 0, y], [0, 0, 1, z], [0, 0, 0, 1]]


def struct(name, colour, tris, extra=()):
    lines = ["  - name: %s" % name, "    elements:",
             "      - color: [%s]" % ", ".join(fmt(c) for c in colour)]
    for t in tris:
        lines.append("      - triangle: [%s]" % ", ".join(
            "[%s]" % ", ".join(fmt(x) for x in v) for v in t))
    lines.extend(extra)
    return "\n".join(lines)


def main():
    print(__doc__.replace('"""', "").strip().replace("\n", "\n# ")
          .join(["# ", ""]))
    print("structure_database: 1\nstructures:")
    print(struct("lug", [0.7, 0.7, 0.7],
                 [[[x * 0.04, y * 0.04, z * 0.04 + 0.17] for x, y, z in t]
                  for t in box([-1, -1, -1], [1, 1, 1], 1)]))
    lugs = []
    for k in range(5):
        a = 2 * math.pi * k / 5
        lugs += [matrix(translate(0.12 * math.cos(a), 0.12 * math.sin(a), 0),
                        "concat"), "      - execute: lug",
                 matrix(translate(-0.12 * math.cos(a), -0.12 * math.sin(a), 0),
                        "concat")]
    print(struct("wheel", [0.08, 0.08, 0.08], cylinder(0.38, 0.15, 12), lugs))
    wheels = []
    for x, z in ((1.3, 0.95), (-1.3, 0.95), (1.3, -0.95), (-1.3, -0.95)):
        wheels += [matrix(translate(x, 0.38, z), "concat"),
                   "      - execute: wheel",
                   matrix(translate(-x, -0.38, -z), "concat")]
    body = box([-2.1, 0.5, -0.9], [2.1, 1.2, 0.9], 3) + \
        box([-1.9, 1.2, -0.85], [0.4, 1.8, 0.85], 2)
    print(struct("car", [0.75, 0.15, 0.12], body, wheels))
    world = []
    for k in range(12):
        a = 2 * math.pi * k / 12
        th = -(a + math.pi / 2)
        c, s = math.cos(th), math.sin(th)
        world += [matrix([[c, 0, s, 6 * math.cos(a)], [0, 1, 0, 0],
                          [-s, 0, c, 6 * math.sin(a)], [0, 0, 0, 1]]),
                  "      - execute: car"]
    print("  - name: world\n    elements:\n" + "\n".join(world))
    print("posted: [world]")


main()
