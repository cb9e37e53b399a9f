#!/usr/bin/env python3
"""Distance between two cloth meshes of any triangulation (OBJ files, e.g. weft run
--export-meshes obj --up z): for each mesh, the area-weighted mean and the largest distance of
its vertices from the other's surface (exact point-triangle distance, triangles bucketed on a
uniform 1 cm grid). Prints mean_ab mean_ba max_ab max_ba in millimetres. Used for the
adaptive-against-uniform table of docs/remeshing.md.

    python3 scripts/mesh_distance.py A.obj B.obj
"""
import math, sys
from collections import defaultdict

def read_obj(path):
    V, F = [], []
    for line in open(path):
        p = line.split()
        if not p: continue
        if p[0] == 'v': V.append(tuple(float(x) for x in p[1:4]))
        elif p[0] == 'f':
            idx = [int(t.split('/')[0]) - 1 for t in p[1:]]
            for k in range(1, len(idx) - 1): F.append((idx[0], idx[k], idx[k + 1]))
    return V, F

def sub(a, b): return (a[0]-b[0], a[1]-b[1], a[2]-b[2])
def dot(a, b): return a[0]*b[0]+a[1]*b[1]+a[2]*b[2]
def cross(a, b): return (a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0])
def add_s(a, b, s): return (a[0]+s*b[0], a[1]+s*b[1], a[2]+s*b[2])

def closest_on_triangle(p, a, b, c):
    """The point of triangle abc closest to p, by the Voronoi regions of its vertices, edges and
    face (as in Ericson, Real-Time Collision Detection, 5.1.5)."""
    ab, ac, ap = sub(b, a), sub(c, a), sub(p, a)
    d1, d2 = dot(ab, ap), dot(ac, ap)
    if d1 <= 0 and d2 <= 0: return a
    bp = sub(p, b); d3, d4 = dot(ab, bp), dot(ac, bp)
    if d3 >= 0 and d4 <= d3: return b
    vc = d1*d4 - d3*d2
    if vc <= 0 and d1 >= 0 and d3 <= 0: return add_s(a, ab, d1/(d1-d3))
    cp = sub(p, c); d5, d6 = dot(ab, cp), dot(ac, cp)
    if d6 >= 0 and d5 <= d6: return c
    vb = d5*d2 - d1*d6
    if vb <= 0 and d2 >= 0 and d6 <= 0: return add_s(a, ac, d2/(d2-d6))
    va = d3*d6 - d5*d4
    if va <= 0 and (d4-d3) >= 0 and (d5-d6) >= 0:
        w = (d4-d3)/((d4-d3)+(d5-d6)); return add_s(b, sub(c, b), w)
    denom = 1.0/(va+vb+vc); v, w = vb*denom, vc*denom
    return add_s(add_s(a, ab, v), ac, w)

def distances(P, V, F, cell=0.01):
    grid = defaultdict(list)
    key = lambda x: tuple(int(math.floor(t/cell)) for t in x)
    for t, (i, j, k) in enumerate(F):
        lo = [min(V[i][d], V[j][d], V[k][d]) for d in range(3)]
        hi = [max(V[i][d], V[j][d], V[k][d]) for d in range(3)]
        a, b = key(lo), key(hi)
        for x in range(a[0], b[0]+1):
            for y in range(a[1], b[1]+1):
                for z in range(a[2], b[2]+1): grid[(x, y, z)].append(t)
    out = []
    for p in P:
        c = key(p); best = float('inf'); r = 0
        while True:
            for x in range(c[0]-r, c[0]+r+1):
                for y in range(c[1]-r, c[1]+r+1):
                    for z in range(c[2]-r, c[2]+r+1):
                        if max(abs(x-c[0]), abs(y-c[1]), abs(z-c[2])) != r: continue
                        for t in grid.get((x, y, z), ()):
                            i, j, k = F[t]; q = closest_on_triangle(p, V[i], V[j], V[k])
                            d = math.sqrt(dot(sub(p, q), sub(p, q)))
                            if d < best: best = d
            if best <= r*cell or r > 100: break
            r += 1
        out.append(best)
    return out

def vertex_areas(V, F):
    A = [0.0]*len(V)
    for i, j, k in F:
        n = cross(sub(V[j], V[i]), sub(V[k], V[i])); a = 0.5*math.sqrt(dot(n, n))/3
        A[i] += a; A[j] += a; A[k] += a
    return A

def one_way(VA, FA, VB, FB):
    d = distances(VA, VB, FB); w = vertex_areas(VA, FA)
    return sum(x*y for x, y in zip(d, w))/sum(w), max(d)

VA, FA = read_obj(sys.argv[1]); VB, FB = read_obj(sys.argv[2])
mab, xab = one_way(VA, FA, VB, FB); mba, xba = one_way(VB, FB, VA, FA)
print("%.2f %.2f %.1f %.1f" % (1e3*mab, 1e3*mba, 1e3*xab, 1e3*xba))
