#!/usr/bin/env bash
# Runs every fuzz target for SECONDS (default 600) in turn, one process at a time,
# logging to fuzz/logs/TARGET.log. Usage: fuzz/run_all.sh [SECONDS] [TARGET...]
set -u
cd "$(dirname "$0")"
secs=${1:-600}
shift || true
targets=${*:-decompose parse_obj parse_ply parse_stl parse_off parse_gltf load_mmap gltf_structured exports}
mkdir -p logs
# Corpus meshes seed the parsers too; they are read from ../shared, never committed.
shared=../../shared/datasets/corpus
[ -d "$shared" ] || echo "CORPUS ABSENT: $shared not found; fuzzing from the committed seeds only" >&2
for f in tiny_joined_tetrahedra.obj tiny_jacked.obj parry_stairs.obj:obj \
  tiny_2triangles.off:off tiny_plane_quad.ply:ply tiny_7_8ths_cube.stl:stl \
  tiny_shared_edge.STL:stl kenney_pavement_fountain.glb:gltf; do
  name=${f%%:*}; dir=${f##*:}; [ "$dir" = "$f" ] && dir=obj
  mkdir -p "corpus_seeds/$dir"
  [ -f "$shared/$name" ] && cp "$shared/$name" "corpus_seeds/$dir/"
done
for t in $targets; do
  case $t in
    parse_obj) f=obj ;; parse_ply) f=ply ;; parse_stl) f=stl ;;
    parse_off) f=off ;; parse_gltf) f=gltf ;; *) f= ;;
  esac
  seeds=
  [ -n "$f" ] && seeds="seeds/$f corpus_seeds/$f"
  [ "$t" = load_mmap ] && for f in obj ply stl off; do seeds="$seeds seeds/$f corpus_seeds/$f"; done
  mkdir -p corpus/$t
  echo "== $t $(date -u +%FT%TZ)" >> logs/runs.txt
  RAYON_NUM_THREADS=1 cargo +nightly fuzz run "$t" "corpus/$t" $seeds -- \
    -max_total_time="$secs" -rss_limit_mb=4096 -timeout=30 -print_final_stats=1 \
    > "logs/$t.log" 2>&1
  echo "   exit $? $(date -u +%FT%TZ)" >> logs/runs.txt
done
