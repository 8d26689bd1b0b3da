"""Shared set-up of the export checks: the binaries (built by scripts/test.sh), the
made-up inputs and the corpus, and the results and exports every test reads (made
once per session)."""
import json
import os
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
TARGET = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
BIN = Path(os.environ.get("PRIMDECOMP_BIN", TARGET / "release" / "primdecomp"))
TESTKIT = Path(os.environ.get("PRIMDECOMP_TESTKIT", TARGET / "release" / "primdecomp-testkit"))
CORPUS = Path(os.environ.get("PRIMDECOMP_CORPUS", ROOT.parent / "shared" / "datasets" / "corpus"))
IN_CI = bool(os.environ.get("CI")) and os.environ.get("CI") not in ("0", "false")

# The cases: (name, input, decompose arguments). The made-up ones (inputs the
# repository writes at test time, `primdecomp-testkit inputs`) run everywhere and hold
# all six kinds (test_enclosure.py::test_all_six_kinds_present checks it), a skewed
# prism (the default run's nearest fit of a scalene triangle), a z-up STL and the two
# per-object inputs: a glTF of named nodes with transforms and an OBJ of named groups.
# The corpus cases add breadth where ../shared is present.
MADE_UP = [
    ("demo", "demo_scene.obj", ["-n", "40"]),
    ("kinds", "kinds.obj", ["-n", "6"]),
    ("wedges", "wedges.off", []),
    ("robot", "robot.stl", ["-n", "12"]),
    ("nodes", "nodes.glb", ["-n", "12", "--per-object"]),
    ("groups", "groups.obj", ["-n", "9", "--per-object"]),
]
CORPUS_CASES = [
    ("stairs", "parry_stairs.obj", ["-n", "24", "--kinds", "box,prism"]),
    ("c_wedges", "tiny_2triangles.off", []),
    ("bottle", "coacd_bottle.obj", ["-n", "24", "--kinds", "frustum,cylinder,sphere,capsule"]),
    ("spot", "spot.obj", ["-n", "24", "--kinds", "sphere,capsule,frustum"]),
    ("mixer", "kitchenaid_mixer.obj", ["-n", "48"]),
    ("character", "kenney_character.glb", ["-n", "30", "--per-object"]),
    ("lamp", "vhacd_lamp.obj", ["-n", "30", "--per-object"]),
]
# The corpus cases are collected where the corpus is, and under CI (where its absence
# fails them); elsewhere a clone without ../shared runs the made-up cases alone, none
# skipped (scripts/test.sh's summary notes the corpus's absence).
CORPUS_PRESENT = CORPUS.is_dir()
CASES = MADE_UP + (CORPUS_CASES if CORPUS_PRESENT or IN_CI else [])
CASE_NAMES = {c[0] for c in CASES}
CORPUS_NAMES = {c[0] for c in CORPUS_CASES}

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
        assert b.exists(), f"{b} missing: scripts/test.sh builds it (cargo test --release --workspace)"
    return tmp_path_factory.mktemp("exports")


_inputs = []


def made_up(name):
    """A made-up input: from PRIMDECOMP_TEST_INPUTS (scripts/test.sh writes them once),
    else written here by `primdecomp-testkit inputs`."""
    given = os.environ.get("PRIMDECOMP_TEST_INPUTS")
    if given:
        return Path(given) / name
    if not _inputs:
        d = Path(tempfile.mkdtemp(prefix="primdecomp-inputs-"))
        run([TESTKIT, "inputs", d])
        _inputs.append(d)
    return _inputs[0] / name


def source(case):
    """The input file of a case (skipped, or failed under CI, when it is a corpus
    case and the corpus is absent)."""
    name, mesh, _ = next(c for c in CASES if c[0] == case)
    if name in CORPUS_NAMES:
        need_corpus()
        return CORPUS / mesh
    return made_up(mesh)


_results = {}


def result(workdir, case):
    """(result JSON path, input path, faces dict) of a case, made once."""
    if case in _results:
        return _results[case]
    name, _, args = next(c for c in CASES if c[0] == case)
    src = source(case)
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
