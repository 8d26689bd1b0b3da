#!/usr/bin/env bash
# benches/same_output.sh: do two builds give the same primitives? Per corpus mesh, runs
# `decompose MESH ARGS -o DIR/o.json --quiet` with OLD and with NEW (user and wall
# seconds of each), then compares every level file field by field: the primitive
# count, whether the primitives are bit for bit the same, the largest difference of
# any parameter over the diagonal, and each build's declared distance and what
# limited it (`stats.distance`).
# Usage: OLD=/path/old NEW=/path/new [ARGS="--tolerance 2%,1%"] benches/same_output.sh MESH...
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
corpus="$root/../shared/datasets/corpus"
[[ -d "$corpus" ]] || { echo "CORPUS ABSENT: $corpus" >&2; exit 1; }
[[ -x "${OLD:-}" && -x "${NEW:-}" ]] || { echo "set OLD and NEW to two binaries" >&2; exit 2; }
read -ra args <<< "${ARGS:-}"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
for m in "$@"; do
    rm -rf "$tmp/a" "$tmp/b"; mkdir -p "$tmp/a" "$tmp/b"
    /usr/bin/time -f "%U %e" -o "$tmp/ta" "$OLD" decompose "$corpus/$m" "${args[@]}" -o "$tmp/a/o.json" --quiet
    /usr/bin/time -f "%U %e" -o "$tmp/tb" "$NEW" decompose "$corpus/$m" "${args[@]}" -o "$tmp/b/o.json" --quiet
    python3 - "$m" "$(cat "$tmp/ta")" "$(cat "$tmp/tb")" "$tmp" <<'PY'
import json, os, sys
mesh, ta, tb, tmp = sys.argv[1:5]
def numbers(x):
    if isinstance(x, dict):
        return [v for k in sorted(x) for v in numbers(x[k])]
    if isinstance(x, list):
        return [v for e in x for v in numbers(e)]
    return [x] if isinstance(x, (int, float)) and not isinstance(x, bool) else []
for f in sorted(os.listdir(f"{tmp}/a")):
    a, b = (json.load(open(f"{tmp}/{d}/{f}")) for d in "ab")
    lo, hi = a["input"]["aabb_min"], a["input"]["aabb_max"]
    diag = sum((p - q) ** 2 for p, q in zip(lo, hi)) ** 0.5
    pa, pb = a["primitives"], b["primitives"]
    same_kinds = len(pa) == len(pb) and all(p["kind"] == q["kind"] for p, q in zip(pa, pb))
    dev = "-"
    if same_kinds:
        d = [abs(x - y) for x, y in zip(numbers(pa), numbers(pb))]
        dev = f"{max(d + [0.0]) / diag:.1e}"
    da, db = a["stats"].get("distance", {}), b["stats"].get("distance", {})
    dist = lambda d: f"{d.get('of_diagonal', float('nan')):.6f}"
    print(f"{mesh:30s} {f:15s} old {ta:11s} new {tb:11s} prims {len(pa)}/{len(pb)} "
          f"bitwise {pa == pb} maxdev/diag {dev} distance {dist(da)} {dist(db)} "
          f"limited {da.get('limited_by')} {db.get('limited_by')}")
PY
done
