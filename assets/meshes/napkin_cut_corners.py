#!/usr/bin/env python3
"""Writes napkin_cut_corners.obj beside this script: a square napkin with its four corners cut
off at 45 degrees (an octagon), as a triangle mesh for `cloth.mesh` (docs/meshes.md).

The napkin is side x side metres with corners cut `cut` along each edge, on a square lattice of
spacing h; each lattice cell is split along the diagonal parallel to the cut of its quadrant, so
the cut edges are straight and the mesh is made of triangles only (weft reads it as a triangle
mesh, not a grid). Texture coordinates are the flat pattern in metres (u along the warp);
positions lay it flat and horizontal, centred on the z axis at height z0.

    python3 assets/meshes/napkin_cut_corners.py
"""
import os

side, cut, n, z0 = 0.8, 0.16, 40, 0.87  # m, m, cells per side, m
h = side / n
k = round(cut / h)  # cells cut along each edge


def inside(i, j):
    """Whether lattice point (i, j) lies in the octagon (on its boundary included)."""
    return (i + j >= k and (n - i) + j >= k and i + (n - j) >= k and (n - i) + (n - j) >= k)


index = {}
lines = ["# napkin with cut corners: written by napkin_cut_corners.py"]
for j in range(n + 1):
    for i in range(n + 1):
        if inside(i, j):
            index[(i, j)] = len(index) + 1
            u, v = i * h, j * h
            lines.append("v %.9g %.9g %.9g" % (u - side / 2, v - side / 2, z0))
            lines.append("vt %.9g %.9g" % (u, v))
faces = []
for j in range(n):
    for i in range(n):
        a, b, c, d = (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)
        # The diagonal parallel to the nearest cut: a–c in the lower-right and upper-left
        # quadrants, b–d in the others.
        left, low = i < n // 2, j < n // 2
        tris = [(a, b, c), (a, c, d)] if left != low else [(a, b, d), (b, c, d)]
        for t in tris:
            if all(p in index for p in t):
                faces.append(t)
for t in faces:
    lines.append("f " + " ".join("%d/%d" % (index[p], index[p]) for p in t))
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "napkin_cut_corners.obj")
with open(out, "w") as f:
    f.write("\n".join(lines) + "\n")
print("%s: %d vertices, %d triangles" % (out, len(index), len(faces)))
