#!/usr/bin/env bash
# benches/default_compare.sh: the default tolerance against a fixed count
# (docs/decisions/0037). Reads the level files of a benches/tolerance_check.sh run
# (TOL_DIR, run with TOLS="4%,2%,1%,0.5%" SAMPLES=200000), runs
# `decompose -n COUNT` (default 64) and `eval --samples SAMPLES` (default 200000) on
# the same meshes into N_DIR, and prints a markdown summary (primitives, eval
# Hausdorff and Chamfer over the diagonal, bytes) and one row per mesh.
# Usage: benches/default_compare.sh TOL_DIR N_DIR   Env: BIN, COUNT, SAMPLES.
# Resumable: a mesh whose eval file is in N_DIR is not run again.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
corpus="$root/../shared/datasets/corpus"
[[ -d "$corpus" ]] || { echo "CORPUS ABSENT: $corpus" >&2; exit 1; }
[[ $# -eq 2 ]] || { echo "usage: $0 TOL_DIR N_DIR" >&2; exit 2; }
tol="$1" out="$2"
bin="${BIN:-$root/target/release/primdecomp}" count="${COUNT:-64}" samples="${SAMPLES:-200000}"
mkdir -p "$out"
for u in "$tol"/*.user; do
    m="$(basename "$u" .user)"
    [[ -f "$out/$m.json.eval.json" ]] && continue
    echo "$(date -u +%T) $m" >&2
    /usr/bin/time -f %U -o "$out/$m.user" "$bin" decompose "$corpus/$m" -n "$count" \
        -o "$out/$m.json" --quiet
    "$bin" eval --input "$corpus/$m" "$out/$m.json" --samples "$samples" \
        --json "$out/$m.json.eval.json" > /dev/null
done
python3 - "$tol" "$out" "$count" <<'PY'
import glob, json, os, statistics, sys
tol, out, count = sys.argv[1:]
rows = []
for f in sorted(glob.glob(f"{out}/*.json.eval.json")):
    m = os.path.basename(f)[: -len(".json.eval.json")]
    def level(doc, ev):
        e = json.load(open(ev))["colliders"][0]
        s = json.load(open(doc))["stats"]
        d = s.get("distance") or {}
        met = "yes" if d.get("worst", 0) <= d.get("tolerance", float("inf")) else "no"
        return (s["primitives"], e["hausdorff"], e["chamfer"], s["bytes"], met)
    r = {"m": m, "n": level(f"{out}/{m}.json", f)}
    for lab in ("t4pct", "t2pct", "t1pct"):
        r[lab] = level(f"{tol}/{m}_{lab}.json", f"{tol}/{m}_{lab}.json.eval.json")
    rows.append(r)
names = {"n": f"-n {count}", "t4pct": "--tolerance 4%", "t2pct": "--tolerance 2% (default)", "t1pct": "--tolerance 1%"}
print(f"{len(rows)} meshes\n")
print("| run | median primitives | mean | max | median H | mean H | median Chamfer | mean Chamfer | median bytes | H below -n by >5% | above by >5% |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for k in ("n", "t4pct", "t2pct", "t1pct"):
    col = lambda i: [r[k][i] for r in rows]
    n, h, c, b = col(0), col(1), col(2), col(3)
    better = sum(r[k][1] < 0.95 * r["n"][1] for r in rows)
    worse = sum(r[k][1] > 1.05 * r["n"][1] for r in rows)
    print(f"| {names[k]} | {statistics.median(n):.0f} | {sum(n)/len(n):.1f} | {max(n)} | "
          f"{statistics.median(h):.4f} | {sum(h)/len(h):.4f} | {statistics.median(c):.2e} | "
          f"{sum(c)/len(c):.2e} | {statistics.median(b):.0f} | {better} | {worse} |")
print()
print(f"| mesh | -n {count}: primitives | H | Chamfer | 4%: primitives | H | 2%: primitives | H | Chamfer | 2% met (JSON) | 1%: primitives | H |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|")
for r in rows:
    n, a, b, c = r["n"], r["t4pct"], r["t2pct"], r["t1pct"]
    print(f"| {r['m']} | {n[0]} | {n[1]:.4f} | {n[2]:.2e} | {a[0]} | {a[1]:.4f} | {b[0]} | "
          f"{b[1]:.4f} | {b[2]:.2e} | {b[4]} | {c[0]} | {c[1]:.4f} |")
PY
