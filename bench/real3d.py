#!/usr/bin/env python3
"""Real models side by side (issue 12): idmesh vs TetGen (Debian's `tetgen`) on every model of
../shared/data/3d, as users run them.

For each model and switch set (default `-pq` and `-pq1.414`), both tools run in fresh processes
on their own copies of the file, interleaved (idmesh, TetGen, idmesh, TetGen, ...), each run
after the machine has gone quiet:
    target/release/idmesh tetgen -<switches>Q FILE
    tetgen -<switches>Q FILE
The time is the whole process (read, mesh, write the .node/.ele/.face files), the parent's wall
clock; the peak memory is the child's ru_maxrss (wait4). The last mesh of each tool then goes
through ../shared/tools/verify3d.py --require-delaunay (untimed), and the table reports its
two verdicts apart: "Delaunay" (no vertex strictly inside any tet's circumsphere) and
"verifier" (every other check: conformity to the input surface, volume, orientation, the
radius-edge bound asked for).

verify3d.py judges each input polygon as one planar facet, so where idmesh triangulates
non-planar polygons of an `.off` file (mpi.off, with a warning) it reports those facets as not
covered; the figures are shown all the same.

Usage: python3 bench/real3d.py [--inputs a.off,b.off] [--switches pq,pq1.414] [--repeat 3]
                               [--markdown] [--timeout S] [--idmesh BINARY] [--no-verify]
                               [--verify-tools idmesh,tetgen]
Outputs go to target/real3d/.
"""

import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench3d  # noqa: E402  (the shared child-process, quiet-machine and machine-info helpers)

ROOT = bench3d.ROOT
SHARED = os.path.join(os.path.dirname(ROOT), "shared")
DATA3D = os.path.join(SHARED, "data", "3d")
VERIFY3D = os.path.join(SHARED, "tools", "verify3d.py")
WORK = os.path.join(ROOT, "target", "real3d")
EXTS = (".off", ".poly", ".smesh", ".stl", ".ply", ".mesh")


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def count_of(path):
    """The first number of the first data line of a TetGen file (its item count), or None."""
    try:
        with open(path) as f:
            for line in f:
                line = line.split("#", 1)[0].split()
                if line:
                    return int(line[0])
    except (OSError, ValueError):
        pass
    return None


def one_run(tool, exe, switches, src, case_dir, timeout):
    """Runs `tool` once on a fresh copy of `src` in `case_dir/tool`; returns a result dict."""
    d = os.path.join(case_dir, tool)
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    name = os.path.basename(src)
    shutil.copy(src, d)
    cmd = [exe, "tetgen", "-" + switches + "Q", name] if tool == "idmesh" else \
        [exe, "-" + switches + "Q", name]
    c = bench3d.run_child(cmd, timeout, cwd=d)
    stem = os.path.join(d, os.path.splitext(name)[0] + ".1")
    r = {"time_s": c.wall, "total_kb": c.ru.ru_maxrss, "stem": stem,
         "input": os.path.join(d, name)}
    if c.code != 0:
        why = "timeout" if c.code is None else "exit %s" % c.code
        text = (c.err.strip() or c.out.strip()).splitlines()
        r["error"] = why + (": " + text[-1][:160] if text else "")
    else:
        r["tets"] = count_of(stem + ".ele")
    return r


def verify(r, switches, timeout):
    """verify3d.py --require-delaunay on a result's mesh: (Delaunay yes/no, verifier verdict)."""
    args = [sys.executable, VERIFY3D, "--require-delaunay"]
    if "q" in switches:
        num = re.match(r"[0-9.]*", switches.split("q", 1)[1]).group(0)
        args += ["--radius-edge", num or "2.0"]
    args += [r["input"], r["stem"] + ".node", r["stem"] + ".ele", r["stem"] + ".face"]
    try:
        out = subprocess.run(args, capture_output=True, text=True, timeout=timeout).stdout
    except subprocess.TimeoutExpired:
        return "?", "verifier timeout"
    checks = [ln.split() for ln in out.splitlines() if ln.strip().startswith("[")]
    delaunay = next((c[0] == "[PASS]" for c in checks if len(c) > 1 and c[1] == "delaunay"), None)
    failed = [c[1] for c in checks if len(c) > 1 and c[0] == "[FAIL]" and c[1] != "delaunay"]
    return ("yes" if delaunay else "no" if delaunay is not None else "?",
            "OK" if not failed and checks else "FAIL: " + ", ".join(failed) if failed else "?")


def median_spread(xs):
    return statistics.median(xs), min(xs), max(xs)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--inputs", help="comma-separated file names in ../shared/data/3d "
                    "(default: every model there)")
    ap.add_argument("--switches", default="pq,pq1.414")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--markdown", action="store_true")
    ap.add_argument("--timeout", type=float, default=600)
    ap.add_argument("--wait-idle", type=float, default=60, help="seconds to wait for quiet")
    ap.add_argument("--idmesh", help="the idmesh binary (default target/release/idmesh, built)")
    ap.add_argument("--no-verify", action="store_true")
    ap.add_argument("--verify-tools", default="idmesh,tetgen",
                    help="whose meshes go through verify3d.py (it is slow on meshes that are "
                    "not Delaunay: minutes on TetGen's fandisk -pq1.414)")
    a = ap.parse_args()

    if not os.path.isdir(DATA3D):
        sys.exit("real3d: %s not found" % DATA3D)
    tetgen = shutil.which("tetgen")
    if not tetgen:
        sys.exit("real3d: Debian's tetgen is not installed (apt-get install tetgen)")
    exe = a.idmesh
    if not exe:
        subprocess.run(["cargo", "build", "--release", "--quiet", "--bin", "idmesh"], cwd=ROOT,
                       check=True)
        exe = os.path.join(ROOT, "target", "release", "idmesh")
    exe = os.path.abspath(exe)
    names = a.inputs.split(",") if a.inputs else sorted(
        f for f in os.listdir(DATA3D) if f.endswith(EXTS))
    info = bench3d.machine_info()
    rows = []
    for name in names:
        src = os.path.join(DATA3D, name)
        for sw in a.switches.split(","):
            case_dir = os.path.join(WORK, name + "-" + sw)
            log(f"{name} -{sw}")
            runs = {"idmesh": [], "tetgen": []}
            for rep in range(a.repeat):
                for tool, x in (("idmesh", exe), ("tetgen", tetgen)):
                    busy = bench3d.wait_for_quiet(a.wait_idle)
                    r = one_run(tool, x, sw, src, case_dir, a.timeout)
                    r["busy"] = busy
                    runs[tool].append(r)
                    log("   %-7s run %d: %s" % (tool, rep + 1, r.get("error") or
                                               "%.3f s, %s tets, %.0f MB" % (
                                                   r["time_s"], r["tets"], r["total_kb"] / 1024)))
                    if "error" in r:
                        break
            row = {"model": name, "switches": sw}
            for tool, rs in runs.items():
                ok = [r for r in rs if "error" not in r]
                if len(ok) < len(rs) or not ok:
                    row[tool] = {"error": next(r["error"] for r in rs if "error" in r)}
                    continue
                t = median_spread([r["time_s"] for r in ok])
                row[tool] = {"time": t, "tets": ok[-1]["tets"],
                             "mb": max(r["total_kb"] for r in ok) / 1024,
                             "busy": max(r["busy"] for r in ok)}
                if not a.no_verify and tool in a.verify_tools.split(","):
                    row[tool]["delaunay"], row[tool]["verdict"] = verify(ok[-1], sw, a.timeout)
            rows.append(row)
    render(rows, info, a)


def cell(x):
    if "error" in x:
        return ["**%s**" % x["error"], "-", "-", "-", "-"]
    t, lo, hi = x["time"]
    return ["%.2f (%.2f-%.2f)" % (t, lo, hi), "{:,}".format(x["tets"] or 0), "%.0f" % x["mb"],
            x.get("delaunay", "-"), x.get("verdict", "-")]


def render(rows, info, a):
    out = []
    out.append("Run %s on %s x %s, %s; idmesh %s, TetGen %s. Whole processes (read, mesh, write), "
               "`-<switches>Q`, median of %d interleaved runs (min-max); each run started after "
               "the machine was quiet (busy cores before a run: at most %.2f)." % (
                   info["date"], info["nproc"], info["cpu"], info["memory"],
                   info["idmesh_commit"], info["tetgen"], a.repeat,
                   max((r[t].get("busy", 0) for r in rows for t in ("idmesh", "tetgen")),
                       default=0)))
    out.append("")
    head = ["model", "switches", "idmesh s", "tets", "peak MB", "Delaunay", "verifier",
            "TetGen s", "tets", "peak MB", "Delaunay", "verifier", "time ratio"]
    out.append("| " + " | ".join(head) + " |")
    out.append("|" + "|".join(["---"] * 2 + ["--:"] * 3 + ["---"] * 2 + ["--:"] * 3 +
                              ["---"] * 2 + ["--:"]) + "|")
    ratios = []
    tot = [0.0, 0.0]
    for r in rows:
        i, g = r["idmesh"], r["tetgen"]
        ratio = "-"
        if "error" not in i and "error" not in g:
            q = i["time"][0] / g["time"][0]
            ratios.append(q)
            tot[0] += i["time"][0]
            tot[1] += g["time"][0]
            ratio = "%.2f" % q
        out.append("| " + " | ".join([r["model"], "-" + r["switches"]] + cell(i) + cell(g) +
                                     [ratio]) + " |")
    out.append("")
    if ratios:
        out.append("Cases both tools meshed: %d; idmesh / TetGen time: median %.2f, range "
                   "%.2f-%.2f, total %.1f s / %.1f s = %.2f; cases at most 0.5: %d." % (
                       len(ratios), statistics.median(ratios), min(ratios), max(ratios),
                       tot[0], tot[1], tot[0] / tot[1], sum(q <= 0.5 for q in ratios)))
    print("\n".join(out))


if __name__ == "__main__":
    main()
