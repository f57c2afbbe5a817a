#!/usr/bin/env python3
"""3D mesh quality side by side (issue 13): idmesh vs TetGen (Debian's `tetgen`) at -pq1.414.

For each input, at `-pq1.414` and at `-pq1.414a<V>` with V chosen for about 100,000 tets (and,
with --large, about 1,000,000), both tools run as users run them, in fresh processes, on their
own copies of the file:
    target/release/idmesh tetgen -pq1.414[a<V>]V FILE      (-V: its report, see below)
    tetgen -pq1.414[a<V>]Q FILE                            (TetGen's default -O2/7 included)
    target/release/idmesh tetgen -pq1.414/0[a<V>]Q FILE    ("idmesh /0": no sliver removal)
The time is the whole process (read, mesh, write), the parent's wall clock. The quality figures
are computed here from the output .node/.ele files with one piece of numpy code for every tool:
    * the smallest and largest dihedral angle, the share of tets whose smallest dihedral angle
      is below 10 and 15 degrees, and of tets with one above 165 degrees;
    * "bad" = tets outside [15, 165] degrees, and how many of them touch a small input angle
      ("at sharp"), judged on the output mesh itself so that both tools are judged alike: a
      tet touches a small input angle if a vertex of it is on a mesh edge where the domain's
      dihedral angle (the sum of the tets' dihedral angles around the edge) is below 60
      degrees, or at a vertex where two crease edges (boundary edges whose domain angle is
      more than CREASE degrees from flat) meet below 60 degrees. Nearly flat facet pairs of a
      triangulated surface are no small input angle by this measure (idmesh's own exemption
      rule in src/mesh3d/plc.rs `Sharp` is broader; idmesh's own count is shown as "exempt");
      angles between interior facets are not seen (an interior edge sums to 360 degrees);
    * the largest radius-edge ratio (circumradius over shortest edge), and the share of tets
      above the bound 1.414 (issue 13, item 5: on the small-angle inputs no higher than
      TetGen's).
idmesh's first mesh of each case goes through ../shared/tools/verify3d.py --require-delaunay
(untimed; --no-verify skips it).

Inputs: the unit cube (examples/data/3d_cube.poly), ../shared/data/3d/{example.poly, sphere.off,
fandisk.off, pipe.off, wedge-1.smesh, spike-1-7.smesh, slit-1.smesh}, and a cylinder (a 48-sided prism, height twice the radius, written by
the script). Volume bounds: V = 2 x (domain volume / target tets), with the domain volume taken
from idmesh's -pq1.414 run (its -V "Volume:"), two significant digits.

Usage: python3 bench/quality3d.py [--inputs cube,example,...] [--large] [--no-plain]
                                  [--no-verify] [--markdown] [--timeout S] [--idmesh BINARY]
Outputs go to target/quality3d/.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# The project's shared data and tools: ../shared beside the repository (or beside the directory
# of worktrees holding it).
SHARED = next((d for d in (os.path.join(os.path.dirname(ROOT), "shared"),
                           os.path.join(os.path.dirname(os.path.dirname(ROOT)), "shared"))
               if os.path.isdir(d)), os.path.join(os.path.dirname(ROOT), "shared"))
DATA3D = os.path.join(SHARED, "data", "3d")
VERIFY3D = os.path.join(SHARED, "tools", "verify3d.py")
IDMESH = os.path.join(ROOT, "target", "release", "idmesh")
WORK = os.path.join(ROOT, "target", "quality3d")
RATIO = "1.414"
# A boundary edge whose domain dihedral angle is more than this many degrees from 180 is a
# crease (for the sharp-vertex test).
CREASE = 10.0
SHARP = 60.0

INPUTS = {
    "cube": os.path.join(ROOT, "examples", "data", "3d_cube.poly"),
    "example": os.path.join(DATA3D, "example.poly"),
    "sphere": os.path.join(DATA3D, "sphere.off"),
    "fandisk": os.path.join(DATA3D, "fandisk.off"),
    "pipe": os.path.join(DATA3D, "pipe.off"),
    "cylinder": None,  # written by the script
    # TetGen's small-angle test inputs (issue 13, item 5: the share of tets above the
    # radius-edge bound, against TetGen's, where input angles are small).
    "wedge": os.path.join(DATA3D, "wedge-1.smesh"),
    "spike": os.path.join(DATA3D, "spike-1-7.smesh"),
    "slit": os.path.join(DATA3D, "slit-1.smesh"),
}


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def write_cylinder(path, sides=48):
    """A cylinder of radius 1 and height 2 as a .poly: an n-gon prism."""
    import math
    pts = [(math.cos(2 * math.pi * k / sides), math.sin(2 * math.pi * k / sides), z)
           for z in (0.0, 2.0) for k in range(sides)]
    with open(path, "w") as f:
        f.write(f"# a {sides}-sided prism, written by bench/quality3d.py\n{len(pts)} 3 0 0\n")
        f.writelines(f"{i} {x!r} {y!r} {z!r}\n" for i, (x, y, z) in enumerate(pts, 1))
        f.write(f"{sides + 2} 0\n")
        f.write("1\n%d %s\n" % (sides, " ".join(str(k + 1) for k in range(sides))))
        f.write("1\n%d %s\n" % (sides, " ".join(str(sides + k + 1) for k in range(sides))))
        for k in range(sides):
            a, b = k + 1, (k + 1) % sides + 1
            f.write(f"1\n4 {a} {b} {b + sides} {a + sides}\n")
        f.write("0\n0\n")


# ---------------------------------------------------------------------------------------------
# Quality figures from .node/.ele (one code for both tools)
# ---------------------------------------------------------------------------------------------

def read_mesh(stem):
    import numpy as np

    def rows(path):
        with open(path) as f:
            lines = [ln.split("#", 1)[0].split() for ln in f]
        lines = [ln for ln in lines if ln]
        n = int(lines[0][0])
        return lines[1:n + 1]
    nodes = rows(stem + ".node")
    ids = np.array([int(r[0]) for r in nodes])
    xyz = np.array([[float(t) for t in r[1:4]] for r in nodes])
    ele = np.array([[int(t) for t in r[1:5]] for r in rows(stem + ".ele")]) - ids.min()
    return xyz, ele


def dihedral_angles(xyz, ele):
    """The six dihedral angles (degrees) of every tet, in the order of EDGES (the angle at the
    edge joining corners i, j)."""
    import numpy as np
    p = xyz[ele]  # (n, 4, 3)
    opp = [(1, 2, 3), (0, 2, 3), (0, 1, 3), (0, 1, 2)]
    normals = []
    for f, (a, b, c) in enumerate(opp):
        n = np.cross(p[:, b] - p[:, a], p[:, c] - p[:, a])
        # Outward: away from the opposite corner f.
        s = np.sign(np.einsum("ij,ij->i", n, p[:, f] - p[:, a]))
        # A tet flat in floating point (a positive volume below rounding: four points on two
        # lines through a spike's apex) has no side: either orientation gives its 0 and 180
        # degree angles, where a zero sign would give NaN.
        s[s == 0] = 1
        n = -n * s[:, None]
        normals.append(n / np.linalg.norm(n, axis=1)[:, None])
    out = []
    for i, j in EDGES:
        k, l = [x for x in range(4) if x not in (i, j)]
        cos = np.einsum("ij,ij->i", normals[k], normals[l])
        out.append(180.0 - np.degrees(np.arccos(np.clip(cos, -1.0, 1.0))))
    return np.stack(out, axis=1)


EDGES = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]


def radius_edge(xyz, ele):
    import numpy as np
    p = xyz[ele]
    b, c, d = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0], p[:, 3] - p[:, 0]
    den = 2.0 * np.einsum("ij,ij->i", b, np.cross(c, d))
    num = (np.einsum("ij,ij->i", b, b)[:, None] * np.cross(c, d)
           + np.einsum("ij,ij->i", c, c)[:, None] * np.cross(d, b)
           + np.einsum("ij,ij->i", d, d)[:, None] * np.cross(b, c))
    with np.errstate(divide="ignore", invalid="ignore"):
        r = np.linalg.norm(num, axis=1) / np.abs(den)
    shortest = np.min([np.linalg.norm(p[:, i] - p[:, j], axis=1) for i, j in EDGES], axis=0)
    return r / shortest


def sharp_vertices(xyz, ele, dih):
    """Mesh vertices touching a small domain angle (see the module docs)."""
    import numpy as np
    n = len(xyz)
    pairs = np.concatenate([ele[:, [i, j]] for i, j in EDGES])
    pairs.sort(axis=1)
    key = pairs[:, 0].astype(np.int64) * n + pairs[:, 1]
    uniq, inv = np.unique(key, return_inverse=True)
    angle = np.bincount(inv, weights=dih.T.ravel(), minlength=len(uniq))
    ea, eb = uniq // n, uniq % n
    sharp = np.zeros(n, dtype=bool)
    # Interior edges sum to 360 degrees; boundary edges to the domain's angle there.
    low = angle < SHARP
    sharp[ea[low]] = True
    sharp[eb[low]] = True
    crease = (angle < 360.0 - 1e-6) & (np.abs(angle - 180.0) > CREASE)
    ca, cb = ea[crease], eb[crease]
    ends = np.concatenate([ca, cb])
    other = np.concatenate([cb, ca])
    order = np.argsort(ends, kind="stable")
    ends, other = ends[order], other[order]
    starts = np.flatnonzero(np.r_[True, ends[1:] != ends[:-1]])
    cos_sharp = np.cos(np.radians(SHARP))
    for s, e in zip(starts, np.r_[starts[1:], len(ends)]):
        if e - s < 2:
            continue
        v = ends[s]
        d = xyz[other[s:e]] - xyz[v]
        d /= np.linalg.norm(d, axis=1)[:, None]
        g = d @ d.T
        np.fill_diagonal(g, -1.0)
        if (g > cos_sharp).any():
            sharp[v] = True
    return sharp


def quality(stem):
    import numpy as np
    xyz, ele = read_mesh(stem)
    dih = dihedral_angles(xyz, ele)
    lo, hi = dih.min(axis=1), dih.max(axis=1)
    bad = (lo < 15.0) | (hi > 165.0)
    at_sharp = sharp_vertices(xyz, ele, dih)[ele].any(axis=1)
    ratio = radius_edge(xyz, ele)
    n = len(ele)
    return {
        "tets": n,
        "min_dih": float(lo.min()),
        "max_dih": float(hi.max()),
        "pct_below10": 100.0 * float((lo < 10.0).sum()) / n,
        "pct_below15": 100.0 * float((lo < 15.0).sum()) / n,
        "bad": int(bad.sum()),
        "bad_at_sharp": int((bad & at_sharp).sum()),
        "bad_elsewhere_min": float(lo[bad & ~at_sharp].min()) if (bad & ~at_sharp).any()
        else None,
        "bad_elsewhere_max": float(hi[bad & ~at_sharp].max()) if (bad & ~at_sharp).any()
        else None,
        "max_radius_edge": float(np.nanmax(ratio)),
        "pct_above_bound": 100.0 * float((ratio > float(RATIO)).sum()) / n,
    }


# ---------------------------------------------------------------------------------------------
# Runs
# ---------------------------------------------------------------------------------------------

def run(tool, switches, src, case_dir, timeout):
    """One whole-process run in its own directory; returns the figures (or an error)."""
    d = os.path.join(case_dir, tool.replace(" ", "_").replace("/", "_"))
    os.makedirs(d, exist_ok=True)
    name = os.path.basename(src)
    shutil.copy(src, os.path.join(d, name))
    stem = os.path.join(d, name.rsplit(".", 1)[0] + ".1")
    for ext in (".node", ".ele", ".face", ".edge"):
        if os.path.exists(stem + ext):
            os.remove(stem + ext)
    cmd = ([IDMESH, "tetgen"] if tool.startswith("idmesh") else ["tetgen"]) + ["-" + switches,
                                                                               name]
    t0 = time.perf_counter()
    try:
        c = subprocess.run(cmd, cwd=d, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"tool": tool, "cmd": " ".join(cmd), "error": f"timeout after {timeout} s"}
    wall = time.perf_counter() - t0
    res = {"tool": tool, "cmd": " ".join([os.path.basename(cmd[0])] + cmd[1:]), "time_s": wall,
           "stem": stem}
    if c.returncode != 0 or not os.path.exists(stem + ".ele"):
        res["error"] = f"exit {c.returncode}: " + " | ".join(
            (c.stderr.strip() or c.stdout.strip()).splitlines()[-2:])
        return res
    text = c.stdout + c.stderr
    m = re.search(r"(\d+) exempt next to small input angles", text)
    res["exempt"] = int(m.group(1)) if m else None
    m = re.search(r"Volume: ([0-9.eE+-]*[0-9])", text)
    res["volume"] = float(m.group(1)) if m else None
    res.update(quality(stem))
    return res


def verify(src, stem, timeout):
    cmd = [sys.executable, VERIFY3D, src, stem + ".node", stem + ".ele", stem + ".face",
           "--require-delaunay"]
    try:
        c = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return "timeout"
    return "OK" if c.returncode == 0 else "FAIL: " + " | ".join(c.stdout.strip().splitlines()[-3:])


def volume_bound(volume, tets):
    """V = 2 x volume / tets, two significant digits, as a decimal string."""
    v = 2.0 * volume / tets
    return "%.1e" % v


def fmt_angle(x):
    return "-" if x is None else "%.2f" % x


def row(case, r, markdown):
    if "error" in r:
        cells = [case, r["tool"], "error: " + r["error"]] + [""] * 11
    else:
        else_ = "-" if r["bad_elsewhere_min"] is None else "%s / %s" % (
            fmt_angle(r["bad_elsewhere_min"]), fmt_angle(r["bad_elsewhere_max"]))
        cells = [case, r["tool"], "{:,}".format(r["tets"]),
                 "%s / %s" % (fmt_angle(r["min_dih"]), fmt_angle(r["max_dih"])),
                 "%.3f" % r["pct_below10"], "%.3f" % r["pct_below15"],
                 "{:,}".format(r["bad"]), "{:,}".format(r["bad_at_sharp"]), else_,
                 "-" if r.get("exempt") is None else str(r["exempt"]),
                 "%.2f" % r["max_radius_edge"], "%.1f" % r["pct_above_bound"],
                 "%.2f" % r["time_s"],
                 r.get("verify", "")]
    return ("| " + " | ".join(cells) + " |") if markdown else "  ".join(cells)


HEADER = ["case", "tool", "tets", "min / max dihedral", "% < 10", "% < 15",
          "bad (<15 or >165)", "bad at sharp", "others' min / max", "idmesh exempt",
          "max radius-edge", "% above " + RATIO, "time s", "verify3d --require-delaunay"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--inputs", default=",".join(INPUTS))
    ap.add_argument("--large", action="store_true", help="add the ~1M-tet volume bounds")
    ap.add_argument("--no-plain", action="store_true", help="skip the idmesh /0 rows")
    ap.add_argument("--no-verify", action="store_true")
    ap.add_argument("--markdown", action="store_true")
    ap.add_argument("--timeout", type=float, default=600)
    ap.add_argument("--idmesh", help="the idmesh binary (default target/release/idmesh, built "
                    "if missing), e.g. an older build for a before/after table")
    args = ap.parse_args()
    global IDMESH
    if args.idmesh:
        IDMESH = os.path.abspath(args.idmesh)
    if not os.path.exists(IDMESH):
        subprocess.run(["cargo", "build", "--release", "--bin", "idmesh"], cwd=ROOT, check=True)
    os.makedirs(WORK, exist_ok=True)
    sizes = [None, 100_000] + ([1_000_000] if args.large else [])
    print("| " + " | ".join(HEADER) + " |" if args.markdown else "  ".join(HEADER))
    if args.markdown:
        print("|" + "|".join(["---"] * 2 + ["--:"] * 11 + ["---"]) + "|")
    for name in args.inputs.split(","):
        src = INPUTS[name]
        if src is None:
            src = os.path.join(WORK, "cylinder.poly")
            write_cylinder(src)
        if not os.path.exists(src):
            log(f"{name}: {src} missing, skipped")
            continue
        volume = None
        for size in sizes:
            if size is not None and volume is None:
                break
            a = "" if size is None else "a" + volume_bound(volume, size)
            case = f"{name} -pq{RATIO}{a}"
            case_dir = os.path.join(WORK, name + ("" if size is None else f"_{size}"))
            runs = [("idmesh", f"pq{RATIO}{a}V"), ("tetgen", f"pq{RATIO}{a}Q")]
            if not args.no_plain:
                runs.append(("idmesh /0", f"pq{RATIO}/0{a}Q"))
            for tool, sw in runs:
                log(f"{case}: {tool} -{sw} ...")
                r = run(tool, sw, src, case_dir, args.timeout)
                if tool == "idmesh" and "error" not in r:
                    if size is None:
                        volume = r["volume"]
                    if not args.no_verify:
                        r["verify"] = verify(src, r["stem"], args.timeout)
                print(row(case, r, args.markdown), flush=True)


if __name__ == "__main__":
    sys.exit(main())
