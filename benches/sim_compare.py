#!/usr/bin/env python3
"""benches/sim_compare: the paper's §4.1 rigid-body benchmark on several meshes,
primdecomp against CoACD and V-HACD -> docs/results/sim.md.

For each mesh: our collider is `primdecomp decompose MESH -n N` with N as
docs/results/compare.json chose it for the mesh (the byte-budget rule of
benches/compare), else by the same rule against the CoACD hulls in the peer cache,
else max(32, 1% of the faces), plus one at each peer's own hull
count (the same number of colliders) (decomposed on every run; the simulation report is
cached under benches/.cache/sim by the mesh's sha256, the settings and a hash of our
primitives, so an engine change re-simulates); the peers' hulls come from peer caches laid out as
benches/compare writes them, PEER_CACHE/<sha256[:16]>-<method>-<key>/hulls.obj
(with status.json saying "ok"), methods `coacd` and `vhacd`; a peer missing from
every cache is listed as "-". Then one `primdecomp sim` run per mesh simulates
the mesh itself (the reference) and all colliders interleaved frame by frame,
and its JSON report and frame-time plot are kept in the cache, with a per-mesh
summary in benches/.cache/sim/summary/<mesh>.json that `benches/compare` folds into
docs/results/compare.md. Standard library only.

Usage:
  python3 benches/sim_compare.py [--meshes NAME ...] [--balls 5000] [--frames 1000]
      [--peer-cache DIR ...] [--bin target/release/primdecomp] [--out docs/results/sim.md]
      [--decompose-args='--rim-weight 0' --no-summary] [--sim-args='--compound']
"""

import argparse
import hashlib
import json
import math
import subprocess
import sys
from pathlib import Path

from compare_lib import ours as our_levels  # the byte rule's targets and choice (standard library only)
from compare_lib.noise import step_spread  # the step-time noise band (standard library only)
from compare_lib.peers import sha256_file  # the peer cache's own key (standard library only)

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT.parent / "shared" / "datasets" / "corpus"
CACHE = ROOT / "benches" / ".cache"
PEERS = ["coacd", "vhacd"]
LABEL = {"coacd": "CoACD", "vhacd": "V-HACD"}
# Game assets first (the paper's focus), then small cases with stairs, holes and walls.
DEFAULT_MESHES = [
    "kenney_pavement_fountain.glb",
    "kenney_road_lightposts.glb",
    "kenney_building_garage.glb",
    "kenney_wall_high.glb",
    "kenney_building_small_a.glb",
    "kenney_building_small_c.glb",
    "cesium_milk_truck.glb",
    "truck_shrec.obj",
    "parry_stairs.obj",
    "tiny_wallhole.obj",
    "vhacd_wall.obj",
    "cube_no_bottom.obj",
    "vhacd_box_thick.obj",
    "tiny_not_convex.obj",
    "parry_poly_cylinder.obj",
    "tiny_7_8ths_cube.stl",
]


def peer_obj(caches, sha, method):
    """(hulls.obj of the first cached successful run of `method` on the mesh, None)
    or (None, what the caches say instead: a failure's status and reason, or "not run")."""
    seen = []
    for c in caches:
        for d in sorted(Path(c).glob(f"{sha[:16]}-{method}-*")):
            try:
                st = json.loads((d / "status.json").read_text())
            except (OSError, ValueError):
                st = {"status": "running or interrupted"}
            if st.get("status") == "ok" and (d / "hulls.obj").is_file():
                return d / "hulls.obj", None
            seen.append(" ".join(str(st.get(k, "")) for k in ["status", "reason"]).strip())
    return None, "; ".join(seen) or "not run"


def faces_of(mesh, binary, work):
    """Face count as primdecomp reads it (from a 1-primitive run)."""
    out = work / "faces.json"
    subprocess.run([binary, "decompose", str(mesh), "-n", "1", "-o", str(out), "--quiet"], check=True)
    return json.loads(out.read_text())["input"]["faces"]


COMPARE_JSON = ROOT / "docs" / "results" / "compare.json"


def compare_target(mesh_name):
    """Our target N for the mesh in docs/results/compare.json (the byte-budget rule of
    benches/compare), or None when the report has no result for it or chose N without
    CoACD's bytes (its 1% fallback)."""
    try:
        recs = json.loads(COMPARE_JSON.read_text())["records"]
    except (OSError, ValueError, KeyError):
        return None
    for r in recs:
        if r.get("mesh") == mesh_name and r.get("budget_bytes") is not None and (r.get("ours") or {}).get("status") == "ok":
            return r["ours"].get("target")
    return None


def byte_rule_target(mesh, sha, binary, work, caches):
    """The comparison report's rule applied here, for a mesh the report has no CoACD
    result for but the peer cache has: the most primitives whose bytes stay within a
    third of CoACD's hulls' (Table 2 bytes), from one
    multi-target pass of the default engine, as benches/compare runs it. None when no
    CoACD hulls are cached or no level fits."""
    obj, _ = peer_obj(caches, sha, "coacd")
    if obj is None:
        return None
    meta = json.loads((obj.parent / "meta.json").read_text())
    budget = our_levels.byte_budget(meta["hull_vertices"], meta["hull_triangles"])
    targets = our_levels.candidate_targets(budget, faces_of(mesh, binary, work))
    run = our_levels.decompose(binary, mesh, targets, work / "byte_rule", timeout=600)
    pick = our_levels.choose(run["levels"], budget) if run["status"] == "ok" else None
    return None if pick is None else pick["settings"]["target"]


def args_tag(args):
    """A short hash of extra command-line arguments, for file names they key ("" for none)."""
    return hashlib.sha256(" ".join(args).encode()).hexdigest()[:8] if args else ""


def ours(mesh, sha, binary, n=None, extra=(), caches=()):
    """Our collider for the mesh, decomposed afresh (the engine may have changed since
    the last run), its target N and rule, and a short hash of its primitives that keys
    the simulation report. N: `n` when given (a peer's hull count), else the comparison
    report's choice (the most primitives whose bytes stay within a third of CoACD's),
    else the same rule against CoACD's hulls in the peer cache, else max(32, 1% of the
    faces)."""
    work = CACHE / "sim" / sha[:16]
    work.mkdir(parents=True, exist_ok=True)
    rule = "a peer's hull count"
    if n is None:
        n, rule = compare_target(mesh.name), "compare.json"
    if n is None:
        n, rule = byte_rule_target(mesh, sha, binary, work, caches), "bytes within a third of cached CoACD's"
    if n is None:
        n, rule = max(32, round(faces_of(mesh, binary, work) / 100)), "max(32, 1% of faces)"
    tag = args_tag(extra)
    out = work / f"ours_n{n}{'_' + tag if tag else ''}.json"
    subprocess.run([binary, "decompose", str(mesh), "-n", str(n), "-o", str(out), "--quiet", *extra], check=True)
    prims = json.dumps(json.loads(out.read_text())["primitives"], sort_keys=True)
    # The report names our collider by its path (ours_n<N>.json), so N is in the key.
    return out, work, rule, f"n{n}{tag}_" + hashlib.sha256(prims.encode()).hexdigest()[:12]


def hull_count(obj):
    """Hulls in a peer's OBJ: one per `o`/`g` line (as `primdecomp sim` reads them)."""
    with open(obj, errors="replace") as f:
        return sum(1 for line in f if line.startswith(("o ", "g ")))


def simulate(mesh, colliders, work, key, a):
    # "p": reports with the perturbed reference (the noise floor); older ones lack it.
    # Extra sim arguments (e.g. --compound) key their own report.
    extra = f"_{args_tag(a.sim_args)}" if a.sim_args else ""
    report = work / f"sim_p_b{a.balls}_f{a.frames}_s{a.seed}_{key}{extra}.json"
    if not report.is_file() or a.rerun:
        cmd = [a.bin, "sim", "--input", str(mesh), *map(str, colliders), "--balls", str(a.balls),
               "--frames", str(a.frames), "--seed", str(a.seed), "--json", str(report),
               "--plot", str(report.with_suffix(".png")), "--quiet", *a.sim_args]
        print("+", " ".join(cmd), file=sys.stderr, flush=True)
        subprocess.run(cmd, check=True)
    return json.loads(report.read_text())


SUMMARY_KEYS = ["frame_ms_median", "cpu_ms_median", "similarity", "similarity_set", "on_object"]


def write_summary(r, a, rule):
    """CACHE/sim/summary/<mesh>.json = {method: {metric: value}} for benches/compare's
    simulation columns (methods: mesh, ours, coacd, vhacd)."""
    d = CACHE / "sim" / "summary"
    d.mkdir(parents=True, exist_ok=True)
    roles = ["mesh", "self", "ours", *PEERS, *(f"ours_at_{p}" for p in PEERS)]
    out = {role: {k: r[role][k] for k in SUMMARY_KEYS + ["shapes"]} for role in roles if r.get(role)}
    out["settings"] = {"balls": a.balls, "frames": a.frames, "seed": a.seed,
                       "ours_n": rule, "ours_primitives": r["ours"]["shapes"]}
    tmp = d / f"{r['name']}.json.tmp"
    tmp.write_text(json.dumps(out, indent=1))
    tmp.replace(d / f"{r['name']}.json")


def row(name, rep, order):
    """Collider entries by role ('mesh', 'self' = the perturbed mesh, 'ours', peers),
    None where absent."""
    by_path = {c["collider"]: c for c in rep["colliders"] if c["kind"] in ("primitives", "hulls")}
    own = next((c for c in rep["colliders"] if c["kind"] == "mesh_perturbed"), None)
    return {role: by_path.get(str(p)) if p else None for role, p in order.items()} | {
        "mesh": rep["colliders"][0], "self": own, "name": name, "faces": rep["input"]["faces"]}


def fmt(x, spec):
    return "-" if x is None else format(x, spec)


def ratio(a, b):
    return None if a is None or b is None or b == 0 else a / b


def tables(rows, a):
    g = lambda r, role, key: r[role][key] if r.get(role) else None  # noqa: E731
    lines = [
        "Fast bodies (balls fired at 0.1–10 diameters per frame, discrete steps and CCD): "
        "[projectiles.md](projectiles.md) (`python3 benches/projectiles.py`).",
        "",
        "### Physics-step time per frame, median ms, and ours as a ratio to the peers",
        "",
        "wall = wall clock of the step; CPU = the process's CPU time during the step (the machine "
        "was shared, so wall times include preemption in multiples of the scheduler tick). "
        "mesh spread = |perturbed mesh / mesh - 1| of the median wall time, at least 0.02: the same "
        "geometry run twice differs this much (chaotic piles and timer jitter), so a ratio within "
        "1 ± spread is a tie.",
        "",
        "| mesh | faces | our prims | CoACD hulls | V-HACD hulls | wall mesh | ours | CoACD | V-HACD "
        "| CPU mesh | ours | CoACD | V-HACD | ours/CoACD wall | CPU | ours/V-HACD wall | CPU | mesh spread |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        wall = {k: g(r, k, "frame_ms_median") for k in ["mesh", "ours", *PEERS]}
        cpu = {k: g(r, k, "cpu_ms_median") for k in ["mesh", "ours", *PEERS]}
        cells = [r["name"], str(r["faces"])] + [fmt(g(r, k, "shapes"), "d") for k in ["ours", *PEERS]]
        cells += [fmt(wall[k], ".2f") for k in ["mesh", "ours", *PEERS]]
        cells += [fmt(cpu[k], ".2f") for k in ["mesh", "ours", *PEERS]]
        for p in PEERS:
            cells += [fmt(ratio(wall["ours"], wall[p]), ".2f"), fmt(ratio(cpu["ours"], cpu[p]), ".2f")]
        cells.append(fmt(spread(r), ".2f") if r.get("self") else "-")
        lines.append("| " + " | ".join(cells) + " |")
    lines += [
        "",
        "### Behaviour against the mesh itself",
        "",
        "similarity = per-ball (same ball within one diameter of its end on the mesh); "
        "set = the same without ball identity; on object = fraction not fallen off or through "
        "(definitions: `src/sim/mod.rs`). mesh vs itself = the mesh's own run with every ball "
        "started up to 1e-4 ball radii away: the noise floor. Ball piles are chaotic, so even a "
        "perfectly faithful collider scores only about that; a collider near it is as close to the "
        "mesh as the measure can tell, one far below it (the summary counts below half) sends "
        "balls elsewhere.",
        "",
        "| mesh | similarity mesh vs itself | ours | CoACD | V-HACD | set mesh vs itself | ours | CoACD | V-HACD "
        "| on object mesh | ours | CoACD | V-HACD |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        sim = [fmt(g(r, k, "similarity"), ".3f") for k in ["self", "ours", *PEERS]]
        st = [fmt(g(r, k, "similarity_set"), ".3f") for k in ["self", "ours", *PEERS]]
        on = [fmt(g(r, k, "on_object"), ".3f") for k in ["mesh", "ours", *PEERS]]
        lines.append(f"| {r['name']} | " + " | ".join(sim + st + on) + " |")
    lines += [
        "",
        "### Ours at each peer's own shape count",
        "",
        "The same simulation, with ours decomposed to N = the peer's hull count (`-n N --fill`: "
        "where removing nested primitives would leave fewer, the merge stops earlier so that up to N "
        "remain; fewer where no merge target gives exactly N, or where coplanar faces merge into "
        "plates for free, docs/decisions/0025-free-merges-into-plates.md): the same number of colliders in the "
        "scene, or fewer.",
        "",
        "| mesh | peer | peer hulls | our prims | ours/peer step wall | CPU | similarity mesh vs itself "
        "| ours | peer | set mesh vs itself | ours | peer | on object ours | peer |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        for p in PEERS:
            at = f"ours_at_{p}"
            if not (r.get(at) and r.get(p)):
                continue
            cells = [r["name"], LABEL[p], fmt(g(r, p, "shapes"), "d"), fmt(g(r, at, "shapes"), "d"),
                     fmt(ratio(g(r, at, "frame_ms_median"), g(r, p, "frame_ms_median")), ".2f"),
                     fmt(ratio(g(r, at, "cpu_ms_median"), g(r, p, "cpu_ms_median")), ".2f")]
            for k in ["similarity", "similarity_set", "on_object"]:
                cells += [fmt(g(r, m, k), ".3f") for m in ([at, p] if k == "on_object" else ["self", at, p])]
            lines.append("| " + " | ".join(cells) + " |")
    return lines


def spread(r):
    """The step time's noise on this mesh (`compare_lib.noise.step_spread`)."""
    return step_spread(r["self"]["frame_ms_median"], r["mesh"]["frame_ms_median"])


def summary(rows):
    out = []
    for peer in PEERS:
        for mine, how in (("ours", "byte rule"), (f"ours_at_{peer}", "same shape count")):
            both = [r for r in rows if r.get(mine) and r.get(peer)]
            if not both:
                continue
            faster = sum(r[mine]["frame_ms_median"] <= r[peer]["frame_ms_median"] for r in both)
            cheaper = sum(r[mine]["cpu_ms_median"] <= r[peer]["cpu_ms_median"] for r in both)
            closer = sum(r[mine]["similarity"] >= r[peer]["similarity"] for r in both)
            closer_set = sum(r[mine]["similarity_set"] >= r[peer]["similarity_set"] for r in both)
            # Off = below half of what the mesh scores against itself (a faithful
            # collider scores about that); count meshes where exactly one of the two is off.
            floor = [(r, r["self"]["similarity"] / 2) for r in both if r.get("self")]
            worse = sum(r[mine]["similarity"] < f <= r[peer]["similarity"] for r, f in floor)
            better = sum(r[peer]["similarity"] < f <= r[mine]["similarity"] for r, f in floor)
            # Slower beyond noise: by more than the mesh's own spread, |perturbed / mesh - 1|
            # (the same geometry run twice, chaos and timer jitter alike), and by 2% at least.
            timed = [r for r in both if r.get("self")]
            slower = sum(ratio(r[mine]["frame_ms_median"], r[peer]["frame_ms_median"]) - 1 > spread(r) for r in timed)
            ratios = [x for x in (ratio(r[mine]["frame_ms_median"], r[peer]["frame_ms_median"]) for r in both) if x]
            geomean = math.exp(sum(math.log(x) for x in ratios) / len(ratios))
            out.append(f"- vs {LABEL[peer]} on {len(both)} meshes, ours at the {how}: our median step ≤ theirs "
                       f"on {faster} by wall clock (geometric mean of ours / theirs {geomean:.3f}), {cheaper} by CPU time, slower by more than the mesh's own "
                       f"spread on {slower} of {len(timed)}; our similarity ≥ theirs on {closer}, "
                       f"set similarity on {closer_set}; of {len(floor)} with the noise floor, only ours is off "
                       f"(similarity below half of mesh vs itself) on {worse}, only theirs on {better}.")
    return out


def main(argv):
    ap = argparse.ArgumentParser(prog="benches/sim_compare.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--meshes", nargs="*", default=DEFAULT_MESHES)
    ap.add_argument("--balls", type=int, default=5000)
    ap.add_argument("--frames", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--peer-cache", nargs="*", default=[str(CACHE / "peers")])
    ap.add_argument("--bin", default=str(ROOT / "target" / "release" / "primdecomp"))
    ap.add_argument("--out", default=str(ROOT / "docs" / "results" / "sim.md"))
    ap.add_argument("--rerun", action="store_true", help="simulate again even when a report is cached")
    ap.add_argument("--decompose-args", default="", type=str.split,
                    help="extra arguments for our `primdecomp decompose` runs, one string "
                         "(e.g. --decompose-args='--rim-weight 0'); "
                         "use with --out and --no-summary to keep the default report")
    ap.add_argument("--sim-args", default="", type=str.split,
                    help="extra arguments for `primdecomp sim`, one string (e.g. "
                         "--sim-args='--compound': each collider as one compound shape); "
                         "use with --out and --no-summary to keep the default report")
    ap.add_argument("--no-summary", action="store_true",
                    help="do not write benches/.cache/sim/summary (the columns of docs/results/compare.md)")
    a = ap.parse_args(argv)
    rows, missing = [], []
    for name in a.meshes:
        mesh = CORPUS / name if not Path(name).is_file() else Path(name)
        if not mesh.is_file():
            print(f"CORPUS ABSENT or no such mesh: {mesh}", file=sys.stderr)
            continue
        sha = sha256_file(mesh)
        mine, work, rule, key = ours(mesh, sha, a.bin, extra=a.decompose_args, caches=a.peer_cache)
        found = {p: peer_obj(a.peer_cache, sha, p) for p in PEERS}
        order = {"ours": mine} | {p: f[0] for p, f in found.items()}
        keys = [key]
        for p, (obj, _) in found.items():
            if obj is not None:
                # Ours at the peer's own shape count: the same number of colliders
                # (--fill: nested primitives removed do not leave the budget unused).
                at, _, _, k = ours(mesh, sha, a.bin, hull_count(obj), ["--fill", *a.decompose_args])
                order[f"ours_at_{p}"] = at
                keys.append(k)
        colliders = list(dict.fromkeys(str(p) for p in order.values() if p))
        rep = simulate(mesh, colliders, work, "_".join(sorted(set(keys))), a)
        rows.append(row(mesh.name, rep, order))
        if not a.no_summary:
            write_summary(rows[-1], a, rule)
        missing += [f"- {mesh.name}: no {LABEL[p]} hulls ({f[1]})" for p, f in found.items() if f[0] is None]
    cmd = "python3 benches/sim_compare.py " + " ".join(sys.argv[1:])
    text = [
        "# Rigid-body simulation: frame time and behaviour (paper §4.1)",
        "",
        f"{a.balls} balls, {a.frames} frames at 1/60 s, seed {a.seed}, Rapier single-threaded, all colliders of a "
        "mesh interleaved frame by frame in one process (`primdecomp sim`"
        + (f" {' '.join(a.sim_args)}" if a.sim_args else "") + "; "
        + ("each collider's parts as one compound shape" if "--compound" in a.sim_args
           else "one Rapier collider per primitive or hull") + "). Ours: N as chosen in "
        "`docs/results/compare.json` (the most primitives whose bytes stay within a third of CoACD's), "
        "else the same rule against the cached CoACD hulls, else max(32, 1% of faces); and, in the last table, at each peer's own hull count (`-n N --fill`). "
        "Regenerate with:",
        "",
        "```sh",
        "cargo build --release",
        cmd.strip(),
        "```",
        "",
        *tables(rows, a),
        "",
        *summary(rows),
        "",
        *(["Peers missing (the peer caches' status):", "", *missing, ""] if missing else []),
    ]
    Path(a.out).parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(a.out).with_suffix(".md.tmp")
    tmp.write_text("\n".join(text))
    tmp.replace(a.out)
    print(f"wrote {a.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
