"""docs/results/compare.md: run (or read cached) peers, run our engine with the
stated target rule, evaluate everything with `primdecomp eval`, and write the
per-mesh tables, the Table-3-style summary, the failures and the plots."""

import datetime
import json
import math
import os
import platform
import statistics as st
import subprocess
import sys
import time
from pathlib import Path

from . import ours, peers, plots, thumbs

RULE = (
    "our target per mesh: from one multi-target pass over targets from the most primitives "
    "that could fit the budget down to 1 (steps of about 7%), the level with the most primitives "
    "whose bytes stay at or below one third of CoACD's (default settings) on that mesh; "
    "where CoACD has no result, the 1% target (faces/100, at least 1)"
)
CUT_RULE = (
    "our row per mesh (`--ours-mode cut`): one run of `primdecomp decompose MESH -n TOP --max-bytes B` with "
    "B = floor(one third of CoACD's (default settings) bytes on that mesh), the merge-tree cut of least worst "
    "distance whose bytes fit B, and TOP the byte rule's top count (the most primitives that could fit B, all "
    "spheres; at most the faces) as a cap; where CoACD has no result, `-n T --cut` with T the 1% target "
    "(faces/100, at least 1). The row 'ours (byte rule)' is the default report's rule on the same meshes: "
    + RULE
)


def git_commit(root):
    try:
        out = subprocess.run(["git", "-C", str(root), "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
        dirty = subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no"], capture_output=True, text=True)
        return out.stdout.strip() + ("-dirty" if dirty.stdout.strip() else "")
    except OSError:
        return "unknown"


def peer_record(a, mesh, method, cache):
    """The peer's cache status, running it unless --cached-only."""
    if a.cached_only:
        d = peers.entry_dir(cache, peers.sha256_file(mesh), method, a.threads)
        st_ = peers.read_status(d)
        if st_ is None:
            return {"status": "not run", "reason": "no cached result (--cached-only)"}, d
        return st_, d
    return peers.run_peer(sys.executable, mesh, method, cache, a.timeout, a.threads)


def run_mesh(a, mesh, methods, cache, work):
    rec = {"mesh": mesh.name, "peers": {}, "ours": {}}
    colliders = {}
    for m in methods:
        st_, d = peer_record(a, mesh, m, cache)
        r = {"status": st_["status"], "reason": st_.get("reason", "")}
        if st_["status"] == "ok":
            meta = json.loads((d / "meta.json").read_text())
            r.update(
                hulls=meta["hulls"],
                hull_vertices=meta["hull_vertices"],
                hull_triangles=meta["hull_triangles"],
                seconds=meta["seconds"],
                peak_rss_mib=meta["peak_rss_mib"],
            )
            colliders[m] = d / "hulls.obj"
        rec["peers"][m] = r
    mdir = work / mesh.name
    budget = None
    if "coacd" in colliders:
        c = rec["peers"]["coacd"]
        budget = ours.byte_budget(c["hull_vertices"], c["hull_triangles"])
    faces = count_faces(mesh)
    targets = ours.candidate_targets(budget, faces or 100)
    cut = getattr(a, "ours_mode", "level") == "cut"
    level, path, in_faces = ours_level(a, mesh, targets, budget, mdir / "ours")
    if cut:
        rec["ours_rule"] = level
        if path:
            colliders["ours-rule"] = path
        level, path, cut_faces = ours_cut(a, mesh, targets[0], budget, mdir / "ours_cut")
        in_faces = in_faces or cut_faces
    rec["ours"] = level
    if in_faces is not None:
        rec["faces"] = in_faces
    if path:
        colliders["ours"] = path
    rec["budget_bytes"] = budget
    rec.setdefault("faces", faces)
    evaluate_all(a, mesh, rec, colliders, mdir)
    if not cut:
        draw_thumbs(a, mesh, rec, colliders)
    return rec


def ours_level(a, mesh, targets, budget, out_dir):
    """The byte rule (RULE): our slot, the chosen level's path and the input's faces."""
    run = ours.decompose(a.bin, mesh, targets, out_dir, a.timeout)
    slot_ = {"status": run["status"], "reason": run["reason"]}
    if run["status"] != "ok":
        return slot_, None, None
    pick = ours.choose(run["levels"], budget)
    if pick is None:
        return {"status": "failed", "reason": "no level within one third of CoACD's bytes"}, None, None
    s = pick["stats"]
    slot_.update(target=pick["settings"]["target"], primitives=s["primitives"], counts=s["counts"],
                 seconds=s["seconds"]["total"], levels=len(run["levels"]))
    return slot_, Path(pick["_path"]), pick["input"]["faces"]


def ours_cut(a, mesh, cap, budget, out_dir):
    """CUT_RULE: `-n CAP --max-bytes floor(budget)` (the merge-tree cut of least worst
    distance that fits), or `-n CAP --cut` without a budget. Returns as ours_level."""
    extra = ["--max-bytes", str(math.floor(budget))] if budget is not None else ["--cut"]
    run = ours.decompose(a.bin, mesh, [cap], out_dir, a.timeout, extra=extra)
    slot_ = {"status": run["status"], "reason": run["reason"]}
    if run["status"] != "ok":
        return slot_, None, None
    doc = run["levels"][0]
    s = doc["stats"]
    if budget is not None and s["bytes"] > budget:
        return {"status": "failed", "reason": f"--max-bytes gave {s['bytes']} bytes, over {math.floor(budget)}"}, None, None
    slot_.update(target=doc["settings"]["target"], primitives=s["primitives"], counts=s["counts"],
                 seconds=s["seconds"]["total"], levels=len(run["levels"]), flags=extra)
    return slot_, Path(doc["_path"]), doc["input"]["faces"]


def draw_thumbs(a, mesh, rec, colliders):
    """The record's row of pictures (thumbs.COLUMNS) into OUT/thumbs."""
    pics = {k: v for k, v in colliders.items() if k in thumbs.COLUMNS}
    drawn, failed = thumbs.render(a.bin, mesh, pics, Path(a.out) / thumbs.DIR, a.timeout)
    rec["thumbs"] = drawn
    if failed:
        rec["thumb_errors"] = failed
        for col, err in failed.items():
            print(f"[compare] {mesh.name}: no {col} picture: {err}", file=sys.stderr)


def count_faces(mesh):
    from . import corpus

    return corpus.faces(mesh)


def evaluate_all(a, mesh, rec, colliders, mdir):
    if not colliders:
        return
    paths = list(colliders.values())
    res, errs = ours.evaluate(a.bin, mesh, paths, mdir / "eval.json", a.samples, a.timeout)
    for name, path in colliders.items():
        s = slot(rec, name)
        m = res.get(str(path))
        if m is None:
            s["status"] = "eval failed"
            s["reason"] = errs.get(str(path), "no metrics")
            continue
        s["metrics"] = {k: m[k] for k in m if k not in ("collider", "counts")}
        s["bytes"] = m["bytes"]


def load_sim(sim_dir, mesh_name):
    """Optional simulation results: SIM_DIR/<mesh file name>.json, an object
    {method: {metric: number}} (methods: ours, coacd, coacd-paper, vhacd)."""
    if not sim_dir:
        return None
    p = Path(sim_dir) / f"{mesh_name}.json"
    try:
        return json.loads(p.read_text())
    except (OSError, ValueError):
        return None


def main(a, meshes, methods, cache):
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    work = cache / "work"
    t0 = time.time()
    records = []
    for mesh in meshes:
        print(f"[compare] {mesh.name}", file=sys.stderr, flush=True)
        rec = run_mesh(a, mesh, methods, cache, work)
        rec["sim"] = load_sim(getattr(a, "sim", None), mesh.name)
        records.append(rec)
    cut = getattr(a, "ours_mode", "level") == "cut"
    name = getattr(a, "report_name", None) or ("compare_cut" if cut else "compare")
    ours_rows = ["ours", "ours-rule"] if cut else ["ours"]
    data = {"methods": ours_rows + methods, "records": records, "rule": CUT_RULE if cut else RULE}
    (out / f"{name}.json").write_text(json.dumps(data, indent=1) + "\n")
    plots.compare_plots(records, ours_rows + methods, out, name)
    from . import markdown

    text = markdown.render(records, methods, a, argv_line(), git_commit(Path(__file__).resolve().parents[2]), time.time() - t0)
    tmp = out / f".{name}.md.tmp.{os.getpid()}"
    tmp.write_text(text)
    os.replace(tmp, out / f"{name}.md")
    print(f"wrote {out / f'{name}.md'}", file=sys.stderr)
    return 0


def refresh_sim(a):
    """`benches/compare --refresh-sim`: the simulation section of OUT/compare.md and the
    records' `sim` fields in OUT/compare.json from the current SIM summaries, the rest
    untouched (its figures stay those of the run the report's first lines name)."""
    from . import markdown

    out = Path(a.out)
    data = json.loads((out / "compare.json").read_text())
    for rec in data["records"]:
        rec["sim"] = load_sim(a.sim, rec["mesh"])
    head, sep, _ = (out / "compare.md").read_text().partition(markdown.SIM_HEADING)
    if not sep:
        print(f"{out / 'compare.md'} has no '{markdown.SIM_HEADING}' section", file=sys.stderr)
        return 1
    note = (f"Section refreshed by `{argv_line()}` at commit `{git_commit(Path(__file__).resolve().parents[2])}` "
            f"on {datetime.date.today()}; the rest of this report is from the run named at the top.")
    text = head + "\n".join(markdown.sim_table(data["records"], note))
    write_report(out, data, text)
    print(f"refreshed the simulation section of {out / 'compare.md'}", file=sys.stderr)
    return 0


def write_report(out, data, text):
    """OUT/compare.json and OUT/compare.md, each through a temporary file and a rename."""
    for name, body in (("compare.json", json.dumps(data, indent=1) + "\n"), ("compare.md", text)):
        tmp = out / f".{name}.tmp.{os.getpid()}"
        tmp.write_text(body)
        os.replace(tmp, out / name)


def refresh_thumbs(a, cache):
    """`benches/compare --thumbs-only`: the pictures section of OUT/compare.md and the
    records' `thumbs` in OUT/compare.json, every other figure untouched. Ours is
    decomposed again at the report's target by today's binary; peers' hulls come from
    the cache where it has them (none is run)."""
    from . import corpus, markdown

    out = Path(a.out)
    data = json.loads((out / "compare.json").read_text())
    names = {Path(m).name for m in a.meshes} if a.meshes else None
    for rec in data["records"]:
        if names is not None and rec["mesh"] not in names:
            continue
        mesh = corpus.CORPUS / rec["mesh"]
        if not mesh.is_file():
            print(f"[compare] {rec['mesh']}: not in the corpus, no pictures", file=sys.stderr)
            continue
        print(f"[compare] pictures of {rec['mesh']}", file=sys.stderr, flush=True)
        colliders = {}
        target = rec["ours"].get("target")
        if target:
            run = ours.decompose(a.bin, mesh, [target], cache / "work" / rec["mesh"] / "thumbs", a.timeout)
            if run["status"] == "ok":
                colliders["ours"] = Path(run["levels"][0]["_path"])
        sha = peers.sha256_file(mesh)
        for m in ("coacd", "vhacd"):
            d = peers.entry_dir(cache, sha, m, a.threads)
            st_ = peers.read_status(d)
            if st_ and st_["status"] == "ok":
                colliders[m] = d / "hulls.obj"
        rec.pop("thumb_errors", None)
        draw_thumbs(a, mesh, rec, colliders)
    have = lambda col: sum(1 for r in data["records"] if col in r.get("thumbs", {}))  # noqa: E731
    note = (f"Pictures drawn by `{argv_line()}` at commit `{git_commit(Path(__file__).resolve().parents[2])}` on "
            f"{datetime.date.today()}: ours decomposed again at the report's target by that commit's binary (the "
            f"figures above are from the run named at the top); peers' hulls from `benches/.cache` where it has them "
            f"(CoACD's for {have('coacd')}, V-HACD's for {have('vhacd')} of the {len(data['records'])} meshes), "
            "'–' where it has none.")
    text = markdown.replace_section((out / "compare.md").read_text(), markdown.PICS_HEADING,
                                    markdown.pictures(data["records"], note), markdown.PICS_BEFORE)
    write_report(out, data, text)
    print(f"refreshed the pictures of {out / 'compare.md'}", file=sys.stderr)
    return 0


def argv_line():
    return "benches/compare " + " ".join(sys.argv[1:])


def machine():
    return f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}"


def summary_rows(records, methods):
    """Per method: meshes, wins, mean/median distances, bytes and seconds over the
    meshes where every method in `methods` has metrics."""
    common = [r for r in records if all(metrics_of(r, m) for m in methods)]
    rows = []
    for m in methods:
        h = [metrics_of(r, m)["hausdorff"] for r in common]
        c = [metrics_of(r, m)["chamfer"] for r in common]
        b = [slot(r, m)["bytes"] for r in common]
        s = [slot(r, m)["seconds"] for r in common]
        e = [metrics_of(r, m)["enclosure"] for r in common]
        wins_h = sum(1 for r in common if wins(r, m, methods, "hausdorff"))
        wins_c = sum(1 for r in common if wins(r, m, methods, "chamfer"))
        rows.append(dict(method=m, n=len(common), wins_h=wins_h, wins_c=wins_c, h=h, c=c, b=b, s=s, e=e))
    return common, rows


# Distances (over the diagonal) closer than this are ties: round-off on exact colliders.
TIE = 1e-9


def wins(r, m, methods, key):
    return metrics_of(r, m)[key] <= min(metrics_of(r, x)[key] for x in methods) + TIE


def slot(r, m):
    if m == "ours-rule":  # --ours-mode cut: the byte rule's level beside the cut
        return r.get("ours_rule", {})
    return r["ours"] if m == "ours" else r["peers"].get(m, {})


def metrics_of(r, m):
    return slot(r, m).get("metrics")


def mean(v):
    return st.mean(v) if v else float("nan")


def median(v):
    return st.median(v) if v else float("nan")
