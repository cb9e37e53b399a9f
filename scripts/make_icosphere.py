#!/usr/bin/env python3
"""Writes a unit-radius icosphere as a Wavefront OBJ: a regular icosahedron whose triangles are
split into four, SUBDIVISIONS times, each new vertex pushed out onto the unit sphere. Closed,
triangles counter-clockwise seen from outside (outward normals), vertices shared.

Its sagitta (the largest gap between a flat triangle and the sphere, r - sqrt(r^2 - rho^2) for a
triangle of circumradius rho) is printed as a fraction of the radius; scale the mesh to radius r
and the gap is that times r. assets/meshes/icosphere_3.obj is

    scripts/make_icosphere.py 3 assets/meshes/icosphere_3.obj

(642 vertices, 1280 triangles, sagitta 0.0045 of the radius: 0.23 mm at r = 5 cm).
"""

import math
import sys


def icosahedron():
    t = (1.0 + math.sqrt(5.0)) / 2.0
    vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0),
                (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
                (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
             (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
             (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
             (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    return [unit(v) for v in vertices], faces


def unit(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def subdivide(vertices, faces):
    midpoint_of = {}

    def midpoint(a, b):
        key = (min(a, b), max(a, b))
        if key not in midpoint_of:
            vertices.append(unit(tuple((p + q) / 2.0 for p, q in zip(vertices[a], vertices[b]))))
            midpoint_of[key] = len(vertices) - 1
        return midpoint_of[key]

    out = []
    for a, b, c in faces:
        ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
        out += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    return out


def sub(p, q):
    return tuple(x - y for x, y in zip(p, q))


def cross(p, q):
    return (p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0])


def dot(p, q):
    return sum(x * y for x, y in zip(p, q))


def max_sagitta(vertices, faces):
    worst = 0.0
    for a, b, c in faces:
        pa, pb, pc = vertices[a], vertices[b], vertices[c]
        n = cross(sub(pb, pa), sub(pc, pa))
        assert dot(n, pa) > 0.0, "a triangle faces inwards"
        # The plane's distance from the centre; the circumcircle's radius follows.
        h = dot(n, pa) / math.sqrt(dot(n, n))
        worst = max(worst, 1.0 - h)
    return worst


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: make_icosphere.py SUBDIVISIONS OUT.obj")
    levels = int(sys.argv[1])
    vertices, faces = icosahedron()
    for _ in range(levels):
        faces = subdivide(vertices, faces)
    sagitta = max_sagitta(vertices, faces)
    with open(sys.argv[2], "w") as f:
        f.write("# Unit-radius icosphere, %d subdivisions of an icosahedron: %d vertices, %d "
                "triangles,\n# counter-clockwise seen from outside; sagitta %.6f of the radius.\n"
                "# Written by scripts/make_icosphere.py.\n"
                % (levels, len(vertices), len(faces), sagitta))
        for v in vertices:
            f.write("v %.9f %.9f %.9f\n" % v)
        for a, b, c in faces:
            f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))
    print("%s: %d vertices, %d triangles, sagitta %.6f of the radius"
          % (sys.argv[2], len(vertices), len(faces), sagitta))


if __name__ == "__main__":
    main()
