#!/usr/bin/env bash
# Corpus sweep of `--reprice` settings (docs/results/reprice.md): every corpus mesh below
# 871k faces (all but dragon_vrip_full.ply) at `-n 1%`, one run per mode, then
# `primdecomp eval --samples 30000`. Writes OUT/MODE.tsv (mesh, user seconds of the
# decompose run, Hausdorff, Chamfer, primitives) and prints, per mode against the first:
# mean and median Hausdorff and Chamfer, meshes better / worse by more than 2%, summed
# user seconds over all meshes and over the seven slowest.
# Usage: benches/reprice_sweep.sh OUT exact 64 deferred
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
corpus="$root/../shared/datasets/corpus"
[[ -d "$corpus" ]] || { echo "CORPUS ABSENT: $corpus" >&2; exit 0; }
bin="$root/target/release/primdecomp"
out="$1"; shift
mkdir -p "$out"
for mode in "$@"; do
    : > "$out/$mode.tsv"
    for mesh in "$corpus"/*; do
        name="$(basename "$mesh")"
        [[ "$name" == dragon_vrip_full.ply ]] && continue
        json="$out/$mode.$name.json"
        /usr/bin/time -f %U -o "$out/time" "$bin" decompose "$mesh" -n 1% -o "$json" \
            --quiet --reprice "$mode"
        "$bin" eval --input "$mesh" "$json" --samples 30000 --json "$json.eval" >/dev/null
        python3 - "$json.eval" "$name" "$(tail -1 "$out/time")" >>"$out/$mode.tsv" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))["colliders"][0]
print(sys.argv[2], sys.argv[3], c["hausdorff"], c["chamfer"], sum(c["counts"].values()), sep="\t")
PY
    done
done
python3 - "$out" "$@" <<'PY'
import sys, statistics as st
out, modes = sys.argv[1], sys.argv[2:]
slow = ("samurai_monastery", "japanese_maple_tree", "engine_2cylinder", "happy_buddha_100k",
        "lucy_100k", "armadillo_libigl", "tank")
def load(mode):
    rows = (l.split("\t") for l in open(f"{out}/{mode}.tsv"))
    return {r[0]: tuple(map(float, r[1:4])) for r in rows}
base = load(modes[0])
for mode in modes:
    d = load(mode)
    ms = sorted(set(d) & set(base))
    h, c = [d[m][1] for m in ms], [d[m][2] for m in ms]
    def moved(k, sign):
        return sum(sign * (d[m][k] - base[m][k]) > 0.02 * base[m][k] for m in ms)
    user = sum(d[m][0] for m in ms) / sum(base[m][0] for m in ms)
    pick = [m for m in ms if m.startswith(slow)]
    user7 = sum(d[m][0] for m in pick) / sum(base[m][0] for m in pick)
    print(f"{mode}: {len(ms)} meshes; Hausdorff mean {st.mean(h):.4f} median {st.median(h):.4f}, "
          f"Chamfer mean {st.mean(c):.3e} median {st.median(c):.3e}; "
          f"Hausdorff better/worse by >2%: {moved(1, -1)}/{moved(1, 1)}, "
          f"Chamfer {moved(2, -1)}/{moved(2, 1)}; user x{user:.3f}, slowest seven x{user7:.3f}")
PY
