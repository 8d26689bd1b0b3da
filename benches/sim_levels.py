#!/usr/bin/env python3
"""benches/sim_levels: our collider at a ladder of shape counts against CoACD, V-HACD
and the mesh itself, all in one `primdecomp sim` run per mesh and seed
-> docs/results/sim_levels.md. It answers the simulation benchmark's question for the meshes where
docs/results/sim.md leaves ours slower than a peer: is there a shape count at which
our physics step is no slower than the peer's with a similarity no lower, and how do
step time and behaviour move with the count (the speed/fidelity trade a user picks N by)?

Levels: N = the byte rule's target as benches/sim_compare.py chooses it (the most
primitives whose bytes stay within a third of CoACD's), then N/2, N/4, ... while N is
at least half the smaller peer's hull count, plus each peer's own hull count; all from
one default multi-target pass (`primdecomp decompose MESH -n a,b,c`, no `--fill`, so a
level may hold fewer primitives than its N). Simulation reports are cached under
benches/.cache/sim_levels by the mesh, the settings and a hash of every level's
primitives. Standard library only.

Usage:
  python3 benches/sim_levels.py [--meshes NAME ...] [--seeds 0 1] [--balls 2000]
      [--frames 600] [--bin target/release/primdecomp] [--out docs/results/sim_levels.md]
"""

import argparse
import hashlib
import json
import subprocess
import sys
import time
from pathlib import Path

import sim_compare as sc
from compare_lib.peers import sha256_file  # the peer cache's own key (standard library only)

ROOT, CORPUS, CACHE = sc.ROOT, sc.CORPUS, sc.CACHE / "sim_levels"
# The meshes sim.md left ours slower on than a peer beyond the mesh's own spread, and two more.
DEFAULT_MESHES = [
    "truck_shrec.obj",
    "cesium_milk_truck.glb",
    "parry_poly_cylinder.obj",
    "tiny_7_8ths_cube.stl",
    "kenney_building_garage.glb",
    "kenney_building_small_a.glb",
    "kenney_pavement_fountain.glb",
]


def byte_target(mesh, sha, binary, work, caches):
    """N as benches/sim_compare.py's byte rule picks it (compare.json, else the rule
    against cached CoACD hulls, else max(32, 1% of faces)), and which rule gave it."""
    n = sc.compare_target(mesh.name)
    if n is not None:
        return n, "compare.json"
    n = sc.byte_rule_target(mesh, sha, binary, work, caches)
    if n is not None:
        return n, "bytes within a third of cached CoACD's"
    return max(32, round(sc.faces_of(mesh, binary, work) / 100)), "max(32, 1% of faces)"


def ladder(top, peer_counts):
    """top, top/2, top/4, ... while at least half the smaller peer count (or 1), plus
    the peers' own counts; largest first."""
    floor = max(1, min(peer_counts) // 2) if peer_counts else 1
    out, n = set(peer_counts), top
    while n >= floor:
        out.add(n)
        n //= 2
    return sorted(out, reverse=True)


def decompose(binary, mesh, levels, work):
    """One multi-target pass; {N: path of its level} and a hash of all primitives."""
    for old in work.glob("levels_n*.json"):
        old.unlink()
    out = work / "levels.json"
    subprocess.run([binary, "decompose", str(mesh), "-n", ",".join(map(str, levels)), "-o", str(out), "--quiet"],
                   check=True)
    paths = {n: work / f"levels_n{n}.json" for n in levels}
    if len(levels) == 1:
        out.replace(paths[levels[0]])
    h = hashlib.sha256()
    for n in levels:
        h.update(json.dumps(json.loads(paths[n].read_text())["primitives"], sort_keys=True).encode())
    return paths, h.hexdigest()[:12]


def simulate(binary, mesh, colliders, report, a, seed):
    if not report.is_file() or a.rerun:
        cmd = [binary, "sim", "--input", str(mesh), *map(str, colliders), "--balls", str(a.balls),
               "--frames", str(a.frames), "--seed", str(seed), "--json", str(report), "--quiet"]
        print("+", " ".join(cmd), file=sys.stderr, flush=True)
        subprocess.run(cmd, check=True)
    return json.loads(report.read_text())


def run_mesh(name, a):
    """{name, rule, top, rows: [{label, n, shapes, step[seed], sim[seed], set[seed], on[seed]}],
    mesh/self/peers likewise} for one mesh, or None when the mesh or both peers are absent."""
    mesh = CORPUS / name if not Path(name).is_file() else Path(name)
    if not mesh.is_file():
        print(f"CORPUS ABSENT or no such mesh: {mesh}", file=sys.stderr)
        return None
    sha = sha256_file(mesh)
    work = CACHE / sha[:16]
    work.mkdir(parents=True, exist_ok=True)
    peers = {p: sc.peer_obj(a.peer_cache, sha, p)[0] for p in sc.PEERS}
    peers = {p: o for p, o in peers.items() if o is not None}
    if not peers:
        print(f"no cached peer hulls for {name}: skipped", file=sys.stderr)
        return None
    counts = {p: sc.hull_count(o) for p, o in peers.items()}
    top, rule = byte_target(mesh, sha, a.bin, sc.CACHE / "sim" / sha[:16], a.peer_cache)
    levels = ladder(top, sorted(set(counts.values())))
    paths, key = decompose(a.bin, mesh, levels, work)
    colliders = [paths[n] for n in levels] + list(peers.values())
    reps = [simulate(a.bin, mesh, colliders, work / f"sim_b{a.balls}_f{a.frames}_s{s}_{key}.json", a, s)
            for s in a.seeds]
    def entry(label, n, pick):
        cs = [pick(r) for r in reps]
        return {"label": label, "n": n, "shapes": cs[0]["shapes"],
                "step": [c["frame_ms_median"] for c in cs], "sim": [c["similarity"] for c in cs],
                "set": [c["similarity_set"] for c in cs], "on": [c["on_object"] for c in cs]}
    by_path = lambda path: lambda r: next(c for c in r["colliders"] if c["collider"] == str(path))  # noqa: E731
    rows = [entry("ours", n, by_path(paths[n])) for n in levels]
    out = {"name": name, "rule": rule, "top": top, "rows": rows,
           "mesh": entry("mesh", None, lambda r: r["colliders"][0]),
           "self": entry("mesh vs itself", None, lambda r: next(c for c in r["colliders"] if c["kind"] == "mesh_perturbed")),
           "peers": {p: entry(sc.LABEL[p], counts[p], by_path(o)) for p, o in peers.items()}}
    return out


def mean(xs):
    return sum(xs) / len(xs)


def ratios(a, b):
    return [x / y for x, y in zip(a, b)]


def meets(row, peer):
    """On every seed: step no slower than the peer's, similarity no lower."""
    return all(s <= t for s, t in zip(row["step"], peer["step"])) and all(
        s >= t for s, t in zip(row["sim"], peer["sim"]))


def table(m, a):
    peers = list(m["peers"])
    head = ["collider", "N", "shapes", "median step ms"] + ["/ mesh"] + [f"/ {sc.LABEL[p]}" for p in peers]
    head += ["similarity", "set", "on object"] + [f"meets vs {sc.LABEL[p]}" for p in peers]
    lines = [f"## {m['name']}", "",
             f"Byte rule N = {m['top']} ({m['rule']}). Step ratios per seed ({', '.join(map(str, a.seeds))}); "
             f"similarity, set and on object as the mean over the seeds. Noise floor: the mesh against "
             f"itself scores similarity {mean(m['self']['sim']):.3f}, set {mean(m['self']['set']):.3f}, "
             f"and its median step moves by {', '.join(f'{abs(r - 1):.3f}' for r in ratios(m['self']['step'], m['mesh']['step']))} "
             f"between the two runs.", "",
             "| " + " | ".join(head) + " |", "|---|" + "---:|" * (len(head) - 1)]
    def cells(r, mark):
        c = [r["label"], "-" if r["n"] is None else str(r["n"]), str(r["shapes"]),
             ", ".join(f"{x:.2f}" for x in r["step"]),
             ", ".join(f"{x:.2f}" for x in ratios(r["step"], m["mesh"]["step"]))]
        c += [", ".join(f"{x:.2f}" for x in ratios(r["step"], m["peers"][p]["step"])) for p in peers]
        c += [f"{mean(r['sim']):.3f}", f"{mean(r['set']):.3f}", f"{mean(r['on']):.3f}"]
        c += [("✓" if meets(r, m["peers"][p]) else "") if mark else "" for p in peers]
        return "| " + " | ".join(c) + " |"
    lines += [cells(r, True) for r in m["rows"]]
    lines += [cells(m["peers"][p], False) for p in peers] + [cells(m["mesh"], False), ""]
    return lines


def summary(ms):
    out = []
    for p in sc.PEERS:
        have = [m for m in ms if p in m["peers"]]
        ok = [m for m in have if any(meets(r, m["peers"][p]) for r in m["rows"])]
        at_top = [m for m in have if meets(m["rows"][[r["n"] for r in m["rows"]].index(m["top"])], m["peers"][p])]
        out.append(f"- vs {sc.LABEL[p]} on {len(have)} meshes: some level meets both (step ≤, similarity ≥ "
                   f"on every seed) on {len(ok)} ({', '.join(m['name'] for m in ok) or 'none'}); "
                   f"the byte rule's level on {len(at_top)}.")
    return out


def main(argv):
    ap = argparse.ArgumentParser(prog="benches/sim_levels.py", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--meshes", nargs="*", default=DEFAULT_MESHES)
    ap.add_argument("--seeds", nargs="*", type=int, default=[0, 1])
    ap.add_argument("--balls", type=int, default=2000)
    ap.add_argument("--frames", type=int, default=600)
    ap.add_argument("--peer-cache", nargs="*", default=[str(sc.CACHE / "peers")])
    ap.add_argument("--bin", default=str(ROOT / "target" / "release" / "primdecomp"))
    ap.add_argument("--out", default=str(ROOT / "docs" / "results" / "sim_levels.md"))
    ap.add_argument("--rerun", action="store_true", help="simulate again even when a report is cached")
    a = ap.parse_args(argv)
    if not CORPUS.is_dir():
        print(f"CORPUS ABSENT: {CORPUS} (../shared/datasets/corpus beside the repository)", file=sys.stderr)
        return 2
    t0 = time.time()
    ms = [m for m in (run_mesh(n, a) for n in a.meshes) if m]
    if not ms:
        print("no mesh could be run", file=sys.stderr)
        return 1
    head = ["# Simulation at a ladder of shape counts", "",
            f"{a.balls} balls, {a.frames} frames at 1/60 s, seeds {', '.join(map(str, a.seeds))}, Rapier "
            "single-threaded; per mesh and seed one `primdecomp sim` run holds every level, both peers' "
            "hulls and the mesh (and its perturbed copy), interleaved frame by frame, so the ratios hold "
            "on a noisy machine. Levels: the byte rule's N (as in sim.md), halved down to half the "
            "smaller peer hull count, and each peer's count, from one default multi-target pass "
            "(`primdecomp decompose MESH -n a,b,c`; no `--fill`, so a level can hold fewer shapes than "
            "its N). ✓ = on every seed ours steps no slower than the peer and scores a similarity no "
            "lower (definitions: `src/sim/mod.rs`, sim.md). Regenerate with:", "",
            "```sh", "cargo build --release",
            f"python3 benches/sim_levels.py --seeds {' '.join(map(str, a.seeds))} --balls {a.balls} --frames {a.frames}",
            "```", "", *summary(ms), "",
            f"Generated in {(time.time() - t0) / 60:.1f} min (cached reports are reused).", ""]
    body = [line for m in ms for line in table(m, a)]
    out = Path(a.out)
    tmp = out.with_suffix(".md.tmp")
    tmp.write_text("\n".join(head + body).rstrip("\n") + "\n")
    tmp.replace(out)
    print(f"wrote {out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
