#!/usr/bin/env bash
# The whole test suite, runnable on a fresh machine (the README's second command).
# Installs what it needs when missing: Debian packages for the C/C++ harness and the
# reference tools, Python packages for the conformance verifiers.
set -euo pipefail
cd "$(dirname "$0")/.."
# A one-off build gains nothing from incremental state, which took over a gigabyte of disk.
export CARGO_INCREMENTAL=0

need_apt=()
for pkg in cmake g++ pkg-config libcgal-dev libgmp-dev libmpfr-dev libtet1.5-dev tetgen python3-pip valgrind; do
  dpkg -s "$pkg" >/dev/null 2>&1 || need_apt+=("$pkg")
done
if [ ${#need_apt[@]} -gt 0 ]; then
  echo "== installing Debian packages: ${need_apt[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && command -v sudo >/dev/null && SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need_apt[@]}" >/dev/null
fi
if ! python3 -c 'import numpy, scipy, triangle' >/dev/null 2>&1; then
  echo "== installing Python packages: numpy scipy triangle"
  python3 -m pip install -q numpy scipy triangle ||
    python3 -m pip install -q --break-system-packages numpy scipy triangle
fi
# meshio reads the exchange formats back in tests/exchange.rs.
if ! python3 -c 'import meshio' >/dev/null 2>&1; then
  echo "== installing Python package: meshio"
  python3 -m pip install -q meshio || python3 -m pip install -q --break-system-packages meshio
fi

echo "== cargo fmt --check"
cargo fmt --check
echo "== cargo clippy"
cargo clippy --all-targets --quiet -- -D warnings
echo "== cargo doc (no broken links, private items included)"
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --document-private-items --quiet
echo "== cargo test"
cargo test --quiet 2>&1 | tee /tmp/idmesh-cargo-test.log | grep -E '^(test result|error|failures|---- )' || true
if grep -qE '^test result: FAILED|^error' /tmp/idmesh-cargo-test.log; then
  echo "cargo test failed"; exit 1
fi
grep -q '^test result: ok' /tmp/idmesh-cargo-test.log || { echo "cargo test ran no test"; exit 1; }
echo "== CMake C/C++ harness (CGAL comparison)"
bash scripts/ctest.sh
echo "== C/C++ harness again under ASan + UBSan (leak checks on)"
IDMESH_SANITIZE=address,undefined BUILD_DIR=build/asan bash scripts/ctest.sh
echo "== C/C++ tests under valgrind (no invalid access, no definite leak)"
for t in test_c_api test_mesher3d test_progress triangle_client_c triangle_client_cxx tetgen_client_idmesh tetgen_bad_input_idmesh tetgen_switches_idmesh; do
  if ! (cd build/cmake/ctests && valgrind -q --error-exitcode=99 --leak-check=full \
        --errors-for-leak-kinds=definite "./$t" >"/tmp/idmesh-valgrind-$t.log" 2>&1); then
    echo "valgrind found errors in $t:"; tail -40 "/tmp/idmesh-valgrind-$t.log"; exit 1
  fi
  echo "valgrind: $t clean"
done
echo "== fuzz smoke run (readers, C API and meshing targets, 60 s each)"
bash scripts/fuzz_smoke.sh 60
echo "== the exact rechecks of the campaign's verifier failures pass right meshes, fail wrong ones"
python3 fuzz/test_recheck.py
if [ -d ../shared/data/2d ]; then
  echo "== conformance against ../shared/data/2d"
  bash conformance/run2d.sh
  echo "== conformance against ../shared/data/3d"
  bash conformance/run3d.sh
else
  echo "== conformance skipped: ../shared not found"
fi
if [ -d ../shared/data/3d ] && [ -f ../shared/tools/verify3d.py ]; then
  echo "== a verified fuzz campaign: 300 runs per dimension (seed 1), every mesh through the shared verifiers"
  cargo build --release --quiet --example fuzz_campaign
  for d in 2d 3d; do
    out="/tmp/idmesh-campaign-$d"
    rm -rf "$out"
    IDMESH_CAMPAIGN_DUMP="$out" target/release/examples/fuzz_campaign "$d" 1 0..300 > "$out.log" 2>&1
    sed -n '/campaign, seed/,$p' "$out.log"
    if grep -qE 'INTERNAL|HANG|panic|other error' "$out.log"; then
      echo "the campaign failed:"; grep -A1 '^run ' "$out.log" | head -20; exit 1
    fi
    bash fuzz/verify_campaign.sh "$out" ../shared/tools | tail -3
  done
fi
echo "== the same meshes on 1 and 2 threads (scripts/digest.sh: conformance cases, examples, campaign runs)"
for t in 1 2; do
  IDMESH_THREADS=$t CAMPAIGN=300 bash scripts/digest.sh \
    > "/tmp/idmesh-digest-$t.txt" || { echo "scripts/digest.sh failed"; exit 1; }
done
[ -s /tmp/idmesh-digest-1.txt ] || { echo "scripts/digest.sh digested nothing"; exit 1; }
diff /tmp/idmesh-digest-1.txt /tmp/idmesh-digest-2.txt \
  || { echo "the meshes above differ between 1 and 2 threads"; exit 1; }
echo "$(wc -l < /tmp/idmesh-digest-1.txt) meshes identical on 1 and 2 threads"
echo "== all tests passed"
