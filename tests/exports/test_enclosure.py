"""Enclosure survives every export: each exported file is read back into world-space
shapes (readers.py, through the consumer where one runs here) and every input face
must lie inside one of them (contain.py), on made-up meshes with all six kinds (and
the corpus's, where present), for --up y and z and a non-unit --scale."""
import json

import numpy as np
import pytest

from conftest import CASES, FORMATS, FRAMES, MADE_UP, export, result, to_format_frame, tolerance
from contain import faces_enclosed
from readers import READERS


def kinds_of(res):
    doc = json.loads(res.read_text())
    return {p["kind"] for p in doc["primitives"]}, len(doc["primitives"])


def test_all_six_kinds_present(workdir):
    """The made-up cases alone hold every kind, so a clone without the corpus checks
    every kind in every format."""
    kinds = set()
    for case, _, _ in MADE_UP:
        k, _ = kinds_of(result(workdir, case)[0])
        kinds |= k
    assert kinds == {"box", "sphere", "capsule", "cylinder", "frustum", "prism"}, kinds


def test_a_skewed_prism_present(workdir):
    """The exports' checks see a skewed prism's section (shift_z), not only the
    paper's isosceles one (docs/decisions/0045)."""
    doc = json.loads(result(workdir, "wedges")[0].read_text())
    shifts = [p.get("shift_z", 0.0) for p in doc["primitives"] if p["kind"] == "prism"]
    assert any(abs(s) > 0.1 for s in shifts), shifts


@pytest.mark.parametrize("up,scale", FRAMES)
@pytest.mark.parametrize("fmt", list(FORMATS))
@pytest.mark.parametrize("case", [c[0] for c in CASES])
def test_export_encloses_every_face(workdir, case, fmt, up, scale):
    res, _, faces = result(workdir, case)
    path = export(workdir, case, fmt, up, scale)
    shapes = READERS[fmt](path)
    _, n = kinds_of(res)
    doc = json.loads(res.read_text())
    # One shape per primitive (URDF's cylinder and two spheres joined back into
    # the capsule they form, readers.join_capsules).
    assert len(shapes) == n
    V = to_format_frame(fmt, up, scale, faces["vertices"])
    tol = tolerance(V)
    ok = faces_enclosed(shapes, V, faces["faces"], tol)
    assert ok.all(), f"{(~ok).sum()} of {len(ok)} faces outside every {fmt} shape (tol {tol:.3g})"
