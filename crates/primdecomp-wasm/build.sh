#!/usr/bin/env bash
# Builds the npm package into crates/primdecomp-wasm/pkg (install it with
# `npm install ./crates/primdecomp-wasm/pkg`) and the live page,
# pkg/primdecomp-live.html (one file: open it from disk).
#
# Needs the wasm32-unknown-unknown target (`rustup target add`), wasm-bindgen-cli at
# exactly the version of the wasm-bindgen crate in Cargo.lock (`cargo install`) and
# node; the first two are installed when missing (cargo install keeps the tool in
# ~/.cargo/bin, so later runs reuse it). Exit status 3: a tool is missing and could
# not be installed.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
cd "$root"

missing() {
  echo "build.sh: $1" >&2
  exit 3
}

if ! rustc --print target-libdir --target wasm32-unknown-unknown 2>/dev/null | xargs -I{} test -d {}; then
  command -v rustup >/dev/null 2>&1 || missing "the wasm32-unknown-unknown target is not installed and there is no rustup"
  echo "-- rustup target add wasm32-unknown-unknown"
  rustup target add wasm32-unknown-unknown >/dev/null || missing "rustup target add wasm32-unknown-unknown failed"
fi

# The CLI must be the crate's version exactly: the two halves share a private format.
want=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/version = |"/, ""); print; exit }' Cargo.lock)
[ -n "$want" ] || missing "no wasm-bindgen in Cargo.lock"
# The one on PATH, else the one `cargo install` put in CARGO_HOME (not always on PATH).
installed="${CARGO_HOME:-$HOME/.cargo}/bin/wasm-bindgen"
version_of() { "$1" --version 2>/dev/null | awk '{print $2}' || true; }
bindgen=wasm-bindgen
have=$(version_of wasm-bindgen)
if [ "$have" != "$want" ] && [ "$(version_of "$installed")" = "$want" ]; then
  bindgen=$installed
  have=$want
fi
if [ "$have" != "$want" ]; then
  echo "-- cargo install wasm-bindgen-cli --version $want (have: ${have:-none})"
  # --locked first; a registry mirror that lacks one of the lock's crates needs the
  # resolver's choice instead. --force: replace another version CARGO_HOME holds.
  cargo install --quiet --force wasm-bindgen-cli --version "=$want" --locked 2>/dev/null ||
    cargo install --quiet --force wasm-bindgen-cli --version "=$want" ||
    missing "cargo install wasm-bindgen-cli --version $want failed"
  bindgen=$installed
  [ "$(version_of "$bindgen")" = "$want" ] || missing "cargo install put no wasm-bindgen $want at $bindgen"
fi
command -v node >/dev/null 2>&1 || missing "node is needed to assemble the live page"

target=$(cargo metadata --format-version 1 --no-deps | python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')
echo "-- cargo build -p primdecomp-wasm --target wasm32-unknown-unknown --profile wasm"
cargo build --quiet -p primdecomp-wasm --target wasm32-unknown-unknown --profile wasm

pkg="$here/pkg"
rm -rf "$pkg"
mkdir -p "$pkg"
# The reset function lets the JavaScript side start a fresh instance after a trap
# (a panic cannot unwind on this target).
"$bindgen" --target web --experimental-reset-state-function --remove-name-section \
  --out-dir "$pkg" --out-name primdecomp_wasm "$target/wasm32-unknown-unknown/wasm/primdecomp_wasm.wasm"
cp "$here/npm/index.js" "$here/npm/index.d.ts" "$here/npm/package.json" "$here/npm/README.md" "$pkg/"
version=$(cargo metadata --format-version 1 --no-deps | python3 -c 'import json, sys; print(next(p["version"] for p in json.load(sys.stdin)["packages"] if p["name"] == "primdecomp-wasm"))')
node -e "const p = require('$pkg/package.json'); if (p.version !== '$version') { console.error('npm/package.json version ' + p.version + ' is not the crate\\'s $version'); process.exit(1); }"
# The live page runs the engine in a classic Worker (a page opened from file:// cannot
# start a module worker from a blob): the same .wasm with wasm-bindgen's classic-script glue.
classic=$(mktemp -d)
trap 'rm -rf "$classic"' EXIT
"$bindgen" --target no-modules --remove-name-section \
  --out-dir "$classic" --out-name primdecomp_wasm "$target/wasm32-unknown-unknown/wasm/primdecomp_wasm.wasm"
node "$here/live/build.mjs" "$classic" "$pkg" "$pkg/primdecomp-live.html"

wasm="$pkg/primdecomp_wasm_bg.wasm"
echo "built $pkg: primdecomp_wasm_bg.wasm $(wc -c <"$wasm") bytes, $(gzip -9 -c "$wasm" | wc -c) gzipped; primdecomp-live.html $(wc -c <"$pkg/primdecomp-live.html") bytes"
