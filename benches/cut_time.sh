#!/usr/bin/env bash
# benches/cut_time.sh: user seconds of the greedy pass and of the merge-tree cut
# (--cut) at TARGET (default 1%) on a list of corpus meshes, with one binary or two
# (BIN, and BIN_OLD for the cut of an older build), alternating runs, ROUNDS rounds
# (default 1) each keeping the least; prints a markdown table with the ratios.
# GREEDY and CUT replace the two runs' arguments (default "-n TARGET" and
# "-n TARGET --cut"), e.g. GREEDY="-n 64" CUT="" for the default run against -n 64.
# Usage: BIN_OLD=/path/old benches/cut_time.sh MESH... (names in the corpus).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
corpus="$root/../shared/datasets/corpus"
[[ -d "$corpus" ]] || { echo "CORPUS ABSENT: $corpus" >&2; exit 1; }
target=${TARGET:-1%} rounds=${ROUNDS:-1} bin="${BIN:-$root/target/release/primdecomp}"
old="${BIN_OLD:-}"
read -ra greedy <<< "${GREEDY-"-n $target"}"
read -ra cut <<< "${CUT-"-n $target --cut"}"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
user() { /usr/bin/time -f %U -o "$tmp/u" "$@" >/dev/null 2>&1; cat "$tmp/u"; }
least() { python3 -c "import sys; print(min(float(x) for x in sys.argv[1:]))" "$@"; }
if [[ -n "$old" ]]; then
    echo "| mesh | greedy s | cut s (old) | cut s | cut / greedy (old) | cut / greedy |"
    echo "|---|---:|---:|---:|---:|---:|"
else
    echo "| mesh | greedy s | cut s | cut / greedy |"
    echo "|---|---:|---:|---:|"
fi
for m in "$@"; do
    g=() c=() o=()
    for _ in $(seq "$rounds"); do
        g+=("$(user "$bin" decompose "$corpus/$m" ${greedy[@]+"${greedy[@]}"} -q -o "$tmp/g.json")")
        [[ -n "$old" ]] && o+=("$(user "$old" decompose "$corpus/$m" ${cut[@]+"${cut[@]}"} -q -o "$tmp/o.json")")
        c+=("$(user "$bin" decompose "$corpus/$m" ${cut[@]+"${cut[@]}"} -q -o "$tmp/c.json")")
    done
    g=$(least "${g[@]}") c=$(least "${c[@]}")
    if [[ -n "$old" ]]; then
        o=$(least "${o[@]}")
        python3 -c "import sys; m,g,o,c=sys.argv[1],*map(float,sys.argv[2:]); print(f'| {m} | {g:.2f} | {o:.2f} | {c:.2f} | {o/g:.2f} | {c/g:.2f} |')" "$m" "$g" "$o" "$c"
    else
        python3 -c "import sys; m,g,c=sys.argv[1],*map(float,sys.argv[2:]); print(f'| {m} | {g:.2f} | {c:.2f} | {c/g:.2f} |')" "$m" "$g" "$c"
    fi
done
