#!/usr/bin/env python3
# benches/made_up/lowpoly_scene.py: writes scene.obj (33 faces) in the current folder.
# A low-poly scene made for the new-user check of docs/decisions/0045 (not in the
# corpus): an open umbrella of 7 uneven triangular panels on a pole, a low-poly rock
# (hull of 14 random points), and a lean-to roof of two scalene triangles.
import math, random
random.seed(11)
V, F = [], []
def add(vs, fs):
    o = len(V); V.extend(vs); F.extend([[o + i for i in f] for f in fs])
# umbrella: apex at (0, 0, 2), rim points at uneven angles and radii, slightly lower
apex = (0.0, 0.0, 2.0)
angs = sorted(random.uniform(0, 2 * math.pi) for _ in range(7))
rim = [(r * math.cos(a), r * math.sin(a), 1.55 + random.uniform(-0.1, 0.1))
       for a, r in zip(angs, [random.uniform(0.9, 1.4) for _ in angs])]
add([apex] + rim, [[0, 1 + i, 1 + (i + 1) % 7] for i in range(7)])
# pole: a thin hexagonal prism from z=0 to z=2
pv = []
for z in (0.0, 2.0):
    for k in range(6):
        a = k * math.pi / 3
        pv.append((0.03 * math.cos(a), 0.03 * math.sin(a), z))
pf = [[k, (k + 1) % 6, 6 + (k + 1) % 6] for k in range(6)] + [[k, 6 + (k + 1) % 6, 6 + k] for k in range(6)]
add(pv, pf)
# rock: convex hull of random points around (3, 0, 0.5)
import itertools
pts = [(3 + random.uniform(-0.8, 0.8), random.uniform(-0.6, 0.6), 0.5 + random.uniform(-0.5, 0.5)) for _ in range(14)]
def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def cross(a, b): return (a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0])
def dot(a, b): return sum(x * y for x, y in zip(a, b))
hull = []
for i, j, k in itertools.combinations(range(len(pts)), 3):
    n = cross(sub(pts[j], pts[i]), sub(pts[k], pts[i]))
    s = [dot(n, sub(p, pts[i])) for p in pts]
    if all(x <= 1e-12 for x in s): hull.append([i, j, k])
    elif all(x >= -1e-12 for x in s): hull.append([i, k, j])
add(pts, hull)
# lean-to roof: two scalene triangles sharing an edge, tilted
add([(-3, -1, 0), (-1.2, -1.3, 1.1), (-2.6, 1.1, 0.2), (-0.9, 0.8, 1.6)], [[0, 1, 2], [1, 3, 2]])
with open("scene.obj", "w") as f:
    for v in V: f.write("v %.6f %.6f %.6f\n" % v)
    for t in F: f.write("f %d %d %d\n" % tuple(i + 1 for i in t))
print(len(V), len(F))
