"""benches/compare --sweep: our engine over targets, excess-volume caps and the
kind set on a handful of meshes, each point a separate single-target run (so its
seconds are its own), evaluated with `primdecomp eval` -> docs/results/tradeoff.md
and PNGs (Hausdorff and Chamfer against primitives, bytes and seconds, with each
mesh's Pareto front over bytes marked)."""

import datetime
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from . import ours  # noqa: E402

DEFAULT_MESHES = ["spot.obj", "cad_fandisk.obj", "kenney_building_small_c.glb", "cgal_bones.off", "chess_table.obj"]
TARGETS = [4, 8, 16, 32, 64, 128, 256]
CONFIGS = [
    ("default", []),
    ("excess 0.1", ["--max-excess-volume", "0.1"]),
    ("excess 0.01", ["--max-excess-volume", "0.01"]),
    ("excess 0.001", ["--max-excess-volume", "0.001"]),
    ("boxes only", ["--kinds", "box"]),
    ("box+sphere+capsule", ["--kinds", "box,sphere,capsule"]),
    ("reprice exact", ["--reprice", "exact"]),
    ("reprice deferred", ["--reprice", "deferred"]),
]
SAMPLES = 50_000


def run_point(a, mesh, name, extra, target, work):
    d = work / mesh.name / name.replace(" ", "_").replace("+", "_") / str(target)
    run = ours.decompose(a.bin, mesh, [target], d, a.timeout, extra=extra)
    if run["status"] != "ok":
        return {"config": name, "target": target, "status": run["status"], "reason": run["reason"]}
    doc = run["levels"][0]
    res, errs = ours.evaluate(a.bin, mesh, [doc["_path"]], d / "eval.json", a.samples or SAMPLES, a.timeout)
    if not res:
        return {"config": name, "target": target, "status": "eval failed", "reason": "; ".join(errs.values())}
    m = next(iter(res.values()))
    return {
        "config": name,
        "target": target,
        "status": "ok",
        "primitives": doc["stats"]["primitives"],
        "bytes": doc["stats"]["bytes"],
        "seconds": doc["stats"]["seconds"]["total"],
        "hausdorff": m["hausdorff"],
        "chamfer": m["chamfer"],
        "enclosure": m["enclosure"],
    }


def pareto(points, key):
    """Points not dominated in (bytes, key): no other point is at most as large in
    both and smaller in one."""
    front = []
    for p in points:
        if not any(q is not p and q["bytes"] <= p["bytes"] and q[key] <= p[key] and (q["bytes"] < p["bytes"] or q[key] < p[key]) for q in points):
            front.append(p)
    return front


def plot(results, key, path):
    meshes = list(results)
    fig, axes = plt.subplots(len(meshes), 3, figsize=(13, 3.2 * len(meshes)), constrained_layout=True, squeeze=False)
    for i, mesh in enumerate(meshes):
        pts = [p for p in results[mesh] if p["status"] == "ok"]
        front = pareto(pts, key)
        for j, x in enumerate(["primitives", "bytes", "seconds"]):
            ax = axes[i][j]
            for name, _ in CONFIGS:
                ps = sorted((p for p in pts if p["config"] == name), key=lambda p: p[x])
                if x == "seconds":
                    # Time is noisy and not monotone in the target: points, not a line.
                    ax.scatter([p[x] for p in ps], [p[key] for p in ps], s=10, label=name)
                else:
                    ax.plot([p[x] for p in ps], [p[key] for p in ps], marker="o", ms=3, label=name)
            if x == "bytes":
                ax.scatter([p["bytes"] for p in front], [p[key] for p in front], s=60, facecolors="none", edgecolors="k", label="Pareto front")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel(x)
            ax.set_ylabel(f"{key} / diagonal")
            ax.grid(alpha=0.3)
            if j == 0:
                ax.set_title(mesh, loc="left", fontsize=9)
        if i == 0:
            axes[0][1].legend(fontsize=7)
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main(a, meshes):
    from . import corpus

    if not a.meshes:
        meshes = corpus.mesh_list(DEFAULT_MESHES)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    work = Path(a.cache) / "sweep"
    t0 = time.time()
    results = {}
    for mesh in meshes:
        results[mesh.name] = []
        for name, extra in CONFIGS:
            for t in TARGETS:
                print(f"[sweep] {mesh.name} {name} n={t}", file=sys.stderr, flush=True)
                results[mesh.name].append(run_point(a, mesh, name, extra, t, work))
    (out / "tradeoff.json").write_text(json.dumps(results, indent=1) + "\n")
    plot(results, "hausdorff", out / "tradeoff_hausdorff.png")
    plot(results, "chamfer", out / "tradeoff_chamfer.png")
    text = render(results, a, time.time() - t0)
    tmp = out / f".tradeoff.md.tmp.{os.getpid()}"
    tmp.write_text(text)
    os.replace(tmp, out / "tradeoff.md")
    print(f"wrote {out / 'tradeoff.md'}", file=sys.stderr)
    return 0


def render(results, a, seconds):
    from .report import git_commit, machine

    commit = git_commit(Path(__file__).resolve().parents[2])
    lines = [
        "# Speed/accuracy trade of our engine",
        "",
        f"Generated by `benches/compare {' '.join(sys.argv[1:])}` at commit `{commit}` on {datetime.date.today()} "
        f"({machine()}), in {seconds / 60:.1f} min. Each point is its own single-target run of the release binary "
        f"(`--threads 1`), evaluated by `primdecomp eval --samples {a.samples or SAMPLES}`; distances over the input's "
        "AABB diagonal. Configurations: " + "; ".join(f"{n} (`{' '.join(e) or 'no flags'}`)" for n, e in CONFIGS) + ".",
        "",
        "![Hausdorff](tradeoff_hausdorff.png)",
        "",
        "![Chamfer](tradeoff_chamfer.png)",
        "",
        "Pareto front (marked ✓): no other point of the same mesh has both fewer or equal bytes and a lower or equal Hausdorff distance.",
        "",
    ]
    for mesh, pts in results.items():
        ok = [p for p in pts if p["status"] == "ok"]
        front = {id(p) for p in pareto(ok, "hausdorff")}
        lines += [f"## {mesh}", "", "| config | N | primitives | bytes | seconds | Hausdorff | Chamfer | enclosure | Pareto |", "|---|---:|---:|---:|---:|---:|---:|---:|:---:|"]
        for p in pts:
            if p["status"] != "ok":
                lines.append(f"| {p['config']} | {p['target']} | {p['status']}: {p['reason']} | | | | | | |")
                continue
            lines.append(
                f"| {p['config']} | {p['target']} | {p['primitives']} | {p['bytes']} | {p['seconds']:.3f} | {p['hausdorff']:.4f} | "
                f"{p['chamfer']:.3e} | {p['enclosure']:.4f} | {'✓' if id(p) in front else ''} |"
            )
        lines.append("")
    return "\n".join(lines)
