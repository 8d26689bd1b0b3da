"""Runs one peer convex decomposition on one mesh and writes its hulls as OBJ
(one `o hull_K` object per hull, global 1-based indices) plus a JSON sidecar
with the wall time of the decomposition call, the peak resident memory of this
process, the hull count, the tool's version and every setting passed.

Methods:
  coacd        CoACD, library defaults
  coacd-paper  CoACD with the settings the paper's first author reported:
               threshold 0.08, resolution 5000, preprocess_resolution 50,
               decimate on, merge off
  vhacd        V-HACD 4 (vhacdx) with its defaults

Usage: run_peer.py METHOD MESH OUT.obj OUT.json [--seed S]

CoACD parallelises with OpenMP; set OMP_NUM_THREADS=1 for single-threaded
runs (benches/compare does). Exit code 0 on success, 1 on a tool failure
(message on stderr), 2 on bad arguments.
"""

import argparse
import hashlib
import json
import os
import resource
import sys
import time

import numpy as np
import trimesh

COACD_PAPER = dict(
    threshold=0.08,
    resolution=5000,
    preprocess_resolution=50,
    decimate=True,
    merge=False,
)


def load_triangles(path):
    """Vertices (float64) and triangles (int64) of every mesh in the file,
    scene node transforms applied, polygons triangulated, nothing merged."""
    m = trimesh.load(path, force="mesh", process=False)
    if not isinstance(m, trimesh.Trimesh) or len(m.faces) == 0:
        raise ValueError(f"{path}: no triangles")
    return np.asarray(m.vertices, dtype=np.float64), np.asarray(m.faces, dtype=np.int64)


def run_coacd(v, f, settings, seed):
    import coacd

    coacd.set_log_level("error")
    parts = coacd.run_coacd(coacd.Mesh(v, f), seed=seed, **settings)
    return [(np.asarray(pv, dtype=np.float64), np.asarray(pf, dtype=np.int64)) for pv, pf in parts]


def run_vhacd(v, f):
    from vhacdx import compute_vhacd

    # vhacdx reads faces as a flat [3, a, b, c, 3, ...] array; an (F, 3) array
    # is silently misread as polygons of other sizes.
    flat = np.column_stack((np.full(len(f), 3, dtype=np.uint32), f.astype(np.uint32))).ravel()
    parts = compute_vhacd(v, flat)
    return [(np.asarray(pv, dtype=np.float64), np.asarray(pf, dtype=np.int64).reshape(-1, 3)) for pv, pf in parts]


def write_obj(path, hulls):
    lines = [f"# {len(hulls)} convex hulls\n"]
    base = 1
    for k, (pv, pf) in enumerate(hulls):
        lines.append(f"o hull_{k}\n")
        lines.extend(f"v {x!r} {y!r} {z!r}\n" for x, y, z in pv.tolist())
        lines.extend(f"f {a + base} {b + base} {c + base}\n" for a, b, c in pf.tolist())
        base += len(pv)
    write_atomic(path, "".join(lines))


def write_atomic(path, text):
    tmp = f"{path}.tmp.{os.getpid()}"
    with open(tmp, "w") as fh:
        fh.write(text)
        fh.flush()
        os.fsync(fh.fileno())
    os.replace(tmp, path)


def version(module):
    try:
        from importlib.metadata import version as v

        return v(module)
    except Exception:  # a missing distribution record is not fatal
        return "unknown"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("method", choices=["coacd", "coacd-paper", "vhacd"])
    ap.add_argument("mesh")
    ap.add_argument("out_obj")
    ap.add_argument("out_json")
    ap.add_argument("--seed", type=int, default=0)
    a = ap.parse_args()

    v, f = load_triangles(a.mesh)
    rss_before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    t0 = time.perf_counter()
    if a.method == "vhacd":
        settings, tool = {}, "vhacdx"
        hulls = run_vhacd(v, f)
    else:
        settings, tool = (COACD_PAPER if a.method == "coacd-paper" else {}), "coacd"
        hulls = run_coacd(v, f, settings, a.seed)
    seconds = time.perf_counter() - t0
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    hulls = [(pv, pf) for pv, pf in hulls if len(pf) > 0]
    if not hulls:
        print(f"{a.method}: no hull produced for {a.mesh}", file=sys.stderr)
        return 1
    write_obj(a.out_obj, hulls)
    with open(a.mesh, "rb") as fh:
        sha = hashlib.sha256(fh.read()).hexdigest()
    meta = {
        "method": a.method,
        "tool": tool,
        "version": version(tool),
        "settings": settings,
        "seed": a.seed if tool == "coacd" else None,
        "omp_num_threads": os.environ.get("OMP_NUM_THREADS"),
        "mesh": a.mesh,
        "mesh_sha256": sha,
        "input_vertices": int(len(v)),
        "input_triangles": int(len(f)),
        "hulls": len(hulls),
        "hull_vertices": int(sum(len(pv) for pv, _ in hulls)),
        "hull_triangles": int(sum(len(pf) for _, pf in hulls)),
        "seconds": seconds,
        "peak_rss_mib": rss / 1024.0,
        "rss_before_mib": rss_before / 1024.0,
    }
    write_atomic(a.out_json, json.dumps(meta, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
