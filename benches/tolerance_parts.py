#!/usr/bin/env python3
"""Which primitives of a `--tolerance` level stand farther than the tolerance, and where.

For a FAIL of benches/tolerance_check.sh: evaluates every primitive alone (one JSON per
primitive, `primdecomp eval --samples PER_PART`, its `hausdorff_all` = that primitive's
whole surface), lists those over the level's tolerance, then cuts the worst box or prism
into G x G flat patches per face (a cylinder or frustum: each cap into G rings x 8
sectors, the side into G bands x 8 sectors), each written as a one-hull OBJ and
evaluated alone, and prints the patches standing farthest: where on the primitive the
farthest point lies. Sizes are printed as half extents (box), half_x, half_y,
half_z_top, half_z_bottom (prism), radius or radius0, radius1 and the axis length (round kinds),
over the diagonal.

Usage: benches/tolerance_parts.py MESH LEVEL.json [--per-part 20000] [--grid 6]
       [--patch-samples 3000] [--top 5]   (BIN env: the primdecomp binary)
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.environ.get("BIN", os.path.join(ROOT, "target/release/primdecomp"))


def evaluate(mesh, files, samples, tmp):
    out = os.path.join(tmp, "eval.json")
    subprocess.run([BIN, "eval", "--input", mesh, *files, "--samples", str(samples), "--json", out],
                   check=True, stdout=subprocess.DEVNULL)
    return [c["hausdorff_all"] for c in json.load(open(out))["colliders"]]


def corners(p):
    """The 8 corners of a box or prism, keyed by the signs of its local axes."""
    x, y, z, w = p["rotation"]  # scalar-last unit quaternion
    r = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    c = p["center"]

    def at(sx, sy, sz):
        if p["kind"] == "box":
            h = p["half_extents"]
            loc = [sx * h[0], sy * h[1], sz * h[2]]
        else:  # prism: z half-width hz_bottom at y = -hy, hz_top at y = +hy, about
            # z = -shift_z and +shift_z (absent: isosceles)
            hz = p["half_z_top"] if sy > 0 else p["half_z_bottom"]
            loc = [sx * p["half_x"], sy * p["half_y"], sy * p.get("shift_z", 0.0) + sz * hz]
        return [c[i] + sum(r[i][k] * loc[k] for k in range(3)) for i in range(3)]
    return at


def face_quads(p):
    """The 6 faces of a box or prism: (axis, sign, corner(a, b)) with a, b in [-1, 1]
    along the face's other two axes."""
    at = corners(p)
    for ax in range(3):
        o = [k for k in range(3) if k != ax]
        for s in (-1, 1):
            def pt(a, b, ax=ax, o=o, s=s):
                v = [0, 0, 0]
                v[ax], v[o[0]], v[o[1]] = s, a, b
                return at(*v)
            yield ax, s, pt


def write_quad(path, vs):
    """One flat quad as a two-triangle OBJ."""
    with open(path, "w") as f:
        f.write("o patch\n" + "".join(f"v {x:.12g} {y:.12g} {z:.12g}\n" for x, y, z in vs))
        f.write("f 1 2 3\nf 1 3 4\n")


def patches(p, g, d):
    """Write G x G patches of each of the 6 faces as OBJs; returns (path, label) pairs."""
    out = []
    lerp = lambda a, b, t: [a[i] + (b[i] - a[i]) * t for i in range(3)]
    for ax, s, pt in face_quads(p):
        o = [k for k in range(3) if k != ax]
        q00, q10, q01, q11 = pt(-1, -1), pt(1, -1), pt(-1, 1), pt(1, 1)
        bil = lambda u, v: lerp(lerp(q00, q10, u), lerp(q01, q11, u), v)
        for i in range(g):
            for j in range(g):
                vs = [bil(i / g, j / g), bil((i + 1) / g, j / g),
                      bil((i + 1) / g, (j + 1) / g), bil(i / g, (j + 1) / g)]
                label = (f"face {'xyz'[ax]}{'-+'[s > 0]}, cell {i},{j} of {g}x{g} "
                         f"(along {'xyz'[o[0]]}, {'xyz'[o[1]]})")
                path = os.path.join(d, f"patch_{ax}{s}_{i}_{j}.obj")
                write_quad(path, vs)
                out.append((path, label))
    return out


def round_patches(p, g, d, sectors=8):
    """Cylinder or frustum: each cap cut into G rings x SECTORS flat quads (ring 0 at
    the centre), the side into G bands x SECTORS quads, as OBJs; (path, label) pairs."""
    p0, p1 = p["p0"], p["p1"]
    r0, r1 = (p["radius"], p["radius"]) if p["kind"] == "cylinder" else (p["radius0"], p["radius1"])
    a = [p1[i] - p0[i] for i in range(3)]
    la = math.sqrt(sum(x * x for x in a))
    a = [x / la for x in a]
    t = [1.0, 0.0, 0.0] if abs(a[0]) < 0.9 else [0.0, 1.0, 0.0]
    u = [a[1] * t[2] - a[2] * t[1], a[2] * t[0] - a[0] * t[2], a[0] * t[1] - a[1] * t[0]]
    nu = math.sqrt(sum(x * x for x in u))
    u = [x / nu for x in u]
    v = [a[1] * u[2] - a[2] * u[1], a[2] * u[0] - a[0] * u[2], a[0] * u[1] - a[1] * u[0]]
    def at(h, rho, phi):  # h in [0, 1] along the axis, rho in [0, 1] of the radius there
        r = (r0 + (r1 - r0) * h) * rho
        return [p0[i] + a[i] * la * h + r * (math.cos(phi) * u[i] + math.sin(phi) * v[i]) for i in range(3)]
    out = []
    def write(vs, label, name):
        path = os.path.join(d, name + ".obj")
        write_quad(path, vs)
        out.append((path, label))
    for k in range(sectors):
        f0, f1 = 2 * math.pi * k / sectors, 2 * math.pi * (k + 1) / sectors
        for i in range(g):
            for h, cap in ((0.0, "p0"), (1.0, "p1")):
                write([at(h, i / g, f0), at(h, (i + 1) / g, f0), at(h, (i + 1) / g, f1), at(h, i / g, f1)],
                      f"cap {cap}, ring {i} of {g} (0 = centre), sector {k}", f"cap{cap}_{i}_{k}")
            write([at(i / g, 1, f0), at((i + 1) / g, 1, f0), at((i + 1) / g, 1, f1), at(i / g, 1, f1)],
                  f"side, band {i} of {g} from p0, sector {k}", f"side_{i}_{k}")
    return out


def sizes(p, diag):
    """Half sizes (box, prism) or radii and length (round kinds) over the diagonal."""
    keys = ["half_extents", "half_x", "half_y", "half_z_top", "half_z_bottom", "radius", "radius0", "radius1"]
    vals = []
    for k in keys:
        if k in p:
            vals += p[k] if isinstance(p[k], list) else [p[k]]
    if "p0" in p:
        vals.append(math.dist(p["p0"], p["p1"]))
    return [round(x / diag, 4) for x in vals]


def estimator_density(p, diag):
    """How densely the cut's own estimate samples `p` (crates/primdecomp/src/cut/error.rs,
    docs/decisions/0036: the vertices of the 24-segment tessellation, points along its
    faces' edges one per 1% of the diagonal, then ceil(N x area share) points per
    triangle, the first at its centroid, N = area / (1% of the diagonal)^2 within
    [192, 4096]): the mean spacing sqrt(area / N) over the diagonal, and for round kinds
    the most points any fan triangle of each cap gets."""
    count = lambda area: min(max(math.ceil(area / (0.01 * diag) ** 2), 192), 4096)
    k, circ = 24, 1 / math.cos(math.pi / 24)
    if p["kind"] in ("box", "prism"):
        quads = [[pt(-1, -1), pt(1, -1), pt(1, 1), pt(-1, 1)] for _, _, pt in face_quads(p)]
        area = sum(tri_area(q[0], q[1], q[2]) + tri_area(q[0], q[2], q[3]) for q in quads)
        return f"estimate's spacing ~{math.sqrt(area / count(area)) / diag:.4f} of the diagonal"
    r0, r1 = (p["radius"], p["radius"]) if p["kind"] == "cylinder" else (p["radius0"], p["radius1"])
    r0, r1, h = r0 * circ, r1 * circ, math.dist(p["p0"], p["p1"])
    poly = lambda r: [(r * math.cos(2 * math.pi * j / k), r * math.sin(2 * math.pi * j / k), 0.0) for j in range(k)]
    fans = lambda r: [tri_area(poly(r)[0], poly(r)[j - 1], poly(r)[j]) for j in range(2, k)]
    side = k * 0.5 * (r0 + r1) * 2 * math.sin(math.pi / k) * math.hypot(h, (r1 - r0) * math.cos(math.pi / k))
    area = side + sum(fans(r0)) + sum(fans(r1))
    n = count(area)
    most = [max(math.ceil(n * a / area) for a in fans(r)) for r in (r0, r1)]
    return (f"estimate's spacing ~{math.sqrt(area / n) / diag:.4f} of the diagonal; most points in a fan "
            f"triangle of cap p0: {most[0]}, of cap p1: {most[1]}")


def tri_area(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    w = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    return 0.5 * math.sqrt(sum(x * x for x in w))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mesh")
    ap.add_argument("level")
    ap.add_argument("--per-part", type=int, default=20000)
    ap.add_argument("--grid", type=int, default=6)
    ap.add_argument("--patch-samples", type=int, default=3000)
    ap.add_argument("--top", type=int, default=5)
    a = ap.parse_args()
    doc = json.load(open(a.level))
    dist = doc["stats"]["distance"]
    diag = dist["worst"] / dist["of_diagonal"]
    tol = dist["tolerance"] / diag
    prims = doc["primitives"]
    with tempfile.TemporaryDirectory() as tmp:
        files = []
        for i, p in enumerate(prims):
            files.append(os.path.join(tmp, f"p{i:05d}.json"))
            json.dump(dict(doc, primitives=[p]), open(files[-1], "w"))
        h = evaluate(a.mesh, files, a.per_part, tmp)
        over = sorted((x, i) for i, x in enumerate(h) if x > tol)[::-1]
        print(f"{a.level}: tolerance {tol:.5f} of the diagonal, own estimate {dist['of_diagonal']:.5f}; "
              f"{len(over)} of {len(prims)} primitives over it alone (eval --samples {a.per_part}, hausdorff_all)")
        for x, i in over[: a.top]:
            p = prims[i]
            print(f"  #{i} {p['kind']}: {x:.5f} ({x / tol:.3f} x tolerance), {p['faces']} faces, "
                  f"sizes / diagonal {sizes(p, diag)}"
                  + (f"; {estimator_density(p, diag)}" if p["kind"] in ("box", "prism", "cylinder", "frustum") else ""))
        known = [(x, i) for x, i in over if prims[i]["kind"] in ("box", "prism", "cylinder", "frustum")]
        if not known:
            return
        x, i = known[0]
        pd = os.path.join(tmp, "patches")
        os.makedirs(pd)
        flat = prims[i]["kind"] in ("box", "prism")
        ps = (patches if flat else round_patches)(prims[i], a.grid, pd)
        hp = evaluate(a.mesh, [f for f, _ in ps], a.patch_samples, tmp)
        print(f"  farthest patches of #{i} (eval --samples {a.patch_samples} per patch):")
        for v, (_, label) in sorted(zip(hp, ps), key=lambda t: -t[0])[: a.top]:
            print(f"    {v:.5f}  {label}")
        if not flat:
            return
        # The 8 corners (vertices of the tessellation, which the estimate measures
        # exactly), each as a tetrahedron 1e-9 of the diagonal across.
        at, cf = corners(prims[i]), []
        for n, sg in enumerate([(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]):
            c, e = at(*sg), 1e-9 * diag
            cf.append(os.path.join(pd, f"corner{n}.obj"))
            with open(cf[-1], "w") as f:
                f.write("o corner\n" + "".join(f"v {c[0] + dx:.15g} {c[1] + dy:.15g} {c[2] + dz:.15g}\n"
                                               for dx, dy, dz in [(0, 0, 0), (e, 0, 0), (0, e, 0), (0, 0, e)]))
                f.write("f 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n")
        print(f"    farthest corner: {max(evaluate(a.mesh, cf, 100, tmp)):.5f}")


if __name__ == "__main__":
    sys.exit(main())
