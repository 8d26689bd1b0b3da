#!/usr/bin/env bash
# The test command (README.md). Runs, each in its own section:
#   documents every relative link resolves, every decision record opens with its
#            header and the records' index matches them, ARCHITECTURE.md's API table names what lib.rs makes public (scripts/check_docs.py);
#   embedder the core and its sibling crates built without test features, no warnings;
#   rust     every Rust test of the workspace (unit, property, paper-claim, corpus-wide
#            and CLI tests, doctests), built once: the consumer checks below use the
#            binaries this build makes, so nothing is compiled twice;
#   exports  every engine export loaded by its real consumer (MuJoCo, yourdfpy and
#            pybullet, usd-core, the Khronos glTF Validator; Godot's scene parsed back)
#            with enclosure checked per format (tests/exports);
#   browser  the viewer page in a real headless Chromium (tests/browser);
#   python   the Python wheel built with maturin, pip-installed into a venv, and its
#            pytest suite (crates/primdecomp-py/tests);
#   ray      one scan as tiles on a local Ray cluster of two nodes, against the CLI's
#            tiled run (scripts/test_ray_cluster.sh).
# Every section runs on inputs the repository writes at test time (the demo scene,
# made-up meshes of every primitive kind, a z-up STL, a multi-node glTF and a
# multi-group OBJ: `primdecomp-testkit inputs`), so a clone without ../shared runs
# every consumer for real; the corpus (../shared/datasets/corpus) adds breadth where
# present. Each section installs what it needs (Python packages into .venv and
# .venv-py, npm packages beside their tests, Debian's chromium and fonts with apt-get
# when run as root). It ends with a summary of what ran and what was skipped, per
# section; under CI (`CI` set) any skip is a failure. Extra arguments go to
# `cargo test` (e.g. a test name filter).
set -uo pipefail
cd "$(dirname "$0")/.."
root=$PWD
target=${CARGO_TARGET_DIR:-$root/target}
export PRIMDECOMP_BIN=$target/release/primdecomp
export PRIMDECOMP_TESTKIT=$target/release/primdecomp-testkit
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export PRIMDECOMP_SKIP_LOG=$work/rust_skips
corpus=$root/../shared/datasets/corpus
started=$SECONDS

in_ci() { [ -n "${CI:-}" ] && [ "${CI}" != "false" ] && [ "${CI}" != "0" ]; }
section() { echo; echo "== $1 ($(( SECONDS - started )) s so far)"; }

# The summary: one row per section (name|passed|failed|skipped|notes).
rows=()
row() { rows+=("$1|$2|$3|$4|$5"); }
# A section that cannot run at all: a failure under CI, else one loud skip.
cannot_run() {
  if in_ci; then
    echo "FATAL: $1: $2 (required under CI)" >&2
    row "$1" 0 1 0 "could not run: $2"
  else
    echo "!!!!!!!! SKIPPED $1: $2" >&2
    row "$1" 0 0 1 "not run: $2"
  fi
}
# pytest's and node's closing counts from a log: "passed failed skipped".
pytest_counts() {
  python3 - "$1" <<'EOF'
import re, sys
text = open(sys.argv[1], errors="replace").read().splitlines()
last = next((l for l in reversed(text) if re.search(r"\d+ (passed|failed|skipped|error)", l)), "")
get = lambda w: sum(int(n) for n in re.findall(r"(\d+) " + w, last))
print(get("passed"), get("failed") + get("error"), get("skipped"))
EOF
}
node_counts() {
  awk '/^# pass /{p=$3} /^# fail /{f=$3} /^# skipped /{s=$3} /^# cancelled /{f+=$3} END{print p+0, f+0, s+0}' "$1"
}
pip_install() { # VENV ARGS...: pip without its progress bar, one line per package
  "$1/bin/pip" install --disable-pip-version-check --progress-bar off "${@:2}" | grep -E "^(Collecting|Successfully)" || true
}

# ---------------------------------------------------------------- documents
section "documents: every relative link resolves, every decision record has its header, the API table matches lib.rs (scripts/check_docs.py)"
if python3 scripts/check_docs.py; then
  row documents 1 0 0 "links and decision records"
else
  row documents 0 1 0 "scripts/check_docs.py found problems (above)"
fi

# ---------------------------------------------------------------- module graph
section "module graph: no import cycles, no import through a crate root, no import against the core's stage order (scripts/module_cycles.py)"
if python3 scripts/module_cycles.py; then
  row modules 1 0 0 "cycles, crate-root imports, back-stage imports: none"
else
  row modules 0 1 0 "scripts/module_cycles.py found the imports above"
fi

# ---------------------------------------------------------------- embedder build
section "embedder build: the core and the crates beside it as an embedder compiles them (no test features): no warnings"
# The workspace's tests turn on `test-internals`; code behind it can leave imports that
# only an embedder's build sees, so those crates are checked alone.
cargo check --release --lib -p primdecomp -p primdecomp-math -p primdecomp-files -p primdecomp-export \
  --message-format short 2>&1 | tee "$work/embedder.log" | grep -E "(^|: )(warning|error)" || true
if grep -qE "(^|: )(warning|error)" "$work/embedder.log" || ! grep -q "Finished" "$work/embedder.log"; then
  row embedder 0 1 0 "warnings or errors above (cargo check --release --lib -p primdecomp …)"
else
  row embedder 1 0 0 "primdecomp, -math, -files, -export: no warnings"
fi

# ---------------------------------------------------------------- system packages
section "system packages: chromium (the browser test), fonts (the sim plot test)"
want_apt=()
chromium=${CHROMIUM:-/usr/bin/chromium}
[ -x "$chromium" ] || [ "$chromium" != /usr/bin/chromium ] || want_apt+=(chromium)
[ -n "${PRIMDECOMP_FONT:-}" ] || [ -f /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf ] || want_apt+=(fonts-dejavu-core)
if [ ${#want_apt[@]} -gt 0 ]; then
  if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
    echo "-- apt-get install ${want_apt[*]} (a minute or two)"
    (apt-get update -q && DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${want_apt[@]}") 2>&1 \
      | grep -E "^(Get:|Setting up|E:)" | sed 's/^/   /' || true
  else
    echo "cannot install ${want_apt[*]}: not root or no apt-get" >&2
  fi
else
  echo "-- all there"
fi

# ---------------------------------------------------------------- rust
section "rust: cargo test --release --workspace (one build; the binaries below come from it)"
: >"$PRIMDECOMP_SKIP_LOG"
# --no-fail-fast: every test binary runs, so the summary counts all of them.
cargo test --release --workspace --no-fail-fast "$@" 2>&1 | tee "$work/rust.log"
rust_status=${PIPESTATUS[0]}
read -r r_pass r_fail r_ign < <(awk '/^test result:/{
    for (i = 1; i <= NF; i++) { if ($(i+1) ~ /^passed/) p += $i; if ($(i+1) ~ /^failed/) f += $i; if ($(i+1) ~ /^ignored/) g += $i }
  } END { print p+0, f+0, g+0 }' "$work/rust.log")
r_skip=$(sort -u "$PRIMDECOMP_SKIP_LOG" | wc -l)
[ "$rust_status" = 0 ] || [ "$r_fail" -gt 0 ] || r_fail=1  # a build failure fails the section
note="$r_ign ignored by design (measurements run by hand)"
if [ "$r_skip" -gt 0 ]; then
  note="$note; $r_skip passed without their corpus part: $(cut -d: -f2 "$PRIMDECOMP_SKIP_LOG" | sort -u | tr '\n' ' ')"
  in_ci && r_fail=$(( r_fail + r_skip ))
fi
row rust "$(( r_pass - r_skip ))" "$r_fail" "$r_skip" "$note"
built=1
for b in "$PRIMDECOMP_BIN" "$PRIMDECOMP_TESTKIT"; do [ -x "$b" ] || built=0; done

# ---------------------------------------------------------------- made-up inputs
export PRIMDECOMP_TEST_INPUTS=$work/inputs
if [ "$built" = 1 ]; then
  section "made-up inputs (primdecomp-testkit inputs): what every consumer check runs on"
  "$PRIMDECOMP_TESTKIT" inputs "$PRIMDECOMP_TEST_INPUTS" | tr '\n' ' '; echo
  if [ -d "$corpus" ]; then echo "-- and the corpus: $corpus"; else echo "-- no corpus at $corpus: its cases are skipped"; fi
fi

# ---------------------------------------------------------------- exports
section "exports: MuJoCo, yourdfpy + pybullet, usd-core, Khronos glTF Validator, enclosure per format (tests/exports)"
exports_ok=1
req=tests/exports/requirements.txt
if [ "$built" = 0 ]; then
  cannot_run exports "the Rust build failed"; exports_ok=0
elif ! command -v python3 >/dev/null 2>&1; then
  cannot_run exports "python3 not found"; exports_ok=0
elif [ ! -x .venv/bin/python ] || ! cmp -s "$req" .venv/.requirements 2>/dev/null; then
  echo "-- installing $req into .venv (a few minutes the first time)"
  if python3 -m venv .venv && pip_install .venv -r "$req" && .venv/bin/python -c "import mujoco, pxr, yourdfpy, pybullet"; then
    cp "$req" .venv/.requirements
  else
    cannot_run exports "cannot install $req into .venv"; exports_ok=0
  fi
fi
if [ "$exports_ok" = 1 ]; then
  if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
    cannot_run exports "node/npm not found (the glTF Validator runs on node)"; exports_ok=0
  elif ! (cd tests/exports && node -e "const w = require('./package.json').dependencies['gltf-validator']; process.exit(require('./node_modules/gltf-validator/package.json').version === w ? 0 : 1)") 2>/dev/null; then
    echo "-- npm ci in tests/exports (gltf-validator)"
    (cd tests/exports && npm ci --no-audit --no-fund --loglevel=error) || { cannot_run exports "npm ci failed in tests/exports"; exports_ok=0; }
  fi
fi
if [ "$exports_ok" = 1 ]; then
  (cd tests/exports && ../../.venv/bin/python -m pytest -q -rs -p no:cacheprovider) 2>&1 | tee "$work/exports.log"
  status=${PIPESTATUS[0]}
  read -r p f s < <(pytest_counts "$work/exports.log")
  [ "$status" = 0 ] || [ "$f" -gt 0 ] || f=1
  note=""
  [ -d "$corpus" ] || note="made-up cases only: no corpus at $corpus (its cases are not collected)"
  row exports "$p" "$f" "$s" "$note"
fi

# ---------------------------------------------------------------- browser
section "browser: the viewer page in headless Chromium (tests/browser)"
# view.test.mjs: the page becomes ready, draws every kind, switches levels and panes;
# hostile.test.mjs: built from hostile file and collider names, it still starts and
# runs no injected script.
if [ "$built" = 0 ]; then
  cannot_run browser "the Rust build failed"
elif [ ! -x "$chromium" ]; then
  cannot_run browser "no Chromium at $chromium (apt-get install chromium)"
elif ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  cannot_run browser "node/npm not found"
elif ! (cd tests/browser && npm ci --no-audit --no-fund --loglevel=error); then
  cannot_run browser "npm ci failed in tests/browser"
else
  CHROMIUM="$chromium" node --test --test-reporter=spec --test-reporter-destination=stdout \
    --test-reporter=tap --test-reporter-destination="$work/browser.tap" tests/browser/view.test.mjs tests/browser/hostile.test.mjs
  status=$?
  read -r p f s < <(node_counts "$work/browser.tap")
  [ "$status" = 0 ] || [ "$f" -gt 0 ] || f=1
  row browser "$p" "$f" "$s" ""
fi

# ---------------------------------------------------------------- python
section "python: the wheel (maturin), pip-installed into .venv-py, and its pytest suite"
# The test dependencies: numpy, pytest, trimesh + scipy (an independent convexity and
# containment check) and ray (the batch runner on a local Ray instance).
py_req="maturin numpy pytest trimesh scipy ray"
py_ok=1
if [ "$built" = 0 ]; then
  cannot_run python "the Rust build failed"; py_ok=0
elif ! command -v python3 >/dev/null 2>&1; then
  cannot_run python "python3 not found"; py_ok=0
elif [ ! -x .venv-py/bin/python ] || [ "$(cat .venv-py/.requirements 2>/dev/null)" != "$py_req" ]; then
  echo "-- installing $py_req into .venv-py (a few minutes the first time)"
  rm -rf .venv-py
  # shellcheck disable=SC2086
  if python3 -m venv .venv-py && pip_install .venv-py $py_req; then
    echo "$py_req" >.venv-py/.requirements
  else
    cannot_run python "cannot install $py_req into .venv-py"; py_ok=0
  fi
fi
if [ "$py_ok" = 1 ]; then
  # The extension module is a second build of the core (it links against Python,
  # without the tests' feature set): shown as it goes, in the same target directory.
  echo "-- building the wheel (maturin build --release; the first time a few minutes)"
  if CARGO_TARGET_DIR="$target" .venv-py/bin/maturin build --release -m crates/primdecomp-py/Cargo.toml \
      --out "$work/wheels" 2>&1 | grep -vE "^\s+(Compiling|Fresh) " ; then
    wheel=$(ls "$work"/wheels/*.whl 2>/dev/null | head -1)
  fi
  if [ -z "${wheel:-}" ] || ! pip_install .venv-py --force-reinstall --no-deps "$wheel"; then
    cannot_run python "the wheel did not build or install"; py_ok=0
  fi
fi
if [ "$py_ok" = 1 ]; then
  so=$(.venv-py/bin/python -c "import primdecomp._native as n; print(n.__file__)")
  sizes="wheel $(du -k "$wheel" | cut -f1) KiB, installed module $(du -k "$so" | cut -f1) KiB, CLI $(du -k "$PRIMDECOMP_BIN" | cut -f1) KiB"
  echo "-- sizes: $sizes"
  (cd /tmp && "$root/.venv-py/bin/python" -m pytest -q -rs -p no:cacheprovider "$root/crates/primdecomp-py/tests") 2>&1 | tee "$work/python.log"
  status=${PIPESTATUS[0]}
  read -r p f s < <(pytest_counts "$work/python.log")
  [ "$status" = 0 ] || [ "$f" -gt 0 ] || f=1
  row python "$p" "$f" "$s" "$sizes"
fi

# ---------------------------------------------------------------- ray cluster
section "ray cluster: one scan as Ray tasks on a local cluster of two nodes (scripts/test_ray_cluster.sh)"
# ray start --head and ray start --address, one CPU each, on this machine; the driver
# (primdecomp.ray_tiles) must equal the CLI's --tiles run byte for byte, run tasks on
# both nodes, resume from its cache, and rerun a corrupted cached tile.
if [ "${py_ok:-0}" != 1 ]; then
  cannot_run "ray" "the Python section did not install the wheel"
else
  scripts/test_ray_cluster.sh .venv-py "$PRIMDECOMP_BIN" "$PRIMDECOMP_TEST_INPUTS/lumpy.ply" "$work/ray" 2>&1 \
    | tee "$work/ray.log"
  status=${PIPESTATUS[0]}
  p=$(grep -c '^ok ' "$work/ray.log" || true)
  f=$(grep -c '^FAILED ' "$work/ray.log" || true)
  [ "$status" = 0 ] || [ "$f" -gt 0 ] || f=1
  row ray "$p" "$f" 0 "$(grep '^times:' "$work/ray.log" | cut -c8-)"
fi

# ---------------------------------------------------------------- embedding
section "embedding: the C ABI (cc, c++, AddressSanitizer), the npm package with Rapier.js in node, the live page in Chromium"
# scripts/test_embedding.sh installs what it needs (g++ and pkg-config, the wasm32
# target, wasm-bindgen-cli, npm packages); under CI a missing piece fails. Its three
# parts (c, wasm, live) each count as one check here; their own counts are above.
if [ "$built" = 0 ]; then
  cannot_run embedding "the Rust build failed"
else
  CHROMIUM="$chromium" scripts/test_embedding.sh 2>&1 | tee "$work/embedding.log"
  status=${PIPESTATUS[0]}
  e_skip=$(grep -c '^!!!!!!!! SKIPPED (embedding):' "$work/embedding.log" || true)
  if [ "$status" = 0 ]; then
    row embedding "$(( 3 - e_skip ))" 0 "$e_skip" "c, wasm, live"
  else
    row embedding 0 1 0 "scripts/test_embedding.sh failed (above)"
  fi
fi

# ---------------------------------------------------------------- summary
section "summary"
total_p=0 total_f=0 total_s=0
printf '%-9s %8s %8s %8s  %s\n' section passed failed skipped notes
for r in "${rows[@]}"; do
  IFS='|' read -r name p f s note <<<"$r"
  printf '%-9s %8s %8s %8s  %s\n' "$name" "$p" "$f" "$s" "$note"
  total_p=$(( total_p + p )) total_f=$(( total_f + f )) total_s=$(( total_s + s ))
done
if [ "$total_s" -gt 0 ] && in_ci; then
  echo "FATAL: $total_s skipped under CI: every check must run here" >&2
  total_f=$(( total_f + total_s ))
fi
echo "$total_p passed, $total_f failed, $total_s skipped"
[ "$total_f" = 0 ]
