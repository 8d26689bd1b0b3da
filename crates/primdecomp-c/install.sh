#!/usr/bin/env bash
# Builds the C library (release) and installs it under PREFIX (default /usr/local):
# PREFIX/lib/libprimdecomp_c.{so,a}, PREFIX/include/primdecomp.h and
# PREFIX/lib/pkgconfig/primdecomp.pc, so that
#   cc app.c $(pkg-config --cflags --libs primdecomp)
# compiles and links (PKG_CONFIG_PATH=PREFIX/lib/pkgconfig if PREFIX is not a
# system prefix; add -Wl,-rpath,PREFIX/lib or LD_LIBRARY_PATH to find the .so).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
prefix=$(mkdir -p "${1:-/usr/local}" && cd "${1:-/usr/local}" && pwd)
cd "$here"
# An installed library carries no debug line tables (30 MB of the .so otherwise).
export CARGO_PROFILE_RELEASE_DEBUG=${CARGO_PROFILE_RELEASE_DEBUG:-0}
target=$(cargo metadata --format-version 1 --no-deps | python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')
version=$(cargo metadata --format-version 1 --no-deps | python3 -c 'import json, sys; print(next(p["version"] for p in json.load(sys.stdin)["packages"] if p["name"] == "primdecomp-c"))')
# Both libraries in one build; rustc prints what the static one needs from the system
# when it links it (nothing when the build was fresh: then Linux's list, as rustc gives it).
private=$(cargo rustc --release --quiet -p primdecomp-c --crate-type staticlib,cdylib -- --print native-static-libs 2>&1 |
  sed -n 's/.*native-static-libs: //p' | tail -1)
private=${private:--lgcc_s -lutil -lrt -lpthread -lm -ldl -lc}
mkdir -p "$prefix/lib/pkgconfig" "$prefix/include"
install -m 644 "$target/release/libprimdecomp_c.a" "$prefix/lib/"
install -m 755 "$target/release/libprimdecomp_c.so" "$prefix/lib/"
install -m 644 include/primdecomp.h "$prefix/include/"
sed -e "s|@PREFIX@|$prefix|" -e "s|@VERSION@|$version|" -e "s|@PRIVATE_LIBS@|$private|" \
  primdecomp.pc.in >"$prefix/lib/pkgconfig/primdecomp.pc"
echo "installed primdecomp $version (C library) under $prefix"
