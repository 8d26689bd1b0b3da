#!/usr/bin/env bash
# The test command (README.md): every Rust test of the workspace (unit, property,
# paper-claim, corpus-wide and CLI tests, and the doctests), then the checks that
# need a real consumer outside Rust, each in its own section below. Each section
# installs what it needs itself (Python packages into .venv, npm packages into
# node_modules, Debian packages with apt-get) and fails loudly; under CI (`CI` set)
# a consumer that cannot be installed is a failure, never a skip.
# Extra arguments go to `cargo test` (e.g. a test name filter).
set -euo pipefail
cd "$(dirname "$0")/.."

echo "== documents: every relative link resolves, every decision record has its header (scripts/check_docs.py)"
python3 scripts/check_docs.py

echo "== cargo test --release --workspace"
cargo test --release --workspace "$@"

echo "== browser: the viewer page in a real headless Chromium (tests/browser)"
# `primdecomp view`'s page opened from file:// with the network refused: it must
# become ready, report the JSON's primitive counts, draw every kind in its colour,
# switch levels and panes, and show a clicked primitive (tests/browser/view.test.mjs);
# built from hostile file and collider names, it must still start and run no injected
# script (tests/browser/hostile.test.mjs).
# Needs the release binary, Debian's chromium, Node and playwright-core (npm ci, from
# tests/browser/package-lock.json); chromium is installed here with apt-get when
# missing. Under CI a missing piece fails; elsewhere it is skipped, loudly.
in_ci() { [ -n "${CI:-}" ] && [ "${CI}" != "false" ] && [ "${CI}" != "0" ]; }
browser_missing() {
  if in_ci; then
    echo "FATAL: $1; the browser test cannot run under CI" >&2
    exit 1
  fi
  echo "!!!!!!!! SKIPPED the browser test: $1" >&2
}
chromium=${CHROMIUM:-/usr/bin/chromium}
if [ ! -x "$chromium" ] && [ "$chromium" = /usr/bin/chromium ] && command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
  echo "-- installing Debian's chromium"
  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium) >/dev/null \
    || echo "apt-get could not install chromium" >&2
fi
if [ ! -x "$chromium" ]; then
  browser_missing "no Chromium at $chromium (apt-get install chromium)"
elif ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  browser_missing "no node/npm on PATH"
else
  cargo build --release --quiet -p primdecomp-cli
  (cd tests/browser && npm ci --no-audit --no-fund --loglevel=error)
  CHROMIUM="$chromium" node --test tests/browser/view.test.mjs tests/browser/hostile.test.mjs
fi

echo "== export consumers: MuJoCo, yourdfpy, usd-core, glTF Validator, enclosure per format"
# The engine exports are checked by the real consumers (tests/exports/README.md):
# Python packages pinned in tests/exports/requirements.txt go into .venv, the Khronos
# glTF Validator (npm) into tests/exports/node_modules. Installs are skipped when
# already there; under CI a consumer that cannot be installed fails the run.
fail_or_skip() {
  if in_ci; then
    echo "FATAL: $1 (required under CI)" >&2
    exit 1
  fi
  echo "WARNING: $1; the export consumer checks are skipped (CI fails here)" >&2
  exports_ok=0
}
exports_ok=1
req=tests/exports/requirements.txt
if ! command -v python3 >/dev/null 2>&1; then
  fail_or_skip "python3 not found"
fi
if [ "$exports_ok" = 1 ] && { [ ! -x .venv/bin/python ] || ! cmp -s "$req" .venv/.requirements 2>/dev/null; }; then
  echo "-- installing $req into .venv"
  if python3 -m venv .venv && .venv/bin/pip install --quiet --disable-pip-version-check -r "$req"; then
    cp "$req" .venv/.requirements
  else
    fail_or_skip "cannot install $req into .venv"
  fi
fi
if [ "$exports_ok" = 1 ]; then
  if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
    fail_or_skip "node/npm not found (the glTF Validator runs on node)"
  elif ! (cd tests/exports && node -e "const w = require('./package.json').dependencies['gltf-validator']; process.exit(require('./node_modules/gltf-validator/package.json').version === w ? 0 : 1)") 2>/dev/null; then
    echo "-- npm ci in tests/exports (gltf-validator)"
    (cd tests/exports && npm ci --no-audit --no-fund --loglevel=error) || fail_or_skip "npm ci failed in tests/exports"
  fi
fi
if [ "$exports_ok" = 1 ]; then
  cargo build --release --quiet -p primdecomp-cli -p primdecomp-testkit
  # pytest's exit 5 (no test collected) is a failure here too.
  (cd tests/exports && ../../.venv/bin/python -m pytest -q -p no:cacheprovider)
fi

# The Python package (crates/primdecomp-py/README.md): a fresh venv (.venv-py), maturin,
# numpy, pytest, trimesh + scipy (the independent convexity/containment check) and ray
# (the batch runner on a local Ray instance) from PyPI, then a real
# `pip install ./crates/primdecomp-py` (the wheel built by maturin into the venv) and
# its pytest suite, which compares with the release CLI's JSON (built first, below).
# Under CI a missing piece fails; elsewhere it is skipped.
py_fail_or_skip() {
  if in_ci; then
    echo "FATAL: $1 (required under CI)" >&2
    exit 1
  fi
  echo "WARNING: $1; the Python package tests are skipped (CI fails here)" >&2
  py_ok=0
}
py_ok=1
command -v python3 >/dev/null 2>&1 || py_fail_or_skip "python3 not found"
if [ "$py_ok" = 1 ]; then
  echo "-- building the Python package into a fresh .venv-py"
  rm -rf .venv-py
  if ! { python3 -m venv .venv-py &&
    .venv-py/bin/pip install --quiet --disable-pip-version-check maturin numpy pytest trimesh scipy ray &&
    CARGO_TARGET_DIR="$PWD/target" .venv-py/bin/pip install --quiet --disable-pip-version-check ./crates/primdecomp-py; }; then
    py_fail_or_skip "cannot pip install ./crates/primdecomp-py into .venv-py"
  fi
fi
if [ "$py_ok" = 1 ]; then
  cargo build --release --quiet -p primdecomp-cli
  root=$PWD
  (cd /tmp && "$root/.venv-py/bin/python" -m pytest -q -p no:cacheprovider "$root/crates/primdecomp-py/tests")
fi

echo "== embedding: the C ABI (cc, c++, AddressSanitizer), the npm package with Rapier.js in node, the live page in Chromium"
# scripts/test_embedding.sh installs what it needs; under CI a missing piece fails.
CHROMIUM="$chromium" scripts/test_embedding.sh

echo "== all tests passed"
