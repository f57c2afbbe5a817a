#!/usr/bin/env bash
# Installs the CMake build in $1 to a temporary prefix, checks the installed files (the shared
# library's SONAME and symlinks, headers, CMake package, pkg-config files), then builds and
# runs two out-of-tree consumers: one with find_package(idmesh CONFIG), one with pkg-config.
# No pipefail: `ldd ... | grep` may see ldd killed by SIGPIPE once grep has its line.
set -eu
BUILD="$1"
SRC="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
PREFIX="$TMP/prefix"
fail() { echo "FAIL: $*" >&2; exit 1; }

cmake --install "$BUILD" --prefix "$PREFIX" >/dev/null
A="$(cd "$PREFIX" && find . -name libidmesh.a | head -1)"
LIBDIR="$(dirname "${A#./}")"
[ -n "$A" ] || fail "libidmesh.a not installed"
L="$PREFIX/$LIBDIR"
for f in libidmesh.a libidmesh.so libidmesh_triangle.a pkgconfig/idmesh.pc \
         pkgconfig/idmesh-triangle.pc cmake/idmesh/idmeshConfig.cmake; do
  [ -e "$L/$f" ] || fail "$LIBDIR/$f not installed"
done
for f in include/idmesh.h include/idmesh/triangle/triangle.h; do
  [ -e "$PREFIX/$f" ] || fail "$f not installed"
done
SONAME="$(readelf -d "$L/libidmesh.so" | sed -n 's/.*Library soname: \[\(.*\)\].*/\1/p')"
case "$SONAME" in libidmesh.so.[0-9]*) ;; *) fail "libidmesh.so has SONAME '$SONAME'" ;; esac
[ -L "$L/$SONAME" ] && [ -L "$L/libidmesh.so" ] || fail "$SONAME / libidmesh.so are not symlinks"
[ -f "$(readlink -f "$L/$SONAME")" ] || fail "$SONAME dangles"
echo "installed: $LIBDIR/libidmesh.so -> $(readlink "$L/libidmesh.so"), SONAME $SONAME"

# 1. find_package.
cmake -S "$SRC" -B "$TMP/fp" -DCMAKE_PREFIX_PATH="$PREFIX" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$TMP/fp" >/dev/null
"$TMP/fp/consumer_static"
LD_LIBRARY_PATH="$L" "$TMP/fp/consumer_shared"
LD_LIBRARY_PATH="$L" ldd "$TMP/fp/consumer_shared" | grep "$SONAME => $L/" >/dev/null ||
  fail "consumer_shared did not load $SONAME from the prefix"

# 2. pkg-config.
if ! command -v pkg-config >/dev/null; then
  echo "pkg-config not found (apt-get install pkg-config): pkg-config consumer skipped"
  exit 0
fi
export PKG_CONFIG_PATH="$L/pkgconfig"
pkg-config --exists idmesh-triangle || fail "pkg-config does not find idmesh-triangle"
# shellcheck disable=SC2046
cc -Wall -Wextra -Werror -o "$TMP/pc" "$SRC/consumer.c" $(pkg-config --cflags --libs idmesh-triangle)
LD_LIBRARY_PATH="$L" "$TMP/pc"
LD_LIBRARY_PATH="$L" ldd "$TMP/pc" | grep "$SONAME => $L/" >/dev/null || fail "pkg-config consumer did not load $SONAME"
echo "install test passed"
