#!/usr/bin/env python3
# benches/made_up/crystals.py: writes crystals.obj (110 faces) in the current folder,
# for the new-user check after the review of docs/decisions/0045 (not in the corpus).
# Crystal cluster: 9 random convex hulls (6-10 points each, elongated along random
# directions) leaning out of a low slab; scalene faces everywhere.
import itertools, math, random
random.seed(3)
V, F = [], []
def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def cross(a, b): return (a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0])
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def hull(pts):
    o = len(V); V.extend(pts)
    for i, j, k in itertools.combinations(range(len(pts)), 3):
        n = cross(sub(pts[j], pts[i]), sub(pts[k], pts[i]))
        if dot(n, n) < 1e-18: continue
        s = [dot(n, sub(p, pts[i])) for p in pts]
        if all(x <= 1e-9 for x in s): F.append([o + i, o + j, o + k])
        elif all(x >= -1e-9 for x in s): F.append([o + i, o + k, o + j])
hull([(x, y, z) for x in (-2, 2) for y in (-1.5, 1.5) for z in (0, 0.2)])
for c in range(9):
    base = (random.uniform(-1.5, 1.5), random.uniform(-1, 1), 0.1)
    th, ph = random.uniform(0, 2 * math.pi), random.uniform(0, 0.6)
    d = (math.sin(ph) * math.cos(th), math.sin(ph) * math.sin(th), math.cos(ph))
    L, r = random.uniform(0.8, 2.0), random.uniform(0.12, 0.3)
    pts = []
    for _ in range(random.randint(6, 10)):
        t = random.uniform(0, L)
        pts.append(tuple(base[i] + d[i] * t + random.uniform(-r, r) * (1 - t / L * 0.8) for i in range(3)))
    hull(pts)
with open("crystals.obj", "w") as f:
    for v in V: f.write("v %.6f %.6f %.6f\n" % v)
    for t in F: f.write("f %d %d %d\n" % tuple(i + 1 for i in t))
print(len(V), len(F))
