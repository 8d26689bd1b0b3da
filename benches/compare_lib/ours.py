"""Our engine on one mesh: one multi-target pass (`-n a,b,c`), then the level
chosen by the report's rule, and `primdecomp eval` of a set of colliders."""

import json
import math
import subprocess
import time
from pathlib import Path

# Largest bytes per primitive (a prism, 11 floats) and smallest (a sphere, 4).
MAX_PRIM_BYTES, MIN_PRIM_BYTES = 44, 16


def byte_budget(hull_vertices, hull_triangles):
    """The rule's budget: one third of CoACD's hulls' bytes by the paper's Table 2
    (12 per vertex, 6 per triangle)."""
    return (12 * hull_vertices + 6 * hull_triangles) / 3.0


def candidate_targets(budget_bytes, faces):
    """Targets from the most primitives that could fit `budget_bytes` (all
    spheres) down to 1, in steps of about 7%; without a budget, 1% of the faces."""
    if budget_bytes is None:
        return [max(1, round(faces / 100))]
    top = max(1, min(faces, int(budget_bytes // MIN_PRIM_BYTES)))
    out, n = [], float(top)
    while n >= 1:
        out.append(int(n))
        n = min(n - 1, n * 0.93)
    return sorted(set(out + [1]), reverse=True)


def decompose(binary, mesh, targets, out_dir, timeout, threads=1, extra=()):
    """Runs one pass; returns ({"status", "reason", "levels": [doc, ...]}). Each level
    doc is the parsed JSON with its path under "_path"."""
    out_dir.mkdir(parents=True, exist_ok=True)
    for old in out_dir.glob("*.json"):
        old.unlink()
    out = out_dir / "ours.json"
    cmd = [str(binary), "decompose", str(mesh), "-n", ",".join(map(str, targets)), "-o", str(out), "--quiet", "--timings", "--threads", str(threads), *extra]
    t0 = time.time()
    try:
        p = subprocess.run(cmd, capture_output=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"status": "timeout", "reason": f"no result within {timeout} s", "levels": []}
    if p.returncode != 0:
        msg = (p.stderr.decode(errors="replace").strip().splitlines() or ["(no message)"])[-1]
        return {"status": "failed", "reason": f"exit {p.returncode}: {msg[:300]}", "levels": []}
    levels = []
    for f in sorted(out_dir.glob("ours*.json")):
        doc = json.loads(f.read_text())
        doc["_path"] = str(f)
        levels.append(doc)
    return {"status": "ok", "reason": "", "levels": levels, "wall_s": time.time() - t0}


def choose(levels, budget_bytes):
    """The rule: the level with the most primitives whose bytes stay within the
    budget (ties: the larger target); without a budget, the only level."""
    ok = [d for d in levels if budget_bytes is None or d["stats"]["bytes"] <= budget_bytes]
    if not ok:
        return None
    return max(ok, key=lambda d: (d["stats"]["primitives"], d["settings"]["target"]))


def evaluate(binary, mesh, colliders, out_json, samples, timeout):
    """`primdecomp eval` of `colliders` (paths); returns {path: metrics} and an
    error message per collider that could not be evaluated."""
    base = [str(binary), "eval", "--input", str(mesh)]
    if samples:
        base += ["--samples", str(samples)]
    results, errors = {}, {}

    def run(paths, dest):
        p = subprocess.run(base + [str(c) for c in paths] + ["--json", str(dest)], capture_output=True, timeout=timeout)
        if p.returncode != 0:
            return (p.stderr.decode(errors="replace").strip().splitlines() or ["(no message)"])[-1]
        for c in json.loads(Path(dest).read_text())["colliders"]:
            results[c["collider"]] = c
        return None

    try:
        err = run(colliders, out_json)
    except subprocess.TimeoutExpired:
        err = f"eval took over {timeout} s"
    if err:
        # Isolate the failing collider(s).
        for i, c in enumerate(colliders):
            try:
                e = run([c], Path(f"{out_json}.{i}"))
            except subprocess.TimeoutExpired:
                e = f"eval took over {timeout} s"
            if e:
                errors[str(c)] = e
    return results, errors


def finite(x):
    return x is not None and not (isinstance(x, float) and math.isnan(x))
