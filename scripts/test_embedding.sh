#!/usr/bin/env bash
# The embedding checks (scripts/test.sh runs this after the Rust tests):
#   c      crates/primdecomp-c/tests/run.sh: the library installed with its pkg-config
#          file, examples/decompose.c built by `cc` and run, tests/abi_test.cpp built
#          by `c++` under AddressSanitizer and run against the CLI (the CLI's JSON byte
#          for byte from files, memory and arrays on three meshes; every export);
#   wasm   crates/primdecomp-wasm/build.sh (the npm package and the live page), then
#          tests/wasm in node: the package installed from the repository beside
#          @dimforge/rapier3d-compat (Rapier.js), compared with the CLI, one collider
#          per primitive, balls dropped; bad input and hostile names across the
#          boundary (tests/wasm/bad_input.test.mjs);
#   live   tests/browser/live.test.mjs: the live page from file:// in headless Chromium.
# Each installs what it needs: g++ and pkg-config with apt-get as root; the wasm32
# target and wasm-bindgen-cli (build.sh, kept in ~/.cargo/bin for later runs); npm
# packages with npm ci. Under CI (`CI` set) a piece that cannot be installed fails;
# elsewhere its check is skipped, loudly, and named at the end (exit status 0).
# Environment: CHROMIUM (default /usr/bin/chromium), PRIMDECOMP_BIN (default the
# release CLI of the workspace's target directory).
set -euo pipefail
cd "$(dirname "$0")/.."
in_ci() { [ -n "${CI:-}" ] && [ "${CI}" != "false" ] && [ "${CI}" != "0" ]; }
skipped=()
missing() {
  if in_ci; then
    echo "FATAL: $1 (required under CI)" >&2
    exit 1
  fi
  echo "!!!!!!!! SKIPPED $1" >&2
  skipped+=("$1")
}
target=$(cargo metadata --format-version 1 --no-deps | python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')
export PRIMDECOMP_BIN=${PRIMDECOMP_BIN:-$target/release/primdecomp}
chromium=${CHROMIUM:-/usr/bin/chromium}
# The CLI the checks compare with: the test run's build when there is one (a second
# build with other features would recompile the core for minutes).
[ -x "$PRIMDECOMP_BIN" ] || cargo build --release -p primdecomp-cli

echo "-- c: the C example (cc) and the C++ test (c++, AddressSanitizer)"
if ! command -v c++ >/dev/null 2>&1 || ! command -v pkg-config >/dev/null 2>&1; then
  if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
    echo "-- installing Debian's g++ and pkg-config"
    (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq g++ pkg-config) >/dev/null ||
      echo "apt-get could not install g++ and pkg-config" >&2
  fi
fi
if command -v cc >/dev/null 2>&1 && command -v c++ >/dev/null 2>&1 && command -v pkg-config >/dev/null 2>&1; then
  crates/primdecomp-c/tests/run.sh
else
  missing "c: no cc, c++ or pkg-config (apt-get install g++ pkg-config)"
fi

echo "-- wasm: the npm package and the live page (crates/primdecomp-wasm/build.sh), Rapier.js in node"
wasm_built=0
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  missing "wasm and live: no node/npm on PATH"
else
  status=0
  crates/primdecomp-wasm/build.sh || status=$?
  if [ "$status" = 3 ]; then
    missing "wasm and live: build.sh could not install a tool it needs (above)"
  elif [ "$status" != 0 ]; then
    echo "FATAL: crates/primdecomp-wasm/build.sh failed" >&2
    exit 1
  else
    wasm_built=1
    (cd tests/wasm && npm ci --no-audit --no-fund --loglevel=error)
    node --test tests/wasm/rapier.test.mjs tests/wasm/bad_input.test.mjs
  fi
fi

echo "-- live: the live page in headless Chromium"
if [ "$wasm_built" = 1 ]; then
  if [ -x "$chromium" ]; then
    (cd tests/browser && npm ci --no-audit --no-fund --loglevel=error)
    CHROMIUM="$chromium" node --test tests/browser/live.test.mjs
  else
    missing "live: no Chromium at $chromium"
  fi
fi

if [ "${#skipped[@]}" -gt 0 ]; then
  printf '!!!!!!!! SKIPPED (embedding): %s\n' "${skipped[@]}" >&2
else
  echo "-- embedding: c, wasm and live all ran"
fi
