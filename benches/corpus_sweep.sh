#!/usr/bin/env bash
# benches/corpus_sweep.sh: settings or builds compared over the corpus.
# Every corpus mesh below 871k faces (all but dragon_vrip_full.ply) is decomposed at
# TARGET (default 1%) under each CONFIG, timed (/usr/bin/time user seconds), and
# evaluated with `primdecomp eval --samples 30000`; then benches/corpus_sweep_summary.py
# prints, per config against the first: meshes with identical primitives, mean and
# median Hausdorff, Chamfer and reverse Chamfer, meshes better / worse by more than
# 2%, the least enclosure, and summed user seconds over all meshes and the seven slowest.
#
# Usage: benches/corpus_sweep.sh OUT CONFIG... ; CONFIG is NAME=ARGS (extra decompose
# arguments, word-split, for target/release/primdecomp) or NAME@BINARY=ARGS (another
# build). Examples (docs/results/reprice.md, docs/decisions/0014-output-fits-turn-about-the-normal.md):
#   benches/corpus_sweep.sh OUT exact='--reprice exact' 64='--reprice 64' deferred='--reprice deferred'
#   benches/corpus_sweep.sh OUT before@/tmp/primdecomp-before= after=
# Environment: TARGET (default 1%), SAMPLES (default 30000). Resumable: a mesh whose
# OUT/NAME/<mesh>.eval.json exists is skipped.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
corpus="$root/../shared/datasets/corpus"
[[ -d "$corpus" ]] || { echo "CORPUS ABSENT: $corpus" >&2; exit 1; }
out="$1"; shift
target=${TARGET:-1%} samples=${SAMPLES:-30000}
for config in "$@"; do
    name=${config%%=*} args=${config#*=} bin="$root/target/release/primdecomp"
    [[ "$name" == *@* ]] && { bin=${name#*@}; name=${name%%@*}; }
    mkdir -p "$out/$name"
    printf '%s\n' "$bin $args" > "$out/$name/config"
    for mesh in "$corpus"/*; do
        m=$(basename "$mesh")
        case "$m" in CATALOG.tsv | README* | dragon_vrip_full.ply) continue ;; esac
        json="$out/$name/$m.json"
        [[ -f "$json.eval.json" ]] && continue
        # shellcheck disable=SC2086 # ARGS are meant to be word-split
        /usr/bin/time -f %U -o "$json.user" "$bin" decompose "$mesh" -n "$target" \
            -o "$json" --quiet $args || { echo "$name failed on $m" >&2; continue; }
        "$bin" eval --input "$mesh" "$json" --samples "$samples" --json "$json.eval.json" \
            > /dev/null || echo "eval failed on $m ($name)" >&2
    done
done
names=()
for config in "$@"; do name=${config%%=*}; names+=("${name%%@*}"); done
python3 "$root/benches/corpus_sweep_summary.py" "$out" "${names[@]}"
