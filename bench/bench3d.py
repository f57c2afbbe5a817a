#!/usr/bin/env python3
"""Side-by-side 3D Delaunay benchmark: idmesh vs TetGen (Debian's `tetgen`) vs CGAL.

The issue's case: the Delaunay tetrahedralization of 1,000,000 uniform random points in the unit
cube (100,000 with --quick). Every tool runs in a fresh child process per run, interleaved
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
reset through /proc/self/clear_refs just before the call) and their whole-life peak; all tools
print or are checked against an `input_hash` of the coordinate bits.

Targets (from the issue): idmesh time <= 0.5 x TetGen's, <= 1.0 x CGAL's, and idmesh's peak
memory <= TetGen's.

Usage: python3 bench/bench3d.py [--quick] [--points N] [--seed S] [--repeat K] [--markdown]
                                [--no-cgal] [--no-tetgen] [--json OUT] [--render OUT.json]
                                [--selftest] [--wait-idle S] [--timeout S]
Inputs, outputs and the CGAL binary go to target/bench3d/.
"""

import argparse
import datetime
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


# ---------------------------------------------------------------------------------------------
# Setup
# ---------------------------------------------------------------------------------------------

def ensure_numpy():
    try:
        import numpy  # noqa: F401
    except ImportError:
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


def build_idmesh():
    log("building idmesh: cargo build --release --example bench3d_points")
    r = subprocess.run(["cargo", "build", "--release", "--example", "bench3d_points", "-q"],
                       cwd=ROOT, capture_output=True, text=True)
    if r.returncode != 0:
        first = next((ln for ln in r.stderr.splitlines() if ln.startswith("error")), "")
        log(r.stderr[-3000:])
        return None, "cargo build failed: " + first
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    exe = os.path.join(target, "release", "examples", "bench3d_points")
    if not os.path.exists(exe):
        return None, f"built bench3d_points but cannot find it at {exe}"
    return exe, None


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


def run_child(cmd, timeout, cwd=ROOT):
    """Runs cmd in a fresh process. Returns (stdout text, stderr text, exit code or None on
    timeout, wall seconds, child's rusage)."""
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
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
        return (out.read().decode(errors="replace"), err.read().decode(errors="replace"), code,
                wall, ru)


def json_child(cmd, timeout):
    """Runs a child that prints one JSON line (idmesh, CGAL)."""
    text, etext, code, wall, ru = run_child(cmd, timeout)
    if code is None:
        return {"error": f"timeout after {timeout:.0f} s"}
    res = None
    for line in reversed(text.strip().splitlines()):
        try:
            res = json.loads(line)
            break
        except ValueError:
            continue
    if res is None:
        tail = (etext or "no output").strip().splitlines()[-3:]
        return {"error": f"exit {code}: " + " | ".join(tail)}
    if code != 0 and "error" not in res:
        res["error"] = f"exit {code}"
    res["process_s"] = wall
    res["cpu_s"] = ru.ru_utime + ru.ru_stime
    # The child's whole-life peak: VmHWM before the reset covers set-up, after covers the call.
    if "hwm_after_kb" in res:
        res["peak_kb"] = res["hwm_after_kb"] - res["rss_before_kb"]
        res["total_kb"] = max(res["hwm_before_kb"], res["hwm_after_kb"])
    return res


def tetgen_child(node_path, workdir, timeout):
    """Runs `tetgen -V` on the .node file in a scratch copy of the directory; parses its own
    timings and counts. The peak RSS is wait4's ru_maxrss (tetgen is exec'd directly)."""
    text, etext, code, wall, ru = run_child(["tetgen", "-V", node_path], timeout, cwd=workdir)
    if code is None:
        return {"error": f"timeout after {timeout:.0f} s"}
    if code != 0 or "Delaunay seconds" not in text:
        tail = (etext or text or "no output").strip().splitlines()[-3:]
        return {"error": f"exit {code}: " + " | ".join(tail)}

    def number(pattern, cast=float):
        m = re.search(pattern, text)
        return cast(m.group(1)) if m else None

    stem = node_path[: -len(".node")]
    for ext in (".1.node", ".1.ele", ".1.face", ".1.edge"):
        try:
            os.remove(stem + ext)
        except OSError:
            pass
    return {
        "tool": "tetgen",
        "time_s": wall,
        "process_s": wall,
        "cpu_s": ru.ru_utime + ru.ru_stime,
        "delaunay_s": number(r"Delaunay seconds:\s*([0-9.eE+-]+)"),
        "total_running_s": number(r"Total running seconds:\s*([0-9.eE+-]+)"),
        "vertices": number(r"Mesh points:\s*(\d+)", int),
        "tets": number(r"Mesh tetrahedra:\s*(\d+)", int),
        "hull_faces": number(r"Convex hull faces:\s*(\d+)", int),
        "input_points": number(r"Input points:\s*(\d+)", int),
        "total_kb": ru.ru_maxrss,
    }


def summarise(runs):
    """Median time over the repeats; memory as the largest seen."""
    ok = [r for r in runs if "error" not in r]
    if not ok:
        return {"error": runs[0].get("error", "failed") if runs else "not run"}
    out = dict(ok[0])
    out["times"] = [r["time_s"] for r in ok]
    out["time_s"] = statistics.median(out["times"])
    out["best_s"] = min(out["times"])
    for key in ("process_s", "cpu_s", "delaunay_s"):
        vals = [r[key] for r in ok if r.get(key) is not None]
        out[key] = statistics.median(vals) if vals else None
    for key in ("peak_kb", "total_kb"):
        vals = [r[key] for r in ok if r.get(key) is not None]
        out[key] = max(vals) if vals else None
    out["runs"] = len(ok)
    out["busy_cores_max"] = max(r.get("busy_cores_before", 0.0) for r in ok)
    bad = [r for r in ok if r.get("valid") is False]
    if bad:
        out["note"] = "INVALID mesh: " + bad[0].get("invalid_reason", "")[:80]
    elif any(r.get("valid") for r in ok):
        out["note"] = "validate() ok"
    return out


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


HEADER = ["tool", "time s", "best s", "CPU s", "÷ TetGen process", "÷ TetGen Delaunay",
          "÷ CGAL", "tets", "hull faces", "call peak MB", "process peak MB", "note"]


def build_rows(res):
    tg, cg = res.get("tetgen", {}), res.get("cgal", {})
    tg_t = tg.get("time_s") if "error" not in tg else None
    tg_d = tg.get("delaunay_s") if "error" not in tg else None
    cg_t = cg.get("time_s") if "error" not in cg else None
    rows = []
    for tool in ("idmesh", "tetgen", "cgal"):
        r = res.get(tool)
        if r is None:
            continue
        if "error" in r:
            rows.append([tool, "error: " + r["error"][:90]] + [""] * (len(HEADER) - 2))
            continue
        notes = [r["note"]] if r.get("note") else []
        if tool == "tetgen":
            notes.append("time = whole process (read .node, tetrahedralize, write); "
                         "its own 'Delaunay seconds' (CPU): %s" % tfmt(r.get("delaunay_s")))
        if r.get("busy_cores_max", 0.0) > 0.3:
            notes.append("other jobs used up to %.1f cores" % r["busy_cores_max"])
        rows.append([
            tool, tfmt(r["time_s"]), tfmt(r["best_s"]), tfmt(r.get("cpu_s")),
            ratio(r["time_s"], tg_t), ratio(r["time_s"], tg_d), ratio(r["time_s"], cg_t),
            "{:,}".format(r["tets"]) if r.get("tets") is not None else "-",
            "{:,}".format(r["hull_faces"]) if r.get("hull_faces") is not None else "-",
            mb(r.get("peak_kb")), mb(r.get("total_kb")), "; ".join(notes),
        ])
    return rows


def targets(res):
    out = []
    i, t, c = (res.get(k) for k in ("idmesh", "tetgen", "cgal"))
    ok = lambda r: r is not None and "error" not in r  # noqa: E731
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
    return out


def print_table(rows, markdown, out=sys.stdout):
    if markdown:
        print("| " + " | ".join(HEADER) + " |", file=out)
        print("|" + "|".join("---" if k in (0, len(HEADER) - 1) else "--:"
                             for k in range(len(HEADER))) + "|", file=out)
        for r in rows:
            print("| " + " | ".join(str(x) for x in r) + " |", file=out)
        return
    widths = [max(len(str(r[k])) for r in rows + [HEADER]) for k in range(len(HEADER))]
    line = "  ".join(h.ljust(w) for h, w in zip(HEADER, widths))
    print(line, file=out)
    print("-" * len(line), file=out)
    for r in rows:
        print("  ".join(str(x).ljust(w) for x, w in zip(r, widths)), file=out)


def render(report, markdown):
    res, info = report["results"], report["machine"]
    rows = build_rows(res)
    if markdown:
        print(f"# 3D Delaunay benchmark: {report['points']:,} random points\n")
        print("Produced by `python3 bench/bench3d.py " + " ".join(report.get("argv", [])) +
              "`. Times are medians of fresh processes, tools interleaved.\n")
        print(f"Run {info['date']} on {info['nproc']} × {info['cpu']}, {info['memory']} RAM "
              f"({info['os']}).  ")
        print(f"idmesh {info['idmesh_commit']} ({info['rustc']}), TetGen {info['tetgen']} "
              f"(Debian), CGAL {info['cgal']} ({info['gxx']}, -O2).\n")
    print_table(rows, markdown)
    print()
    for label, text, ok in targets(res):
        verdict = "" if ok is None else (" — met" if ok else " — NOT met")
        print(("* " if markdown else "") + f"{label}: {text}{verdict}")
    if markdown:
        print("\nPer-run times in seconds, in run order:\n")
        for tool, r in res.items():
            if "times" in r:
                print(f"* {tool}: " + ", ".join("%.3f" % t for t in r["times"]))


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


def selftest(workdir, idmesh, cgal, use_tetgen):
    """Checks that could fail: all tools read the same bits, the mesh is valid, and on points in
    general position (unique Delaunay tetrahedralization) the three tools agree on counts."""
    import numpy as np
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
    if failures:
        log(f"{len(failures)} self-test check(s) failed")
        return 1
    log("self-test passed")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help=f"{QUICK_POINTS:,} points")
    ap.add_argument("--points", type=int, help="number of points (overrides --quick)")
    ap.add_argument("--seed", type=int, default=SEED)
    ap.add_argument("--repeat", type=int, default=3, help="runs per tool (median time)")
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
                    help="quick consistency checks of the three tools' inputs and outputs")
    a = ap.parse_args()

    if a.render:
        with open(a.render) as f:
            render(json.load(f), a.markdown)
        return 0
    ensure_numpy()
    os.makedirs(a.workdir, exist_ok=True)
    apt_ok = ensure_apt_deps(not a.no_cgal, not a.no_tetgen)
    use_tetgen = not a.no_tetgen and shutil.which("tetgen") is not None
    idmesh, idmesh_err = build_idmesh()
    cgal = None
    if not a.no_cgal and apt_ok:
        try:
            cgal = build_cgal(a.workdir)
        except (OSError, subprocess.CalledProcessError) as e:
            log(f"CGAL build failed ({e}); CGAL skipped")
    if a.selftest:
        return selftest(a.workdir, idmesh, cgal, use_tetgen)

    n = a.points or (QUICK_POINTS if a.quick else FULL_POINTS)
    bin_path, node_path, h = prepare(a.workdir, n, a.seed)
    tools = {
        "idmesh": (lambda first: json_child(
            [idmesh, str(n), str(a.seed)] + (["--validate"] if first else []), a.timeout))
        if idmesh else None,
        "tetgen": (lambda first: tetgen_child(node_path, a.workdir, a.timeout))
        if use_tetgen else None,
        "cgal": (lambda first: json_child([cgal, bin_path], a.timeout)) if cgal else None,
    }
    runs = {t: [] for t, f in tools.items() if f}
    log(f"== Delaunay of {n:,} random points (seed {a.seed}), {a.repeat} runs per tool")
    for rep in range(a.repeat):
        for tool, fn in tools.items():
            if not fn:
                continue
            busy = wait_for_quiet(a.wait_idle)
            # The first idmesh run also checks its mesh exactly, after the timed call.
            r = fn(rep == 0)
            r["busy_cores_before"] = round(busy, 2)
            if "error" not in r and "input_hash" in r and r["input_hash"] != h:
                r = {"error": f"input hash {r['input_hash']} != {h}: different coordinates"}
            if "error" not in r and r.get("input_points") not in (None, n):
                r = {"error": f"read {r.get('input_points')} points, expected {n}"}
            runs[tool].append(r)
            msg = r.get("error") or "%.3f s, %s tets" % (r["time_s"], r.get("tets"))
            log(f"   {tool:7s} run {rep + 1}: {msg}")
    results = {tool: summarise(rs) for tool, rs in runs.items()}
    if not idmesh:
        results["idmesh"] = {"error": idmesh_err or "not built"}
    report = {"machine": machine_info(), "points": n, "seed": a.seed, "repeat": a.repeat,
              "argv": sys.argv[1:], "results": results}
    if a.json:
        with open(a.json, "w") as f:
            json.dump(report, f, indent=1)
    render(report, a.markdown)
    return 0


if __name__ == "__main__":
    sys.exit(main())
