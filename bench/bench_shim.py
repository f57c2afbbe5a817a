#!/usr/bin/env python3
"""The TetGen compatibility layer's overhead (issue 10): compat/tetgen's tetrahedralize against
idmesh's own C API on the same ~1M-tetrahedron run.

bench/shim_bench3d.cpp meshes the unit cube with radius-edge 1.414 and the volume bound V
(2e-6, ~1M tetrahedra; 2e-5 with --quick) in one of two modes, each in a fresh process,
interleaved (capi, shim, capi, ...):
  capi  idm_mesher3d_* calls, the output copied into the caller's arrays;
  shim  tetgenio + tetrahedralize("pq1.414a<V>Q"), which fills tetgenio's arrays
        (pointlist, pointmarkerlist, tetrahedronlist, trifacelist + markers, point2tetlist).
The time is each process's own wall clock from building the input to having the output in the
caller's arrays. The table gives the median and best time per mode and the shim's median over
the C API's. Target (issue 10): shim <= 1.05 x C API.

The program is built by the script with g++ -O2 -Wall -Wextra -Werror from
bench/shim_bench3d.cpp and compat/tetgen/tetgen.cxx, linked with target/release/libidmesh.a
(cargo build --release --lib), so both modes run the same machine code.

Usage: python3 bench/bench_shim.py [--quick] [--volume V] [--repeat K] [--markdown]
                                   [--timeout S]
Outputs go to target/bench_shim/.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WORK = os.path.join(ROOT, "target", "bench_shim")


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def build():
    log("building libidmesh (cargo build --release --lib) ...")
    subprocess.run(["cargo", "build", "--release", "--lib"], cwd=ROOT, check=True)
    os.makedirs(WORK, exist_ok=True)
    exe = os.path.join(WORK, "shim_bench3d")
    lib = os.path.join(ROOT, "target", "release")
    cmd = [
        "g++", "-O2", "-std=c++17", "-Wall", "-Wextra", "-Werror",
        "-I", os.path.join(ROOT, "compat", "tetgen"), "-I", os.path.join(ROOT, "include"),
        os.path.join(ROOT, "bench", "shim_bench3d.cpp"),
        os.path.join(ROOT, "compat", "tetgen", "tetgen.cxx"),
        os.path.join(lib, "libidmesh.a"), "-lpthread", "-ldl", "-lm", "-o", exe,
    ]
    log("building " + exe + " ...")
    subprocess.run(cmd, check=True)
    return exe


def run(exe, mode, volume, timeout):
    p = subprocess.run([exe, mode, repr(volume)], capture_output=True, text=True,
                       timeout=timeout)
    if p.returncode != 0:
        raise SystemExit(f"{mode} failed ({p.returncode}): {p.stderr.strip()}")
    return json.loads(p.stdout.strip().splitlines()[-1])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="V = 2e-5 (~100k tetrahedra)")
    ap.add_argument("--volume", type=float, help="the volume bound (default 2e-6)")
    ap.add_argument("--repeat", type=int, default=3, help="runs per mode (default 3)")
    ap.add_argument("--markdown", action="store_true", help="print a Markdown table")
    ap.add_argument("--timeout", type=float, default=600, help="seconds per run")
    a = ap.parse_args()
    volume = a.volume or (2e-5 if a.quick else 2e-6)
    exe = build()
    runs = {"capi": [], "shim": []}
    for k in range(a.repeat):
        for mode in ("capi", "shim"):
            r = run(exe, mode, volume, a.timeout)
            log(f"run {k + 1}/{a.repeat} {mode}: {r['seconds']:.3f} s, {r['tets']} tets")
            runs[mode].append(r)
    tets = {m: {r["tets"] for r in rs} for m, rs in runs.items()}
    if tets["capi"] != tets["shim"] or len(tets["capi"]) != 1:
        raise SystemExit(f"the modes made different meshes: {tets}")
    med = {m: statistics.median(r["seconds"] for r in rs) for m, rs in runs.items()}
    best = {m: min(r["seconds"] for r in rs) for m, rs in runs.items()}
    ratio = med["shim"] / med["capi"]
    n = tets["capi"].pop()
    if a.markdown:
        print(f"Unit cube, -pq1.414a{volume:g}: {n} tetrahedra, {a.repeat} runs per mode.\n")
        print("| mode | median s | best s |")
        print("|---|---|---|")
        for m, name in (("capi", "idmesh C API"), ("shim", "compat/tetgen tetrahedralize")):
            print(f"| {name} | {med[m]:.3f} | {best[m]:.3f} |")
        print(f"\nShim / C API (median): {ratio:.3f} (target <= 1.05).")
    else:
        print(f"{n} tetrahedra; C API median {med['capi']:.3f} s (best {best['capi']:.3f}); "
              f"shim median {med['shim']:.3f} s (best {best['shim']:.3f}); "
              f"shim / C API {ratio:.3f} (target <= 1.05)")


if __name__ == "__main__":
    main()
