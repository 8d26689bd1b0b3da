#!/usr/bin/env bash
# Sampling error of `primdecomp eval`: evaluates a primitive collider (JSON) and its
# conservative tessellation as hulls (OBJ) on three corpus meshes with seeds 0-9 at
# a given sample count, and prints, per metric, the mean and the spread (max - min)
# over the seeds, relative to the mean. Usage: benches/eval_spread.sh [SAMPLES]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
corpus="$root/../shared/datasets/corpus"
[[ -d "$corpus" ]] || { echo "CORPUS ABSENT: $corpus" >&2; exit 0; }
bin="$root/target/release/primdecomp"
samples="${1:-200000}"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
for mesh in cad_plate_holes.STL spot.obj kenney_building_small_a.glb; do
    stem="${mesh%.*}"
    "$bin" decompose "$corpus/$mesh" -n 32 -o "$tmp/$stem.json" --obj "$tmp/$stem.obj" --quiet
    for seed in 0 1 2 3 4 5 6 7 8 9; do
        "$bin" eval --input "$corpus/$mesh" "$tmp/$stem.json" "$tmp/$stem.obj" \
            --samples "$samples" --seed "$seed" --json "$tmp/$stem.$seed.eval.json" >/dev/null
    done
done
python3 - "$tmp" "$samples" <<'PY'
import glob, json, sys, statistics as st
tmp, samples = sys.argv[1], sys.argv[2]
keys = ["hausdorff", "chamfer", "reverse_hausdorff", "reverse_chamfer", "enclosure"]
rows = {}
for f in sorted(glob.glob(f"{tmp}/*.eval.json")):
    d = json.load(open(f))
    for c in d["colliders"]:
        name = c["collider"].rsplit("/", 1)[-1]
        for k in keys:
            rows.setdefault((name, k), []).append(c[k])
print(f"samples per surface: {samples}, seeds 0-9")
print("| collider | metric | mean | spread (max-min) | spread / mean |")
print("|---|---|---:|---:|---:|")
worst = {}
for (name, k), v in sorted(rows.items()):
    m, s = st.mean(v), max(v) - min(v)
    rel = s / m if m else 0.0
    worst[k] = max(worst.get(k, 0.0), rel)
    print(f"| {name} | {k} | {m:.4e} | {s:.2e} | {rel:.2%} |")
print()
print("worst relative spread per metric: " + ", ".join(f"{k} {v:.2%}" for k, v in worst.items()))
PY
