#!/usr/bin/env bash
# benches/cut_sweep.sh: the greedy snapshot against the merge-tree cut (--cut,
# docs/decisions/0032) on a list of corpus meshes at TARGET (default 1%): each
# decomposed both ways, timed (/usr/bin/time user seconds), evaluated with
# `primdecomp eval --samples SAMPLES` (default 30000); prints a markdown table.
# Usage: benches/cut_sweep.sh OUT MESH... (names in the corpus). Resumable.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
corpus="$root/../shared/datasets/corpus"
[[ -d "$corpus" ]] || { echo "CORPUS ABSENT: $corpus" >&2; exit 1; }
out="$1"; shift
target=${TARGET:-1%} samples=${SAMPLES:-30000} bin="${BIN:-$root/target/release/primdecomp}"
mkdir -p "$out"
for m in "$@"; do
    for mode in greedy cut; do
        json="$out/$m.$mode.json"
        [[ -f "$json.eval.json" ]] && continue
        args=(); [[ $mode == cut ]] && args=(--cut)
        /usr/bin/time -f %U -o "$json.user" "$bin" decompose "$corpus/$m" -n "$target" \
            -o "$json" --quiet "${args[@]}"
        "$bin" eval --input "$corpus/$m" "$json" --samples "$samples" --json "$json.eval.json" > /dev/null
    done
done
python3 - "$out" "$@" <<'PY'
import json, sys
out, meshes = sys.argv[1], sys.argv[2:]
def get(m, mode):
    e = json.load(open(f"{out}/{m}.{mode}.json.eval.json"))
    e = e["colliders"][0]
    e["parts"] = sum(e["counts"].values())
    return e, float(open(f"{out}/{m}.{mode}.json.user").read())
print("| mesh | parts greedy | parts cut | Hausdorff greedy | Hausdorff cut | Chamfer greedy | Chamfer cut | user s greedy | user s cut |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
for m in meshes:
    (g, tg), (c, tc) = get(m, "greedy"), get(m, "cut")
    print(f"| {m} | {g['parts']} | {c['parts']} | {g['hausdorff']:.4f} | {c['hausdorff']:.4f} | "
          f"{g['chamfer']:.5f} | {c['chamfer']:.5f} | {tg:.2f} | {tc:.2f} |")
PY
