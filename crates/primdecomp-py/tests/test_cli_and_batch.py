"""The Python package against the CLI on made-up meshes (and corpus meshes where
present), the coacd-style hulls against an independent containment check (trimesh),
other input formats, zero-copy input, and the batch runner on a local Ray instance
and on the thread-pool fallback (Ctrl-C included)."""

import contextlib
import json
import os
import shutil
import signal
import subprocess
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import primdecomp
import primdecomp.batch

from conftest import CLI, ROOT, collected, made_up, mesh, need

# Made-up meshes of three formats (kinds of every primitive, a scalene pair, a z-up
# STL), then small corpus meshes, the first two of which differed from the CLI in the
# last bit before load() returned the file's coordinates unrounded.
MESHES = collected(["made-up/kinds.obj", "made-up/wedges.off", "made-up/robot.stl", "corpus/coacd_bottle.obj",
                    "corpus/parry_poly_cylinder.obj", "corpus/cad_featuretype.STL"])
BATCH = ["kinds.obj", "wedges.off", "robot.stl"]


@pytest.fixture(scope="session")
def cli():
    """The release CLI (scripts/test.sh builds it)."""
    need(CLI)
    return CLI


def cli_json(cli, mesh, out, n=16):
    subprocess.run([cli, "decompose", mesh, "-n", str(n), "-o", out], check=True, capture_output=True)
    return Path(out).read_bytes()


@contextlib.contextmanager
def ctrl_c_once(ready, delay=0.0):
    """Ctrl-C from another thread: SIGINT to this process once `ready()` holds and
    `delay` seconds more have passed, unless the block has ended by then (Python runs
    the handler on the main thread, as for a user's Ctrl-C). Yields a list that holds
    the moment it was sent (`time.perf_counter()`), empty if it was not; the sender is
    joined when the block ends."""
    done = threading.Event()
    sent = []

    def send():
        while not done.is_set() and not ready():
            time.sleep(0.01)
        if not done.wait(delay):
            sent.append(time.perf_counter())
            os.kill(os.getpid(), signal.SIGINT)

    sender = threading.Thread(target=send)
    sender.start()
    try:
        yield sent
    finally:
        done.set()
        sender.join()


def prims(text):
    return json.dumps(json.loads(text)["primitives"])


@pytest.mark.parametrize("name", MESHES)
def test_arrays_and_file_equal_cli(cli, tmp_path, name):
    path = mesh(name)
    want = cli_json(cli, path, tmp_path / "c.json")
    v, f = primdecomp.load(path)
    assert prims(primdecomp.decompose(v, f, targets=[16]).to_json()) == prims(want)
    assert primdecomp.decompose_file(str(path), targets=[16]).to_json().encode() == want


@pytest.mark.parametrize("name", MESHES)
def test_percent_targets_equal_cli(cli, tmp_path, name):
    """`targets="2%"` is `-n 2%`: the same parser, the count resolved on the same faces."""
    path = mesh(name)
    want = cli_json(cli, path, tmp_path / "c.json", n="2%")
    assert primdecomp.decompose_file(str(path), targets="2%").to_json().encode() == want
    v, f = primdecomp.load(path)
    assert prims(primdecomp.decompose(v, f, targets=["2%"]).to_json()) == prims(want)


def inside_some_hull(points, hulls, tol):
    """Independent of the engine: a point is inside a convex mesh when it is behind
    every face plane (trimesh's face normals) within `tol`."""
    covered = np.zeros(len(points), dtype=bool)
    for h in hulls:
        n = h.face_normals
        d = np.einsum("ij,ij->i", n, h.triangles[:, 0, :])
        covered |= np.all(points @ n.T - d <= tol, axis=1)
    return covered


def test_as_hulls_are_convex_and_contain_the_input():
    trimesh = pytest.importorskip("trimesh")
    v, f = primdecomp.load(made_up("kinds.obj"))
    hulls = [trimesh.Trimesh(hv, hf) for hv, hf in primdecomp.as_hulls(v, f, targets=[12])]
    assert 1 <= len(hulls) <= 12
    assert all(h.is_convex and h.is_watertight for h in hulls)
    tol = 1e-9 * np.linalg.norm(v.max(0) - v.min(0))
    assert inside_some_hull(v, hulls, tol).all()
    # The check can fail: a shrunken hull set misses vertices.
    small = [trimesh.Trimesh(h.vertices * 0.9 + 0.1 * h.centroid, h.faces) for h in hulls]
    assert not inside_some_hull(v, small, tol).all()


def test_load_ply_stl_gltf(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64) + 0.1
    f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    tet = trimesh.Trimesh(v, f, process=False)
    ply = tmp_path / "t.ply"
    ply.write_text("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                   "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
                   + "".join(f"{a} {b} {c}\n" for a, b, c in v) + "".join(f"3 {a} {b} {c}\n" for a, b, c in f))
    for path in (ply, tmp_path / "t.stl", tmp_path / "t.glb"):
        if path.suffix != ".ply":
            tet.export(path)
        lv, lf = primdecomp.load(path)
        assert lv.dtype == np.float64 and lv.shape[1] == 3
        assert isinstance(lf, np.ndarray) and lf.shape == (4, 3)
        tris = {tuple(np.round(lv[list(t)], 6).ravel()) for t in lf}
        want = {tuple(np.round(v.astype(np.float32).astype(np.float64)[list(t)], 6).ravel()) for t in f}
        assert tris == want, path
        assert primdecomp.decompose(lv, lf, targets=[1]).levels[0].primitives
    # Mixed polygons come back as a list.
    obj = tmp_path / "m.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\nf 1 4 3 2\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n")
    _, mf = primdecomp.load(obj)
    assert isinstance(mf, list) and [len(p) for p in mf] == [4, 3, 3, 3, 3]
    with pytest.raises(ValueError, match="bad.obj"):
        (tmp_path / "bad.obj").write_text("v 0 0\nf 1 2 3\n")
        primdecomp.load(tmp_path / "bad.obj")


def test_input_arrays_are_not_copied():
    """C-contiguous float64 vertices and uint32 / int32 faces reach Rust as they are:
    the arrays handed to the native module are the caller's (same memory)."""
    from primdecomp import _faces, _vertices

    v = np.random.default_rng(1).random((10, 3))
    assert _vertices(v) is v
    for dt in (np.uint32, np.int32):
        f = np.arange(12, dtype=dt).reshape(4, 3) % 10
        assert np.shares_memory(_faces(f)[0], f)
    # Other dtypes and layouts are converted (one copy), with the same result.
    assert not np.shares_memory(_vertices(v.astype(np.float32)), v)
    fs = (np.arange(24).reshape(4, 6) % 10)[:, ::2]
    assert not fs.flags.c_contiguous and _faces(fs)[0].flags.c_contiguous


def test_faces_dtypes_and_layouts_agree():
    # Triangles (an STL), so the faces are one (F, 3) array in every dtype and layout.
    v, f = primdecomp.load(made_up("robot.stl"))
    ref = primdecomp.decompose(v, f, targets=[6]).to_json()
    f = np.asarray(f)
    wide = np.zeros((len(f), 6), dtype=np.int64)
    wide[:, ::2] = f
    for ff in (f.astype(np.int32), f.astype(np.int64), f.astype(np.uint16), np.asfortranarray(f), wide[:, ::2]):
        assert primdecomp.decompose(v, ff, targets=[6]).to_json() == ref


def batch_inputs(tmp_path):
    bad = tmp_path / "in" / "broken.obj"
    bad.parent.mkdir()
    bad.write_text("v 0 0 0\nf 1 2 3\n")
    return [str(made_up(n)) for n in BATCH] + [str(bad)]


def check_batch(cli, tmp_path, rows, inputs, out):
    assert [r["input"] for r in rows] == inputs
    for r in rows[:3]:
        assert r["status"] in ("done", "skipped") and r["primitives"] and r["faces"], r
        want = cli_json(cli, r["input"], tmp_path / "cli.json")
        assert Path(r["output"]).read_bytes() == want, r["input"]
    assert rows[3]["status"] == "error" and "broken.obj" in rows[3]["error"]
    assert not Path(rows[3]["output"]).exists()
    lines = (out / primdecomp.batch.SUMMARY).read_text().splitlines()
    assert [json.loads(x) for x in lines] == rows


def test_batch_on_local_ray(cli, tmp_path):
    ray = pytest.importorskip("ray") if not os.environ.get("CI") else __import__("ray")
    inputs = batch_inputs(tmp_path)
    out = tmp_path / "out"
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    try:
        rows = primdecomp.batch.run(inputs, out, use_ray=True, targets=[16])
        assert [r["status"] for r in rows] == ["done"] * 3 + ["error"]
        check_batch(cli, tmp_path, rows, inputs, out)
        # Resumed: finished outputs are skipped, a missing one and the failure run again.
        os.remove(rows[1]["output"])
        again = primdecomp.batch.run(inputs, out, use_ray=True, targets=[16])
        assert [r["status"] for r in again] == ["skipped", "done", "skipped", "error"]
        check_batch(cli, tmp_path, again, inputs, out)
        # Other settings are not "done": everything runs again.
        other = primdecomp.batch.run(inputs, out, use_ray=True, targets=[8])
        assert [r["status"] for r in other] == ["done"] * 3 + ["error"]
    finally:
        ray.shutdown()


def test_batch_on_ray_cancels_its_tasks_on_ctrl_c(tmp_path, monkeypatch):
    """Ctrl-C during a Ray batch raises KeyboardInterrupt and cancels every task not
    finished: one not started never runs, a running one stops at its native watcher's
    next look (Ray raises KeyboardInterrupt in it). The signal goes once two Ray
    workers run the task (their process title says so) and a tenth of one input's
    uninterrupted run (timed just before on the same machine) has passed. Each
    cancelled task's ray.get raises TaskCancelledError and writes no output, or, for
    at most the two tasks running when the signal went, gives its row: Ray's cancel
    took 0.3 to 0.6 of one input's run on two loaded cores and 1.3 of it once in CI,
    so a running task may finish first. Without the cancel every task ran to its end
    (the two running and two more wrote their outputs after the KeyboardInterrupt)."""
    ray = pytest.importorskip("ray") if not os.environ.get("CI") else __import__("ray")
    if not Path("/proc/self/cmdline").exists():
        pytest.skip("no /proc to see which processes run a task")
    src = made_up("lumpy.ply")
    (tmp_path / "in").mkdir()
    inputs = [shutil.copy(src, tmp_path / "in" / f"lumpy{k}.ply") for k in range(6)]
    t0 = time.perf_counter()
    primdecomp.decompose_file(src, targets=[1])
    whole = time.perf_counter() - t0

    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    cancelled = []
    cancel = ray.cancel

    def recorded(ref, **kw):
        cancelled.append(ref)
        return cancel(ref, **kw)

    monkeypatch.setattr(ray, "cancel", recorded)

    def running():
        """Processes running the batch's task: Ray titles them `ray::TASK`."""
        n = 0
        for p in Path("/proc").iterdir():
            try:
                n += p.name.isdigit() and (p / "cmdline").read_bytes().startswith(b"ray::decompose_one")
            except OSError:
                pass
        return n

    try:
        with ctrl_c_once(lambda: running() >= 2, delay=whole / 10) as sent:
            with pytest.raises(KeyboardInterrupt):
                primdecomp.batch.run(inputs, tmp_path / "out", use_ray=True, targets=[1])
            outcomes = []
            for ref in cancelled:
                try:
                    outcomes.append(ray.get(ref)["status"])
                except ray.exceptions.TaskCancelledError:
                    outcomes.append("cancelled")
    finally:
        ray.shutdown()
    assert sent
    # Six tasks on two CPUs: at least four were not finished, and every one of them
    # was cancelled but for at most the two that ran when the signal went.
    assert len(cancelled) >= 4, cancelled
    assert set(outcomes) <= {"cancelled", "done"}, outcomes
    assert outcomes.count("cancelled") >= len(cancelled) - 2, outcomes
    out = tmp_path / "out"
    written = [p for p in out.iterdir() if p.name.endswith(".primdecomp.json")]
    assert len(written) == 6 - outcomes.count("cancelled"), (written, outcomes)
    assert not (out / primdecomp.batch.SUMMARY).exists()
    assert all(p.name.endswith(".primdecomp.json") for p in out.iterdir())


def test_batch_thread_pool_fallback_and_folder(cli, tmp_path):
    folder = tmp_path / "meshes"
    folder.mkdir()
    for n in BATCH:
        shutil.copy(made_up(n), folder / n)
    (folder / "notes.txt").write_text("not a mesh")
    inputs = primdecomp.batch.inputs_of(folder)
    assert [Path(p).name for p in inputs] == sorted(BATCH)
    rows = primdecomp.batch.run(folder, tmp_path / "out", use_ray=False, workers=2, targets=[16])
    for r in rows:
        assert r["status"] == "done"
        assert Path(r["output"]).read_bytes() == cli_json(cli, r["input"], tmp_path / "c.json")
    assert rows[0]["output"] == primdecomp.batch.output_of(inputs[0], tmp_path / "out")
    with pytest.raises(ValueError, match="rename"):
        primdecomp.batch.run([folder / BATCH[0], tmp_path / "x" / BATCH[0]], tmp_path / "o2", use_ray=False)
    with pytest.raises(ValueError, match="one value of targets"):
        primdecomp.batch.run(folder, tmp_path / "o3", use_ray=False, targets=[8, 4])


def test_batch_thread_pool_stops_on_ctrl_c(tmp_path):
    """Ctrl-C during a thread-pool batch raises KeyboardInterrupt soon after, on the
    main thread: the inputs not started are dropped and the running ones stopped
    (Python shows the signal to the main thread only), not finished first. The signal
    goes once both of the pool's threads run; "soon" is a small part of one input's run
    uninterrupted, timed just before on the same machine."""
    src = made_up("lumpy.ply")
    (tmp_path / "in").mkdir()
    inputs = [shutil.copy(src, tmp_path / "in" / f"lumpy{k}.ply") for k in range(6)]
    t0 = time.perf_counter()
    primdecomp.decompose_file(src, targets=[1])
    whole = time.perf_counter() - t0

    def pool_threads():
        return sum(t.name.startswith("ThreadPoolExecutor") for t in threading.enumerate())

    with ctrl_c_once(lambda: pool_threads() >= 2) as sent:
        with pytest.raises(KeyboardInterrupt):
            primdecomp.batch.run(inputs, tmp_path / "out", use_ray=False, workers=2, targets=[1])
        raised = time.perf_counter()
    assert sent
    assert raised - sent[0] < whole / 2, (raised - sent[0], whole)
    # No summary (the batch did not finish), and no temporary file left: only outputs
    # written whole.
    out = tmp_path / "out"
    assert not (out / primdecomp.batch.SUMMARY).exists()
    assert all(p.name.endswith(".primdecomp.json") for p in out.iterdir())
