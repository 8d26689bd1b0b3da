"""Shared set-up of the export checks: the binaries (built by scripts/test.sh), the
corpus, and the results and exports every test reads (made once per session)."""
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
BIN = ROOT / "target" / "release" / "primdecomp"
TESTKIT = ROOT / "target" / "release" / "primdecomp-testkit"
CORPUS = Path(os.environ.get("PRIMDECOMP_CORPUS", ROOT.parent / "shared" / "datasets" / "corpus"))
IN_CI = bool(os.environ.get("CI"))

# The corpus cases: (name, input, decompose arguments). Together they hold all six
# kinds (test_enclosure.py::test_all_six_kinds_present checks it) and a skewed prism
# (the default run's nearest fit of a right triangle); the two last are per-object:
# a multi-node glTF with node transforms and a multi-group OBJ.
CASES = [
    ("stairs", "parry_stairs.obj", ["-n", "24", "--kinds", "box,prism"]),
    ("wedges", "tiny_2triangles.off", []),
    ("bottle", "coacd_bottle.obj", ["-n", "24", "--kinds", "frustum,cylinder,sphere,capsule"]),
    ("spot", "spot.obj", ["-n", "24", "--kinds", "sphere,capsule,frustum"]),
    ("mixer", "kitchenaid_mixer.obj", ["-n", "48"]),
    ("character", "kenney_character.glb", ["-n", "30", "--per-object"]),
    ("lamp", "vhacd_lamp.obj", ["-n", "30", "--per-object"]),
]

# Every export format with the file name it gets and the extra arguments.
FORMATS = {
    "gltf": ("out.gltf", []),
    "glb": ("out.glb", []),
    "omi.gltf": ("out.omi.gltf", ["--gltf-physics", "omi"]),
    "xml": ("out.xml", ["--format", "mjcf"]),
    "urdf": ("out.urdf", []),
    "usda": ("out.usda", []),
    "tscn": ("out.tscn", []),
}

# (up, scale) combinations every format is checked at.
FRAMES = [("y", 1.0), ("z", 1.0), ("z", 0.01), ("y", 0.01)]


def run(args, **kw):
    r = subprocess.run([str(a) for a in args], capture_output=True, text=True, **kw)
    if r.returncode != 0:
        raise AssertionError(f"{' '.join(map(str, args))} exited {r.returncode}:\n{r.stdout}\n{r.stderr}")
    return r


def need_corpus():
    if not CORPUS.is_dir():
        if IN_CI:
            pytest.fail(f"CORPUS ABSENT: {CORPUS} (required under CI)")
        pytest.skip(f"CORPUS ABSENT: {CORPUS}")


@pytest.fixture(scope="session")
def workdir(tmp_path_factory):
    for b in (BIN, TESTKIT):
        assert b.exists(), f"{b} missing: scripts/test.sh builds it (cargo build --release -p primdecomp-cli -p primdecomp-testkit)"
    return tmp_path_factory.mktemp("exports")


_results = {}


def result(workdir, case):
    """(result JSON path, input path, faces dict) of a corpus case, made once."""
    if case in _results:
        return _results[case]
    need_corpus()
    name, mesh, args = next(c for c in CASES if c[0] == case)
    src = CORPUS / mesh
    d = workdir / name
    d.mkdir(exist_ok=True)
    out = d / "result.json"
    run([BIN, "decompose", src, *args, "-o", out, "--quiet"])
    faces = d / "faces.json"
    run([TESTKIT, "faces", src, faces])
    _results[case] = (out, src, json.loads(faces.read_text()))
    return _results[case]


_exports = {}


def export(workdir, case, fmt, up, scale):
    key = (case, fmt, up, scale)
    if key not in _exports:
        res, _, _ = result(workdir, case)
        d = workdir / case / f"{up}_{scale}"
        d.mkdir(exist_ok=True)
        name, extra = FORMATS[fmt]
        out = d / name
        run([BIN, "export", res, "-o", out, "--up", up, "--scale", scale, *extra])
        _exports[key] = out
    return _exports[key]


def to_format_frame(fmt, up, scale, V):
    """Result coordinates → the format's: glTF and Godot +Y up, MJCF and URDF +Z up
    (a turn of 90° about x), USD as given; then the scale."""
    V = np.asarray(V, float)
    x, y, z = V[:, 0], V[:, 1], V[:, 2]
    native = {"gltf": "y", "glb": "y", "omi.gltf": "y", "tscn": "y", "xml": "z", "urdf": "z", "usda": up}[fmt]
    if up == "y" and native == "z":
        V = np.stack([x, -z, y], axis=1)
    elif up == "z" and native == "y":
        V = np.stack([x, z, -y], axis=1)
    return V * scale


def tolerance(V):
    """As crates/testkit's check::tolerance: 1e-6 of the diagonal plus the round-off
    of coordinates of this magnitude."""
    V = np.asarray(V, float)
    diag = np.linalg.norm(V.max(axis=0) - V.min(axis=0))
    return 1e-6 * diag + 64 * np.finfo(float).eps * np.abs(V).max()
