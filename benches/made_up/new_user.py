#!/usr/bin/env python3
# benches/made_up/new_user.py: writes three made-up meshes into the current folder for
# a new user's trial of the CLI, the viewer and the exports (in neither the corpus nor
# the tests):
#   desk_lamp.stl   a z-up desk lamp (binary STL): weighted base, two arm links, joint
#                   cylinders, a conical shade with a bulb inside; 7 parts
#   bookshelf.obj   a y-up bookshelf (OBJ, one `g` group per shelf's contents): frame,
#                   three shelves, 42 books of varied sizes, a plant pot; 51 parts
#   rock.ply        a y-up boulder (binary PLY): one closed bumpy part, 20,480 triangles
import math
import struct


def box(lo, hi):
    v = [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    f = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    return v, f


def frustum(c, axis, r0, r1, h, n=32):
    """Closed truncated cone from c along unit axis (0 x, 1 y, 2 z), radii r0 → r1."""
    v = []
    for z, r in ((0.0, r0), (h, r1)):
        for i in range(n):
            a = 2 * math.pi * i / n
            local = [r * math.cos(a), r * math.sin(a)]
            p = [0.0, 0.0, 0.0]
            others = [k for k in range(3) if k != axis]
            p[others[0]], p[others[1]], p[axis] = local[0], local[1], z
            v.append(tuple(c[k] + p[k] for k in range(3)))
    f = [(i, (i + 1) % n, n + (i + 1) % n, n + i) for i in range(n)]
    f += [tuple(range(n - 1, -1, -1)), tuple(range(n, 2 * n))]
    return v, f


def join(parts):
    V, F = [], []
    for v, f in parts:
        o = len(V)
        V += v
        F += [tuple(i + o for i in face) for face in f]
    return V, F


def tris(f):
    return [(p[0], p[k], p[k + 1]) for p in f for k in range(1, len(p) - 1)]


def lamp():
    return join([
        frustum((0, 0, 0), 2, 0.6, 0.55, 0.12),           # weighted base
        frustum((0, 0, 0.12), 2, 0.06, 0.06, 0.9),        # lower arm
        frustum((-0.1, 0, 1.02), 0, 0.09, 0.09, 0.2),     # elbow joint
        box((-0.05, -0.05, 1.02), (0.85, 0.05, 1.1)),     # upper arm
        frustum((0.8, 0, 1.1), 2, 0.05, 0.05, 0.1),       # head joint
        frustum((0.8, 0, 0.75), 2, 0.35, 0.08, 0.4),      # shade
        frustum((0.8, 0, 0.8), 2, 0.08, 0.08, 0.12),      # bulb, inside the shade
    ])


def write_stl(path, V, F):
    T = tris(F)
    with open(path, "wb") as out:
        out.write(b"desk lamp, made up for a new user's trial".ljust(80, b" "))
        out.write(struct.pack("<I", len(T)))
        for t in T:
            out.write(struct.pack("<3f", 0, 0, 0))
            for i in t:
                out.write(struct.pack("<3f", *V[i]))
            out.write(b"\0\0")


def bookshelf():
    groups = {"frame": [box((0, 0, 0), (0.04, 2, 0.35)), box((1.16, 0, 0), (1.2, 2, 0.35)),
                        box((0.04, 1.96, 0), (1.16, 2, 0.35)), box((0.04, 0, 0), (1.16, 0.04, 0.35)),
                        box((0.04, 0.04, 0), (1.16, 1.96, 0.02))]}
    for s, y in enumerate((0.5, 1.0, 1.5)):
        groups[f"shelf_{s + 1}"] = [box((0.04, y, 0.02), (1.16, y + 0.03, 0.35))]
    seed = 7
    for s, y in enumerate((0.04, 0.53, 1.03)):
        books, x = [], 0.06
        for k in range(14):
            seed = (seed * 1103515245 + 12345) % (1 << 31)
            w = 0.03 + 0.04 * (seed % 100) / 100
            h = 0.25 + 0.15 * ((seed // 100) % 100) / 100
            books.append(box((x, y, 0.05), (x + w, y + h, 0.28)))
            x += w + 0.004
        groups[f"books_{s + 1}"] = books
    groups["plant"] = [frustum((0.9, 1.53, 0.18), 1, 0.09, 0.12, 0.2)]
    lines, base = [], 0
    for name, parts in groups.items():
        V, F = join(parts)
        lines.append(f"g {name}")
        lines += [f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in V]
        lines += ["f " + " ".join(str(i + base + 1) for i in face) for face in F]
        base += len(V)
    return "\n".join(lines) + "\n", sum(len(p) for p in groups.values())


def rock():
    t = (1 + 5 ** 0.5) / 2
    V = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
         (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    F = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(5):
        mid, G = {}, []

        def m(a, b):
            k = (min(a, b), max(a, b))
            if k not in mid:
                V.append(tuple((V[a][i] + V[b][i]) / 2 for i in range(3)))
                mid[k] = len(V) - 1
            return mid[k]
        for a, b, c in F:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            G += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        F = G
    out = []
    for x, y, z in V:
        n = (x * x + y * y + z * z) ** 0.5
        x, y, z = x / n, y / n, z / n
        r = 1 + 0.15 * math.sin(2.1 * x + 0.3) * math.cos(1.7 * z) + 0.06 * math.sin(5 * y)
        out.append((1.4 * r * x, 0.8 * r * y + 0.8, r * z))
    return out, F


def write_ply(path, V, F):
    with open(path, "wb") as out:
        out.write((f"ply\nformat binary_little_endian 1.0\nelement vertex {len(V)}\n"
                   "property float x\nproperty float y\nproperty float z\n"
                   f"element face {len(F)}\nproperty list uchar int vertex_indices\nend_header\n").encode())
        for p in V:
            out.write(struct.pack("<3f", *p))
        for f in F:
            out.write(struct.pack("<B3i", 3, *f))


if __name__ == "__main__":
    V, F = lamp()
    write_stl("desk_lamp.stl", V, F)
    text, parts = bookshelf()
    open("bookshelf.obj", "w").write(text)
    RV, RF = rock()
    write_ply("rock.ply", RV, RF)
    print(f"desk_lamp.stl: {len(tris(F))} triangles, 7 parts; bookshelf.obj: {parts} parts; "
          f"rock.ply: {len(RF)} triangles")
