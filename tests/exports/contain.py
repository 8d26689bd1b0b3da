"""Containment of points in collider shapes, for the export enclosure checks.

Written from the shapes' definitions only (no code shared with the fitting code or
with the Rust oracle in crates/testkit/src/contain.rs, against which
test_contain_vs_rust.py checks it). A shape is a dict in world coordinates:

- {"kind": "box", "center", "axes" (3 rows: local x, y, z in world), "half"}
- {"kind": "sphere", "center", "radius"}
- {"kind": "capsule", "p0", "p1", "radius"}
- {"kind": "round", "p0", "p1", "r0", "r1"}  (cylinder r0 == r1, frustum/cone)
- {"kind": "hull", "points"}                 (convex hull of the points)
- {"kind": "prism", ...} in the primdecomp JSON form, for the cross-check.

`inside(shape, P, tol)` says for each row of P whether it lies within `tol` of the
shape (exactly for boxes, spheres and capsules; for solids of revolution and hulls
within tol of every bounding plane/line, which is within tol·sqrt(2) of the solid).
A face lies in a convex shape iff its vertices do.
"""
import numpy as np
from scipy.spatial import ConvexHull


def _unit(v):
    v = np.asarray(v, float)
    n = np.linalg.norm(v)
    return v / n if n > 0 else v


def inside(shape, P, tol):
    P = np.asarray(P, float).reshape(-1, 3)
    k = shape["kind"]
    if k == "sphere":
        return np.linalg.norm(P - shape["center"], axis=1) <= shape["radius"] + tol
    if k == "box":
        A = np.asarray(shape["axes"], float)  # rows: local axes in world
        L = (P - shape["center"]) @ A.T
        out = np.maximum(np.abs(L) - np.asarray(shape["half"], float), 0.0)
        return np.linalg.norm(out, axis=1) <= tol
    if k == "capsule":
        a, b = np.asarray(shape["p0"], float), np.asarray(shape["p1"], float)
        d = b - a
        dd = float(d @ d)
        t = np.zeros(len(P)) if dd == 0 else np.clip((P - a) @ d / dd, 0.0, 1.0)
        q = a + t[:, None] * d
        return np.linalg.norm(P - q, axis=1) <= shape["radius"] + tol
    if k == "round":
        a, b = np.asarray(shape["p0"], float), np.asarray(shape["p1"], float)
        length = float(np.linalg.norm(b - a))
        if length == 0:
            return np.linalg.norm(P - a, axis=1) <= max(shape["r0"], shape["r1"]) + tol
        u = (b - a) / length
        t = (P - a) @ u
        rad = np.linalg.norm((P - a) - t[:, None] * u, axis=1)
        r0, r1 = float(shape["r0"]), float(shape["r1"])
        slope = (r1 - r0) / length
        tc = np.clip(t, 0.0, length)
        limit = r0 + slope * tc
        # Distance to the slanted side's line, measured perpendicular to it.
        side = (rad - limit) / np.sqrt(1.0 + slope * slope)
        return (t >= -tol) & (t <= length + tol) & (side <= tol)
    if k == "hull":
        pts = np.asarray(shape["points"], float)
        eq = shape.get("_eq")
        if eq is None:
            eq = ConvexHull(pts, qhull_options="Qt").equations  # unit normals, n.x + d <= 0
            shape["_eq"] = eq
        return np.all(P @ eq[:, :3].T + eq[:, 3] <= tol, axis=1)
    if k == "prism":
        # primdecomp JSON prism: local x in [-hx, hx], y in [-hy, hy], |z| <= w(y).
        q = np.asarray(shape["rotation"], float)
        A = quat_axes(q)
        L = (P - np.asarray(shape["center"], float)) @ A.T
        hx, hy = shape["half_x"], shape["half_y"]
        zt, zb = shape["half_z_top"], shape["half_z_bottom"]
        # A skewed section: top side centred at z = shift_z, bottom at -shift_z.
        t = shape.get("shift_z", 0.0)
        corners = np.array([[-hy, -t - zb], [hy, t - zt], [hy, t + zt], [-hy, -t + zb]])
        ok = np.abs(L[:, 0]) <= hx + tol
        for i in range(4):
            p, q2 = corners[i], corners[(i + 1) % 4]
            e = q2 - p
            n = np.array([e[1], -e[0]])
            nn = np.linalg.norm(n)
            if nn == 0:
                continue
            n = n / nn
            # Outward normal: the centre is on the inner side.
            if n @ (-p) > 0:
                n = -n
            ok &= (L[:, 1:] - p) @ n <= tol
        return ok
    raise ValueError(f"unknown shape kind {k!r}")


def quat_axes(q):
    """Rows: images of local x, y, z under scalar-last unit quaternion q."""
    x, y, z, w = np.asarray(q, float) / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w)],
        [2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w)],
        [2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)],
    ])


def from_primdecomp(p):
    """A primdecomp JSON primitive as a shape dict."""
    k = p["kind"]
    if k == "box":
        return {"kind": "box", "center": p["center"], "axes": quat_axes(p["rotation"]), "half": p["half_extents"]}
    if k == "sphere":
        return {"kind": "sphere", "center": p["center"], "radius": p["radius"]}
    if k == "capsule":
        return {"kind": "capsule", "p0": p["p0"], "p1": p["p1"], "radius": p["radius"]}
    if k == "cylinder":
        return {"kind": "round", "p0": p["p0"], "p1": p["p1"], "r0": p["radius"], "r1": p["radius"]}
    if k == "frustum":
        return {"kind": "round", "p0": p["p0"], "p1": p["p1"], "r0": p["radius0"], "r1": p["radius1"]}
    if k == "prism":
        return dict(p)
    raise ValueError(k)


def aabb(shape):
    """A bounding box (lo, hi) of a shape, for culling."""
    k = shape["kind"]
    if k == "sphere":
        c, r = np.asarray(shape["center"], float), shape["radius"]
        return c - r, c + r
    if k == "box":
        A = np.asarray(shape["axes"], float)
        e = np.abs(A.T) @ np.asarray(shape["half"], float)
        c = np.asarray(shape["center"], float)
        return c - e, c + e
    if k in ("capsule", "round"):
        a, b = np.asarray(shape["p0"], float), np.asarray(shape["p1"], float)
        r = shape.get("radius", max(shape.get("r0", 0), shape.get("r1", 0)))
        return np.minimum(a, b) - r, np.maximum(a, b) + r
    if k == "hull":
        pts = np.asarray(shape["points"], float)
        return pts.min(axis=0), pts.max(axis=0)
    c = np.asarray(shape["center"], float)
    zmax = abs(shape.get("shift_z", 0.0)) + max(shape["half_z_top"], shape["half_z_bottom"])
    r = np.linalg.norm([shape["half_x"], shape["half_y"], zmax])
    return c - r, c + r


def faces_enclosed(shapes, vertices, faces, tol):
    """For each face (indices into vertices), whether one shape holds all its vertices."""
    V = np.asarray(vertices, float)
    n = len(faces)
    # Pad faces to a rectangle of vertex indices (repeat the first vertex).
    width = max(len(f) for f in faces)
    F = np.array([list(f) + [f[0]] * (width - len(f)) for f in faces], dtype=np.int64)
    done = np.zeros(n, bool)
    flo = V[F].min(axis=1)
    fhi = V[F].max(axis=1)
    for s in shapes:
        lo, hi = aabb(s)
        cand = np.where(~done & np.all(flo >= lo - tol, axis=1) & np.all(fhi <= hi + tol, axis=1))[0]
        if len(cand) == 0:
            continue
        used = np.unique(F[cand])
        ok_v = np.zeros(len(V), bool)
        ok_v[used] = inside(s, V[used], tol)
        done[cand] |= np.all(ok_v[F[cand]], axis=1)
    return done
