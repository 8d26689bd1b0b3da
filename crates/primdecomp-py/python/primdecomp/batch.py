"""Decompose many meshes on a Ray cluster (or, without Ray, a local thread pool).

    import ray, primdecomp.batch
    ray.init()                         # or ray.init(address="auto") / RAY_ADDRESS=...
    rows = primdecomp.batch.run("assets/", "out/", targets=[64])

One result file per input, OUT_DIR/STEM.primdecomp.json, the same bytes as
`primdecomp decompose INPUT -o OUT_DIR/STEM.primdecomp.json` with the same settings
(the same loader and writer), renamed into place only when complete. A summary table
OUT_DIR/summary.jsonl gets one JSON line per input: input, output, status ("done",
"skipped" or "error"), primitives, faces, seconds, error. Resumable: an input whose
output already exists (complete, since outputs are written atomically) with the
requested settings is skipped; a failed input is reported and the others continue.
"""

import concurrent.futures as _cf
import json as _json
import os as _os
import threading as _threading
import time as _time
from pathlib import Path as _Path

MESH_EXTENSIONS = (".obj", ".ply", ".stl", ".off", ".gltf", ".glb")
SUMMARY = "summary.jsonl"
# Seconds between the thread pool's looks at Ctrl-C (the native watcher's poll).
_LOOK = 0.05

__all__ = ["run", "inputs_of", "output_of", "MESH_EXTENSIONS", "SUMMARY"]


def inputs_of(inputs):
    """The input files: every mesh file directly in a folder (sorted by name), or the
    given list of paths as they are."""
    if isinstance(inputs, (str, _os.PathLike)) and _Path(inputs).is_dir():
        d = _Path(inputs)
        return sorted(str(p) for p in d.iterdir() if p.suffix.lower() in MESH_EXTENSIONS and p.is_file())
    if isinstance(inputs, (str, _os.PathLike)):
        return [str(inputs)]
    return [str(p) for p in inputs]


def output_of(input_path, out_dir):
    """OUT_DIR/STEM.primdecomp.json, the name the CLI uses for a batch (-o DIR)."""
    return str(_Path(out_dir) / (_Path(input_path).stem + ".primdecomp.json"))


def _complete(output, settings):
    """An existing output that parses and records the requested settings."""
    try:
        with open(output, "rb") as f:
            doc = _json.loads(f.read())
    except (OSError, ValueError):
        return None
    if (not isinstance(doc, dict) or doc.get("format") != "primdecomp" or doc.get("version") != 1
            or "primitives" not in doc):
        return None
    recorded = doc.get("settings", {})
    if any(recorded.get(k) != _json.loads(_json.dumps(v)) for k, v in settings.items()):
        return None
    return doc


def decompose_one(input_path, output, settings, stop=None):
    """Decompose one file into `output` (atomically); never raises but
    KeyboardInterrupt, once `stop` (a threading.Event) is set: a summary row."""
    row = {"input": input_path, "output": output, "status": "done", "primitives": None,
           "faces": None, "seconds": None, "error": None}
    t0 = _time.perf_counter()
    try:
        import primdecomp

        res = primdecomp._decompose_file(input_path, None, settings, stop)
        res.export(output)
        row["primitives"] = len(res.levels[0].primitives) if res.levels else 0
        row["faces"] = res.levels[0]._doc.get("input", {}).get("faces") if res.levels else None
    except Exception as e:  # reported in the row; the batch goes on
        row["status"], row["error"] = "error", f"{type(e).__name__}: {e}"
    row["seconds"] = round(_time.perf_counter() - t0, 3)
    return row


def _skipped(input_path, output, doc):
    return {"input": input_path, "output": output, "status": "skipped",
            "primitives": len(doc["primitives"]), "faces": doc.get("input", {}).get("faces"),
            "seconds": 0.0, "error": None}


def _ray_results(ray, refs, keep):
    """Calls keep(ref) for each of the Ray tasks `refs` as it finishes. On Ctrl-C
    (or any exception, keep's own included) every task not yet finished is cancelled
    before the exception goes on: one not started never starts, and a running one
    gets a KeyboardInterrupt, which the native watcher sees at its next look, so the
    cluster stops working for a run nobody waits for."""
    pending = list(refs)
    try:
        while pending:
            done, pending = ray.wait(pending, num_returns=1)
            for ref in done:
                keep(ref)
    except BaseException:
        for ref in pending:
            try:
                ray.cancel(ref)
            except Exception:  # finished meanwhile, or the cluster is gone
                pass
        raise


def _run_ray(jobs, settings, ray):
    task = ray.remote(num_cpus=1, max_retries=0)(decompose_one)
    refs = {task.remote(i, o, settings): (i, o) for i, o in jobs}
    rows = {}

    def keep(ref):
        i, o = refs[ref]
        try:
            rows[i] = ray.get(ref)
        except Exception as e:  # the worker died (a crash, OOM kill): report it
            rows[i] = {"input": i, "output": o, "status": "error", "primitives": None,
                       "faces": None, "seconds": None, "error": f"{type(e).__name__}: {e}"}

    _ray_results(ray, refs, keep)
    return rows


def _run_pool(jobs, settings, workers):
    rows = {}
    # Threads, not processes: the decomposition releases the GIL, so threads run in
    # parallel, and there is no fork of a threaded process (which can deadlock) nor
    # spawn's re-import of the caller's script (which needs a __main__ guard).
    stop = _threading.Event()
    pool = _cf.ThreadPoolExecutor(max_workers=workers)
    try:
        futs = {pool.submit(decompose_one, i, o, settings, stop): (i, o) for i, o in jobs}
        pending = set(futs)
        while pending:
            # A wait with a timeout: the kernel may hand Ctrl-C to one of the pool's
            # threads, whose handler only flags it; this thread, blocked without a
            # timeout, would raise it when an input finishes, not now.
            done, pending = _cf.wait(pending, timeout=_LOOK, return_when=_cf.FIRST_COMPLETED)
            for fut in done:
                i, o = futs[fut]
                try:
                    rows[i] = fut.result()
                except Exception as e:  # decompose_one never raises; for safety
                    rows[i] = {"input": i, "output": o, "status": "error", "primitives": None,
                               "faces": None, "seconds": None, "error": f"{type(e).__name__}: {e}"}
    except BaseException:
        # Ctrl-C raises here, on the main thread, and nowhere else: the inputs not
        # started are dropped and the running ones stopped at their next look (the
        # threads see no signal), so that KeyboardInterrupt reaches the caller now,
        # not once every input is done; their outputs stay unwritten.
        stop.set()
        pool.shutdown(wait=True, cancel_futures=True)
        raise
    pool.shutdown(wait=True)
    return rows


def _ray_or_none(use_ray):
    if use_ray is False:
        return None
    try:
        import ray
    except ImportError:
        if use_ray:
            raise
        return None
    if not ray.is_initialized():
        if not use_ray and not _os.environ.get("RAY_ADDRESS"):
            return None
        ray.init()  # RAY_ADDRESS, if set, names the cluster
    return ray


def run(inputs, out_dir, *, use_ray=None, workers=None, **settings):
    """Decompose a folder or a list of mesh files into OUT_DIR, one
    STEM.primdecomp.json per input, and write OUT_DIR/summary.jsonl. Returns the
    summary rows in input order.

    `settings`: as for `primdecomp.decompose` (targets, kinds, ...). `use_ray`: None
    uses Ray when it is initialised (or RAY_ADDRESS is set), else a local pool
    of `workers` threads (the GIL is released while decomposing); True requires Ray; False never uses it. Two inputs with the
    same file stem are refused (ValueError) before anything runs, as the CLI does.
    One level per input: one target (`targets=[n]`) or tolerance, or none (the
    default tolerance)."""
    for key in ("targets", "tolerance", "max_bytes"):
        v = settings.get(key)
        if isinstance(v, (list, tuple)) and len(v) > 1:
            raise ValueError(f"batch.run writes one level per input: give one value of {key}")
    paths = inputs_of(inputs)
    out = _Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    outputs = [output_of(p, out) for p in paths]
    seen = {}
    for p, o in zip(paths, outputs):
        if o in seen:
            raise ValueError(f"{seen[o]} and {p} would both write {o}: rename one")
        seen[o] = p
    rows, jobs = {}, []
    for p, o in zip(paths, outputs):
        doc = _complete(o, settings)
        if doc is not None:
            rows[p] = _skipped(p, o, doc)
        else:
            jobs.append((p, o))
    ray = _ray_or_none(use_ray)
    if jobs:
        rows.update(_run_ray(jobs, settings, ray) if ray else _run_pool(jobs, settings, workers))
    ordered = [rows[p] for p in paths]
    text = "".join(_json.dumps(r) + "\n" for r in ordered)
    tmp = out / (SUMMARY + f".tmp{_os.getpid()}")
    tmp.write_text(text)
    _os.replace(tmp, out / SUMMARY)
    return ordered


def _main(argv=None):
    import argparse

    ap = argparse.ArgumentParser(prog="python -m primdecomp.batch", description=__doc__.split("\n\n")[0])
    ap.add_argument("inputs", nargs="+", help="a folder of meshes, or mesh files")
    ap.add_argument("-o", "--out", required=True, help="output folder")
    ap.add_argument("-n", "--targets", default=None,
                    help="a primitive count (default: the fewest within the default tolerance)")
    ap.add_argument("--ray", action="store_true", help="require Ray (ray.init(); RAY_ADDRESS names a cluster)")
    ap.add_argument("--workers", type=int, default=None, help="local threads without Ray")
    a = ap.parse_args(argv)
    inputs = a.inputs[0] if len(a.inputs) == 1 and _Path(a.inputs[0]).is_dir() else a.inputs
    counts = {} if a.targets is None else {"targets": [int(t) for t in a.targets.split(",")]}
    rows = run(inputs, a.out, use_ray=True if a.ray else None, workers=a.workers, **counts)
    bad = [r for r in rows if r["status"] == "error"]
    for r in bad:
        print(f"{r['input']}: {r['error']}")
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(_main())
