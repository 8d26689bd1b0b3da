"""Inputs of the Python package's tests: the made-up meshes the repository writes at
test time (`primdecomp-testkit inputs`; scripts/test.sh writes them once into
PRIMDECOMP_TEST_INPUTS), so every test runs on a clone without ../shared; corpus
meshes add breadth where present (their absence fails under CI), and the release CLI
the results are compared with."""
import os
import subprocess
import tempfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
TARGET = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
CLI = Path(os.environ.get("PRIMDECOMP_BIN", TARGET / "release" / "primdecomp"))
TESTKIT = Path(os.environ.get("PRIMDECOMP_TESTKIT", TARGET / "release" / "primdecomp-testkit"))
CORPUS = ROOT.parent / "shared" / "datasets" / "corpus"
IN_CI = bool(os.environ.get("CI")) and os.environ.get("CI") not in ("0", "false")

_inputs = []


def made_up(name):
    """A made-up input file by name (kinds.obj, robot.stl, lumpy.ply, …)."""
    given = os.environ.get("PRIMDECOMP_TEST_INPUTS")
    if given:
        return Path(given) / name
    if not _inputs:
        need(TESTKIT)
        d = Path(tempfile.mkdtemp(prefix="primdecomp-inputs-"))
        subprocess.run([TESTKIT, "inputs", d], check=True, capture_output=True)
        _inputs.append(d)
    return _inputs[0] / name


def need(p):
    """Skips (fails under CI) when `p` is missing."""
    if not Path(p).exists():
        if IN_CI:
            pytest.fail(f"{p} missing under CI")
        pytest.skip(f"{p} missing")


def corpus(name):
    p = CORPUS / name
    if not CORPUS.is_dir():
        if IN_CI:
            pytest.fail(f"CORPUS ABSENT: {CORPUS} (required under CI)")
        pytest.skip(f"CORPUS ABSENT: {CORPUS}")
    need(p)
    return p


def collected(names):
    """`made-up/…` and `corpus/…` test parameters as collected here: the corpus ones
    where the corpus is, and under CI (where its absence fails them); elsewhere a clone
    without ../shared runs the made-up ones, none skipped."""
    keep = CORPUS.is_dir() or IN_CI
    return [n for n in names if keep or not n.startswith("corpus/")]


def mesh(name):
    """`made-up/NAME` or `corpus/NAME`, as test parameters name them."""
    where, _, file = name.partition("/")
    return made_up(file) if where == "made-up" else corpus(file)
