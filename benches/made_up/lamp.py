#!/usr/bin/env python3
# benches/made_up/lamp.py: writes lamp.obj (1,312 faces) and shade.obj (1,280) in the
# current folder, for the new-user check of docs/decisions/0047 (not in the corpus).
# A made-up lamp: a 2×2×0.3 box base, a 24-sided pole of radius 0.1 up to z = 3, and
# a shade made of an icosahedron subdivided 1-to-4 three times, every vertex on a
# sphere of radius 0.6 about (0, 0, 3.4); shade.obj is the shade alone, radius 1.
import math

V, F = [], []


def add(vs, fs):
    o = len(V)
    V.extend(vs)
    F.extend([[o + i for i in f] for f in fs])


def icosphere(subdivisions):
    t = (1 + 5 ** 0.5) / 2
    iv = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
          (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9],
             [5, 11, 4], [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2],
             [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10],
             [8, 6, 7], [9, 8, 1]]

    def unit(p):
        n = math.sqrt(sum(c * c for c in p))
        return tuple(c / n for c in p)

    pts = [unit(p) for p in iv]
    for _ in range(subdivisions):
        mids, nf = {}, []

        def mid(a, b):
            k = (min(a, b), max(a, b))
            if k not in mids:
                pts.append(unit(tuple((pts[a][i] + pts[b][i]) / 2 for i in range(3))))
                mids[k] = len(pts) - 1
            return mids[k]

        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nf += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
        faces = nf
    return pts, faces


def write(path, vs, fs):
    with open(path, "w") as f:
        for v in vs:
            f.write("v %r %r %r\n" % tuple(v))
        for fc in fs:
            f.write("f " + " ".join(str(i + 1) for i in fc) + "\n")


box = [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (0, 0.3)]
add(box, [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]])
n = 24
ring = lambda z: [(0.1 * math.cos(2 * math.pi * i / n), 0.1 * math.sin(2 * math.pi * i / n), z)
                  for i in range(n)]
add(ring(0.3) + ring(3.0),
    [[i, (i + 1) % n, n + (i + 1) % n, n + i] for i in range(n)]
    + [list(range(n))[::-1], list(range(n, 2 * n))])
pts, faces = icosphere(3)
add([(0.6 * x, 0.6 * y, 3.4 + 0.6 * z) for x, y, z in pts], faces)
write("lamp.obj", V, F)
write("shade.obj", pts, faces)
print(f"lamp.obj: {len(F)} faces; shade.obj: {len(faces)} faces")
