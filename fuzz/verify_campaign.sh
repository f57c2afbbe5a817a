#!/usr/bin/env bash
# Runs the independent checkers of ../shared/tools over the meshes a fuzz campaign dumped
# (IDMESH_CAMPAIGN_DUMP=DIR, see examples/fuzz_campaign.rs): verify2d.py where a case has no
# .face file, verify3d.py where it has one, with the options in its .args file
# (--require-delaunay except under -Y). A 2D case that verify2d.py fails on conformity alone is
# looked at again exactly by fuzz/recheck2d.py (verify2d.py's 16-ulp tolerance puts vertices of
# one segment's chain on a neighbouring segment: see there); it counts as rechecked when every
# segment is a chain of output edges or lies outside the domain. Likewise a 3D case that
# verify3d.py fails only on what it measures in floating point (tets not winding once around a
# vertex or edge, facets partly covered, segment pieces, sides not shown exterior) is decided
# again exactly by fuzz/recheck3d.py (see fuzz/recheck3d_if_float.sh). A checker that does not
# finish within VERIFY_TIMEOUT seconds (default 900) fails the case: verify2d.py ran for more
# than 26 minutes on one 2D case of 20,012 vertices clustered at the ulp scale of coordinates
# near 8e6 (seed 1 run 4942), and a run must not wait for ever. Prints each failing case and
# the counts; exit status 1 if any case fails.
#   fuzz/verify_campaign.sh DIR [TOOLS-DIR]
set -u
dir=${1:?usage: verify_campaign.sh DIR [TOOLS-DIR]}
tools=${2:-$(dirname "$0")/../../shared/tools}
limit=${VERIFY_TIMEOUT:-900}
pass=0
rechecked=0
fail=0
for poly in "$dir"/r*.poly; do
    [ -e "$poly" ] || continue
    b=${poly%.poly}
    read -r args < "$b.args" || args=
    if [ -e "$b.face" ]; then
        # shellcheck disable=SC2086
        out=$(timeout "$limit" python3 "$tools/verify3d.py" "$poly" "$b.node" "$b.ele" "$b.face" $args 2>&1)
    else
        # shellcheck disable=SC2086
        out=$(timeout "$limit" python3 "$tools/verify2d.py" "$poly" "$b.node" "$b.ele" $args 2>&1)
    fi
    status=$?
    if [ $status -eq 124 ]; then
        fail=$((fail + 1))
        echo "FAIL $b ($args): the checker did not finish within $limit s (VERIFY_TIMEOUT)"
        continue
    fi
    if [ $status -ne 0 ] && [ ! -e "$b.face" ] \
        && ! echo "$out" | grep '\[FAIL\]' | grep -qv '\[FAIL\] conformity'; then
        if python3 "$(dirname "$0")/recheck2d.py" "$poly" "$b.node" "$b.ele" > /dev/null; then
            rechecked=$((rechecked + 1))
            echo "RECHECKED $b: verify2d.py's conformity failure does not stand the exact recheck (fuzz/recheck2d.py)"
            continue
        fi
    fi
    if [ $status -ne 0 ] && [ -e "$b.face" ] \
        && echo "$out" | "$(dirname "$0")/recheck3d_if_float.sh" /dev/stdin \
            "$poly" "$b.node" "$b.ele" "$b.face"; then
        rechecked=$((rechecked + 1))
        echo "RECHECKED $b: verify3d.py's failure does not stand the exact recheck (fuzz/recheck3d.py)"
        continue
    fi
    if [ $status -eq 0 ]; then
        pass=$((pass + 1))
    else
        fail=$((fail + 1))
        echo "FAIL $b ($args)"
        echo "$out" | grep -v '^ *ok\|PASS' | head -8 | sed 's/^/    /'
    fi
done
echo "verified: $pass passed, $rechecked passed the exact recheck, $fail failed ($dir)"
[ "$fail" -eq 0 ]
