#!/usr/bin/env bash
# Builds idmesh with CMake (cargo underneath) and runs the C/C++ tests in ctests/ with ctest.
# Installs the missing system packages first (Debian/Ubuntu). Works from any directory.
#
#   scripts/ctest.sh                 # Release build in build/cmake
#   IDMESH_SANITIZE=address,undefined scripts/ctest.sh   # sanitized test programs
#   BUILD_DIR=/tmp/b scripts/ctest.sh                    # another build directory
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build/cmake}"
PACKAGES=(cmake g++ libcgal-dev libgmp-dev libmpfr-dev)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "ctest.sh: installing missing packages: ${missing[*]}"
  if [[ $(id -u) -eq 0 ]]; then
    SUDO=()
  elif command -v sudo >/dev/null 2>&1; then
    SUDO=(sudo)
  else
    echo "ctest.sh: not root and no sudo; install these first: ${missing[*]}" >&2
    exit 1
  fi
  "${SUDO[@]}" apt-get update
  "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y "${missing[@]}"
fi

if ! command -v cargo >/dev/null 2>&1 && [[ -x "${CARGO_HOME:-$HOME/.cargo}/bin/cargo" ]]; then
  export PATH="${CARGO_HOME:-$HOME/.cargo}/bin:$PATH"
fi

# IDMESH_SANITIZE is always passed so an earlier sanitized configure does not stick.
cmake -S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release "-DIDMESH_SANITIZE=${IDMESH_SANITIZE:-}"
cmake --build "$BUILD_DIR" -j2
ctest --test-dir "$BUILD_DIR" --output-on-failure
