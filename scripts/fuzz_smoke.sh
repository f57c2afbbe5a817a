#!/usr/bin/env bash
# A short run of cargo-fuzz targets (fuzz/fuzz_targets), about SECONDS seconds each (default
# 60): by default all of them, the readers, the C API call sequences and the structure-aware
# meshing targets (mesh2d, mesh3d), each from its committed corpus (fuzz/corpus/TARGET), which
# libFuzzer replays in full first (the meshing corpora take about 2 and 3 minutes).
# Any crash, panic, internal error from a meshing target, mesh returned as a success that
# fails validate(), or input that runs past the time limit fails the run and leaves the input
# under fuzz/artifacts/.
# A fixed seed (-seed=1) keeps the CI run repeatable: a failure there fails again on rerun.
# Installs cargo-fuzz (and uses the nightly toolchain) when missing.
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
SECONDS_PER_TARGET="${1:-60}"
shift || true
TARGETS="${*:-read_tetgen read_surface read_triangle c_api mesh2d mesh3d}"
if ! cargo +nightly --version >/dev/null 2>&1; then
  echo "== fuzz smoke skipped: no nightly toolchain"; exit 0
fi
if ! cargo fuzz --version >/dev/null 2>&1; then
  echo "== installing cargo-fuzz"
  cargo install -q cargo-fuzz
fi
cargo +nightly fuzz build -O 2>&1 | grep -E '^(error|warning)' -A5 || true
for t in $TARGETS; do
  mkdir -p "corpus/$t"
  # A private copy of the corpus: the committed seeds stay as they are.
  work=$(mktemp -d)
  cp -r "corpus/$t/." "$work/"
  echo "== fuzz $t (${SECONDS_PER_TARGET} s)"
  if ! cargo +nightly fuzz run -O "$t" "$work" -- -max_total_time="$SECONDS_PER_TARGET" \
      -seed=1 -timeout=20 -rss_limit_mb=4096 -max_len=4096 -print_final_stats=0 >"$work.log" 2>&1; then
    tail -40 "$work.log"
    echo "fuzz target $t failed (input under fuzz/artifacts/$t)"; exit 1
  fi
  grep -E '^Done [0-9]+ runs' "$work.log" || true
  rm -rf "$work" "$work.log"
done
