#!/usr/bin/env python3
# benches/made_up/hall.py: writes hall.obj (648 faces) in the current folder, for the
# new-user check of docs/decisions/0049 (not in the corpus; tests/tolerance.rs builds
# the same hall). A 10 × 4 × 10 hall: a floor slab 0.2 thick, four walls 0.2 thick,
# no roof, and a 7 × 7 grid of 0.5-wide crates 0.3 to 0.6 tall standing on the floor.
import itertools

V, F = [], []


def cuboid(lo, hi):
    b = len(V)
    for i in range(8):
        V.append([hi[k] if i >> k & 1 else lo[k] for k in range(3)])
    for q in [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]:
        F.append((b + q[0], b + q[1], b + q[2]))
        F.append((b + q[0], b + q[2], b + q[3]))


L, H, T = 10.0, 4.0, 0.2
cuboid([0, 0, 0], [L, T, L])
cuboid([0, 0, 0], [T, H, L])
cuboid([L - T, 0, 0], [L, H, L])
cuboid([0, 0, 0], [L, H, T])
cuboid([0, 0, L - T], [L, H, L])
for i, j in itertools.product(range(7), range(7)):
    x, z = 1.0 + i * 1.2, 1.0 + j * 1.2
    cuboid([x, T, z], [x + 0.5, T + 0.3 + 0.1 * ((i * 3 + j) % 4), z + 0.5])
with open("hall.obj", "w") as f:
    f.writelines("v %g %g %g\n" % tuple(v) for v in V)
    f.writelines("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1) for t in F)
print("hall.obj:", len(F), "faces")
