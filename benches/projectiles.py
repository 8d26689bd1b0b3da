#!/usr/bin/env python3
"""benches/projectiles: the tunnelling benchmark -> docs/results/projectiles.md.

For each mesh: ours = `primdecomp decompose MESH` (default settings, N = 64) and the
variants in VARIANTS (`--solid`, `--min-thickness T`), each timed (least of --runs
runs); CoACD and V-HACD hulls from
benches/.cache/projectiles/peers/<mesh>-<method>.obj (made here with
benches/peers/run_peer.py, OMP_NUM_THREADS=1, under `nice`, when missing and
--run-peers is given; a peer missing is listed as "-"). Then
`primdecomp sim --scenario projectiles` fires the same shots at the input mesh (as a
triangle mesh), ours, its variants, CoACD and V-HACD, once with CCD off (engines'
default) and once with --ccd, and `primdecomp eval` measures every collider's
distances to the input. Standard library only (the peers need benches/.venv).

Usage:
  python3 benches/projectiles.py [--meshes NAME ...] [--shots 256] [--runs 3]
      [--run-peers] [--bin target/release/primdecomp] [--out docs/results/projectiles.md]
"""

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CORPUS = ROOT.parent / "shared" / "datasets" / "corpus"
CACHE = ROOT / "benches" / ".cache" / "projectiles"
PEERS = [("coacd", "CoACD"), ("vhacd", "V-HACD")]
# Small meshes of benches/sim_compare.py's list, then closed corpus parts.
DEFAULT_MESHES = [
    "tiny_7_8ths_cube.stl",
    "vhacd_box_thick.obj",
    "tiny_not_convex.obj",
    "parry_poly_cylinder.obj",
    "kenney_wall_high.glb",
    "kenney_building_garage.glb",
    "panda_link6_collision.obj",
    "kuka_iiwa_link0.obj",
    "spot.obj",
]
SPEEDS = ["slow", "walking", "thrown", "bullet"]
# Our colliders: label, extra `decompose` arguments (the first is the default).
VARIANTS = [
    ("ours", []),
    ("ours --solid", ["--solid"]),
    ("ours --min-thickness 0.03", ["--min-thickness", "0.03"]),
    ("ours --min-thickness 0.1", ["--min-thickness", "0.1"]),
    ("ours --min-thickness 0.3", ["--min-thickness", "0.3"]),
    ("ours --solid --min-thickness 0.1", ["--solid", "--min-thickness", "0.1"]),
]


def peer_obj(mesh, method, run_peers):
    out = CACHE / "peers" / f"{mesh.name}-{method}.obj"
    if not out.is_file() and run_peers:
        py = subprocess.run(["bash", str(ROOT / "benches/peers/venv.sh")], check=True,
                            capture_output=True, text=True).stdout.strip()
        out.parent.mkdir(parents=True, exist_ok=True)
        env = dict(os.environ, OMP_NUM_THREADS="1")
        subprocess.run(["nice", py, str(ROOT / "benches/peers/run_peer.py"), method, str(mesh),
                        str(out), str(out.with_suffix(".json"))], env=env)
    return out if out.is_file() else None


def ours(binary, mesh, label, args, runs):
    """(primitives JSON, least seconds of `runs`) of one decomposition with `args`."""
    tag = "-".join(a.lstrip("-") for a in args) or "default"
    out = CACHE / "ours" / f"{mesh.name}-{tag}.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    cmd = [binary, "decompose", str(mesh), "-o", str(out), "--quiet"] + args
    best = float("inf")
    for _ in range(runs):
        t = time.perf_counter()
        subprocess.run(cmd, check=True)
        best = min(best, time.perf_counter() - t)
    return out, best


def distances(binary, mesh, colliders):
    """`primdecomp eval` of every collider: [(hausdorff, chamfer)], in order."""
    out = CACHE / "eval" / f"{mesh.name}.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    cmd = [binary, "eval", "--input", str(mesh), "--json", str(out)] + [str(c) for c in colliders]
    subprocess.run(cmd, check=True, capture_output=True)
    rep = json.loads(out.read_text())
    return [(c["hausdorff"], c["chamfer"]) for c in rep["colliders"]]


def simulate(binary, mesh, colliders, shots, ccd):
    out = CACHE / "sim" / f"{mesh.name}-{'ccd' if ccd else 'discrete'}.json"
    out.parent.mkdir(parents=True, exist_ok=True)
    cmd = [binary, "sim", "--scenario", "projectiles", "--input", str(mesh), "--shots", str(shots),
           "--json", str(out), "--quiet"] + [str(c) for c in colliders] + (["--ccd"] if ccd else [])
    subprocess.run(cmd, check=True)
    return json.loads(out.read_text())


def rows(mesh, report, names):
    n = report["shots"]
    for c, name in zip(report["colliders"], names):
        yield [mesh, name, str(c["shapes"])] + [f"{t['passed'] / n:.3f}" for t in c["tallies"]]


def table(header, body):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * 2 + "---:|" * (len(header) - 2)]
    return "\n".join(lines + ["| " + " | ".join(r) + " |" for r in body])


def summary(per_mesh, names, dist=None, times=None):
    """Per collider and speed: mean pass-through over the meshes every collider ran
    on; with `dist` also their mean Hausdorff and Chamfer, with `times` ours' summed
    time over the default's."""
    keep = [i for i, m in enumerate(per_mesh) if all(x is not None for x in m)]
    out = []
    for k, name in enumerate(names):
        vals = [[per_mesh[i][k][s] for i in keep] for s in range(len(SPEEDS))]
        row = [name, str(len(keep))] + [f"{sum(v) / len(v):.3f}" if v else "-" for v in vals]
        if dist is not None:
            d = [dist[i][k] for i in keep if dist[i][k] is not None]
            row += [f"{sum(x[j] for x in d) / len(d):.4f}" if d else "-" for j in (0, 1)]
        if times is not None:
            t = [times[i] for i in keep]
            ok = name in t[0] if t else False
            row.append(f"{sum(x[name] for x in t) / sum(x['ours'] for x in t):.2f}" if ok else "-")
        out.append(row)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--meshes", nargs="*", default=DEFAULT_MESHES)
    ap.add_argument("--shots", type=int, default=256)
    ap.add_argument("--run-peers", action="store_true")
    ap.add_argument("--bin", default=str(ROOT / "target/release/primdecomp"))
    ap.add_argument("--out", default=str(ROOT / "docs/results/projectiles.md"))
    ap.add_argument("--runs", type=int, default=3)
    a = ap.parse_args()
    ours_names = [label for label, _ in VARIANTS]
    names = ["input mesh"] + ours_names + [label for _, label in PEERS]
    speeds = None
    sections = {}
    fractions = {False: [], True: []}
    dist, dist_rows, times, timing = [], [], [], []
    for name in a.meshes:
        mesh = CORPUS / name
        made = [ours(a.bin, mesh, label, args, a.runs) for label, args in VARIANTS]
        t0 = made[0][1]
        times.append({label: t for (label, _), (_, t) in zip(VARIANTS, made)})
        timing.append([name] + [f"{t:.3f}" for _, t in made] + [f"{t / t0:.2f}" for _, t in made[1:]])
        peers = [peer_obj(mesh, m, a.run_peers) for m, _ in PEERS]
        cols = [out for out, _ in made] + [p for p in peers if p is not None]
        have = ["input mesh"] + ours_names + [l for (_, l), p in zip(PEERS, peers) if p]
        for ccd in (False, True):
            rep = simulate(a.bin, mesh, cols, a.shots, ccd)
            speeds = rep["speeds"]
            sections.setdefault(ccd, []).extend(rows(name, rep, have))
            n = rep["shots"]
            by = {l: [t["passed"] / n for t in c["tallies"]] for l, c in zip(have, rep["colliders"])}
            fractions[ccd].append([by.get(l) for l in names])
        got = dict(zip(have[1:], distances(a.bin, mesh, cols)))
        dist.append([None] + [got.get(l) for l in names[1:]])
        dist_rows += [[name, l, f"{h:.4f}", f"{c:.5f}"] for l, (h, c) in got.items()]
        print(f"{name}: done", file=sys.stderr)
    head = ["mesh", "collider", "shapes"] + [f"{s['name']} ({s['diameters_per_frame']:g} d/f, "
                                             f"{s['metres_per_second']:g} m/s)" for s in speeds]
    shead = ["collider", "meshes"] + [s["name"] for s in speeds]
    cmd = "python3 benches/projectiles.py" + (" --shots %d" % a.shots if a.shots != 256 else "")
    dhead = shead + ["Hausdorff", "Chamfer", "time / default"]
    thead = ["mesh"] + ours_names + [f"{l} / default" for l in ours_names[1:]]
    text = f"""# Projectiles: pass-through of fast balls

{a.shots} shots per collider and speed (Fibonacci-sphere directions, each aimed at a
seeded area-sampled surface point), no gravity, fixed steps of 1/60 s, balls of radius
0.01 D in a scene scaled to D = 10 m (definitions: `crates/primdecomp-sim/src/projectiles.rs`).
A shot *passes* when its ball's centre crosses the input's surface (ray cast of every
frame's move) and ends inside the input's volume (winding number > 1/2) or past the
input's last triangle on its line. CCD off = plain discrete steps (Rapier 0.36's own
sweep of fast bodies against fixed colliders turned off, as in most engines' default);
CCD on = that sweep plus CCD on the balls. Fraction of the counted shots (lines that
meet the input). A ball that sinks into a solid part during a long step and is pushed
out through another face (near an edge or corner) counts too: that is why solid hulls
pass balls at 2 and 10 diameters per frame. Ours: `primdecomp decompose MESH` (default,
N = 64), with `--solid` and with `--min-thickness T` (plates thickened inward to T·D
where the part is closed behind them, docs/decisions/0033). Peers: pinned CoACD and
V-HACD with their defaults (benches/peers). Distances: `primdecomp eval` (200,000
samples, seed 0; Hausdorff and Chamfer from the collider's union surface to the input,
over D). Times: least of {a.runs} runs of `primdecomp decompose`, shared 2-core machine.
Regenerate with:

```sh
cargo build --release
bash benches/peers/venv.sh && {cmd} --run-peers
```

## Mean pass-through over the meshes every collider ran on, CCD off

With the mean distances over the same meshes and ours' summed decomposition time
over the default's.

{table(dhead, summary(fractions[False], names, dist, times))}

## Mean pass-through, CCD on

{table(shead, summary(fractions[True], names))}

## Per mesh, CCD off

{table(head, sections[False])}

## Per mesh, CCD on

{table(head, sections[True])}

## Distances to the input (`primdecomp eval`)

{table(["mesh", "collider", "Hausdorff", "Chamfer"], dist_rows)}

## Decomposition time, s (least of {a.runs} runs, shared machine)

{table(thead, timing)}
"""
    Path(a.out).write_text(text)
    print(f"wrote {a.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
