#!/usr/bin/env bash
# ab_time.sh BEFORE AFTER [ROUNDS]: user seconds of two primdecomp binaries, run
# alternately in one session (so both see the same machine load): the dragon at
# -n 2000 and the whole corpus at -n 10%, one thread each. Prints one line per run.
set -euo pipefail
before=$1 after=$2 rounds=${3:-3}
corpus="$(cd "$(dirname "$0")/.." && pwd)/../shared/datasets/corpus"
[ -d "$corpus" ] || { echo "corpus absent: $corpus" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for r in $(seq "$rounds"); do
  for w in before after; do
    bin=$before; [ "$w" = after ] && bin=$after
    /usr/bin/time -f "$w dragon round$r user %U real %e" "$bin" decompose "$corpus/dragon_vrip_full.ply" \
      -n 2000 -o "$out/$w.json" --quiet --threads 1
    /usr/bin/time -f "$w corpus10 round$r user %U real %e" "$bin" decompose "$corpus"/* \
      -n 10% -o "$out/$w-10/" --quiet --threads 1 --jobs 1
  done
done
