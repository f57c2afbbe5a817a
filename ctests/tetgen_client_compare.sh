#!/usr/bin/env bash
# Runs tetgen_client built against Debian's libtet and against idmesh, and checks that both
# report the same volume per region and the same area per boundary marker (to 1e-9), i.e. valid
# meshes of the same domain (each client checks its own mesh's validity and exits 1 if not).
#   tetgen_client_compare.sh DEBIAN_CLIENT IDMESH_CLIENT
set -euo pipefail
debian=$("$1")
ours=$("$2")
echo "$ours"
[[ -n "$ours" ]] || { echo "FAIL: no output from $2" >&2; exit 1; }
round() { awk '{ $NF = sprintf("%.9f", $NF); print }'; }
if ! diff <(round <<<"$debian") <(round <<<"$ours"); then
  echo "FAIL: region volumes or marker areas differ (< TetGen, > idmesh)" >&2
  exit 1
fi
echo "OK: the same regions and boundary markers as TetGen"
