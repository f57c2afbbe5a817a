#!/usr/bin/env bash
# Runs Debian's unchanged /usr/bin/tetgen on our libtet.so.1.5 (LD_LIBRARY_PATH) and checks
# that our library was loaded, that it exports Debian's tetgenio methods, and that every
# written mesh passes tetgen_check_mesh.
#   tetgen_binary.sh LIBDIR CHECKER DATADIR[:PREFIX]...
# Every .poly/.smesh/.off/.stl/.ply/.mesh file (named PREFIX*) of the first existing DATADIR is
# meshed (a file idmesh itself fails on must fail here too) with
# -pq1.414; the smallest one also with -pq1.414a<volume> (its volume bound checked), and that
# mesh refined with -rq1.414a<volume/4>.
set -euo pipefail
# Absolute paths: the meshing runs in a scratch directory.
libdir=$(readlink -f "$1"); checker=$(readlink -f "$2"); shift 2
tetgen=/usr/bin/tetgen
data=""
prefix=""
for arg in "$@"; do
  d="${arg%%:*}"
  if [[ -d "$d" ]]; then
    data="$d"
    [[ "$arg" == *:* ]] && prefix="${arg#*:}"
    break
  fi
done
[[ -n "$data" ]] || { echo "no data directory among: $*" >&2; exit 1; }

loaded=$(LD_LIBRARY_PATH="$libdir" ldd "$tetgen" | awk '$1 == "libtet.so.1.5" {print $3}')
if [[ "$(readlink -f "$loaded")" != "$(readlink -f "$libdir/libtet.so.1.5")" ]]; then
  echo "FAIL: $tetgen loads '$loaded', not $libdir/libtet.so.1.5" >&2
  exit 1
fi
echo "ldd: $tetgen loads $loaded"

# Every tetgenio method Debian's libtet exports, ours exports too (a program may call any).
defined() { nm -DC --defined-only "$1" | sed -E 's/^[0-9a-f]+ [A-Za-z] //' | grep '^tetgenio::' | sort -u; }
debian=$(ldd "$tetgen" | awk '$1 == "libtet.so.1.5" {print $3}')
if [[ -f "$debian" ]]; then
  missing=$(comm -23 <(defined "$debian") <(defined "$libdir/libtet.so.1.5"))
  if [[ -n "$missing" ]]; then
    echo "FAIL: tetgenio methods of $debian missing from ours:" >&2
    echo "$missing" >&2
    exit 1
  fi
  echo "symbols: every tetgenio method of $debian is exported"
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
n=0
smallest=""
for ext in poly smesh off stl ply mesh; do
 for f in "$data/$prefix"*."$ext"; do
  [[ -f "$f" ]] || continue
  name=$(basename "$f")
  stem="${name%.*}"
  cp "$f" "$work/"
  # A .smesh or .poly may take its points from the .node beside it.
  [[ -f "${f%.*}.node" ]] && cp "${f%.*}.node" "$work/"
  if ! (cd "$work" && LD_LIBRARY_PATH="$libdir" timeout 600 "$tetgen" -pq1.414Q "$name" 2>"$work/stderr"); then
    # Input idmesh itself refuses (e.g. a non-planar facet) or fails on must fail here too.
    if "$checker" --fails "$work/$name" pq1.414; then
      echo "$name: tetgen on our library fails as idmesh does"
      continue
    fi
    cat "$work/stderr" >&2
    echo "FAIL: tetgen -pq1.414 $name failed" >&2
    exit 1
  fi
  "$checker" "$work/$name" "$work/$stem.1"
  n=$((n + 1))
  if [[ -z "$smallest" || $(stat -c %s "$f") -lt $(stat -c %s "$smallest") ]]; then
    smallest="$f"
  fi
 done
done
[[ $n -gt 0 ]] || { echo "no input files in $data" >&2; exit 1; }

# -a: a volume bound of 1/1000 of the domain's bounding box volume.
name=$(basename "$smallest"); stem="${name%.*}"
box=$(awk 'NR > 1 && NF >= 4 {for (k = 2; k <= 4; k++) {if (!(k in lo) || $k < lo[k]) lo[k] = $k; if (!(k in hi) || $k > hi[k]) hi[k] = $k}}
           END {printf "%.6g", (hi[2]-lo[2])*(hi[3]-lo[3])*(hi[4]-lo[4]) / 1000}' "$work/$stem.1.node")
(cd "$work" && rm -f "$stem".1.* && LD_LIBRARY_PATH="$libdir" "$tetgen" -pq1.414a"$box"Q "$name")
"$checker" "$work/$name" "$work/$stem.1" "$box"

# -r: that mesh refined again (load_tetmesh reads .node + .ele + .face) to a quarter of the
# bound; the result must still mesh the same domain.
quarter=$(awk -v b="$box" 'BEGIN {printf "%.6g", b / 4}')
(cd "$work" && LD_LIBRARY_PATH="$libdir" "$tetgen" -rq1.414a"$quarter"Q "$stem.1")
"$checker" "$work/$name" "$work/$stem.2" "$quarter"
echo "OK: $n files with -pq1.414, $name with -pq1.414a$box and -rq1.414a$quarter"
