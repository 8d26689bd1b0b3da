#!/usr/bin/env python3
"""benches/count_modes.py: what `-n N` gives on multi-part meshes, run by run.

For each mesh and each count N, runs every MODE (a name and the extra `decompose`
arguments, e.g. greedy= cut=--cut fill=--fill; NAME@BIN=ARGS runs another binary), then `primdecomp eval` on the result (the sampled one-way
Hausdorff and Chamfer over the diagonal), and prints a markdown table: primitives,
Hausdorff, Chamfer and user seconds per mode. `--json OUT` keeps every row.

    python3 benches/count_modes.py --targets 8,32,128 --mode greedy= --mode cut=--cut \
        --multi-part            # every corpus mesh of more than one component
    python3 benches/count_modes.py --mesh /tmp/inputs/cabinet.obj --mode auto=

Meshes: --mesh PATH (repeatable), or --multi-part for the corpus's meshes with more
than one connected component (CATALOG.tsv), the largest left out with --max-faces.

`--summary ROWS.json` reads what --json wrote and says, per mode, how many levels are
short of their count (fewer than min(N, faces) less max(2, N/32) primitives while the
Hausdorff is above 0.003, so distance was left to gain) and on how many meshes the
Hausdorff does not fall as N grows (a level's above 1.05 times the previous one's plus
0.001), listing them.
"""
import argparse
import csv
import json
import os
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DATASETS = ROOT.parent / "shared" / "datasets"


def multi_part(max_faces):
    cat = DATASETS / "CATALOG.tsv"
    if not cat.exists():
        sys.exit(f"CORPUS ABSENT: {cat}")
    rows = list(csv.DictReader(cat.open(), delimiter="\t"))
    return [DATASETS / "corpus" / r["name"] for r in rows
            if int(r["components"]) > 1 and int(r["triangles"]) <= max_faces]


def user_seconds(cmd):
    with tempfile.NamedTemporaryFile() as t:
        r = subprocess.run(["/usr/bin/time", "-f", "%U", "-o", t.name, *map(str, cmd)],
                           capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError(f"{' '.join(map(str, cmd))}: {r.stderr.strip()}")
        return float(Path(t.name).read_text().split()[-1])


FLOOR = 0.003


def summary(path):
    rows = json.loads(Path(path).read_text())
    modes = [k for k in rows[0] if isinstance(rows[0][k], dict)]
    meshes = sorted({r["mesh"] for r in rows})
    print(f"{len(meshes)} meshes, {len(rows)} levels")
    for mode in modes:
        short = [(r["mesh"], r["n"], r[mode]["primitives"]) for r in rows
                 if r[mode]["primitives"] + max(2, min(r["n"], r["faces"]) // 32) < min(r["n"], r["faces"])
                 and r[mode]["hausdorff"] > FLOOR]
        rising = []
        for m in meshes:
            hs = [r[mode]["hausdorff"] for r in sorted((r for r in rows if r["mesh"] == m), key=lambda r: r["n"])]
            if any(b > 1.05 * a + 0.001 for a, b in zip(hs, hs[1:])):
                rising.append((m, [round(h, 4) for h in hs]))
        secs = sum(r[mode]["seconds"] for r in rows)
        mean_h = sum(r[mode]["hausdorff"] for r in rows) / len(rows)
        print(f"- {mode}: {len(short)} levels short, Hausdorff not falling on {len(rising)} meshes, "
              f"mean Hausdorff {mean_h:.4f}, {secs:.1f} user s in all")
        for m, n, p in short:
            print(f"  short: {m} -n {n}: {p}")
        for m, hs in rising:
            print(f"  not falling: {m} {hs}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--mesh", action="append", default=[])
    ap.add_argument("--multi-part", action="store_true")
    ap.add_argument("--max-faces", type=int, default=10**9)
    ap.add_argument("--targets", default="8,32,128")
    ap.add_argument("--mode", action="append", default=[], help="NAME=ARGS, or NAME@BIN=ARGS for another binary")
    ap.add_argument("--bin", default=str(ROOT / "target" / "release" / "primdecomp"))
    ap.add_argument("--samples", type=int, default=20000)
    ap.add_argument("--json")
    ap.add_argument("--summary", metavar="ROWS.json")
    a = ap.parse_args()
    if a.summary:
        return summary(a.summary)
    meshes = [Path(m) for m in a.mesh] + (multi_part(a.max_faces) if a.multi_part else [])
    modes = []
    for m in a.mode or ["greedy="]:
        name, _, rest = m.partition("=")
        name, _, binary = name.partition("@")
        modes.append((name, binary or a.bin, shlex.split(rest)))
    targets = [int(t) for t in a.targets.split(",")]
    rows = []
    head = "| mesh | faces | N | " + " | ".join(f"{n} prims | {n} Hausdorff | {n} Chamfer | {n} s" for n, _, _ in modes) + " |"
    print(head)
    print("|---|---:|---:|" + "---:|" * (4 * len(modes)))
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for mesh in meshes:
            for n in targets:
                cells, row = [], {"mesh": mesh.name, "n": n}
                outs = []
                for name, binary, extra in modes:
                    out = tmp / f"{name}.json"
                    secs = user_seconds([binary, "decompose", mesh, "-n", n, *extra, "-q", "-o", out])
                    doc = json.loads(out.read_text())
                    row["faces"] = doc["input"]["faces"]
                    row[name] = {"primitives": doc["stats"]["primitives"], "seconds": secs}
                    outs.append((name, out))
                ev = tmp / "eval.json"
                subprocess.run([a.bin, "eval", "--input", mesh, *[o for _, o in outs],
                                "--samples", str(a.samples), "--json", ev],
                               check=True, capture_output=True)
                for (name, _), c in zip(outs, json.loads(ev.read_text())["colliders"]):
                    row[name].update(hausdorff=c["hausdorff"], chamfer=c["chamfer"])
                    r = row[name]
                    cells.append(f"{r['primitives']} | {r['hausdorff']:.4f} | {r['chamfer']:.2e} | {r['seconds']:.2f}")
                rows.append(row)
                print(f"| {mesh.name} | {row['faces']} | {n} | " + " | ".join(cells) + " |", flush=True)
    if a.json:
        Path(a.json).write_text(json.dumps(rows, indent=1) + "\n")


if __name__ == "__main__":
    main()
