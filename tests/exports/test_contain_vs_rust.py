"""contain.py (the Python containment check) agrees with the tests' Rust oracle
(crates/testkit/src/contain.rs, through `primdecomp-testkit contain`) on every kind,
on points near each primitive's surface."""
import json

import numpy as np

from conftest import TESTKIT, run
from contain import aabb, from_primdecomp, inside

PRIMS = [
    {"kind": "box", "center": [1, 2, 3], "rotation": [0.1, 0.7, -0.2, 0.6782329983125268], "half_extents": [0.5, 1.25, 0.1]},
    {"kind": "sphere", "center": [-1, 0.5, 2], "radius": 0.3},
    {"kind": "capsule", "p0": [0, 0, 0], "p1": [1, 1, 0.5], "radius": 0.2},
    {"kind": "cylinder", "p0": [2, -1, 0], "p1": [2.5, -1, 1.5], "radius": 0.7},
    {"kind": "frustum", "p0": [-2, -2, -2], "p1": [-1, -2.5, -1], "radius0": 0.4, "radius1": 0.1},
    {"kind": "prism", "center": [3, 3, 3], "rotation": [0, 0, 0.3826834323650898, 0.9238795325112867],
     "half_x": 1.0, "half_y": 0.5, "half_z_top": 0.01, "half_z_bottom": 0.75},
    # Skewed: the top side's midpoint 0.6 along z, the bottom's at -0.6.
    {"kind": "prism", "center": [-3, 1, 0], "rotation": [0.2, -0.1, 0.3, 0.9273618495495703],
     "half_x": 1.0, "half_y": 0.8, "half_z_top": 0.3, "half_z_bottom": 0.7, "shift_z": 0.6},
]


def test_python_containment_matches_rust(tmp_path):
    rng = np.random.default_rng(7)
    tol = 1e-3
    for p in PRIMS:
        s = from_primdecomp(p)
        # Points filling the primitive's bounding box and a margin around it.
        lo, hi = aabb(s)
        pad = 0.1 * (hi - lo)
        pts = rng.uniform(lo - pad, hi + pad, size=(6000, 3))
        shapes = tmp_path / "s.json"
        shapes.write_text(json.dumps({"primitives": [p]}))
        pf = tmp_path / "p.json"
        pf.write_text(json.dumps(pts.tolist()))
        rust = np.array(json.loads(run([TESTKIT, "contain", shapes, pf, tol]).stdout))
        py = inside(s, pts, tol)
        # Python accepts within tol of each bounding plane (up to tol·sqrt(2) at
        # edges): points the two disagree on must lie within 2·tol of the surface,
        # i.e. the Rust oracle accepts them at 2·tol.
        diff = np.where(rust != py)[0]
        if len(diff):
            pf.write_text(json.dumps(pts[diff].tolist()))
            loose = np.array(json.loads(run([TESTKIT, "contain", shapes, pf, 2 * tol]).stdout))
            assert loose.all() and not rust[diff].any(), f"{p['kind']}: {len(diff)} points disagree"
        assert py.sum() > 100 and (~py).sum() > 100, p["kind"]
