#!/usr/bin/env bash
# Runs every fuzz target for SECONDS (default 600) in turn, one process at a time,
# logging to fuzz/logs/TARGET.log. Usage: fuzz/run_all.sh [SECONDS] [TARGET...]
set -u
cd "$(dirname "$0")"
secs=${1:-600}
shift || true
targets=${*:-decompose parse_obj parse_ply parse_stl parse_off parse_gltf}
mkdir -p logs
for t in $targets; do
  case $t in
    parse_obj) seeds=seeds/obj ;; parse_ply) seeds=seeds/ply ;; parse_stl) seeds=seeds/stl ;;
    parse_off) seeds=seeds/off ;; parse_gltf) seeds=seeds/gltf ;; *) seeds= ;;
  esac
  mkdir -p corpus/$t
  echo "== $t $(date -u +%FT%TZ)" >> logs/runs.txt
  RAYON_NUM_THREADS=1 cargo +nightly fuzz run "$t" "corpus/$t" $seeds -- \
    -max_total_time="$secs" -rss_limit_mb=4096 -timeout=30 -print_final_stats=1 \
    > "logs/$t.log" 2>&1
  echo "   exit $? $(date -u +%FT%TZ)" >> logs/runs.txt
done
