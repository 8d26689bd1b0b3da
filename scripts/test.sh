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

echo "== cargo test --release --workspace"
cargo test --release --workspace "$@"

echo "== browser: the viewer page in a real headless Chromium (tests/browser)"
# `primdecomp view`'s page opened from file:// with the network refused: it must
# become ready, report the JSON's primitive counts, draw every kind in its colour,
# switch levels and panes, and show a clicked primitive (tests/browser/view.test.mjs).
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
  CHROMIUM="$chromium" node --test tests/browser/view.test.mjs
fi

echo "== all tests passed"
