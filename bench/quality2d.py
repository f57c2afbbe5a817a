#!/usr/bin/env python3
"""Mesh size next to small angles and thin channels: idmesh against Triangle (issue 13, item 5).

For every member of the 2D family (tests/data/family2d/*.poly, written by bench/family2d.py)
and every angle bound (default 30 and 33 degrees) it runs
  * idmesh:      `target/release/idmesh triangle -pq<angle>Q FILE` (a whole process, output
                 files written to a temporary directory and read back),
  * Triangle:    `triangle.triangulate(poly, 'pq<angle>Q')` from PyPI `triangle`,
  * Triangle -D: the same with `D` (conforming Delaunay, what idmesh always makes),
and prints one table row per case: triangle counts, idmesh's count over the smaller Triangle
count, the smallest angle, how many triangles lie below the bound, and times. Triangle counts
are deterministic, so machine load changes only the times.

With --verify every idmesh mesh also goes through /work/shared/tools/verify2d.py
(`--min-angle A --require-delaunay`); the column `verify` then shows its verdict and its count
of triangles below the bound that no small-angle rule explains (must be 0).

    cargo build --release
    python3 bench/quality2d.py [--angles 30,33] [--only star-5-10,slot-50] [--verify]
"""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from bench2d import min_angle_deg, read_poly  # noqa: E402

FAMILY = os.path.join(ROOT, "tests", "data", "family2d")
IDMESH = os.path.join(ROOT, "target", "release", "idmesh")
VERIFY2D = "/work/shared/tools/verify2d.py"


def angles_deg(xy, tris):
    """Smallest angle of every triangle, in degrees."""
    p = [xy[tris[:, k]] for k in range(3)]
    out = np.full(len(tris), np.inf)
    for a, b, c in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        u = p[b] - p[a]
        v = p[c] - p[a]
        cross = np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
        dot = u[:, 0] * v[:, 0] + u[:, 1] * v[:, 1]
        out = np.minimum(out, np.degrees(np.arctan2(cross, dot)))
    return out


def read_table(path, cols, dtype):
    rows = []
    with open(path) as f:
        lines = (ln.split("#", 1)[0].split() for ln in f)
        lines = [t for t in lines if t]
    n = int(lines[0][0])
    base = int(lines[1][0]) if n else 0
    for t in lines[1:1 + n]:
        rows.append([dtype(x) for x in t[1:1 + cols]])
    return np.array(rows, dtype=dtype).reshape(-1, cols), base


def run_idmesh(idmesh, poly, angle, tmp, verify):
    name = os.path.basename(poly)
    local = os.path.join(tmp, name)
    shutil.copyfile(poly, local)
    t0 = time.perf_counter()
    r = subprocess.run([idmesh, "triangle", f"-pq{angle}Q", local], capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if r.returncode != 0:
        return {"error": r.stderr.strip()[-200:]}
    stem = local[: -len(".poly")] + ".1"
    xy, _ = read_table(stem + ".node", 2, float)
    tris, base = read_table(stem + ".ele", 3, int)
    tris = tris - (base if base else 0)
    ang = angles_deg(xy, tris)
    res = {"n": len(tris), "min": float(ang.min()), "below": int((ang < float(angle)).sum()),
           "time": dt}
    if verify:
        v = subprocess.run([sys.executable, VERIFY2D, poly, stem + ".node", stem + ".ele",
                            "--min-angle", str(angle), "--require-delaunay", "--json"],
                           capture_output=True, text=True)
        res["verify"] = "ok"
        res["unexplained"] = None
        try:
            import json
            j = json.loads(v.stdout.strip().splitlines()[-1])
            res["unexplained"] = find_key(j, "below_min_angle_unexplained")
            failed = [k for k, c in j.get("checks", {}).items()
                      if isinstance(c, dict) and c.get("ok") is False]
        except (ValueError, KeyError):
            failed = []
        if v.returncode != 0:
            res["verify"] = "FAIL " + ",".join(failed)
    return res


def find_key(j, word):
    """The first number under a key containing `word` in verify2d's JSON report."""
    if isinstance(j, dict):
        for k, v in j.items():
            if k == word and isinstance(v, (int, float)):
                return v
        for v in j.values():
            x = find_key(v, word)
            if x is not None:
                return x
    elif isinstance(j, list):
        for v in j:
            x = find_key(v, word)
            if x is not None:
                return x
    return None


def run_triangle(poly, switches):
    import triangle
    d = read_poly(poly)
    t0 = time.perf_counter()
    out = triangle.triangulate(d, switches)
    dt = time.perf_counter() - t0
    xy, tris = out["vertices"], out["triangles"]
    ang = angles_deg(xy, tris)
    angle = float(switches.split("q")[1].rstrip("DQ"))
    return {"n": len(tris), "min": float(ang.min()), "below": int((ang < float(angle)).sum()),
            "time": dt}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--angles", default="30,33")
    ap.add_argument("--only", default="")
    ap.add_argument("--verify", action="store_true")
    ap.add_argument("--idmesh", default=IDMESH, help="the idmesh binary (default: %(default)s)")
    args = ap.parse_args()
    if not os.path.exists(args.idmesh):
        sys.exit(f"{args.idmesh} missing: run cargo build --release first")
    names = sorted(f[:-5] for f in os.listdir(FAMILY) if f.endswith(".poly"))
    if args.only:
        names = [n for n in names if n in args.only.split(",")]
    head = ("| input | -q | idmesh | Triangle | Triangle -D | idmesh / min(T, T -D) | "
            "min angle idmesh / T / T -D | below bound idmesh / T / T -D | "
            "time idmesh / T / T -D (ms) |")
    if args.verify:
        head += " verify2d (unexplained) |"
    print(head)
    print("|" + "---|" * (head.count("|") - 1))
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            poly = os.path.join(FAMILY, name + ".poly")
            for angle in args.angles.split(","):
                i = run_idmesh(args.idmesh, poly, angle, tmp, args.verify)
                t = run_triangle(poly, f"pq{angle}Q")
                td = run_triangle(poly, f"pq{angle}DQ")
                if "error" in i:
                    print(f"| {name} | {angle} | error: {i['error']} |")
                    continue
                ratio = i["n"] / min(t["n"], td["n"])
                row = (f"| {name} | {angle} | {i['n']} | {t['n']} | {td['n']} | {ratio:.2f} | "
                       f"{i['min']:.2f} / {t['min']:.2f} / {td['min']:.2f} | "
                       f"{i['below']} / {t['below']} / {td['below']} | "
                       f"{1e3 * i['time']:.0f} / {1e3 * t['time']:.0f} / "
                       f"{1e3 * td['time']:.0f} |")
                if args.verify:
                    row += f" {i['verify']} ({i['unexplained']}) |"
                print(row, flush=True)


if __name__ == "__main__":
    main()
