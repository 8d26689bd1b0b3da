#!/usr/bin/env python3
# benches/made_up/gear.py: writes gear.obj (224 faces) in the current folder, for the
# new-user check of docs/decisions/0045 (not in the corpus).
# A made-up low-poly gear: 11 teeth, fan-triangulated caps (long scalene slivers), a
# bore; written as gear.obj.
import math
V, F = [], []
teeth, r_in, r_root, r_tip, h = 11, 0.35, 1.0, 1.25, 0.3
ring = []
for k in range(teeth):
    a0 = 2 * math.pi * k / teeth
    for frac, r in [(0.0, r_root), (0.2, r_tip), (0.45, r_tip), (0.65, r_root)]:
        ring.append((r, a0 + frac * 2 * math.pi / teeth))
n = len(ring)
bore = [(r_in, 2 * math.pi * k / 12) for k in range(12)]
def add_ring(pts, z):
    o = len(V)
    V.extend((r * math.cos(a), r * math.sin(a), z) for r, a in pts)
    return o
ob0, ob1 = add_ring(ring, 0.0), add_ring(ring, h)
ib0, ib1 = add_ring(bore, 0.0), add_ring(bore, h)
for i in range(n):  # outer wall
    j = (i + 1) % n
    F += [[ob0 + i, ob0 + j, ob1 + j], [ob0 + i, ob1 + j, ob1 + i]]
for i in range(12):  # bore wall (facing inward)
    j = (i + 1) % 12
    F += [[ib0 + i, ib1 + j, ib0 + j], [ib0 + i, ib1 + i, ib1 + j]]
# caps: each outer vertex joined to the nearest bore vertex by angle (slivers)
def cap(o_out, o_in, up):
    for i in range(n):
        j = (i + 1) % n
        a = ring[i][1]
        b = int(round(a / (2 * math.pi) * 12)) % 12
        c = int(round(ring[j][1] / (2 * math.pi) * 12)) % 12
        t = [o_out + i, o_out + j, o_in + c]
        F.append(t if up else t[::-1])
        if c != b:
            t = [o_out + i, o_in + c, o_in + b]
            F.append(t if up else t[::-1])
cap(ob1, ib1, True); cap(ob0, ib0, False)
with open("gear.obj", "w") as f:
    for v in V: f.write("v %.6f %.6f %.6f\n" % v)
    for t in F: f.write("f %d %d %d\n" % tuple(i + 1 for i in t))
print(len(V), len(F))
