#!/usr/bin/env bash
# 2D conformance check: meshes every case of conformance/cases2d.txt with
# `idmesh triangle` and judges the output with the shared verifier
# (../shared/tools/verify2d.py, relative to the repository root).
#
# Usage: conformance/run2d.sh            (from any directory)
# Environment:
#   IDMESH_BIN       use this idmesh binary instead of building target/release/idmesh
#   IDMESH_TIMEOUT   seconds allowed per idmesh run (default 600)
#   KEEP_WORK=1      keep the temporary directory with every case's files
#
# Prints one line per case (PASS/FAIL, triangle count, meshing time), the verifier's
# failing checks under a failed case, and a final "N passed, M failed" line.
# Exit status: 0 when every case passes or when ../shared is absent (skipped), 1 otherwise.
set -uo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"
shared="$(cd "$root/.." && pwd)/shared"
data="$shared/data/2d"
verifier="$shared/tools/verify2d.py"
cases="$here/cases2d.txt"

if [ ! -d "$data" ] || [ ! -f "$verifier" ]; then
    echo "run2d: $shared (data/2d and tools/verify2d.py) not found; skipping the 2D conformance check"
    exit 0
fi

if ! python3 -c 'import numpy, scipy' 2>/dev/null; then
    echo "run2d: installing numpy and scipy for the verifier"
    python3 -m pip install --quiet numpy scipy 2>/dev/null \
        || python3 -m pip install --quiet --break-system-packages numpy scipy \
        || { echo "run2d: cannot install numpy/scipy"; exit 1; }
fi

if [ -n "${IDMESH_BIN:-}" ]; then
    # Made absolute: every case runs in its own directory.
    case "$IDMESH_BIN" in
        */*) bin="$(cd "$(dirname "$IDMESH_BIN")" && pwd)/$(basename "$IDMESH_BIN")" ;;
        *) bin="$(command -v "$IDMESH_BIN")" ;;
    esac
    [ -x "$bin" ] || { echo "run2d: IDMESH_BIN=$IDMESH_BIN is not an executable"; exit 1; }
else
    (cd "$root" && cargo build --release --quiet --bin idmesh) || {
        echo "run2d: cargo build --release failed"
        exit 1
    }
    bin="$root/target/release/idmesh"
fi
timeout_s="${IDMESH_TIMEOUT:-600}"

work="$(mktemp -d "${TMPDIR:-/tmp}/idmesh-conformance.XXXXXX")"
if [ "${KEEP_WORK:-0}" = 1 ]; then
    echo "run2d: keeping work files in $work"
else
    trap 'rm -rf "$work"' EXIT
fi

# Writes INPUT.poly plus the segments of its convex hull (exact orientation tests with
# fractions) as OUTPUT.poly, for verifying -c runs.
cat >"$work/add_hull.py" <<'PY'
import sys
from fractions import Fraction

def records(path):
    with open(path) as f:
        for line in f:
            fields = line.split('#')[0].split()
            if fields:
                yield fields

def main(src, dst):
    rows = list(records(src))
    n, i = int(rows[0][0]), 1
    if n == 0:
        node = list(records(src[:-len('.poly')] + '.node'))
        vrows = node[1:1 + int(node[0][0])]
    else:
        vrows, i = rows[1:1 + n], 1 + n
    base = 0 if int(vrows[0][0]) == 0 else 1
    pts = [(float(r[1]), float(r[2])) for r in vrows]
    ns = int(rows[i][0])
    segs = [(int(r[1]) - base, int(r[2]) - base) for r in rows[i + 1:i + 1 + ns]]
    i += 1 + ns
    nh = int(rows[i][0])
    holes = rows[i + 1:i + 1 + nh]
    i += 1 + nh
    regions = rows[i + 1:i + 1 + int(rows[i][0])] if i < len(rows) else []

    def cross(o, a, b):
        o, a, b = pts[o], pts[a], pts[b]
        return ((Fraction(a[0]) - Fraction(o[0])) * (Fraction(b[1]) - Fraction(o[1]))
                - (Fraction(a[1]) - Fraction(o[1])) * (Fraction(b[0]) - Fraction(o[0])))

    order = sorted(set(range(len(pts))), key=lambda k: pts[k])
    hull = []
    for chain in (order, order[::-1]):
        part = []
        for k in chain:
            while len(part) >= 2 and cross(part[-2], part[-1], k) <= 0:
                part.pop()
            part.append(k)
        hull += part[:-1]
    have = {frozenset(s) for s in segs}
    for a, b in zip(hull, hull[1:] + hull[:1]):
        if frozenset((a, b)) not in have:
            segs.append((a, b))
    with open(dst, 'w') as f:
        f.write(f"{len(pts)} 2 0 0\n")
        for k, (x, y) in enumerate(pts):
            f.write(f"{k} {x!r} {y!r}\n")
        f.write(f"{len(segs)} 0\n")
        for k, (a, b) in enumerate(segs):
            f.write(f"{k} {a} {b}\n")
        f.write(f"{len(holes)}\n")
        for r in holes:
            f.write(" ".join(r) + "\n")
        f.write(f"{len(regions)}\n")
        for r in regions:
            f.write(" ".join(r) + "\n")

main(sys.argv[1], sys.argv[2])
PY

# First field of the first non-comment line of a file (the item count of a Triangle file).
count_of() {
    awk '{ sub(/#.*/, "") } NF { print $1; exit }' "$1" 2>/dev/null
}

passed=0
failed=0
listed=" "
case_no=0
while IFS= read -r line || [ -n "$line" ]; do
    line="${line%%#*}"
    read -r -a tok <<<"$line"
    [ "${#tok[@]}" -eq 0 ] && continue
    case_no=$((case_no + 1))
    file="${tok[0]}"
    switches="${tok[1]:-}"
    listed="$listed$file "
    expect_empty=0
    hull=0
    extra=()
    for t in "${tok[@]:2}"; do
        case "$t" in
            --expect-empty) expect_empty=1 ;;
            --hull) hull=1 ;;
            *) extra+=("$t") ;;
        esac
    done
    label="$(printf '%-26s %-16s' "$file" "$switches")"
    dir="$work/case$case_no"
    mkdir -p "$dir"
    if [ ! -f "$data/$file" ]; then
        echo "FAIL $label input $data/$file not found"
        failed=$((failed + 1))
        continue
    fi
    cp "$data/$file" "$dir/"
    stem="${file%.*}"
    [ -f "$data/$stem.node" ] && [ "$file" != "$stem.node" ] && cp "$data/$stem.node" "$dir/"

    t0=$(date +%s.%N)
    (cd "$dir" && timeout "$timeout_s" "$bin" triangle "$switches" -Q "$file") \
        >"$dir/idmesh.out" 2>&1
    rc=$?
    t1=$(date +%s.%N)
    secs=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", b - a }')
    ntri="$(count_of "$dir/$stem.1.ele")"
    ntri="${ntri:-?}"
    result="$(printf '%8s triangles %7s s' "$ntri" "$secs")"

    if [ "$rc" -ne 0 ]; then
        echo "FAIL $label idmesh exit $rc after $secs s"
        sed 's/^/       /' "$dir/idmesh.out" | tail -5
        failed=$((failed + 1))
        continue
    fi
    if [ "$expect_empty" = 1 ]; then
        if [ "$ntri" = 0 ]; then
            echo "PASS $label $result (empty, as expected)"
            passed=$((passed + 1))
        else
            echo "FAIL $label $result (expected no triangles)"
            failed=$((failed + 1))
        fi
        continue
    fi
    vinput="$dir/$file"
    if [ "$hull" = 1 ]; then
        vinput="$dir/${stem}_with_hull.poly"
        python3 "$work/add_hull.py" "$dir/$file" "$vinput" || {
            echo "FAIL $label cannot add hull segments"
            failed=$((failed + 1))
            continue
        }
    fi
    if python3 "$verifier" "$vinput" "$dir/$stem.1.node" "$dir/$stem.1.ele" \
        --require-delaunay "${extra[@]}" >"$dir/verify.out" 2>&1; then
        echo "PASS $label $result"
        passed=$((passed + 1))
    else
        echo "FAIL $label $result"
        grep -E '\[FAIL\]|^ *!|Error|error' "$dir/verify.out" | head -12 | sed 's/^/       /'
        failed=$((failed + 1))
    fi
done <"$cases"

# Every input in the shared data set must have at least one case.
for f in "$data"/*.poly "$data"/*.node; do
    [ -e "$f" ] || continue
    name="$(basename "$f")"
    case "$listed" in
        *" $name "*) ;;
        *)
            # A .node that only holds the vertices of a listed .poly needs no case.
            if [ "${name##*.}" = node ] && [ -f "$data/${name%.node}.poly" ]; then continue; fi
            echo "FAIL $(printf '%-26s' "$name") has no case in conformance/cases2d.txt"
            failed=$((failed + 1))
            ;;
    esac
done

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
