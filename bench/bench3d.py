#!/usr/bin/env python3
"""Side-by-side 3D benchmark: idmesh vs TetGen (Debian's `tetgen`) vs CGAL.

The issue's cases (--cases picks some; the default is all three):

random   The Delaunay tetrahedralization of 1,000,000 uniform random points in the unit cube
         (100,000 with --quick). Every tool runs in a fresh child process per run, interleaved
         (idmesh, TetGen, CGAL, idmesh, ...):
  * idmesh: `cargo build --release --example bench3d_points`; the child generates the points
            itself from the same SplitMix64 seed and times only `idmesh::delaunay3d`;
  * TetGen: `tetgen -V POINTS.node` (a TetGen .node file written once with round-trip-exact
            decimals). The parent times the whole process (reading the .node file, the
            tetrahedralization, writing .node/.ele/.face: the job TetGen users run) and takes
            the peak RSS from wait4(); `-V` instead of `-Q` makes TetGen print its own CPU
            timings, of which "Delaunay seconds" is reported too (the only difference is a few
            lines of output);
  * CGAL:   bench/cgal_bench3d.cpp compiled with g++ -O2 against CGAL (Epick,
            Delaunay_triangulation_3, range insert with CGAL's spatial sort), timing only the
            insertion.
  idmesh and CGAL report their RSS just before the call and their peak RSS during it (VmHWM,
  reset through /proc/self/clear_refs just before the call) and their whole-life peak; all
  tools print or are checked against an `input_hash` of the coordinate bits.

cube     Quality refinement of the unit cube (a .poly file written by the script) with
         radius-edge 1.414 and the volume bound 0.000002 (~1M tets; 0.00002 with --quick).
example  The same for ../shared/data/3d/example.poly (relative to the repository root; skipped
         with a message if ../shared is absent), volume bound 0.000036 (0.0004 with --quick).
  Both tools run as command lines on the same .poly file, each on its own copy in its own
  directory (target/bench3d/CASE/TOOL/), in fresh processes, interleaved:
      target/release/idmesh tetgen -pq1.414a<V>V FILE.poly   (cargo build --release --bin idmesh)
      tetgen -pq1.414a<V>V FILE.poly
  The time is the whole process (read, mesh, write, as users run it) and the peak RSS is
  wait4()'s ru_maxrss. `V` instead of `Q` (--quiet: `Q`; TetGen's -V statistics cost it ~20%
  of its time) makes both print their own timings, which are
  reported as "own meshing s": idmesh's "meshing" (wall clock, reading and writing excluded),
  TetGen's "Total running seconds" minus "Output seconds" (CPU clock; TetGen's total starts
  after reading). Counts come from the headers of the output .ele and .node files. With
  --verify the first idmesh mesh of each case goes through ../shared/tools/verify3d.py
  (--require-delaunay, the radius-edge and volume bounds), untimed.

--whole-process adds two rows to the random case, both whole processes on the same .node file
with no output files, as users time them (issue 15):
      target/release/idmesh tetgen -NEFQ POINTS.node   ("idmesh CLI -NEFQ")
      tetgen -NEFQ POINTS.node                         ("tetgen -NEFQ")
  The time is the parent's wall clock around the process; it includes reading the 1M-point
  .node file, which the in-process idmesh row does not.

Targets (from the issue): random: idmesh time <= 0.5 x TetGen's, <= 1.0 x CGAL's, and idmesh's
peak memory <= TetGen's; refinement cases: idmesh time <= 1.0 x TetGen's and tet count <= 1.3 x
TetGen's.

Usage: python3 bench/bench3d.py [--cases random,cube,example] [--quick] [--points N] [--seed S]
                                [--volume V]
                                [--repeat K] [--verify] [--quiet] [--markdown] [--no-cgal] [--no-tetgen]
                                [--json OUT] [--render OUT.json] [--selftest] [--wait-idle S]
                                [--whole-process]
                                [--timeout S]
Inputs, outputs and the CGAL binary go to target/bench3d/.
"""

import argparse
import collections
import datetime
import importlib.util
import json
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BENCH = os.path.join(ROOT, "bench")
CGAL_SRC = os.path.join(BENCH, "cgal_bench3d.cpp")

FULL_POINTS = 1_000_000
QUICK_POINTS = 100_000
SEED = 20240601

# The project's shared data and tools live next to the repository (../shared).
SHARED = os.path.join(os.path.dirname(ROOT), "shared")
VERIFY3D = os.path.join(SHARED, "tools", "verify3d.py")
RADIUS_EDGE = "1.414"

# The refinement cases. Volume bounds are decimal strings, passed verbatim to both tools: "full"
# gives TetGen about 1,000,000 tets, "quick" about 100,000 (TetGen 1.5.0's counts are in
# bench/README.md). source None: the unit cube, written by the script.
REFINE_CASES = {
    "cube": {"title": "unit cube", "source": None, "full": "0.000002", "quick": "0.00002"},
    "example": {"title": "example.poly", "source": os.path.join(SHARED, "data", "3d",
                                                                 "example.poly"),
                "full": "0.000036", "quick": "0.0004"},
}
ALL_CASES = ["random"] + list(REFINE_CASES)

GOLD = 0x9E3779B97F4A7C15
M64 = (1 << 64) - 1


def log(msg):
    print(msg, file=sys.stderr, flush=True)


# ---------------------------------------------------------------------------------------------
# Inputs (the same bits as examples/bench3d_points.rs)
# ---------------------------------------------------------------------------------------------

def mix64(z):
    """SplitMix64's finaliser on a numpy uint64 array (wrapping arithmetic)."""
    import numpy as np
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


def splitmix_points(n, seed):
    """Point i is (draw 3i+1, 3i+2, 3i+3) of SplitMix64 from `seed`, each (u >> 11) * 2^-53."""
    import numpy as np
    with np.errstate(over="ignore"):
        k = np.arange(1, 3 * n + 1, dtype=np.uint64)
        state = np.uint64(seed & M64) + k * np.uint64(GOLD)
        u = mix64(state)
    return ((u >> np.uint64(11)).astype(np.float64) * 2.0**-53).reshape(n, 3)


def input_hash(xyz):
    """Order-sensitive hash of the coordinate bits, as in examples/bench3d_points.rs."""
    import numpy as np
    w = np.ascontiguousarray(xyz, dtype=np.float64).ravel().view(np.uint64)
    with np.errstate(over="ignore"):
        idx = np.arange(len(w), dtype=np.uint64) * np.uint64(GOLD)
        return "%016x" % int(mix64(w ^ idx).sum(dtype=np.uint64))


def write_node(path, xyz):
    """TetGen .node, 0-based, coordinates as repr() (round-trips exactly through strtod)."""
    with open(path, "w") as f:
        f.write(f"# {len(xyz)} random points, written by bench/bench3d.py\n{len(xyz)} 3 0 0\n")
        rows = xyz.tolist()
        for start in range(0, len(rows), 100_000):
            f.write("".join(f"{i} {x!r} {y!r} {z!r}\n"
                            for i, (x, y, z) in enumerate(rows[start:start + 100_000], start)))


def read_node_back(path):
    """Reads a .node file written by write_node (to check that it round-trips)."""
    import numpy as np
    with open(path) as f:
        lines = [ln for ln in f if ln.strip() and not ln.startswith("#")]
    n = int(lines[0].split()[0])
    return np.array([[float(t) for t in ln.split()[1:4]] for ln in lines[1:n + 1]])


def write_cube_poly(path):
    """The unit cube [0,1]^3 as a TetGen .poly file: 8 points, 6 quadrilateral facets."""
    corners = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
               (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    facets = [(1, 2, 3, 4), (5, 6, 7, 8), (1, 2, 6, 5), (2, 3, 7, 6), (3, 4, 8, 7), (4, 1, 5, 8)]
    with open(path, "w") as f:
        f.write("# the unit cube, written by bench/bench3d.py\n8 3 0 0\n")
        f.writelines(f"{i} {x} {y} {z}\n" for i, (x, y, z) in enumerate(corners, 1))
        f.write("6 0\n")
        f.writelines("1\n4 %d %d %d %d\n" % q for q in facets)
        f.write("0\n0\n")


def data_lines(path, limit=None):
    """The non-empty lines of a TetGen file with comments removed, split into tokens (at most
    `limit` lines)."""
    out = []
    with open(path) as f:
        for line in f:
            tokens = line.split("#", 1)[0].split()
            if tokens:
                out.append(tokens)
                if limit is not None and len(out) >= limit:
                    break
    return out


def poly_extent(path):
    """The number of points and the bounding box (lo, hi) of a .poly file's points; the points
    may also be in the .node file beside it (a point count of 0)."""
    head = data_lines(path, 1)[0]
    n = int(head[0])
    src = path
    if n == 0:
        src = path[: -len(".poly")] + ".node"
        n = int(data_lines(src, 1)[0][0])
    rows = data_lines(src, n + 1)[1:]
    xyz = [[float(t) for t in r[1:4]] for r in rows]
    lo = [min(p[k] for p in xyz) for k in range(3)]
    hi = [max(p[k] for p in xyz) for k in range(3)]
    return n, lo, hi


def header_count(path):
    """The item count in the first data line of a TetGen output file (.node, .ele, .face), or
    None if the file is missing or malformed."""
    try:
        return int(data_lines(path, 1)[0][0])
    except (OSError, IndexError, ValueError):
        return None


# ---------------------------------------------------------------------------------------------
# Setup
# ---------------------------------------------------------------------------------------------

def ensure_numpy():
    """Installs numpy if it is missing. It is imported only where it is used, so that the
    script's own RSS stays small during the refinement runs (see run_child)."""
    if importlib.util.find_spec("numpy") is None:
        log("installing numpy with pip")
        subprocess.check_call([sys.executable, "-m", "pip", "install", "-q", "numpy"])


def ensure_apt_deps(want_cgal, want_tetgen):
    need = []
    if want_cgal:
        if not shutil.which("g++"):
            need.append("g++")
        for header, pkg in (("/usr/include/CGAL/Delaunay_triangulation_3.h", "libcgal-dev"),
                            ("/usr/include/mpfr.h", "libmpfr-dev")):
            if not os.path.exists(header):
                need.append(pkg)
        if not (os.path.exists("/usr/include/gmp.h")
                or os.path.exists("/usr/include/x86_64-linux-gnu/gmp.h")):
            need.append("libgmp-dev")
    if want_tetgen and not shutil.which("tetgen"):
        need.append("tetgen")
    if not need:
        return True
    log("installing with apt-get: " + " ".join(need))
    sudo = [] if os.geteuid() == 0 else ["sudo"]
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    try:
        subprocess.check_call(sudo + ["apt-get", "update", "-q"], env=env)
        subprocess.check_call(sudo + ["apt-get", "install", "-y", "-q", *need], env=env)
        return True
    except (OSError, subprocess.CalledProcessError) as e:
        log(f"apt-get failed ({e}); missing tools will be skipped")
        return False


def build_idmesh(points, cli):
    """Builds the release `bench3d_points` example (random case) and/or the `idmesh` binary
    (refinement cases). Returns ({"points": path, "cli": path}, error message or None)."""
    targets = (["--example", "bench3d_points"] if points else []) + (["--bin", "idmesh"]
                                                                     if cli else [])
    if not targets:
        return {}, None
    log("building idmesh: cargo build --release " + " ".join(targets))
    r = subprocess.run(["cargo", "build", "--release", *targets, "-q"],
                       cwd=ROOT, capture_output=True, text=True)
    if r.returncode != 0:
        first = next((ln for ln in r.stderr.splitlines() if ln.startswith("error")), "")
        log(r.stderr[-3000:])
        return {}, "cargo build failed: " + first
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    exes = {}
    if points:
        exes["points"] = os.path.join(target, "release", "examples", "bench3d_points")
    if cli:
        exes["cli"] = os.path.join(target, "release", "idmesh")
    for key, exe in exes.items():
        if not os.path.exists(exe):
            return {}, f"built {os.path.basename(exe)} but cannot find it at {exe}"
    return exes, None


def build_cgal(workdir):
    exe = os.path.join(workdir, "cgal_bench3d")
    if os.path.exists(exe) and os.path.getmtime(exe) >= os.path.getmtime(CGAL_SRC):
        return exe
    log("compiling bench/cgal_bench3d.cpp with g++ -O2 (takes ~30 s)")
    subprocess.check_call(["g++", "-O2", "-DNDEBUG", "-std=c++17", "-o", exe, CGAL_SRC,
                           "-lgmp", "-lmpfr"])
    return exe


# ---------------------------------------------------------------------------------------------
# Running children
# ---------------------------------------------------------------------------------------------

def busy_cores(window=0.5):
    """CPU cores kept busy by other processes, sampled from /proc/stat over `window` seconds."""
    def sample():
        with open("/proc/stat") as f:
            v = [int(x) for x in f.readline().split()[1:]]
        idle = v[3] + (v[4] if len(v) > 4 else 0)
        return sum(v), idle
    t0, i0 = sample()
    time.sleep(window)
    t1, i1 = sample()
    total = max(t1 - t0, 1)
    return (1.0 - (i1 - i0) / total) * (os.cpu_count() or 1)


def wait_for_quiet(max_wait, threshold=0.3):
    """Waits (up to max_wait s) until other jobs leave the CPUs idle; returns the busy-core
    figure seen at the start."""
    deadline = time.monotonic() + max_wait
    busy = busy_cores()
    first = busy
    announced = False
    while busy > threshold and time.monotonic() < deadline:
        if not announced:
            log(f"   waiting for the machine to go quiet ({busy:.1f} cores busy)")
            announced = True
        time.sleep(2.0)
        busy = busy_cores()
    return min(first, busy)


Child = collections.namedtuple("Child", "out err code wall ru parent_rss_kb")


def reset_own_hwm():
    """Resets this process's peak-RSS mark to its current RSS and returns that RSS in kB.

    Linux folds the parent's peak RSS into a child's wait4() ru_maxrss (the parent's memory
    image is the child's until exec), so a child's figure is never below the parent's peak.
    After this reset that floor is the script's current RSS (~15 MB without numpy, ~30 MB with
    it) instead of its largest ever (e.g. while writing 1M points)."""
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
    except OSError:
        pass
    try:
        with open("/proc/self/status") as f:
            return next(int(ln.split()[1]) for ln in f if ln.startswith("VmRSS:"))
    except (OSError, StopIteration, ValueError):
        return None


def run_child(cmd, timeout, cwd=ROOT):
    """Runs cmd in a fresh process. Returns a Child: stdout text, stderr text, exit code (None
    on timeout), wall seconds, the child's rusage, and the script's own RSS when it started the
    child (the floor of ru_maxrss, see reset_own_hwm)."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        parent_rss = reset_own_hwm()
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, stdout=out, stderr=err, cwd=cwd)
        deadline = time.monotonic() + timeout
        code = None
        while True:
            pid, status, ru = os.wait4(p.pid, os.WNOHANG)
            if pid:
                code = os.waitstatus_to_exitcode(status)
                break
            if time.monotonic() > deadline:
                p.kill()
                _, _, ru = os.wait4(p.pid, 0)
                break
            time.sleep(0.01)
        wall = time.perf_counter() - t0
        out.seek(0)
        err.seek(0)
        return Child(out.read().decode(errors="replace"), err.read().decode(errors="replace"),
                     code, wall, ru, parent_rss)


def grab(pattern, text, cast=float):
    """The first group of the first match of `pattern` in `text`, cast; None if no match."""
    m = re.search(pattern, text)
    return cast(m.group(1)) if m else None


def failure(c, timeout):
    """The error message of a failed Child run: a timeout, or the exit code and the last lines
    of its output."""
    if c.code is None:
        return f"timeout after {timeout:.0f} s"
    tail = (c.err.strip() or c.out.strip() or "no output").splitlines()[-3:]
    return f"exit {c.code}: " + " | ".join(tail)


def json_child(cmd, timeout):
    """Runs a child that prints one JSON line (idmesh, CGAL)."""
    c = run_child(cmd, timeout)
    if c.code is None:
        return {"error": failure(c, timeout)}
    res = None
    for line in reversed(c.out.strip().splitlines()):
        try:
            res = json.loads(line)
            break
        except ValueError:
            continue
    if res is None:
        return {"error": failure(c, timeout)}
    if c.code != 0 and "error" not in res:
        res["error"] = f"exit {c.code}"
    res["process_s"] = c.wall
    res["cpu_s"] = c.ru.ru_utime + c.ru.ru_stime
    # The child's whole-life peak: VmHWM before the reset covers set-up, after covers the call.
    if "hwm_after_kb" in res:
        res["peak_kb"] = res["hwm_after_kb"] - res["rss_before_kb"]
        res["total_kb"] = max(res["hwm_before_kb"], res["hwm_after_kb"])
    return res


def remove_outputs(stem):
    """Deletes STEM.node/.ele/.face/.edge (a run's outputs)."""
    for ext in (".node", ".ele", ".face", ".edge"):
        try:
            os.remove(stem + ext)
        except OSError:
            pass


def tetgen_child(node_path, workdir, timeout):
    """Runs `tetgen -V` on the .node file in a scratch copy of the directory; parses its own
    timings and counts. The peak RSS is wait4's ru_maxrss (tetgen is exec'd directly)."""
    c = run_child(["tetgen", "-V", node_path], timeout, cwd=workdir)
    text = c.out
    if c.code != 0 or "Delaunay seconds" not in text:
        return {"error": failure(c, timeout)}
    remove_outputs(node_path[: -len(".node")] + ".1")
    return {
        "tool": "tetgen",
        "time_s": c.wall,
        "process_s": c.wall,
        "cpu_s": c.ru.ru_utime + c.ru.ru_stime,
        "delaunay_s": grab(r"Delaunay seconds:\s*([0-9.eE+-]+)", text),
        "total_running_s": grab(r"Total running seconds:\s*([0-9.eE+-]+)", text),
        "vertices": grab(r"Mesh points:\s*(\d+)", text, int),
        "tets": grab(r"Mesh tetrahedra:\s*(\d+)", text, int),
        "hull_faces": grab(r"Convex hull faces:\s*(\d+)", text, int),
        "input_points": grab(r"Input points:\s*(\d+)", text, int),
        "total_kb": c.ru.ru_maxrss,
        "parent_rss_kb": c.parent_rss_kb,
    }


# TetGen -V's own timings (CPU seconds from clock(); "Total running" starts after reading).
TETGEN_STAGES = {
    "delaunay_s": "Delaunay seconds",
    "surface_s": "Surface mesh seconds",
    "cdt_s": "Constrained Delaunay seconds",
    "exterior_s": "Exterior tets removal seconds",
    "refine_s": "Refinement seconds",
    "optimize_s": "Optimization seconds",
    "output_s": "Output seconds",
    "total_running_s": "Total running seconds",
}
NUMBER = r"([0-9]+(?:\.[0-9]*)?(?:[eE][+-]?[0-9]+)?)"


def parse_idmesh_verbose(text):
    """The figures of `idmesh tetgen -V`'s closing statistics (None where absent)."""
    return {
        "read_s": grab(r"Time: reading " + NUMBER + " s", text),
        "meshing_s": grab(r"meshing " + NUMBER + " s", text),
        "write_s": grab(r"writing " + NUMBER + " s", text),
        "stdout_tets": grab(r"Mesh: \d+ vertices .*?, (\d+) tetrahedra", text, int),
        "volume": grab(r"Volume: " + NUMBER, text),
        "max_radius_edge": grab(r"Radius-edge ratio: largest " + NUMBER, text),
    }


def parse_tetgen_verbose(text):
    """TetGen -V's stage timings; its own meshing time is the total minus the output stage."""
    out = {k: grab(re.escape(label) + r":\s*" + NUMBER, text) for k, label in
           TETGEN_STAGES.items()}
    total, output = out["total_running_s"], out["output_s"]
    out["meshing_s"] = None if total is None else total - (output or 0.0)
    out["stdout_tets"] = grab(r"Mesh tetrahedra:\s*(\d+)", text, int)
    return out


def refine_child(tool, exe, poly, switches, timeout, keep=False):
    """Runs one refinement job as users run it: `idmesh tetgen -SWITCHES FILE.poly` or
    `tetgen -SWITCHES FILE.poly`, in the directory of the tool's own copy of the input. Returns
    the whole-process wall and CPU time, the peak RSS from wait4(), the tool's own timings, and
    the tet and vertex counts from the output headers. The outputs (FILE.1.*) are removed, or
    with `keep` renamed to FILE.kept.* (later runs do not overwrite them)."""
    workdir, name = os.path.split(poly)
    stem = poly[: -len(".poly")] + ".1"
    remove_outputs(stem)
    cmd = ([exe, "tetgen"] if tool == "idmesh" else [exe]) + ["-" + switches, name]
    c = run_child(cmd, timeout, cwd=workdir)
    tets, vertices = header_count(stem + ".ele"), header_count(stem + ".node")
    res = {"tool": tool, "cmd": " ".join(cmd)}
    if c.code != 0 or tets is None:
        res["error"] = failure(c, timeout) if c.code != 0 else "no .ele output"
    else:
        res.update(parse_idmesh_verbose(c.out) if tool == "idmesh"
                   else parse_tetgen_verbose(c.out))
        res.update({
            "time_s": c.wall, "process_s": c.wall, "cpu_s": c.ru.ru_utime + c.ru.ru_stime,
            "tets": tets, "vertices": vertices, "total_kb": c.ru.ru_maxrss,
            "parent_rss_kb": c.parent_rss_kb,
        })
        if res.get("stdout_tets") not in (None, tets):
            res["note"] = f"prints {res['stdout_tets']:,} tets, .ele has {tets:,}"
        if "Steiner point limit" in c.out + c.err:
            res["note"] = "Steiner point limit reached: incomplete mesh"
    if keep and "error" not in res:
        kept = poly[: -len(".poly")] + ".kept"
        remove_outputs(kept)
        for ext in (".node", ".ele", ".face"):
            os.replace(stem + ext, kept + ext)
        res["kept_stem"] = kept
    remove_outputs(stem)
    return res


def verify_mesh(source, stem, volume, timeout):
    """Checks a kept idmesh output with ../shared/tools/verify3d.py (exact predicates): valid,
    conforming, Delaunay, radius-edge and volume bounds. Untimed. Returns {"ok", "seconds",
    "failed" (names of failed checks), "error"}."""
    cmd = [sys.executable, VERIFY3D, source, stem + ".node", stem + ".ele", stem + ".face",
           "--require-delaunay", "--radius-edge", RADIUS_EDGE, "--max-volume", volume, "--json"]
    c = run_child(cmd, timeout)
    res = {"seconds": round(c.wall, 1), "ok": c.code == 0}
    try:
        summary = json.loads(c.out.strip().splitlines()[-1])
        res["failed"] = [k for k, v in summary.get("checks", {}).items()
                         if isinstance(v, dict) and v.get("ok") is False]
    except (ValueError, IndexError, AttributeError):
        res["error"] = failure(c, timeout)
    return res


def summarise(runs):
    """Median time over the repeats (and the best); memory as the largest seen."""
    ok = [r for r in runs if "error" not in r]
    if not ok:
        return {"error": runs[0].get("error", "failed") if runs else "not run"}
    out = dict(ok[0])
    out["times"] = [r["time_s"] for r in ok]
    out["time_s"] = statistics.median(out["times"])
    out["best_s"] = min(out["times"])
    for key in ("process_s", "cpu_s", "delaunay_s", "meshing_s", "read_s", "write_s",
                "refine_s", "optimize_s", "output_s", "total_running_s"):
        vals = [r[key] for r in ok if r.get(key) is not None]
        out[key] = statistics.median(vals) if vals else None
    for key in ("peak_kb", "total_kb"):
        vals = [r[key] for r in ok if r.get(key) is not None]
        out[key] = max(vals) if vals else None
    out["runs"] = len(ok)
    if len(ok) < len(runs):
        out["failed_runs"] = len(runs) - len(ok)
    out["busy_cores_max"] = max(r.get("busy_cores_before", 0.0) for r in ok)
    bad = [r for r in ok if r.get("valid") is False]
    if bad:
        out["note"] = "INVALID mesh: " + bad[0].get("invalid_reason", "")[:80]
    elif any(r.get("valid") for r in ok):
        out["note"] = "validate() ok"
    # A wait4() peak no larger than the script's own RSS may be the script's (see run_child).
    floor = max((r.get("parent_rss_kb") or 0) for r in ok)
    if out.get("total_kb") is not None and "peak_kb" not in out and out["total_kb"] <= floor:
        out["peak_floor"] = f"peak <= the script's own RSS ({floor / 1024:.0f} MB): an upper bound"
    return out


def interleaved(tools, repeat, wait_idle, check=None):
    """Runs every tool `repeat` times, interleaved (a, b, c, a, b, c, ...), each after waiting
    for the machine to go quiet. tools: {name: fn(rep) -> result dict}. check(result) may
    return an error message that replaces the result. Returns {name: [results]}."""
    runs = {t: [] for t in tools}
    for rep in range(repeat):
        for tool, fn in tools.items():
            busy = wait_for_quiet(wait_idle)
            r = fn(rep)
            r["busy_cores_before"] = round(busy, 2)
            problem = check(r) if check and "error" not in r else None
            if problem:
                r = {"error": problem, "busy_cores_before": r["busy_cores_before"]}
            runs[tool].append(r)
            msg = r.get("error") or "%.3f s, %s tets" % (r["time_s"], "{:,}".format(r["tets"])
                                                          if r.get("tets") is not None else "?")
            if r.get("meshing_s") is not None:
                msg += ", own meshing %.3f s" % r["meshing_s"]
            if r.get("total_kb"):
                msg += ", peak %.0f MB" % (r["total_kb"] / 1024)
            log(f"   {tool:7s} run {rep + 1}: {msg}")
    return runs


# ---------------------------------------------------------------------------------------------
# Report
# ---------------------------------------------------------------------------------------------

def machine_info():
    cpu, mem = "unknown", "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next((ln.split(":", 1)[1].strip() for ln in f if ln.startswith("model name")),
                       "unknown")
        with open("/proc/meminfo") as f:
            kb = next(int(ln.split()[1]) for ln in f if ln.startswith("MemTotal"))
            mem = "%.1f GiB" % (kb / 1024 / 1024)
    except (OSError, StopIteration):
        pass

    def first_line(cmd):
        try:
            return subprocess.run(cmd, capture_output=True, text=True,
                                  cwd=ROOT).stdout.splitlines()[0].strip()
        except (OSError, IndexError):
            return "unknown"

    cgal = "unknown"
    try:
        with open("/usr/include/CGAL/version.h") as f:
            for line in f:
                if "define CGAL_VERSION_STR" in line or line.startswith("#define CGAL_VERSION "):
                    cgal = line.split()[2].strip('"')
                    break
    except OSError:
        pass
    tetgen = "unknown"
    try:
        out = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "tetgen"],
                             capture_output=True, text=True).stdout.strip()
        tetgen = out or tetgen
    except OSError:
        pass
    dirty = ""
    try:
        r = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                           capture_output=True, text=True, cwd=ROOT)
        dirty = " + uncommitted changes" if r.stdout.strip() else ""
    except OSError:
        pass
    return {
        "date": datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z"),
        "nproc": os.cpu_count(), "cpu": cpu, "memory": mem, "os": platform.platform(),
        "rustc": first_line(["rustc", "--version"]), "gxx": first_line(["g++", "--version"]),
        "cgal": cgal, "tetgen": tetgen,
        "idmesh_commit": first_line(["git", "rev-parse", "--short", "HEAD"]) + dirty,
    }


def tfmt(t):
    return "-" if t is None else ("%.3f" % t if t >= 0.01 else "%.2e" % t)


def mb(kb):
    return "-" if kb is None else "%.1f" % (kb / 1024)


def ratio(a, b):
    return "-" if not a or not b else "%.2f" % (a / b)


def count(n):
    return "-" if n is None else "{:,}".format(n)


def ok(r):
    """Whether a summarised tool result exists and did not fail."""
    return r is not None and "error" not in r


HEADER = ["tool", "time s", "best s", "CPU s", "÷ TetGen process", "÷ TetGen Delaunay",
          "÷ CGAL", "tets", "vertices", "hull faces", "call peak MB", "process peak MB",
          "peak ÷ TetGen", "note"]

REFINE_HEADER = ["case", "tool", "time s", "best s", "÷ TetGen", "own meshing s",
                 "own ÷ TetGen own", "CPU s", "tets", "tets ÷ TetGen", "vertices", "peak MB",
                 "peak ÷ TetGen", "note"]


def common_notes(r):
    """Notes every row may carry: the result's own note, a memory floor, a busy machine."""
    notes = [r["note"]] if r.get("note") else []
    if r.get("peak_floor"):
        notes.append(r["peak_floor"])
    if r.get("failed_runs"):
        notes.append(f"{r['failed_runs']} run(s) failed")
    if r.get("busy_cores_max", 0.0) > 0.3:
        notes.append("other jobs used up to %.1f cores" % r["busy_cores_max"])
    return notes


def error_row(prefix, r, width):
    """A table row for a tool that failed or was not run."""
    return prefix + ["error: " + r["error"][:90]] + [""] * (width - len(prefix) - 1)


def build_rows(res):
    """Rows of the random case's table."""
    tg, cg = res.get("tetgen", {}), res.get("cgal", {})
    tg_t = tg.get("time_s") if ok(tg) else None
    tg_d = tg.get("delaunay_s") if ok(tg) else None
    tg_m = tg.get("total_kb") if ok(tg) else None
    cg_t = cg.get("time_s") if ok(cg) else None
    rows = []
    for tool in ("idmesh", "tetgen", "cgal", "idmesh CLI -NEFQ", "tetgen -NEFQ"):
        r = res.get(tool)
        if r is None:
            continue
        if "error" in r:
            rows.append(error_row([tool], r, len(HEADER)))
            continue
        notes = common_notes(r)
        if tool == "tetgen":
            notes.append("time = whole process (read .node, tetrahedralize, write); "
                         "its own 'Delaunay seconds' (CPU): %s" % tfmt(r.get("delaunay_s")))
        if tool.endswith("-NEFQ"):
            notes.append("whole process, reading the .node, no output files")
            other = res.get("tetgen -NEFQ")
            if tool.startswith("idmesh") and ok(other):
                notes.append("%.2f x tetgen -NEFQ" % (r["time_s"] / other["time_s"]))
        rows.append([
            tool, tfmt(r["time_s"]), tfmt(r["best_s"]), tfmt(r.get("cpu_s")),
            ratio(r["time_s"], tg_t), ratio(r["time_s"], tg_d), ratio(r["time_s"], cg_t),
            count(r.get("tets")), count(r.get("vertices")), count(r.get("hull_faces")),
            mb(r.get("peak_kb")), mb(r.get("total_kb")), ratio(r.get("total_kb"), tg_m),
            "; ".join(notes),
        ])
    return rows


def targets(res):
    """The random case's targets: [(label, figure, met: True/False/None for information)]."""
    out = []
    i, t, c = (res.get(k) for k in ("idmesh", "tetgen", "cgal"))
    if not ok(i):
        return [("idmesh", "did not run: " + (i or {}).get("error", "not run")[:80], False)]
    if ok(t):
        r = i["time_s"] / t["time_s"]
        out.append(("(1) time vs TetGen (whole process)", f"ratio {r:.2f} (target <= 0.5)",
                    r <= 0.5))
        if t.get("delaunay_s"):
            r = i["time_s"] / t["delaunay_s"]
            out.append(("    time vs TetGen's own Delaunay seconds (CPU, for information)",
                        f"ratio {r:.2f}", None))
        r = i["total_kb"] / t["total_kb"]
        out.append(("(3) process peak memory vs TetGen", f"ratio {r:.2f} (target <= 1.0)",
                    r <= 1.0))
    if ok(c):
        r = i["time_s"] / c["time_s"]
        out.append(("(2) time vs CGAL", f"ratio {r:.2f} (target <= 1.0)", r <= 1.0))
    wi, wt = res.get("idmesh CLI -NEFQ"), res.get("tetgen -NEFQ")
    if ok(wi) and ok(wt):
        r = wi["time_s"] / wt["time_s"]
        out.append(("(whole process) idmesh CLI -NEFQ vs tetgen -NEFQ",
                    f"ratio {r:.2f} (issue 15 target <= 0.4)", r <= 0.4))
    return out


def case_label(name, case):
    """A refinement case's short name with its switches, e.g. `cube -pq1.414a0.000002V`."""
    return f"{name} -{case['switches']}{case.get('last_switch', '')}"


def build_refine_rows(cases):
    """Rows of the refinement table: one per case and tool."""
    rows = []
    for name, case in cases.items():
        res = case["results"]
        tg = res.get("tetgen", {})
        tg = tg if ok(tg) else {}
        label = case_label(name, case)
        for tool in ("idmesh", "tetgen"):
            r = res.get(tool)
            if r is None:
                continue
            if "error" in r:
                rows.append(error_row([label, tool], r, len(REFINE_HEADER)))
                continue
            notes = common_notes(r)
            if tool == "idmesh":
                if r.get("max_radius_edge") is not None:
                    notes.append("max radius-edge %.3f" % r["max_radius_edge"])
                v = case.get("verify")
                if v:
                    notes.append("verify3d " + ("OK" if v["ok"] else "FAILED: " + ", ".join(
                        v.get("failed") or [v.get("error", "?")])))
            elif r.get("refine_s") is not None:
                notes.append("own = CPU; refinement %s s, optimization %s s" % (
                    tfmt(r.get("refine_s")), tfmt(r.get("optimize_s"))))
            rows.append([
                label, tool, tfmt(r["time_s"]), tfmt(r["best_s"]),
                ratio(r["time_s"], tg.get("time_s")), tfmt(r.get("meshing_s")),
                ratio(r.get("meshing_s"), tg.get("meshing_s")), tfmt(r.get("cpu_s")),
                count(r.get("tets")), ratio(r.get("tets"), tg.get("tets")),
                count(r.get("vertices")), mb(r.get("total_kb")),
                ratio(r.get("total_kb"), tg.get("total_kb")), "; ".join(notes),
            ])
    return rows


def refine_targets(name, case):
    """A refinement case's targets: time <= 1.0 x TetGen's (whole process), tets <= 1.3 x
    TetGen's; own meshing times, memory and verify3d for information."""
    res = case["results"]
    i, t = res.get("idmesh"), res.get("tetgen")
    if not ok(i):
        return [(f"{name}: idmesh", "did not run: " + (i or {}).get("error", "not run")[:80],
                 False)]
    out = []
    if ok(t):
        r = i["time_s"] / t["time_s"]
        out.append((f"{name}: time vs TetGen (whole process)", f"ratio {r:.2f} (target <= 1.0)",
                    r <= 1.0))
        r = i["tets"] / t["tets"]
        out.append((f"{name}: tets vs TetGen", f"ratio {r:.2f} (target <= 1.3)", r <= 1.3))
        if i.get("cpu_s") and t.get("cpu_s"):
            r = i["cpu_s"] / t["cpu_s"]
            out.append((f"    {name}: process CPU time vs TetGen's (for information)",
                        f"ratio {r:.2f}", None))
        if i.get("meshing_s") and t.get("meshing_s"):
            r = i["meshing_s"] / t["meshing_s"]
            out.append((f"    {name}: own meshing time vs TetGen's (for information)",
                        f"ratio {r:.2f}", None))
        if i.get("total_kb") and t.get("total_kb"):
            r = i["total_kb"] / t["total_kb"]
            out.append((f"    {name}: peak memory vs TetGen (for information)",
                        f"ratio {r:.2f}", None))
    else:
        out.append((f"{name}: vs TetGen", "TetGen did not run", None))
    v = case.get("verify")
    if v:
        text = "all checks pass" if v["ok"] else "failed: " + ", ".join(
            v.get("failed") or [v.get("error", "?")])
        out.append((f"{name}: verify3d of idmesh's mesh", f"{text} ({v['seconds']:.0f} s)",
                    v["ok"]))
    return out


def print_table(rows, markdown, header=HEADER, out=sys.stdout):
    if not rows:
        return
    if markdown:
        print("| " + " | ".join(header) + " |", file=out)
        text_cols = (0, 1, len(header) - 1) if header is REFINE_HEADER else (0, len(header) - 1)
        print("|" + "|".join("---" if k in text_cols else "--:"
                             for k in range(len(header))) + "|", file=out)
        for r in rows:
            print("| " + " | ".join(str(x) for x in r) + " |", file=out)
        return
    widths = [max(len(str(r[k])) for r in rows + [header]) for k in range(len(header))]
    line = "  ".join(h.ljust(w) for h, w in zip(header, widths))
    print(line, file=out)
    print("-" * len(line), file=out)
    for r in rows:
        print("  ".join(str(x).ljust(w) for x, w in zip(r, widths)), file=out)


def print_targets(items, markdown):
    for label, text, met in items:
        verdict = "" if met is None else (" — met" if met else " — NOT met")
        print(("* " if markdown else "") + f"{label}: {text}{verdict}")


def upgrade(report):
    """A --json report from before the refinement cases (one random case) in today's form."""
    if "cases" in report:
        return report
    random = {"kind": "random", "points": report["points"], "seed": report.get("seed"),
              "results": report["results"]}
    return dict(report, cases={"random": random})


def render(report, markdown):
    """Prints the tables and target lists of a report (a fresh run or a saved --json)."""
    report = upgrade(report)
    info, cases = report["machine"], report["cases"]
    heading = "## " if markdown else "== "
    if markdown:
        print("# 3D benchmark: idmesh vs TetGen vs CGAL\n")
        print("Produced by `python3 bench/bench3d.py " + " ".join(report.get("argv", [])) +
              "`. Times are medians of fresh processes, tools interleaved.\n")
        print(f"Run {info['date']} on {info['nproc']} × {info['cpu']}, {info['memory']} RAM "
              f"({info['os']}).  ")
        print(f"idmesh {info['idmesh_commit']} ({info['rustc']}), TetGen {info['tetgen']} "
              f"(Debian), CGAL {info['cgal']} ({info['gxx']}, -O2).\n")
    random = cases.get("random")
    if random:
        print(f"{heading}Delaunay tetrahedralization of {random['points']:,} random points\n")
        print_table(build_rows(random["results"]), markdown)
        print()
        print_targets(targets(random["results"]), markdown)
        print()
    refine = {k: c for k, c in cases.items() if c.get("kind") == "refine" and "results" in c}
    skipped = {k: c for k, c in cases.items() if c.get("skipped")}
    if refine or skipped:
        print(f"{heading}Quality refinement, radius-edge {RADIUS_EDGE} and a volume bound "
              "(time = whole process: read, mesh, write)\n")
        for name, c in refine.items():
            extra = f", domain volume {c['domain_volume']:g}" if c.get("domain_volume") else ""
            print(("* " if markdown else "  ") + f"{name}: {c['input']}{extra}")
        for name, c in skipped.items():
            print(("* " if markdown else "  ") + f"{name}: skipped ({c['skipped']})")
        print()
        print_table(build_refine_rows(refine), markdown, REFINE_HEADER)
        print()
        for name, c in refine.items():
            print_targets(refine_targets(name, c), markdown)
        print()
    if markdown:
        print("Per-run times in seconds, in run order:\n")
        for name, c in cases.items():
            for tool, r in c.get("results", {}).items():
                if "times" in r:
                    print(f"* {name}, {tool}: " + ", ".join("%.3f" % t for t in r["times"]))


# ---------------------------------------------------------------------------------------------
# Main
# ---------------------------------------------------------------------------------------------

def prepare(workdir, n, seed):
    """Writes the points once (binary for CGAL, .node for TetGen); returns paths and hash."""
    xyz = splitmix_points(n, seed)
    h = input_hash(xyz)
    bin_path = os.path.join(workdir, f"random3d_{n}_{seed}.bin")
    node_path = os.path.join(workdir, f"random3d_{n}_{seed}.node")
    if not os.path.exists(bin_path) or os.path.getsize(bin_path) != 24 * n:
        xyz.astype("<f8").tofile(bin_path)
    if not os.path.exists(node_path):
        log(f"writing {node_path}")
        write_node(node_path + ".tmp", xyz)
        os.replace(node_path + ".tmp", node_path)
    return bin_path, node_path, h


def selftest(workdir, exes, cgal, use_tetgen):
    """Checks that could fail: all tools read the same bits, the mesh is valid, and on points in
    general position (unique Delaunay tetrahedralization) the three tools agree on counts; then a
    coarse refinement of the unit cube through both command lines: outputs parsed, counts agree
    with what the tools print, and (with ../shared) idmesh's mesh passes verify3d."""
    import numpy as np
    idmesh = exes.get("points")
    failures = []

    def check(cond, what):
        log(("ok    " if cond else "FAIL  ") + what)
        if not cond:
            failures.append(what)

    state, ref = 5, []
    for _ in range(6):
        state = (state + GOLD) & M64
        z = state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & M64
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & M64
        ref.append(((z ^ (z >> 31)) >> 11) / 2.0**53)
    check(splitmix_points(2, 5).ravel().tolist() == ref, "numpy SplitMix64 == int SplitMix64")
    n, seed = 20000, 11
    bin_path, node_path, h = prepare(workdir, n, seed)
    back = read_node_back(node_path)
    check(np.array_equal(back, splitmix_points(n, seed)), ".node file reads back bit-exactly")
    res = {}
    if idmesh:
        res["idmesh"] = json_child([idmesh, str(n), str(seed), "--validate"], 300)
        check(res["idmesh"].get("input_hash") == h, "idmesh generated the same points")
        check(res["idmesh"].get("valid") is True,
              "idmesh mesh passes the exact TetMesh::validate()")
    if cgal:
        res["cgal"] = json_child([cgal, bin_path], 300)
        check(res["cgal"].get("input_hash") == h, "CGAL read the same points")
    if use_tetgen:
        res["tetgen"] = tetgen_child(node_path, workdir, 300)
        check(res["tetgen"].get("input_points") == n, "TetGen read all points")
    for tool, r in res.items():
        check("error" not in r, f"{tool} ran ({r.get('error', 'ok')})")
    counts = {t: (r.get("tets"), r.get("hull_faces")) for t, r in res.items()}
    check(len(set(counts.values())) == 1, f"tet and hull-face counts agree: {counts}")

    volume = "0.001"
    polys = prepare_refine(workdir, "cube", ["idmesh"] + (["tetgen"] if use_tetgen else []))
    switches = f"pq{RADIUS_EDGE}a{volume}V"
    if exes.get("cli"):
        r = refine_child("idmesh", exes["cli"], polys["idmesh"], switches, 300, keep=True)
        kept = r.get("kept_stem")
        check("error" not in r, f"idmesh tetgen -{switches} ran ({r.get('error', 'ok')})")
        check(r.get("meshing_s") is not None and r.get("read_s") is not None,
              "idmesh's 'Time: reading ... meshing ... writing' line parsed")
        check(r.get("tets") is not None and r.get("tets") == r.get("stdout_tets"),
              f"idmesh's .ele header agrees with its printed count ({r.get('tets')})")
        check(abs((r.get("volume") or 0.0) - 1.0) < 1e-9, "idmesh meshed volume 1")
        if os.path.exists(VERIFY3D) and kept:
            v = verify_mesh(polys["idmesh"], kept, volume, 300)
            check(v["ok"], f"verify3d passes idmesh's cube mesh ({v})")
        if kept:
            remove_outputs(kept)
    if use_tetgen:
        r = refine_child("tetgen", "tetgen", polys["tetgen"], switches, 300)
        check("error" not in r, f"tetgen -{switches} ran ({r.get('error', 'ok')})")
        check(r.get("meshing_s") is not None and r.get("refine_s") is not None,
              "TetGen's -V timings parsed")
        check(r.get("tets") is not None and r.get("tets") == r.get("stdout_tets"),
              f"TetGen's .ele header agrees with its printed count ({r.get('tets')})")
    if failures:
        log(f"{len(failures)} self-test check(s) failed")
        return 1
    log("self-test passed")
    return 0


def prepare_refine(workdir, name, tools):
    """Gives each tool its own copy of a refinement case's .poly file, in
    workdir/NAME/TOOL/, so that their outputs do not clash. Returns {tool: path}, or None if
    the input is absent. The cube's .poly file is written to workdir/cube/cube.poly."""
    spec = REFINE_CASES[name]
    src = spec["source"]
    casedir = os.path.join(workdir, name)
    os.makedirs(casedir, exist_ok=True)
    if src is None:
        src = os.path.join(casedir, "cube.poly")
        write_cube_poly(src)
    elif not os.path.exists(src):
        return None
    out = {}
    for tool in tools:
        d = os.path.join(casedir, tool)
        os.makedirs(d, exist_ok=True)
        out[tool] = os.path.join(d, os.path.basename(src))
        shutil.copyfile(src, out[tool])
    return out


def run_random(a, exes, cgal, use_tetgen):
    """The random case: idmesh's bench3d_points, TetGen on the .node file and CGAL, interleaved.
    Returns the case's report entry."""
    n = a.points or (QUICK_POINTS if a.quick else FULL_POINTS)
    bin_path, node_path, h = prepare(a.workdir, n, a.seed)
    idmesh = exes.get("points")
    tools = {}
    if idmesh:
        # The first idmesh run also checks its mesh exactly, after the timed call.
        tools["idmesh"] = lambda rep: json_child(
            [idmesh, str(n), str(a.seed)] + (["--validate"] if rep == 0 else []), a.timeout)
    if use_tetgen:
        tools["tetgen"] = lambda rep: tetgen_child(node_path, a.workdir, a.timeout)
    if cgal:
        tools["cgal"] = lambda rep: json_child([cgal, bin_path], a.timeout)
    if a.whole_process and exes.get("cli"):
        tools["idmesh CLI -NEFQ"] = lambda rep: whole_process_child(
            "idmesh CLI -NEFQ", [exes["cli"], "tetgen", "-NEFQ", node_path], n, a.timeout)
    if a.whole_process and use_tetgen:
        tools["tetgen -NEFQ"] = lambda rep: whole_process_child(
            "tetgen -NEFQ", ["tetgen", "-NEFQ", node_path], n, a.timeout)

    def check(r):
        if "input_hash" in r and r["input_hash"] != h:
            return f"input hash {r['input_hash']} != {h}: different coordinates"
        if r.get("input_points") not in (None, n):
            return f"read {r.get('input_points')} points, expected {n}"
        return None

    log(f"== random: Delaunay of {n:,} random points (seed {a.seed}), {a.repeat} runs per tool")
    runs = interleaved(tools, a.repeat, a.wait_idle, check)
    results = {tool: summarise(rs) for tool, rs in runs.items()}
    if not idmesh:
        results["idmesh"] = {"error": exes.get("error") or "not built"}
    return {"kind": "random", "points": n, "seed": a.seed, "results": results}


def whole_process_child(tool, cmd, n, timeout):
    """One whole-process run with no output files (-NEFQ): the wall clock around the process,
    reading the .node file included; the peak RSS is wait4's ru_maxrss."""
    c = run_child(cmd, timeout, cwd=os.path.dirname(cmd[-1]))
    if c.code != 0:
        return {"error": failure(c, timeout)}
    return {
        "tool": tool,
        "time_s": c.wall,
        "process_s": c.wall,
        "cpu_s": c.ru.ru_utime + c.ru.ru_stime,
        "input_points": n,
        "total_kb": c.ru.ru_maxrss,
        "parent_rss_kb": c.parent_rss_kb,
    }


def run_refine(name, a, exes, use_tetgen):
    """A refinement case: both command lines on their own copies of the same .poly file,
    interleaved; with --verify, verify3d on the first idmesh mesh. Returns the report entry."""
    spec = REFINE_CASES[name]
    volume = a.volume or spec["quick" if a.quick else "full"]
    switches = f"pq{RADIUS_EDGE}a{volume}"
    last = "Q" if a.quiet else "V"
    idmesh = exes.get("cli")
    tool_names = (["idmesh"] if idmesh else []) + (["tetgen"] if use_tetgen else [])
    polys = prepare_refine(a.workdir, name, tool_names)
    if polys is None:
        why = f"{spec['source']} is absent (../shared is not next to the repository)"
        log(f"== {name}: skipped: {why}")
        return {"kind": "refine", "skipped": why}
    shown = os.path.relpath(spec["source"], ROOT) if spec["source"] else "written by the script"
    n, lo, hi = poly_extent(spec["source"] or os.path.join(a.workdir, name, "cube.poly"))
    extent = " x ".join(f"[{l:g}, {h:g}]" for l, h in zip(lo, hi))
    case = {"kind": "refine", "title": spec["title"], "input": f"{spec['title']} ({shown}): "
            f"{n} points, extent {extent}", "volume": volume, "switches": switches,
            "results": {}}
    log(f"== {name}: {case['input']}; -{switches}{last}, {a.repeat} runs per tool")
    case["last_switch"] = last
    tools = {}
    if idmesh:
        tools["idmesh"] = lambda rep: refine_child(
            "idmesh", idmesh, polys["idmesh"], switches + last, a.timeout,
            keep=a.verify and rep == 0)
    if use_tetgen:
        tools["tetgen"] = lambda rep: refine_child("tetgen", "tetgen", polys["tetgen"],
                                                   switches + last, a.timeout)
    runs = interleaved(tools, a.repeat, a.wait_idle)
    case["results"] = {tool: summarise(rs) for tool, rs in runs.items()}
    if not idmesh:
        case["results"]["idmesh"] = {"error": exes.get("error") or "not built"}
    vols = [r["volume"] for r in runs.get("idmesh", []) if r.get("volume")]
    if vols:
        case["domain_volume"] = vols[0]
    if a.verify and idmesh:
        stem = runs["idmesh"][0].get("kept_stem")
        if not os.path.exists(VERIFY3D):
            log(f"   verify3d skipped: {VERIFY3D} is absent")
        elif not stem:
            log("   verify3d skipped: the first idmesh run failed")
        else:
            log("   verify3d on idmesh's first mesh (untimed; slow for 1M tets)")
            case["verify"] = verify_mesh(polys["idmesh"], stem, volume, a.verify_timeout)
            log(f"   verify3d: {case['verify']}")
        if stem:
            remove_outputs(stem)
    return case


def parse_cases(text):
    """The --cases list, checked; refinement cases first (run_child explains why)."""
    names = [c.strip() for c in text.split(",") if c.strip()]
    bad = [c for c in names if c not in ALL_CASES]
    if bad or not names:
        raise SystemExit(f"--cases: unknown {bad}; choose from {','.join(ALL_CASES)}")
    # The random case imports numpy and builds big arrays, which raise the script's own RSS, the
    # floor of every later child's wait4() peak; so it runs last.
    return [c for c in names if c != "random"] + [c for c in names if c == "random"]


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default=",".join(ALL_CASES),
                    help="comma-separated cases to run (default: %(default)s)")
    ap.add_argument("--quick", action="store_true",
                    help=f"{QUICK_POINTS:,} points; ~100k-tet volume bounds for the refinement "
                         "cases")
    ap.add_argument("--points", type=int, help="number of points (overrides --quick)")
    ap.add_argument("--volume", help="volume bound of the refinement cases, a decimal string "
                                     "(overrides their full and --quick bounds; 0.0000002 gives "
                                     "the cube about 10,000,000 tets)")
    ap.add_argument("--seed", type=int, default=SEED)
    ap.add_argument("--repeat", type=int, default=3, help="runs per tool (median time)")
    ap.add_argument("--verify", action="store_true",
                    help="check the first idmesh mesh of each refinement case with "
                         "../shared/tools/verify3d.py (untimed; ~40 s per 1M-tet mesh)")
    ap.add_argument("--quiet", action="store_true",
                    help="refinement runs end their switches with Q instead of V: no own "
                         "timings, and neither tool computes its closing statistics")
    ap.add_argument("--verify-timeout", type=float, default=3600.0,
                    help="seconds per verify3d run")
    ap.add_argument("--markdown", action="store_true", help="emit a Markdown table")
    ap.add_argument("--no-cgal", action="store_true")
    ap.add_argument("--no-tetgen", action="store_true")
    ap.add_argument("--wait-idle", type=float, default=60.0,
                    help="before each run wait up to this many seconds for other jobs to leave "
                         "the CPUs idle (0: never wait)")
    ap.add_argument("--timeout", type=float, default=600.0, help="seconds per child run")
    ap.add_argument("--workdir", default=os.path.join(ROOT, "target", "bench3d"))
    ap.add_argument("--json", help="also write all raw results to this file")
    ap.add_argument("--render", metavar="JSON",
                    help="print the table of a saved --json run again, without running anything")
    ap.add_argument("--selftest", action="store_true",
                    help="quick consistency checks of the tools' inputs and outputs")
    ap.add_argument("--whole-process", action="store_true",
                    help="random case: also time `idmesh tetgen -NEFQ` and `tetgen -NEFQ` on "
                         "the .node file as whole processes (reading included, no output)"),
    a = ap.parse_args()

    if a.render:
        with open(a.render) as f:
            render(json.load(f), a.markdown)
        return 0
    cases = ALL_CASES if a.selftest else parse_cases(a.cases)
    want_random = "random" in cases
    if want_random:
        ensure_numpy()
    os.makedirs(a.workdir, exist_ok=True)
    want_cgal = want_random and not a.no_cgal
    apt_ok = ensure_apt_deps(want_cgal, not a.no_tetgen)
    use_tetgen = not a.no_tetgen and shutil.which("tetgen") is not None
    exes, err = build_idmesh(want_random, any(c != "random" for c in cases) or
                             (want_random and a.whole_process))
    if err:
        exes["error"] = err
    cgal = None
    if want_cgal and apt_ok:
        try:
            cgal = build_cgal(a.workdir)
        except (OSError, subprocess.CalledProcessError) as e:
            log(f"CGAL build failed ({e}); CGAL skipped")
    if a.selftest:
        return selftest(a.workdir, exes, cgal, use_tetgen)

    report = {"machine": machine_info(), "repeat": a.repeat, "quick": a.quick,
              "argv": sys.argv[1:], "cases": {}}
    for name in cases:
        if name == "random":
            report["cases"][name] = run_random(a, exes, cgal, use_tetgen)
        else:
            report["cases"][name] = run_refine(name, a, exes, use_tetgen)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(report, f, indent=1)
    render(report, a.markdown)
    return 0


if __name__ == "__main__":
    sys.exit(main())
