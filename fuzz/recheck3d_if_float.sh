#!/usr/bin/env bash
# Whether a verify3d.py failure stands: exit status 0 when every claim it fails is one it
# decides in floating point (tets not winding exactly once around a vertex or edge, facets
# partly covered, segment pieces, sides not shown exterior: only its topology and conformity
# checks failed) and fuzz/recheck3d.py decides those claims exactly in the mesh's favour;
# 1 otherwise. Used by fuzz/verify_campaign.sh and conformance/run3d.sh.
#   fuzz/recheck3d_if_float.sh VERIFY3D-OUTPUT-FILE CASE.poly CASE.node CASE.ele CASE.face
set -u
out=${1:?usage: recheck3d_if_float.sh VERIFY3D-OUTPUT-FILE POLY NODE ELE FACE}
shift
float_claims='do not wind exactly once\|only partly covered by output faces\|segment pieces are not unions of output edges\|could not be proven exterior'
text=$(cat "$out")  # read once: the output may come on a pipe
fails=$(echo "$text" | grep '\[FAIL\]') || exit 1
echo "$fails" | grep -qv '\[FAIL\] \(topology\|conformity\)' && exit 1
echo "$text" | grep '^ *! ' | grep -qv "$float_claims" && exit 1
python3 "$(dirname "$0")/recheck3d.py" "$@" > /dev/null
