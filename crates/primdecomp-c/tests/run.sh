#!/usr/bin/env bash
# The C ABI with the system's compilers (scripts/test.sh runs this): installs the
# library into a temporary prefix with install.sh, builds examples/decompose.c with
# `cc` through the pkg-config file and runs it, then builds tests/abi_test.cpp with
# `c++` under AddressSanitizer (leak checks on), linked to the static library, and
# runs it against the release CLI. Exit status: the test's.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
root=$(cd "$here/../.." && pwd)
cc=${CC:-cc}
cxx=${CXX:-c++}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
target=$(cd "$root" && cargo metadata --format-version 1 --no-deps | python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')
[ -x "${PRIMDECOMP_BIN:-}" ] || (cd "$root" && cargo build --release -p primdecomp-cli)
"$here/install.sh" "$work/prefix" >/dev/null
export PKG_CONFIG_PATH="$work/prefix/lib/pkgconfig"

echo "-- the C example (cc, pkg-config, the shared library)"
# shellcheck disable=SC2046 # pkg-config's flags are words
"$cc" -std=c99 -Wall -Wextra -Werror -pedantic -O2 "$here/examples/decompose.c" \
  $(pkg-config --cflags --libs primdecomp) -Wl,-rpath,"$work/prefix/lib" -o "$work/decompose"
"$work/decompose"
"$work/decompose" "$root/datasets/demo_scene.obj" '{"targets": [150]}' "$work/demo.glb"
test -s "$work/demo.glb"

echo "-- the C example again, static, under AddressSanitizer"
# shellcheck disable=SC2046
"$cc" -std=c99 -Wall -Wextra -Werror -O1 -g -fsanitize=address -fno-omit-frame-pointer \
  "$here/examples/decompose.c" $(pkg-config --cflags primdecomp) \
  "$work/prefix/lib/libprimdecomp_c.a" $(pkg-config --static --libs-only-l primdecomp | sed 's/-lprimdecomp_c//') \
  -o "$work/decompose_asan"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 "$work/decompose_asan" "$root/datasets/demo_scene.obj" >/dev/null

echo "-- the C++ test (c++, static, AddressSanitizer and LeakSanitizer)"
# shellcheck disable=SC2046
"$cxx" -std=c++17 -Wall -Wextra -Werror -O1 -g -fsanitize=address -fno-omit-frame-pointer \
  "$here/tests/abi_test.cpp" $(pkg-config --cflags primdecomp) \
  "$work/prefix/lib/libprimdecomp_c.a" $(pkg-config --static --libs-only-l primdecomp | sed 's/-lprimdecomp_c//') \
  -o "$work/abi_test"
mkdir -p "$work/run"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 "$work/abi_test" "${PRIMDECOMP_BIN:-$target/release/primdecomp}" \
  "$root/datasets/demo_scene.obj" "$work/run"
