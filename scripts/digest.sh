#!/usr/bin/env bash
# Digests of idmesh's meshes, to show that a refactor leaves them unchanged (issue 11: "the
# meshes do not change unless a change is a deliberate fix").
#
# Meshes every conformance case (conformance/cases2d.txt and cases3d.txt, inputs from
# ../shared/data; skipped when it is absent) and every input of examples/data with its usual
# switches, and, with CAMPAIGN=N, the first N runs of the fuzz campaign in 2D and 3D
# (examples/fuzz_campaign.rs, seed 1: perturbed, translated and scaled inputs, where ties and
# rounding show). Prints one line per mesh: a label and the SHA-256 of its output files (or
# the exit status when it fails), in a fixed order, so that
#
#   scripts/digest.sh > /tmp/before.txt     (on the old commit)
#   scripts/digest.sh | diff /tmp/before.txt -
#
# lists exactly the meshes that changed. Environment: IDMESH_BIN (an idmesh binary; default:
# build target/release/idmesh), CAMPAIGN (runs per dimension, default 0), CAMPAIGN_BIN (a
# fuzz_campaign binary; default: build target/release/examples/fuzz_campaign). Both are built
# before any run, so the sources may be edited while it runs.
set -uo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"
shared="$(cd "$root/.." && pwd)/shared"

work="$(mktemp -d "${TMPDIR:-/tmp}/idmesh-digest.XXXXXX")"
trap 'rm -rf "$work"' EXIT

# The absolute path of a binary: GIVEN when set, else `cargo build --release TARGET...` and a
# copy of target/release/BUILT in the work directory (so the sources may change meanwhile).
binary() {
    local given="$1" built="$2"
    shift 2
    if [ -n "$given" ]; then
        echo "$(cd "$(dirname "$given")" && pwd)/$(basename "$given")"
        return
    fi
    (cd "$root" && cargo build --release --quiet "$@") || {
        echo "digest: cargo build --release $* failed" >&2
        exit 1
    }
    cp "$root/target/release/$built" "$work/" && echo "$work/$(basename "$built")"
}

bin="$(binary "${IDMESH_BIN:-}" idmesh --bin idmesh)" || exit 1
campaign="${CAMPAIGN:-0}"
if [ "$campaign" -gt 0 ]; then
    cbin="$(binary "${CAMPAIGN_BIN:-}" examples/fuzz_campaign --example fuzz_campaign)" || exit 1
fi

# The digest of one run: idmesh DIM SWITCHES on FILE (copied with its .node into a fresh
# directory), hashing every output file in name order.
one() {
    local dim="$1" switches="$2" src="$3"
    local dir="$work/run" file stem
    rm -rf "$dir" && mkdir -p "$dir"
    file="$(basename "$src")"
    stem="${file%.*}"
    cp "$src" "$dir/"
    [ -f "${src%.*}.node" ] && [ "$file" != "$stem.node" ] && cp "${src%.*}.node" "$dir/"
    local label
    label="$(printf '%-8s %-28s %-18s' "$dim" "$file" "$switches")"
    local args=() rc
    [ -n "$switches" ] && args+=("$switches")
    (cd "$dir" && timeout 600 "$bin" "$dim" "${args[@]}" -Q "$file") >/dev/null 2>&1
    rc=$?
    if [ "$rc" -ne 0 ]; then
        echo "$label exit $rc"
        return
    fi
    local sum
    sum="$(cd "$dir" && ls "$stem".1.* 2>/dev/null | sort | xargs -r cat | sha256sum | cut -c1-16)"
    echo "$label $sum"
}

for dim in triangle tetgen; do
    d=2d
    [ "$dim" = tetgen ] && d=3d
    list="$root/conformance/cases$d.txt"
    [ -d "$shared/data/$d" ] || continue
    while IFS= read -r line || [ -n "$line" ]; do
        line="${line%%#*}"
        read -r -a tok <<<"$line"
        [ "${#tok[@]}" -eq 0 ] && continue
        [ -f "$shared/data/$d/${tok[0]}" ] || continue
        one "$dim" "${tok[1]:-}" "$shared/data/$d/${tok[0]}"
    done <"$list"
done

for f in "$root"/examples/data/*; do
    case "$f" in
        */3d_points.node) one tetgen "" "$f" ;;
        */3d_*) one tetgen "-pq" "$f" ;;
        */points.node) one triangle "" "$f" ;;
        *.poly) one triangle "-pq30" "$f" ;;
    esac
done

if [ "$campaign" -gt 0 ]; then
    for d in 2d 3d; do
        out="$work/campaign$d"
        IDMESH_CAMPAIGN_DUMP="$out" "$cbin" "$d" 1 \
            "0..$campaign" >/dev/null 2>&1
        # One line per run that gave a mesh: its output files hashed together.
        for node in $(ls "$out"/r*.node 2>/dev/null | sort -V); do
            r="$(basename "$node" .node)"
            printf '%-8s %-28s %-18s %s\n' "campaign" "$d/$r" "" \
                "$(cat "$out/$r".node "$out/$r".ele "$out/$r".face 2>/dev/null | sha256sum | cut -c1-16)"
        done
    done
fi
