#!/usr/bin/env bash
# benches/ab_quality.sh: A/B quality of two primdecomp binaries over the corpus.
# For every corpus mesh below 871k faces (all but dragon_vrip_full.ply): decompose with
# both binaries at the same target, evaluate both colliders in one `eval` run, then
# print mean/median Hausdorff, Chamfer, reverse Chamfer and enclosure, and how many
# meshes got better/worse by more than 2% (benches/ab_quality_summary.py).
#
# Usage: benches/ab_quality.sh OUTDIR BIN_A BIN_B [TARGET=1%] [SAMPLES=30000]
# Resumable: meshes whose OUTDIR/<mesh>.eval.json exists are skipped.
set -euo pipefail
out=$1 a=$2 b=$3 target=${4:-1%} samples=${5:-30000}
corpus="$(cd "$(dirname "$0")/../.." && pwd)/shared/datasets/corpus"
[ -d "$corpus" ] || { echo "CORPUS ABSENT: $corpus" >&2; exit 1; }
mkdir -p "$out"
for f in "$corpus"/*; do
  m=$(basename "$f")
  case "$m" in CATALOG.tsv | README* | dragon_vrip_full.ply) continue ;; esac
  [ -f "$out/$m.eval.json" ] && continue
  "$a" decompose "$f" -n "$target" -o "$out/$m.a.json" --quiet || { echo "A failed on $m" >&2; continue; }
  "$b" decompose "$f" -n "$target" -o "$out/$m.b.json" --quiet || { echo "B failed on $m" >&2; continue; }
  "$a" eval --input "$f" "$out/$m.a.json" "$out/$m.b.json" --samples "$samples" \
    --json "$out/$m.eval.json" > /dev/null || echo "eval failed on $m" >&2
done
python3 "$(dirname "$0")/ab_quality_summary.py" "$out"
