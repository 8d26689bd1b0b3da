"""Peer runs (CoACD, V-HACD) through benches/peers/run_peer.py, cached by the
mesh's sha256 and the method's settings, with a per-run timeout. A cache entry
records success, failure (with the tool's message) or timeout, so a re-run never
repeats a run whose outcome is known; a timeout is retried only with a longer
timeout."""

import hashlib
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent.parent
RUN_PEER = HERE / "peers" / "run_peer.py"
REQUIREMENTS = HERE / "peers" / "requirements.txt"
METHODS = ["coacd", "coacd-paper", "vhacd"]
LABEL = {"coacd": "CoACD", "coacd-paper": "CoACD (paper settings)", "vhacd": "V-HACD"}


def sha256_file(path):
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def settings_key(method, threads):
    """Everything that changes a peer's output or timing: the method (hence its
    settings, fixed in run_peer.py), the pinned versions, the runner's source
    and the thread count."""
    h = hashlib.sha256()
    h.update(method.encode())
    h.update(REQUIREMENTS.read_bytes())
    h.update(RUN_PEER.read_bytes())
    h.update(str(threads).encode())
    return h.hexdigest()[:12]


def entry_dir(cache, sha, method, threads):
    return Path(cache) / "peers" / f"{sha[:16]}-{method}-{settings_key(method, threads)}"


def read_status(d):
    try:
        return json.loads((d / "status.json").read_text())
    except (OSError, ValueError):
        return None


def write_json(path, obj):
    tmp = path.with_name(path.name + f".tmp.{os.getpid()}")
    tmp.write_text(json.dumps(obj, indent=2) + "\n")
    os.replace(tmp, path)


def run_peer(python, mesh, method, cache, timeout, threads, log=sys.stderr):
    """The cache entry's status for (mesh, method), running the peer if needed.
    Status: {"status": "ok"|"failed"|"timeout", "reason", "timeout_s", "obj", "meta"}."""
    sha = sha256_file(mesh)
    d = entry_dir(cache, sha, method, threads)
    st = read_status(d)
    if st and (st["status"] != "timeout" or st.get("timeout_s", 0) >= timeout):
        return st, d
    d.mkdir(parents=True, exist_ok=True)
    obj, meta = d / "hulls.obj", d / "meta.json"
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    cmd = [python, str(RUN_PEER), method, str(mesh), str(obj), str(meta)]
    print(f"[peer] {method} {Path(mesh).name} (timeout {timeout} s)", file=log, flush=True)
    t0 = time.time()
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
    try:
        out, err = proc.communicate(timeout=timeout)
        if proc.returncode == 0 and obj.exists() and meta.exists():
            st = {"status": "ok", "reason": ""}
        else:
            tail = (err.decode(errors="replace").strip().splitlines() or ["(no message)"])[-1]
            st = {"status": "failed", "reason": f"exit {proc.returncode}: {tail[:300]}"}
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        st = {"status": "timeout", "reason": f"no result within {timeout} s"}
    st.update(
        timeout_s=timeout,
        wall_s=round(time.time() - t0, 3),
        mesh=Path(mesh).name,
        mesh_sha256=sha,
        method=method,
        threads=threads,
    )
    write_json(d / "status.json", st)
    print(f"[peer] {method} {Path(mesh).name}: {st['status']} {st['reason']} ({st['wall_s']} s)", file=log, flush=True)
    return st, d
