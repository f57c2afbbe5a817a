#!/usr/bin/env python3
"""Side-by-side 2D benchmark: idmesh vs Triangle (Shewchuk, via PyPI `triangle`) vs CGAL.

Every tool runs in a fresh child process per run and times only its meshing call:
  * idmesh:   `cargo run --release --example bench2d` (times `idmesh::triangulate`),
  * Triangle: this script in `--child-triangle` mode (times `triangle.triangulate(...)`),
  * CGAL:     bench/cgal_bench2d.cpp compiled with g++ -O3 (times the range insert, or the CDT
              construction plus `refine_Delaunay_mesh_2`).
Each child reports its RSS just before the call and its peak RSS during the call (VmHWM, reset
through /proc/self/clear_refs just before the call); the parent also records the child's total
peak RSS from wait4(). All tools read the same coordinates; `input_hash` proves it.

With --whole-process each case gains a row "idmesh CLI": `target/release/idmesh triangle` run
as users run it, a whole process on a file (the random points as a .node file written once with
round-trip-exact decimals, or the .poly file), no output files (`-NEPQ`), timed by the parent's
wall clock: reading the file is included, unlike the in-process rows and Triangle's call.

Usage: python3 bench/bench2d.py [--quick] [--markdown] [--repeat N] [--cases LIST]
                                [--poly PATH SWITCHES] [--json OUT] [--no-cgal] [--timeout S]
                                [--whole-process]
See bench/README.md.
"""

import argparse
import datetime
import json
import math
import os
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BENCH = os.path.join(ROOT, "bench")
CGAL_SRC = os.path.join(BENCH, "cgal_bench2d.cpp")
# Optional independent verifier (used only with --verify; the benchmark runs without it).
VERIFY2D = "/work/shared/tools/verify2d.py"

# Issue targets: (1) random 1M points, (2) -pq30a0.0000012, (3) -pq33a0.0000012 on the square
# with a hole, each ~1M triangles; --quick uses 1/10 of the size.
FULL = {"points": 1_000_000, "area": 0.0000012}
QUICK = {"points": 100_000, "area": 0.000012}
SEED = 20240601

GOLD = 0x9E3779B97F4A7C15
M64 = (1 << 64) - 1


def log(msg):
    print(msg, file=sys.stderr, flush=True)


# ---------------------------------------------------------------------------------------------
# Shared helpers (also used by the Triangle child)
# ---------------------------------------------------------------------------------------------

def mix64(z):
    """SplitMix64's finaliser on a numpy uint64 array (wrapping arithmetic)."""
    import numpy as np
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


def splitmix_points(n, seed):
    """The same points as `bench2d random N SEED`: x then y from consecutive SplitMix64 draws,
    each (u >> 11) * 2^-53 (exact in float64)."""
    import numpy as np
    with np.errstate(over="ignore"):
        k = np.arange(1, 2 * n + 1, dtype=np.uint64)
        state = np.uint64(seed & M64) + k * np.uint64(GOLD)
        u = mix64(state)
    return ((u >> np.uint64(11)).astype(np.float64) * 2.0**-53).reshape(n, 2)


def input_hash(xy, segments=None):
    """Order-sensitive hash of coordinate bits then segments, as in examples/bench2d.rs."""
    import numpy as np
    words = [np.ascontiguousarray(xy, dtype=np.float64).ravel().view(np.uint64)]
    if segments is not None and len(segments):
        s = np.asarray(segments, dtype=np.uint64)
        words.append((s[:, 0] << np.uint64(32)) | s[:, 1])
    w = np.concatenate(words)
    with np.errstate(over="ignore"):
        idx = np.arange(len(w), dtype=np.uint64) * np.uint64(GOLD)
        return "%016x" % int(mix64(w ^ idx).sum(dtype=np.uint64))


def read_poly(path):
    """Triangle .poly reader (vertices with markers, segments with markers, holes, regions).
    Returns a dict for triangle.triangulate; indices are rebased to 0."""
    import numpy as np

    def lines_of(p):
        with open(p) as f:
            for line in f:
                t = line.split("#", 1)[0].split()
                if t:
                    yield t

    it = lines_of(path)
    head = next(it)
    n = int(head[0])
    src = it
    if n == 0:  # vertices live in the .node file beside the .poly
        src = lines_of(path[: -len(".poly")] + ".node" if path.endswith(".poly") else path)
        head = next(src)
        n = int(head[0])
    nattr = int(head[2]) if len(head) > 2 else 0
    has_marker = int(head[3]) if len(head) > 3 else 0
    verts, vmark, base = [], [], 0
    for i in range(n):
        t = next(src)
        if i == 0:
            base = int(t[0])
        verts.append((float(t[1]), float(t[2])))
        if has_marker:
            vmark.append(int(t[3 + nattr]))
    t = next(it)
    ns, smark_flag = int(t[0]), (int(t[1]) if len(t) > 1 else 0)
    segs, smark = [], []
    for _ in range(ns):
        t = next(it)
        segs.append((int(t[1]) - base, int(t[2]) - base))
        if smark_flag:
            smark.append(int(t[3]))
    holes, regions = [], []
    t = next(it, None)
    if t is not None:
        for _ in range(int(t[0])):
            h = next(it)
            holes.append((float(h[1]), float(h[2])))
        t = next(it, None)
        if t is not None:
            for _ in range(int(t[0])):
                r = next(it)
                attr = float(r[3]) if len(r) > 3 else 0.0
                area = float(r[4]) if len(r) > 4 else -1.0
                regions.append((float(r[1]), float(r[2]), attr, area))
    d = {"vertices": np.array(verts, dtype=np.float64).reshape(-1, 2)}
    if vmark:
        d["vertex_markers"] = np.array(vmark, dtype=np.int32).reshape(-1, 1)
    if segs:
        d["segments"] = np.array(segs, dtype=np.int32).reshape(-1, 2)
    if smark:
        d["segment_markers"] = np.array(smark, dtype=np.int32).reshape(-1, 1)
    if holes:
        d["holes"] = np.array(holes, dtype=np.float64).reshape(-1, 2)
    if regions:
        d["regions"] = np.array(regions, dtype=np.float64).reshape(-1, 4)
    return d


def proc_status():
    out = {}
    with open("/proc/self/status") as f:
        for line in f:
            k, _, v = line.partition(":")
            if k in ("VmRSS", "VmHWM"):
                out[k] = int(v.split()[0])
    return out


def reset_hwm():
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
        return True
    except OSError:
        return False


def min_angle_deg(xy, tris):
    """Smallest triangle angle, same formula as idmesh's angle_range (atan2 of |cross|, dot)."""
    import numpy as np
    if len(tris) == 0:
        return None
    p = [xy[tris[:, k]] for k in range(3)]
    best = np.inf
    for a, b, c in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        u = p[b] - p[a]
        v = p[c] - p[a]
        cross = np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
        dot = u[:, 0] * v[:, 0] + u[:, 1] * v[:, 1]
        best = min(best, float(np.degrees(np.arctan2(cross, dot)).min()))
    return best


def triangle_child(kind, path, switches):
    """Runs inside a fresh process: load input, time triangle.triangulate only, print JSON."""
    import numpy as np
    import triangle

    if kind == "points":
        xy = np.fromfile(path, dtype="<f8").reshape(-1, 2)
        d = {"vertices": xy}
        h = input_hash(xy)
    else:
        d = read_poly(path)
        h = input_hash(d["vertices"], d.get("segments"))
    before = proc_status()
    hwm_reset = reset_hwm()
    t0 = time.perf_counter()
    r = triangle.triangulate(d, switches)
    secs = time.perf_counter() - t0
    after = proc_status()
    tris = r.get("triangles", np.zeros((0, 3), dtype=np.int32))
    res = {
        "tool": "triangle",
        "switches": switches,
        "time_s": secs,
        "vertices": int(len(r["vertices"])),
        "triangles": int(len(tris)),
        "min_angle": min_angle_deg(r["vertices"], tris),
        "input_hash": h,
        "input_points": int(len(d["vertices"])),
        "rss_before_kb": before["VmRSS"],
        "hwm_before_kb": before["VmHWM"],
        "hwm_after_kb": after["VmHWM"],
        "rss_after_kb": after["VmRSS"],
        "hwm_reset": hwm_reset,
    }
    print(json.dumps(res), flush=True)


# ---------------------------------------------------------------------------------------------
# Setup: dependencies and builds
# ---------------------------------------------------------------------------------------------

def ensure_python_deps():
    missing = []
    for mod in ("numpy", "triangle"):
        try:
            __import__(mod)
        except ImportError:
            missing.append(mod)
    if missing:
        log("installing with pip: " + " ".join(missing))
        subprocess.check_call([sys.executable, "-m", "pip", "install", "-q", *missing])


def ensure_apt_deps():
    need = []
    if not shutil.which("g++"):
        need.append("g++")
    for header, pkg in (("/usr/include/CGAL/Delaunay_mesher_2.h", "libcgal-dev"),
                        ("/usr/include/x86_64-linux-gnu/gmp.h", "libgmp-dev"),
                        ("/usr/include/mpfr.h", "libmpfr-dev")):
        if not os.path.exists(header) and not (pkg == "libgmp-dev"
                                               and os.path.exists("/usr/include/gmp.h")):
            need.append(pkg)
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
        log(f"apt-get failed ({e}); CGAL will be skipped")
        return False


def build_idmesh():
    log("building idmesh: cargo build --release --example bench2d --bin idmesh")
    r = subprocess.run(["cargo", "build", "--release", "--example", "bench2d", "--bin", "idmesh",
                        "-q"], cwd=ROOT, capture_output=True, text=True)
    if r.returncode != 0:
        first = next((ln for ln in r.stderr.splitlines() if ln.startswith("error")), "")
        log(r.stderr[-3000:])
        return None, "cargo build failed: " + first
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    exe = os.path.join(target, "release", "examples", "bench2d")
    if not os.path.exists(exe):
        return None, f"built bench2d but cannot find it at {exe}"
    return exe, None


def build_cgal(workdir):
    exe = os.path.join(workdir, "cgal_bench2d")
    if os.path.exists(exe) and os.path.getmtime(exe) >= os.path.getmtime(CGAL_SRC):
        return exe
    log("compiling bench/cgal_bench2d.cpp with g++ -O3 (takes ~15 s)")
    subprocess.check_call(["g++", "-O3", "-DNDEBUG", "-std=c++17", "-o", exe, CGAL_SRC,
                           "-lgmp", "-lmpfr"])
    return exe


def idmesh_cli():
    """The `idmesh` command line built by build_idmesh (None if missing)."""
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    exe = os.path.join(target, "release", "idmesh")
    return exe if os.path.exists(exe) else None


def write_node(path, xy):
    """Writes points as a Triangle .node file, 1-based; %.17g reads back bit for bit."""
    import numpy as np
    if os.path.exists(path):
        return
    log(f"writing {path}")
    table = np.column_stack([np.arange(1, len(xy) + 1, dtype=np.float64), xy])
    with open(path + ".tmp", "w") as f:
        f.write(f"{len(xy)} 2 0 0\n")
        np.savetxt(f, table, fmt=["%d", "%.17g", "%.17g"])
    os.replace(path + ".tmp", path)


def whole_process(cmd, timeout):
    """Runs a command line with no output files as users run it; the time is the parent's wall
    clock around the whole process and the memory is wait4's peak RSS."""
    with tempfile.TemporaryFile() as err:
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=err, cwd=ROOT)
        status, ru, timed_out = wait_child(p, timeout, 0.005)
        secs = time.perf_counter() - t0
        err.seek(0)
        etext = err.read().decode(errors="replace").strip()
    if timed_out:
        return {"error": f"timeout after {timeout:.0f} s"}
    code = os.waitstatus_to_exitcode(status)
    if code != 0:
        return {"error": f"exit {code}: " + " | ".join(etext.splitlines()[-3:])}
    peak = ru.ru_maxrss
    return {"tool": "idmesh CLI", "time_s": secs, "vertices": None, "triangles": None,
            "min_angle": None, "rss_before_kb": 0, "hwm_before_kb": peak, "hwm_after_kb": peak,
            "hwm_reset": True}


# ---------------------------------------------------------------------------------------------
# Inputs
# ---------------------------------------------------------------------------------------------

def hole_pslg(n=64):
    pts = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
    segs = [(0, 1), (1, 2), (2, 3), (3, 0)]
    for i in range(n):
        t = 2.0 * math.pi * i / n
        pts.append((0.5 + 0.25 * math.cos(t), 0.5 + 0.25 * math.sin(t)))
        segs.append((4 + i, 4 + (i + 1) % n))
    return pts, segs, [(0.5, 0.5)]


def write_poly(path, pts, segs, holes, title="square with a circular hole, written by bench/bench2d.py"):
    with open(path, "w") as f:
        f.write(f"# {title}\n{len(pts)} 2 0 0\n")
        for i, (x, y) in enumerate(pts):
            f.write(f"{i} {x!r} {y!r}\n")  # repr round-trips exactly
        f.write(f"{len(segs)} 0\n")
        for i, (a, b) in enumerate(segs):
            f.write(f"{i} {a} {b}\n")
        f.write(f"{len(holes)}\n")
        for i, (x, y) in enumerate(holes):
            f.write(f"{i} {x!r} {y!r}\n")


def plain_decimal(x):
    """Triangle's -a takes a plain decimal (no exponent)."""
    import numpy as np
    return np.format_float_positional(x, trim="-")


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
    """Other jobs share this machine; wait (up to max_wait s) until they leave the CPUs idle, so
    that no tool is timed on a busy machine. Returns the busy-core figure at the start."""
    deadline = time.monotonic() + max_wait
    busy = busy_cores()
    announced = False
    while busy > threshold and time.monotonic() < deadline:
        if not announced:
            log(f"   waiting for the machine to go quiet ({busy:.1f} cores busy)")
            announced = True
        time.sleep(2.0)
        busy = busy_cores()
    return busy


def wait_child(p, timeout, poll):
    """Waits for the Popen `p` with wait4 (for its rusage), killing it after `timeout` seconds.
    Returns (wait status, rusage, whether it timed out)."""
    deadline = time.monotonic() + timeout
    while True:
        pid, status, ru = os.wait4(p.pid, os.WNOHANG)
        if pid:
            return status, ru, False
        if time.monotonic() > deadline:
            p.kill()
            _, status, ru = os.wait4(p.pid, 0)
            return status, ru, True
        time.sleep(poll)


def run_child(cmd, timeout):
    """Runs cmd in a fresh process; returns (parsed JSON or error dict, child's peak RSS kB)."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        p = subprocess.Popen(cmd, stdout=out, stderr=err, cwd=ROOT)
        status, ru, timed_out = wait_child(p, timeout, 0.02)
        p.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        err.seek(0)
        text = out.read().decode(errors="replace").strip().splitlines()
        etext = err.read().decode(errors="replace").strip()
    if timed_out:
        return {"error": f"timeout after {timeout:.0f} s"}, ru.ru_maxrss
    res = None
    for line in reversed(text):
        try:
            res = json.loads(line)
            break
        except ValueError:
            continue
    if res is None:
        tail = (etext or "no output").splitlines()[-3:]
        res = {"error": f"exit {p.returncode}: " + " | ".join(tail)}
    elif p.returncode != 0 and "error" not in res:
        res["error"] = f"exit {p.returncode}"
    return res, ru.ru_maxrss


def summarise(runs, max_rss):
    """Median time over the repeats; memory as the largest seen (conservative for every tool)."""
    ok = [r for r in runs if "error" not in r]
    if not ok:
        return {"error": runs[0].get("error", "failed")}
    out = dict(ok[0])
    out["time_s"] = statistics.median(r["time_s"] for r in ok)
    out["times"] = [r["time_s"] for r in ok]
    out["peak_kb"] = max(r["hwm_after_kb"] - r["rss_before_kb"] for r in ok)
    # The child's whole-life peak: VmHWM before the reset covers loading the input, VmHWM after
    # covers the call. (wait4's ru_maxrss is kept only as a raw figure: the kernel folds the
    # pre-exec image, i.e. the forking Python parent, into it.)
    out["total_kb"] = max(max(r["hwm_before_kb"], r["hwm_after_kb"]) for r in ok)
    out["wait4_maxrss_kb"] = max_rss
    bad = [r for r in ok if r.get("valid") is False]
    if bad:
        out["note"] = "INVALID mesh: " + bad[0].get("invalid_reason", "")[:80]
    elif any(r.get("valid") for r in ok):
        out["note"] = "validate() ok"
    out["hwm_reset"] = all(r.get("hwm_reset") for r in ok)
    out["best_s"] = min(out["times"])
    out["runs"] = len(ok)
    out["busy_cores_max"] = max(r.get("busy_cores_before", 0.0) for r in ok)
    return out


# ---------------------------------------------------------------------------------------------
# Main
# ---------------------------------------------------------------------------------------------

def machine_info():
    cpu = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    mem = "unknown"
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemTotal"):
                    mem = "%.1f GiB" % (int(line.split()[1]) / 1024 / 1024)
    except OSError:
        pass

    def version(cmd):
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
    try:
        from importlib.metadata import version as pv
        tri = pv("triangle")
    except Exception:  # noqa: BLE001 - any failure just means "unknown"
        tri = "unknown"
    return {
        "date": datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z"),
        "nproc": os.cpu_count(),
        "cpu": cpu,
        "memory": mem,
        "os": platform.platform(),
        "rustc": version(["rustc", "--version"]),
        "gxx": version(["g++", "--version"]),
        "cgal": cgal,
        "triangle_pypi": tri,
        "python": platform.python_version(),
        "idmesh_commit": version(["git", "rev-parse", "--short", "HEAD"]) + dirty(),
    }


def dirty():
    """' + local changes' when the benchmarked tree differs from the commit named."""
    try:
        r = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                           capture_output=True, text=True, cwd=ROOT)
        return " + uncommitted changes" if r.stdout.strip() else ""
    except OSError:
        return ""


def tfmt(t):
    return "%.3f" % t if t >= 0.01 else "%.2e" % t


def fmt(x, spec):
    return "-" if x is None else format(x, spec)


def note(r):
    parts = [r["note"]] if r.get("note") else []
    if r.get("busy_cores_max", 0.0) > 0.3:
        parts.append("other jobs used up to %.1f cores during a run" % r["busy_cores_max"])
    return "; ".join(parts)


def count(n):
    return "-" if n is None else "{:,}".format(n)


def note_whole(tool):
    return ("whole process: reads the file, no output files (-NEPQ); peak MB is wait4's, "
            "which counts the forking script's own RSS too (an upper bound)"
            if tool == "idmesh CLI" else "")


def build_rows(results):
    rows = []
    for case in results:
        base = case["tools"].get("triangle", {})
        bt = base.get("time_s") if "error" not in base else None
        bm = base.get("peak_kb") if "error" not in base else None
        for tool, r in case["tools"].items():
            if "error" in r:
                rows.append([case["name"], tool, "error: " + r["error"][:90]] + [""] * 9)
                continue
            ratio = r["time_s"] / bt if bt else None
            mratio = r["peak_kb"] / bm if bm else None
            rows.append([
                case["name"], tool, tfmt(r["time_s"]), tfmt(r["best_s"]), fmt(ratio, ".2f"),
                count(r["vertices"]), count(r["triangles"]),
                fmt(r.get("min_angle"), ".2f"), "%.1f" % (r["peak_kb"] / 1024),
                fmt(mratio, ".2f"), "%.1f" % (r["total_kb"] / 1024),
                "; ".join(x for x in (note(r), note_whole(tool)) if x),
            ])
    return rows


HEADER = ["case", "tool", "time s", "best s", "ratio to Triangle", "vertices", "triangles",
          "min angle", "peak MB", "peak ratio", "total MB", "note"]


def print_table(rows, markdown, out=sys.stdout):
    if markdown:
        print("| " + " | ".join(HEADER) + " |", file=out)
        print("|" + "|".join("---" if i < 2 or i == len(HEADER) - 1 else "--:"
                             for i in range(len(HEADER))) + "|", file=out)
        for r in rows:
            print("| " + " | ".join(str(c) for c in r) + " |", file=out)
        return
    widths = [max(len(str(r[i])) for r in rows + [HEADER]) for i in range(len(HEADER))]
    line = "  ".join(h.ljust(w) for h, w in zip(HEADER, widths))
    print(line, file=out)
    print("-" * len(line), file=out)
    for r in rows:
        print("  ".join(str(c).ljust(w) for c, w in zip(r, widths)), file=out)


def targets(results):
    """The issue's targets, evaluated on the measured numbers."""
    out = []
    by = {c["key"]: c["tools"] for c in results}

    def get(key, tool):
        r = by.get(key, {}).get(tool)
        return None if r is None or "error" in r else r

    def check(label, key, time_ok, count_ok):
        if key not in by:
            return
        i, t = get(key, "idmesh"), get(key, "triangle")
        if not t:
            out.append((label, "Triangle failed, nothing to compare with", None))
            return
        if not i:
            err = by.get(key, {}).get("idmesh", {}).get("error", "not run")
            out.append((label, f"idmesh failed: {err[:80]}", False))
            return
        tr = i["time_s"] / t["time_s"]
        parts = [f"time ratio {tr:.2f} (target <= 1.0)"]
        ok = tr <= 1.0
        if count_ok:
            cr = i["triangles"] / t["triangles"]
            parts.append(f"triangle-count ratio {cr:.3f} (target <= 1.0)")
            ok = ok and cr <= 1.0
        out.append((label, "; ".join(parts), ok))

    check("(1) Delaunay of random points", "random", True, False)
    check("(2) -pq30a on square with hole", "hole30", True, True)
    check("(3) -pq33a on square with hole", "hole33", True, True)
    for key in ("random", "hole30", "hole33"):
        i, t = get(key, "idmesh"), get(key, "triangle")
        if i and t:
            mr = i["peak_kb"] / t["peak_kb"]
            out.append((f"(4) peak memory, {key}",
                        f"meshing-call peak ratio {mr:.2f} (target <= 1.2)", mr <= 1.2))
        elif t:
            out.append((f"(4) peak memory, {key}", "idmesh did not run", False))
    for key in by:
        w, t = get(key, "idmesh CLI"), get(key, "triangle")
        if w and t:
            r = w["time_s"] / t["time_s"]
            out.append((f"(whole process) {key}: idmesh CLI vs Triangle's call",
                        f"time ratio {r:.2f} (issue 15 target <= 0.7)", r <= 0.7))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="100k points / ~100k triangles")
    ap.add_argument("--markdown", action="store_true", help="emit Markdown for bench/RESULTS.md")
    ap.add_argument("--repeat", type=int, default=3, help="runs per tool and case (median time)")
    ap.add_argument("--cases", default="random,hole30,hole33",
                    help="comma list of random, hole30, hole33")
    ap.add_argument("--poly", nargs=2, action="append", default=[],
                    metavar=("PATH", "SWITCHES"),
                    help="extra case: a .poly file with Triangle switches (idmesh and Triangle)")
    ap.add_argument("--seed", type=int, default=SEED)
    ap.add_argument("--no-cgal", action="store_true")
    ap.add_argument("--no-triangle-D", action="store_true",
                    help="skip the extra Triangle -D (conforming Delaunay) row")
    ap.add_argument("--wait-idle", type=float, default=60.0,
                    help="before each run wait up to this many seconds for other jobs to leave "
                         "the CPUs idle (0: never wait)")
    ap.add_argument("--timeout", type=float, default=300.0, help="seconds per child run")
    ap.add_argument("--workdir", default=os.path.join(ROOT, "target", "bench2d"))
    ap.add_argument("--json", help="also write all raw results to this file")
    ap.add_argument("--verify", action="store_true",
                    help=f"check one idmesh mesh per refinement case with {VERIFY2D} (if present)")
    ap.add_argument("--render", metavar="JSON",
                    help="print the table of a saved --json run again, without running anything")
    ap.add_argument("--selftest", action="store_true",
                    help="quick consistency checks of the three tools' inputs and outputs")
    ap.add_argument("--whole-process", action="store_true",
                    help="add an `idmesh triangle -...NEPQ FILE` row per case: the whole "
                         "process, reading the file included, no output files")
    ap.add_argument("--child-triangle", nargs=3, metavar=("KIND", "PATH", "SWITCHES"),
                    help=argparse.SUPPRESS)
    a = ap.parse_args()

    if a.child_triangle:
        triangle_child(*a.child_triangle)
        return 0
    if a.render:
        with open(a.render) as f:
            render(json.load(f), a.markdown)
        return 0

    ensure_python_deps()
    import numpy as np

    os.makedirs(a.workdir, exist_ok=True)
    use_cgal = not a.no_cgal and ensure_apt_deps()
    idmesh, idmesh_err = build_idmesh()
    cgal = None
    if use_cgal:
        try:
            cgal = build_cgal(a.workdir)
        except subprocess.CalledProcessError as e:
            log(f"CGAL build failed ({e}); CGAL skipped")
    if a.selftest:
        return selftest(a.workdir, idmesh, cgal)
    size = QUICK if a.quick else FULL
    n, area = size["points"], size["area"]
    area_s = plain_decimal(area)
    tri_child = [sys.executable, os.path.abspath(__file__), "--child-triangle"]

    # Inputs, written once, read by every tool.
    pts_path = os.path.join(a.workdir, f"random_{n}_{a.seed}.bin")
    xy = splitmix_points(n, a.seed)
    xy.astype("<f8").tofile(pts_path)
    pts_hash = input_hash(xy)
    node_path = os.path.join(a.workdir, f"random_{n}_{a.seed}.node")
    if a.whole_process:
        write_node(node_path, xy)
    del xy
    cli = idmesh_cli() if a.whole_process else None
    hole_path = os.path.join(a.workdir, "square_hole64.poly")
    hp, hs, hh = hole_pslg()
    write_poly(hole_path, hp, hs, hh)
    hole_hash = input_hash(np.array(hp), np.array(hs))

    cases = []
    wanted = [c.strip() for c in a.cases.split(",") if c.strip()]
    for key in wanted:
        if key == "random":
            cases.append({
                "key": key, "name": f"DT {n:,} random pts", "hash": pts_hash, "tools": {
                    "idmesh": [idmesh, "random", str(n), str(a.seed)] if idmesh else None,
                    "triangle": tri_child + ["points", pts_path, ""],
                    "triangle -D": (tri_child + ["points", pts_path, "D"]
                                    if not a.no_triangle_D else None),
                    "cgal": [cgal, "dt", pts_path] if cgal else None,
                    "idmesh CLI": ["whole", cli, "triangle", "-NEPQ", node_path] if cli else None,
                }})
        elif key in ("hole30", "hole33"):
            ang = key[4:]
            sw = f"pq{ang}a{area_s}"
            tools = {
                "idmesh": [idmesh, "file", hole_path, sw] if idmesh else None,
                "triangle": tri_child + ["poly", hole_path, sw],
            }
            if not a.no_triangle_D:
                tools["triangle -D"] = tri_child + ["poly", hole_path, f"pq{ang}Da{area_s}"]
            tools["cgal"] = ("calibrate", cgal, hole_path, float(ang)) if cgal else None
            if cli:
                tools["idmesh CLI"] = ["whole", cli, "triangle", f"-{sw}NEPQ", hole_path]
            cases.append({"key": key, "name": f"hole -{sw}", "hash": hole_hash, "tools": tools,
                          "verify": (hole_path, ang, area_s)})
        else:
            raise SystemExit(f"unknown case {key!r} (use random, hole30, hole33)")
    for path, sw in a.poly:
        d = read_poly(path)
        cases.append({
            "key": f"poly:{path}:{sw}", "name": f"{os.path.basename(path)} -{sw}",
            "hash": input_hash(d["vertices"], d.get("segments")), "tools": {
                "idmesh": [idmesh, "file", os.path.abspath(path), sw] if idmesh else None,
                "triangle": tri_child + ["poly", os.path.abspath(path), sw],
                "idmesh CLI": (["whole", cli, "triangle", f"-{sw}NEPQ", os.path.abspath(path)]
                               if cli else None),
            }})

    # Check that idmesh's own generators give the same bits as the shared files.
    gen_check = {}
    if idmesh:
        gen_check, _ = run_child([idmesh, "hole", "30", area_s, "--hash-only"], a.timeout)
    if gen_check.get("input_hash") and gen_check["input_hash"] != hole_hash:
        log(f"note: `bench2d hole` builds different coordinates ({gen_check['input_hash']} vs "
            f"{hole_hash}); the benchmark uses the shared .poly file for every tool")

    results = []
    for case in cases:
        log(f"== {case['name']}")
        res = {"key": case["key"], "name": case["name"], "tools": {}}
        runs = {t: [] for t, c in case["tools"].items() if c}
        maxrss = {t: 0 for t in runs}
        cgal_edge = None
        for rep in range(a.repeat):
            for tool, cmd in case["tools"].items():
                if not cmd:
                    continue
                if cmd[0] == "calibrate":
                    if cgal_edge is None:
                        tri_runs = runs.get("triangle") or []
                        target = next((r["triangles"] for r in tri_runs if "error" not in r),
                                      None)
                        cgal_edge = calibrate_cgal(cmd[1], cmd[2], cmd[3], area, target,
                                                   a.timeout)
                    if isinstance(cgal_edge, str):
                        runs[tool].append({"error": cgal_edge})
                        continue
                    cmd = [cmd[1], "mesh", cmd[2], str(cmd[3]), repr(cgal_edge)]
                if tool == "idmesh" and rep == 0:
                    # Exact self-check of the first mesh, after the timed call and the memory
                    # readings, so it costs nothing in the figures.
                    cmd = cmd + ["--validate"]
                busy = wait_for_quiet(a.wait_idle)
                if cmd[0] == "whole":
                    r = whole_process(cmd[1:], a.timeout)
                    rss = r.get("hwm_after_kb", 0)
                    r["input_hash"] = case["hash"]  # the same file as the other tools
                else:
                    r, rss = run_child(cmd, a.timeout)
                r["busy_cores_before"] = round(busy, 2)
                if "error" not in r and r.get("input_hash") != case["hash"]:
                    r = {"error": f"input hash {r.get('input_hash')} != {case['hash']}: "
                                  "this tool meshed different coordinates"}
                runs[tool].append(r)
                maxrss[tool] = max(maxrss[tool], rss)
                msg = r.get("error") or "%.3f s, %s triangles" % (r["time_s"],
                                                                    r["triangles"] or "?")
                log(f"   {tool:12s} run {rep + 1}: {msg}")
        if "idmesh" in case["tools"] and not case["tools"]["idmesh"]:
            res["tools"]["idmesh"] = {"error": idmesh_err or "not run"}
        verdict = None
        if a.verify and case.get("verify") and case["tools"].get("idmesh"):
            verdict = verify_idmesh(case, a.workdir, a.timeout)
        for tool in runs:
            s = summarise(runs[tool], maxrss[tool])
            if tool == "idmesh" and verdict and "error" not in s:
                s["note"] = (s.get("note", "") + "; " if s.get("note") else "") + verdict
            if tool == "cgal" and "edge_bound" in s:
                s["note"] = "edge bound %.3g (calibrated to Triangle's count)" % s["edge_bound"]
            if tool == "triangle -D":
                s["note"] = ("conforming Delaunay, like idmesh" if case["key"] != "random" else
                             "-D: splits encroached hull edges (Steiner points)")
            res["tools"][tool] = s
        results.append(res)

    info = machine_info()
    report = {"machine": info, "quick": a.quick, "repeat": a.repeat,
              "argv": sys.argv[1:], "results": results}
    if a.json:
        with open(a.json, "w") as f:
            json.dump(report, f, indent=1)
    render(report, a.markdown)
    return 0


def render(report, markdown):
    """Prints the table and the target verdicts (also used by --render on a saved --json)."""
    results, info = report["results"], report["machine"]
    rows = build_rows(results)
    tg = targets(results)
    if markdown:
        print("# 2D benchmark results: idmesh vs Triangle vs CGAL\n")
        print("Produced by `python3 bench/bench2d.py " + " ".join(report.get("argv", [])) +
              "`; see bench/README.md for what is measured and the caveats. Ratios are to "
              "Triangle's median time and to Triangle's meshing-call peak memory.\n")
        print(f"Run {info['date']} on {info['nproc']} × {info['cpu']}, {info['memory']} RAM "
              f"({info['os']}).  ")
        print(f"idmesh {info['idmesh_commit']} ({info['rustc']}), Triangle via PyPI "
              f"`triangle` {info['triangle_pypi']} (Python {info['python']}), CGAL {info['cgal']} "
              f"({info['gxx']}, -O3). Median of {report.get('repeat', '?')} runs"
              f"{' (--quick)' if report.get('quick') else ''}.\n")
        print_table(rows, True)
        print("\nTargets:\n")
        for label, text, ok in tg:
            verdict = "n/a" if ok is None else ("**met**" if ok else "**not met**")
            print(f"* {label}: {text} — {verdict}")
        print("\nPer-run times in seconds, in run order (tools interleaved within each round):\n")
        for case in results:
            for tool, r in case["tools"].items():
                if "times" in r:
                    print(f"* {case['name']}, {tool}: " +
                          ", ".join("%.3f" % t for t in r["times"]))
    else:
        print_table(rows, False)
        print()
        for label, text, ok in tg:
            verdict = "n/a" if ok is None else ("met" if ok else "NOT met")
            print(f"{label}: {text} -> {verdict}")


def selftest(workdir, idmesh, cgal):
    """Checks that could fail: the three tools see the same bits, and on a point set in general
    position (whose Delaunay triangulation is unique) they agree on the counts."""
    import numpy as np
    failures = []

    def check(cond, what):
        log(("ok    " if cond else "FAIL  ") + what)
        if not cond:
            failures.append(what)

    # numpy SplitMix64 against a plain-int restatement.
    state, ref = 7, []
    for _ in range(6):
        state = (state + GOLD) & M64
        z = state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & M64
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & M64
        ref.append(((z ^ (z >> 31)) >> 11) / 2.0**53)
    check(splitmix_points(3, 7).ravel().tolist() == ref, "numpy SplitMix64 == int SplitMix64")
    check(plain_decimal(0.0000012) == "0.0000012", "Triangle area string has no exponent")

    n = 20000
    xy = splitmix_points(n, 11)
    pts = os.path.join(workdir, "selftest.bin")
    xy.astype("<f8").tofile(pts)
    h = input_hash(xy)
    hp, hs, hh = hole_pslg()
    poly = os.path.join(workdir, "selftest_hole.poly")
    write_poly(poly, hp, hs, hh)
    d = read_poly(poly)
    check(np.array_equal(d["vertices"], np.array(hp)) and d["segments"].tolist() ==
          [list(x) for x in hs], ".poly written and read back bit-exactly")
    ph = input_hash(d["vertices"], d["segments"])

    tri = [sys.executable, os.path.abspath(__file__), "--child-triangle"]
    res = {"triangle": run_child(tri + ["points", pts, ""], 120)[0]}
    if idmesh:
        res["idmesh"] = run_child([idmesh, "random", str(n), "11", "--validate"], 120)[0]
        hr = run_child([idmesh, "hole", "30", "0.01", "--hash-only"], 60)[0]
        check(hr.get("input_hash") == ph,
              "bench2d's own hole PSLG has the same bits as the .poly (same libm cos/sin)")
    if cgal:
        res["cgal"] = run_child([cgal, "dt", pts], 120)[0]
    for tool, r in res.items():
        check("error" not in r, f"{tool} DT ran ({r.get('error', 'ok')})")
        check(r.get("input_hash") == h, f"{tool} read the same {n} points")
    counts = {t: (r.get("vertices"), r.get("triangles")) for t, r in res.items()}
    check(len(set(counts.values())) == 1, f"DT vertex/triangle counts agree: {counts}")
    if "idmesh" in res:
        check(res["idmesh"].get("valid") is True, "idmesh DT passes TriMesh::validate()")

    for tool, cmd in (("triangle", tri + ["poly", poly, "pq30a0.001"]),
                      ("idmesh", [idmesh, "file", poly, "pq30a0.001", "--validate"]
                       if idmesh else None),
                      ("cgal", [cgal, "mesh", poly, "30", "0.05"] if cgal else None)):
        if not cmd:
            continue
        r = run_child(cmd, 120)[0]
        ok = "error" not in r and r.get("input_hash") == ph and r["triangles"] > 500
        check(ok, f"{tool} meshes the hole PSLG from the shared file "
                  f"({r.get('error') or r['triangles']})")
        if ok:
            check(r["min_angle"] >= 30.0 - 1e-9, f"{tool} meets 30 degrees "
                                                   f"(min {r['min_angle']:.4f})")
    if failures:
        log(f"{len(failures)} self-test check(s) failed")
        return 1
    log("self-test passed")
    return 0


def verify_idmesh(case, workdir, timeout):
    """Independent check of one idmesh mesh with verify2d.py (untimed extra run)."""
    poly, ang, area_s = case["verify"]
    if not os.path.exists(VERIFY2D):
        return f"not verified ({VERIFY2D} missing)"
    stem = os.path.join(workdir, f"verify_{case['key']}")
    r, _ = run_child(case["tools"]["idmesh"] + ["--write", stem], timeout)
    if "error" in r:
        return "verify run failed: " + r["error"][:60]
    v = subprocess.run([sys.executable, VERIFY2D, poly, stem + ".node", stem + ".ele",
                        "--min-angle", ang, "--max-area", area_s, "--require-delaunay",
                        "--json"], capture_output=True, text=True, timeout=timeout)
    for ext in (".node", ".ele"):
        try:
            os.remove(stem + ext)
        except OSError:
            pass
    try:
        rep = json.loads(v.stdout.strip().splitlines()[-1])
        failed = [k for k, c in rep.get("checks", {}).items() if not c.get("ok", True)]
        log(f"   verify2d: ok={rep.get('ok')} failed checks={failed}")
    except (ValueError, IndexError):
        log("   verify2d: unreadable output: " + (v.stderr or v.stdout)[-300:])
    return "verify2d OK" if v.returncode == 0 else "verify2d FAILED"


def calibrate_cgal(exe, poly, angle, area, target, timeout):
    """CGAL bounds edge length, not area: pick the bound that gives about Triangle's triangle
    count. One small run at ~1/16 of the size fixes the constant (count ~ 1/edge^2); the result
    is then reported as-is. Returns the edge bound, or an error string."""
    if not target:
        return "no Triangle count to calibrate against"
    # Equilateral triangles of area `area` have edge sqrt(4 area / sqrt 3); 4x that edge gives
    # roughly 1/16 of the count.
    probe = 4.0 * math.sqrt(4.0 * area / math.sqrt(3.0))
    r, _ = run_child([exe, "mesh", poly, str(angle), repr(probe)], timeout)
    if "error" in r:
        return "calibration run failed: " + r["error"]
    edge = probe * math.sqrt(r["triangles"] / target)
    log(f"   cgal calibration: edge {probe:.4g} -> {r['triangles']} triangles; "
        f"using edge {edge:.4g} for ~{target}")
    return edge


if __name__ == "__main__":
    sys.exit(main())
