#!/usr/bin/env python3
"""Writes drape_square_50.obj beside this script: the 50 x 50 cm square of the remeshed sphere
drape (assets/scenes/sphere_drape_20_remeshed.json) as a coarse triangle mesh for `cloth.mesh`
(docs/meshes.md), which the run then remeshes by its curvature (docs/remeshing.md).

The square is side x side metres on a square lattice of n x n cells; each cell is split along
the diagonal that points away from the centre (a "union jack" pattern, symmetric under the
square's quarter turns, so the coarse mesh favours no fold direction). Texture coordinates are
the flat pattern in metres (u along the warp); positions lay it flat and horizontal, centred on
the z axis at height z0.

    python3 assets/meshes/drape_square_50.py

With arguments, `drape_square_50.py CELLS OUT.obj` writes the same square on CELLS x CELLS cells
to OUT.obj instead: the uniform meshes of docs/remeshing.md's adaptive-against-uniform table.
"""
import os
import sys

side, n, z0 = 0.5, 20, 0.405  # m, cells per side, m
if len(sys.argv) == 3:
    n = int(sys.argv[1])
h = side / n

lines = ["# 50 cm square, union-jack triangles: written by drape_square_50.py"]
for j in range(n + 1):
    for i in range(n + 1):
        u, v = i * h, j * h
        lines.append("v %.9g %.9g %.9g" % (u - side / 2, v - side / 2, z0))
        lines.append("vt %.9g %.9g" % (u, v))


def index(i, j):
    return j * (n + 1) + i + 1


faces = []
for j in range(n):
    for i in range(n):
        a, b, c, d = index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)
        left, low = i < n // 2, j < n // 2
        faces += [(a, b, c), (a, c, d)] if left == low else [(a, b, d), (b, c, d)]
for t in faces:
    lines.append("f " + " ".join("%d/%d" % (p, p) for p in t))
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "drape_square_50.obj")
if len(sys.argv) == 3:
    out = sys.argv[2]
with open(out, "w") as f:
    f.write("\n".join(lines) + "\n")
print("%s: %d vertices, %d triangles" % (out, (n + 1) ** 2, len(faces)))
