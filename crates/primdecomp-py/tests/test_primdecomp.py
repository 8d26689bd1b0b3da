"""pytest suite of the primdecomp Python package. Runs on the made-up inputs
(conftest.py) and needs the CLI binary (scripts/test.sh builds it before running
this)."""

import json
import os
import signal
import subprocess
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import primdecomp

from conftest import CLI, ROOT, made_up, need


def lumpy():
    """A made-up mesh of 81,920 triangles: runs long enough to interrupt."""
    return made_up("lumpy.ply")


def cube():
    v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=np.float64)
    q = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    return v, np.array(q)


def test_dtypes_and_layouts_agree():
    v, q = cube()
    ref = primdecomp.decompose(v, q, targets=[4]).to_json()
    wide = np.zeros((8, 6))
    wide[:, ::2] = v
    for vv in (v.astype(np.float32), np.asfortranarray(v), wide[:, ::2]):
        assert primdecomp.decompose(vv, q, targets=[4]).to_json() == ref
    tris = np.array([[p[0], p[k], p[k + 1]] for p in q for k in (1, 2)], dtype=np.int32)
    r = primdecomp.decompose(v, tris, targets=[4])
    assert len(r.levels) == 1 and r.levels[0].primitives
    assert primdecomp.decompose(v, q.tolist(), targets=[4]).to_json() == ref


def test_result_objects():
    v, q = cube()
    r = primdecomp.decompose(v, q, targets=[8, 2])
    assert len(r.levels) == 2
    p = r.levels[0].primitives[0]
    assert p.transform.shape == (4, 4) and p.volume > 0 and p.kind in {
        "box", "sphere", "capsule", "cylinder", "frustum", "prism"}
    mv, mf = p.to_mesh()
    assert mv.shape[1] == 3 and len(mf) >= 4
    assert isinstance(r.stats, dict)


def test_prisms_have_their_shift():
    """A scalene triangle's prism is skewed (shift_z, docs/decisions/0045) and holds
    the triangle; an isosceles prism reads shift_z 0.0 though its JSON omits it."""
    v = np.array([[0, 0, 0], [3, 0, 0], [0.4, 1.3, 0.2]], dtype=np.float64)
    p = primdecomp.decompose(v, np.array([[0, 1, 2]])).levels[0].primitives[0]
    assert p.kind == "prism" and abs(p.shift_z) > 0.1, p.params
    local = (np.linalg.inv(p.transform) @ np.c_[v, np.ones(3)].T).T[:, :3]
    hy, zt, zb, s = p.half_y, p.half_z_top, p.half_z_bottom, p.shift_z
    for x, y, z in local:
        t = (y + hy) / (2 * hy)
        mid, w = s * (2 * t - 1), zb + (zt - zb) * t
        assert abs(x) <= p.half_x + 1e-9 and abs(y) <= hy + 1e-9 and abs(z - mid) <= w + 1e-9
    c, q = cube()
    only = {k: k == "prism" for k in ("box", "sphere", "capsule", "cylinder", "frustum", "prism")}
    r = primdecomp.decompose(c, q, targets=[6], kinds=only)
    prisms = r.levels[0].primitives
    assert prisms and all(p.kind == "prism" and p.shift_z == 0.0 for p in prisms)
    assert all("shift_z" not in pr for pr in json.loads(r.to_json())["primitives"])


@pytest.mark.parametrize("bad,msg", [
    (lambda v, q: (v[:, :2], q), "(N,3)"),
    (lambda v, q: (v.astype(str), q), "dtype"),
    (lambda v, q: (np.where(v == 1, np.nan, v), q), "finite"),
    (lambda v, q: (v, q + 100), "range"),
    (lambda v, q: (v, -q), "range"),
    (lambda v, q: (v, q.astype(float)), "integers"),
])
def test_bad_input_raises_value_error(bad, msg):
    v, q = cube()
    with pytest.raises(ValueError) as e:
        primdecomp.decompose(*bad(v, q))
    assert msg in str(e.value) or "non-finite" in str(e.value) or "NaN" in str(e.value)


def test_bad_settings():
    """Settings errors in Python's vocabulary: an unknown keyword is a TypeError, as
    for any function; a wrong value a ValueError with the CLI's one-line message."""
    v, q = cube()
    with pytest.raises(TypeError, match="unexpected keyword argument 'bogus'"):
        primdecomp.decompose(v, q, bogus=1)
    with pytest.raises(ValueError, match="targets: expected a positive count, got 0"):
        primdecomp.decompose(v, q, targets=[0])
    with pytest.raises(ValueError, match=r"^targets: expected a positive count or a percentage like 1%, got '150%'$"):
        primdecomp.decompose(v, q, targets=["150%"])
    # A count spelled as text is the count; a percentage of the 6 faces, rounded.
    assert primdecomp.decompose(v, q, targets="4").to_json() == primdecomp.decompose(v, q, targets=4).to_json()
    assert primdecomp.decompose(v, q, targets="50%").levels[0].target == 3
    with pytest.raises(ValueError, match="fill needs targets"):
        primdecomp.decompose(v, q, fill=True)
    with pytest.raises(ValueError, match=r"^tolerance: expected a positive distance .* got 'abc'$"):
        primdecomp.decompose(v, q, tolerance="abc")
    with pytest.raises(ValueError, match="is not positive"):
        primdecomp.decompose(v, q, tolerance="-1%")
    with pytest.raises(ValueError, match="unknown primitive kind 'cone'"):
        primdecomp.decompose(v, q, kinds=["box", "cone"])
    with pytest.raises(ValueError, match="min_extent: expected a number, got 'x'"):
        primdecomp.decompose(v, q, min_extent="x")
    with pytest.raises(ValueError, match="max_bytes: expected a positive byte count"):
        primdecomp.decompose(v, q, max_bytes="lots")
    with pytest.raises(ValueError, match=r"^min_extent must be in \(0, 1\), got -1"):
        primdecomp.decompose(v, q, min_extent=-1.0)
    # The CLI's forms work: kinds by name, a partial weights dict, "4K" bytes.
    r = primdecomp.decompose(v, q, kinds=["box"], weights={"box": 2}, max_bytes="4K", targets=4)
    assert {p.kind for p in r.levels[0].primitives} == {"box"}
    # The words the CLI reads, by the library's own parser, with the CLI's messages.
    r = primdecomp.decompose(v, q, targets=4, reprice=64, dedup=0.5, partitions="auto")
    assert r.levels[0].primitives
    r = primdecomp.decompose(v, q, reprice="exact", max_excess_volume=0.5, targets=4)
    assert r.levels[0].primitives
    with pytest.raises(ValueError, match="^reprice: expected exact, deferred or a neighbour count, got 'soon'$"):
        primdecomp.decompose(v, q, reprice="soon")
    with pytest.raises(ValueError, match="^partitions: expected auto or a count, got 'many'$"):
        primdecomp.decompose(v, q, partitions="many")
    with pytest.raises(ValueError, match="^dedup: expected exact, off or a distance, got 'near'$"):
        primdecomp.decompose(v, q, dedup="near")


def test_file_errors_are_os_errors(tmp_path):
    """The file system's errors as Python's own OSError subclasses, with errno and
    the file name; a file that is not a mesh is a ValueError naming its line."""
    import errno

    with pytest.raises(FileNotFoundError) as e:
        primdecomp.load(tmp_path / "nonexistent.obj")
    assert e.value.errno == errno.ENOENT and e.value.filename == str(tmp_path / "nonexistent.obj")
    with pytest.raises(IsADirectoryError):
        primdecomp.load(tmp_path)
    with pytest.raises(FileNotFoundError):
        primdecomp.decompose_file(tmp_path / "missing.stl")
    locked = tmp_path / "locked.obj"
    locked.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    locked.chmod(0)
    try:
        if os.geteuid() != 0:  # root reads it anyway
            with pytest.raises(PermissionError):
                primdecomp.load(locked)
    finally:
        locked.chmod(0o644)
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0\nf 1 2 3\n")
    with pytest.raises(ValueError, match=r"bad.obj:1"):
        primdecomp.load(bad)
    with pytest.raises(TypeError):
        primdecomp.load(42)


def test_reprs_say_what_they_hold():
    v, q = cube()
    r = primdecomp.decompose(v, q, targets=[4, 1])
    text = repr(r)
    assert text.startswith("<primdecomp.Result of arrays (6 faces), 2 levels: count 4: ")
    assert "primitives (" in text and "bytes" in text
    lv = r.levels[1]
    assert repr(lv).startswith("<primdecomp.Level count 1: 1 primitives (1 box), 40 bytes")
    p = lv.primitives[0]
    assert repr(p).startswith("Primitive(box: center=(0.5, 0.5, 0.5), half_extents=(")
    assert "faces=6" in repr(p)
    t = primdecomp.decompose(v, q, tolerance="1%")
    assert "tolerance 1% of the diagonal" in repr(t.levels[0]) and "farthest" in repr(t.levels[0])


def test_repr_of_a_path_holding_line_breaks_is_one_line(tmp_path):
    # A file name may hold U+2028, U+2029 or a line feed: the repr stays one line.
    path = tmp_path / "a\u2028b\u2029c\nd.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    text = repr(primdecomp.decompose_file(path, targets=[1]))
    assert len(text.splitlines()) == 1, text
    assert "a\\u2028b\\u2029c\\nd.obj" in text


def test_as_hulls_and_export(tmp_path):
    v, q = cube()
    hulls = primdecomp.as_hulls(v, q, targets=[3])
    assert hulls and all(h[0].shape[1] == 3 and h[1].shape[1] == 3 for h in hulls)
    r = primdecomp.decompose(v, q, targets=[3])
    for ext in ("json", "obj", "glb", "urdf"):
        out = r.export(tmp_path / f"c.{ext}")
        assert out and Path(out[0]).stat().st_size > 0


def test_same_primitives_as_cli(tmp_path):
    need(CLI)
    mesh = lumpy()
    subprocess.run([CLI, "decompose", mesh, "-n", "16", "-o", tmp_path / "c.json"],
                   check=True, capture_output=True)
    cli = json.loads((tmp_path / "c.json").read_text())["primitives"]
    py = json.loads(primdecomp.decompose_file(mesh, targets=[16]).to_json())["primitives"]
    assert json.dumps(cli) == json.dumps(py)


def test_gil_released():
    """Python runs on other threads during a run: the calling thread holds the GIL only
    for its looks at signals and progress. A thread ticking every 10 ms goes on
    ticking; its longest pause is a small part of the run (a run holding the GIL
    pauses it for the whole run), however late a busy machine wakes it."""
    v, f = primdecomp.load(lumpy())
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.01)

    t = threading.Thread(target=tick)
    t.start()
    while not ticks:
        time.sleep(0.001)
    t0 = time.perf_counter()
    primdecomp.decompose(v, f, targets=[16])
    t1 = time.perf_counter()
    stop.set()
    t.join()
    during = [x for x in ticks if t0 <= x <= t1]
    pause = np.diff([t0] + during + [t1]).max()
    assert len(during) >= 3 and pause < (t1 - t0) / 3, (len(during), pause, t1 - t0)


def test_ctrl_c_interrupts_quickly():
    """Ctrl-C (SIGINT to the process, as a terminal sends it) during a run raises
    KeyboardInterrupt soon after. The signal goes once the run has called the progress
    callback, so it lands inside the run however late a busy machine schedules the
    sender; "soon" is a small part of the same run uninterrupted, timed just before on
    the same machine (a Ctrl-C that waited for the run's end fails it)."""
    v, f = primdecomp.load(lumpy())
    t0 = time.perf_counter()
    primdecomp.decompose(v, f, targets=[1])
    whole = time.perf_counter() - t0

    under_way, done = threading.Event(), threading.Event()
    sent = []

    def ctrl_c():
        under_way.wait()
        if not done.is_set():
            sent.append(time.perf_counter())
            os.kill(os.getpid(), signal.SIGINT)

    seen = []

    def progress(stage, fraction):
        seen.append(stage)
        under_way.set()

    sender = threading.Thread(target=ctrl_c)
    sender.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            primdecomp.decompose(v, f, targets=[1], progress=progress)
        raised = time.perf_counter()
    finally:
        # A run that never reported progress leaves no sender behind to signal a
        # later test.
        done.set()
        under_way.set()
        sender.join()
    assert seen and sent
    assert raised - sent[0] < whole / 4, (raised - sent[0], whole)


def test_tolerance_and_bytes(tmp_path):
    """A closed cube within 1% is one box, as by default and, triangulated, as a count
    of 64 (its greedy level, a shell of plates, comes out short and is cut again);
    a chain of tolerances gives one level each; the same settings as the CLI give its
    primitives."""
    v, f = cube()
    one = primdecomp.decompose(v, f, tolerance="1%")
    assert [p.kind for p in one.levels[0].primitives] == ["box"]
    assert [p.kind for p in primdecomp.decompose(v, f).levels[0].primitives] == ["box"]
    # Triangulated (12 faces), the greedy level's 6 plates are short of 12 and cut again;
    # the 6 quads' greedy level holds one primitive per face, and stays.
    t = np.array([[a, b, c] for q in f for a, b, c in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))])
    assert [p.kind for p in primdecomp.decompose(v, t, targets=64).levels[0].primitives] == ["box"]
    assert len(primdecomp.decompose(v, t, targets=64, greedy=True).levels[0].primitives) > 1
    assert len(primdecomp.decompose(v, f, targets=64).levels[0].primitives) == 6
    dist = json.loads(one.to_json())["stats"]["distance"]
    assert dist["worst"] <= dist["tolerance"]
    with pytest.raises(ValueError, match="tolerance"):
        primdecomp.decompose(v, f, tolerance="1mm%")
    need(CLI)
    mesh = ROOT / "datasets" / "demo_scene.obj"
    chain = primdecomp.decompose_file(mesh, targets=[400, 400], tolerance=["5%", "2%"], max_bytes=2048)
    counts = [len(l.primitives) for l in chain.levels]
    assert len(counts) == 2 and counts[0] < counts[1]
    subprocess.run([CLI, "decompose", mesh, "-n", "400", "--tolerance", "5%,2%", "--max-bytes", "2048",
                    "-o", tmp_path / "d.json"], check=True, capture_output=True)
    cli = json.loads((tmp_path / "d_t2pct.json").read_text())["primitives"]
    assert json.dumps(cli) == json.dumps(json.loads(chain.to_json(1))["primitives"])


def test_measured_to_the_solid_of_a_closed_box_only():
    """Under solid=True a closed box's distance is measured to its solid, the box with
    one side left open to its surface (docs/decisions/0056), as the JSON says; a greedy
    level measures nothing."""
    v = np.array([[2 * x, y, 0.5 * z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=np.float64)
    _, q = cube()
    t = np.array([[a, b, c] for p in q for a, b, c in ((p[0], p[1], p[2]), (p[0], p[2], p[3]))], dtype=np.uint32)

    closed = primdecomp.decompose(v, t, solid=True)
    opened = primdecomp.decompose(v, t[:-2], solid=True)
    plain = primdecomp.decompose(v, t)
    greedy = primdecomp.decompose(v, t, targets=2, solid=True)
    for res, to in ((closed, "solid"), (opened, "mesh"), (plain, "mesh"), (greedy, None)):
        level = res.levels[0]
        assert level.measured_to == to, (to, level)
        dist = json.loads(res.to_json())["stats"].get("distance")
        assert (dist is None) == (to is None)
        assert dist is None or dist.get("measured_to") == ("solid" if to == "solid" else None)
    assert "outside the solid" in repr(closed) and "from the mesh" in repr(opened)
    chain = primdecomp.decompose(v, t, solid=True, tolerance=["2%", "1%"])
    assert [l.measured_to for l in chain.levels] == ["solid", "solid"]


def test_tolerance_without_count_matches_cli(tmp_path):
    """`tolerance="1%"` alone is capped as `primdecomp decompose --tolerance 1%` is."""
    need(CLI)
    mesh = ROOT / "datasets" / "demo_scene.obj"
    subprocess.run([CLI, "decompose", mesh, "--tolerance", "1%", "-o", tmp_path / "t.json"],
                   check=True, capture_output=True)
    cli = json.loads((tmp_path / "t.json").read_text())
    py = json.loads(primdecomp.decompose_file(mesh, tolerance="1%").to_json())
    assert py["settings"]["target"] == cli["settings"]["target"] == 1024
    assert json.dumps(cli["primitives"]) == json.dumps(py["primitives"])
    # No count, tolerance or byte target: the library's default tolerance, as the CLI's.
    subprocess.run([CLI, "decompose", mesh, "-o", tmp_path / "d.json"], check=True, capture_output=True)
    cli = (tmp_path / "d.json").read_bytes()
    assert primdecomp.decompose_file(mesh).to_json().encode() == cli
    assert json.loads(cli)["settings"]["tolerance"] == [{"diagonal": 0.02}]
    # One count caps every level of a chain, as `-n 400 --tolerance 5%,2%` does.
    assert len(primdecomp.decompose_file(mesh, targets=[400], tolerance=["5%", "2%"]).levels) == 2


def test_progress_with_time_left():
    """A callback of three arguments also gets the whole run's seconds left (None
    until known, then a number); one of two keeps its two."""
    v, f = cube()
    three, two = [], []
    primdecomp.decompose(v, f, targets=[4], progress=lambda s, x, left: three.append((s, x, left)))
    primdecomp.decompose(v, f, targets=[4], progress=lambda s, x: two.append((s, x)))
    assert three and two
    assert all(isinstance(s, str) and 0.0 <= x <= 1.0 for s, x, _ in three)
    assert all(left is None or left >= 0.0 for _, _, left in three)
