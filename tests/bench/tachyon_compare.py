#!/usr/bin/env python3
"""Whole-frame speed of Prism against Tachyon, one thread each, on SPD scenes.

For every scene the NFF file is converted once to Tachyon's own scene language
with nff2tachyon.py (Tachyon's built-in NFF reader gets the field of view,
lights, highlights and depth wrong; see docs/performance.md).  Then
one untimed warm-up run of each renderer writes a PNG into --images, and N
timed runs of each follow, alternating between the two renderers (the one
that goes first swaps every round).  Both render the same resolution, 1
sample per pixel, maximum depth 5, on one thread, and both write a PNG.

Measured per run: CPU seconds (user + system) of the child process, from
getrusage(RUSAGE_CHILDREN) deltas, and wall seconds.  CPU time is the
yardstick because the machine is shared; the table shows medians with the
min..max spread, the ratio Prism/Tachyon of the medians and the geometric
mean of the ratios.  The project's target is a ratio <= 0.5.  The fixed CPU
cost of merely starting each program ('prism --version', 'tachyon -help') is
measured too, once per round, and a second ratio with Prism's median start-up
cost taken out is shown for information (the whole-process ratio is the one
that counts).

Tachyon is run with its threaded library (libtachyon-mt-thr) picked through a
private folder holding a libtachyon.so.0 symlink and LD_LIBRARY_PATH, never by
changing the system's alternatives; the script checks with ldd that this
really is the library that gets loaded and stops otherwise.  Every Tachyon
(and Prism) run is killed after --timeout seconds.

Fixed costs come first, in a table of their own: 'prism --version' against
'tachyon -version' (start-up alone), and a 64x64 render of --small-scene by each
(start-up, parse, build, write: the cost of a small job), --fixed-runs
alternating runs each.  Wall seconds, CPU seconds and peak resident memory are
reported per process (memory through /usr/bin/time -f %M, whose own start
adds about a millisecond of wall time to both programs alike).  With
--baseline-prism OTHER a second Prism binary (say, a build of an older
commit) takes part in the same alternation, in these rows and in every scene's
runs (a table of Prism against the baseline follows the scenes' table), so
before and after are measured in one run.  --fixed-only stops after this table.

Scenes are names or paths: a path to an .nff file; a file name (with or
without .nff) in --spd-dir; or NAME-sSIZE for NAME in balls, tetra, rings,
generated with spd_generators.py (next to this script) into the temp folder.

Python 3, standard library only.
"""
import argparse
import csv
import datetime
import hashlib
import math
import os
import re
import resource
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)
import spd_generators  # noqa: E402  (lives next to this script)

DEFAULT_SCENES = ["balls-s2", "rings-s3", "teapot-s3", "tetra-s4", "tree-s7",
                  "balls-s3", "balls-s4", "rings-s7", "tetra-s8"]
DEFAULT_PRISM = os.path.join(REPO, "build", "prism")
DEFAULT_TACHYON = "/usr/bin/tachyon-nox"
DEFAULT_TACHYON_LIB = "/usr/lib/x86_64-linux-gnu/libtachyon-mt-thr.so.0"
DEFAULT_SPD_DIR = os.path.join(REPO, "tests", "data", "nff")
DEFAULT_NFF2TACHYON = os.path.join(HERE, "nff2tachyon.py")
TARGET_RATIO = 0.5


# ------------------------------------------------------------------ errors

def die(msg):
    sys.exit("tachyon_compare: error: " + msg)


# ---------------------------------------------------------- Tachyon flavour

def setup_tachyon_flavour(tachyon, lib, workdir):
    """Make a private folder with libtachyon.so.0 -> LIB and return the
    environment that makes TACHYON load it.  Checks with ldd that it does and
    that LIB is the plain threaded build (no MPI, no OpenMP); dies otherwise."""
    if not os.path.isfile(lib):
        die("Tachyon library %s not found (Debian package libtachyon-mt-0)" % lib)
    libdir = os.path.join(workdir, "tachyon-lib")
    os.makedirs(libdir, exist_ok=True)
    link = os.path.join(libdir, "libtachyon.so.0")
    if os.path.lexists(link):
        os.remove(link)
    os.symlink(os.path.realpath(lib), link)
    env = dict(os.environ)
    env["LD_LIBRARY_PATH"] = libdir + (":" + env["LD_LIBRARY_PATH"] if env.get("LD_LIBRARY_PATH") else "")

    # 1. the binary must resolve libtachyon.so.0 to our symlink
    out = subprocess.run(["ldd", tachyon], env=env, capture_output=True, text=True).stdout
    m = re.search(r"^\s*libtachyon\.so\.0\s*=>\s*(\S+)", out, re.M)
    if not m:
        die("ldd %s shows no libtachyon.so.0:\n%s" % (tachyon, out))
    loaded = os.path.realpath(m.group(1))
    if loaded != os.path.realpath(lib):
        die("Tachyon would load %s, not the chosen %s:\n%s" % (loaded, lib, out))
    # 2. the library must be the threaded flavour: mt-thr, no MPI or OpenMP
    if "mt-thr" not in os.path.basename(loaded):
        die("%s is not the threaded (mt-thr) Tachyon library" % loaded)
    deps = subprocess.run(["ldd", loaded], capture_output=True, text=True).stdout
    bad = [d for d in ("libmpi", "libgomp", "libomp") if d in deps]
    if bad:
        die("%s links %s: not the plain threaded flavour:\n%s" % (loaded, ", ".join(bad), deps))
    with open(loaded, "rb") as f:
        if b"pthread_create" not in f.read():
            die("%s does not use pthreads: not the threaded flavour" % loaded)
    return env, loaded


def snapshot_binary(path, workdir):
    """Copy the binary into WORKDIR so that a rebuild by someone else during
    the benchmark cannot change what is measured halfway through."""
    return snapshot_as(path, workdir, "prism-under-test")


def snapshot_as(path, workdir, name):
    """Copy the binary into its own folder in WORKDIR, with the OpenImageIO module that sits
    next to it (prism_image_oiio.so, loaded only for formats other than PNG and EXR)."""
    folder = os.path.join(workdir, name + ".d")
    os.makedirs(folder, exist_ok=True)
    dst = os.path.join(folder, "prism")
    shutil.copy2(path, dst)
    module = os.path.join(os.path.dirname(os.path.abspath(path)), "prism_image_oiio.so")
    if os.path.isfile(module):
        shutil.copy2(module, folder)
    return dst


def sha256_of(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


# ------------------------------------------------------------------ scenes

GENERATED = re.compile(r"^(%s)-s(\d+)$" % "|".join(sorted(spd_generators.GENERATORS)))


def resolve_scene(name, spd_dir, workdir):
    """Return (label, nff_path, origin) for a scene argument."""
    if os.path.isfile(name):
        return os.path.splitext(os.path.basename(name))[0], os.path.abspath(name), "file"
    base = name[:-4] if name.endswith(".nff") else name
    shared = os.path.join(spd_dir, base + ".nff")
    if os.path.isfile(shared):
        return base, shared, "SPD file"
    m = GENERATED.match(base)
    if m:
        kind, size = m.group(1), int(m.group(2))
        path = os.path.join(workdir, base + ".nff")
        with open(path, "w") as f:
            spd_generators.GENERATORS[kind](size, spd_generators.NffWriter(f))
        return base, path, "generated"
    die("unknown scene %r: not a file, not in %s, not NAME-sSIZE with NAME in %s"
        % (name, spd_dir, ", ".join(sorted(spd_generators.GENERATORS))))


def count_primitives(nff_path):
    """Count NFF primitives: spheres, cones/cylinders, polygons, patches."""
    counts = {"s": 0, "c": 0, "p": 0, "pp": 0}
    with open(nff_path) as f:
        for line in f:
            tok = line.split(None, 1)
            if tok and tok[0] in counts:
                counts[tok[0]] += 1
    return sum(counts.values()), counts


def convert_to_tachyon(nff2tachyon, nff_path, dat_path):
    with open(dat_path, "w") as out:
        r = subprocess.run([sys.executable, nff2tachyon, nff_path], stdout=out, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        die("nff2tachyon failed on %s:\n%s" % (nff_path, r.stderr))


# ------------------------------------------------------------------ running

def run_timed(cmd, env, log_path, timeout):
    """Run CMD (output to LOG_PATH) and return (cpu_user, cpu_sys, wall, rc,
    maxrss_kb).  The process gets its own session and is killed with its
    whole process group after TIMEOUT seconds (rc is then -9)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    with open(log_path, "w") as log:
        p = subprocess.Popen(cmd, env=env, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        try:
            rc = p.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)  # our own child's group only
            p.wait()
            rc = -9
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime, after.ru_stime - before.ru_stime, wall, rc, after.ru_maxrss)


def prism_cmd(args, nff, png, quiet=True, binary=None):
    cmd = [binary or args.prism, "render", nff, "-o", png, "--overwrite", "--threads", "1", "--width", str(args.width),
           "--height", str(args.height), "--spp", "1", "--max-depth", str(args.depth)]
    return cmd + (["--quiet"] if quiet else [])


def tachyon_cmd(args, dat, png):
    return [args.tachyon, dat, "-numthreads", "1", "-res", str(args.width), str(args.height),
            "-raydepth", str(args.depth), "-aasamples", "0", "-format", "PNG", "-o", png]


def tachyon_trace_time(log_path):
    """Tachyon's own 'Ray Tracing Time' from its log, or None."""
    try:
        with open(log_path, errors="replace") as f:
            m = re.search(r"Ray Tracing Time:\s*([0-9.]+)", f.read())
        return float(m.group(1)) if m else None
    except OSError:
        return None


def startup_cpu(cmd, env, workdir, timeout):
    """CPU seconds of a command that starts the program and exits at once
    (e.g. 'prism --version'): the fixed cost every timed run includes."""
    user, sys_, _, _, _ = run_timed(cmd, env, os.path.join(workdir, "startup.log"), timeout)
    return user + sys_


def check_rc(what, rc, log_path, timeout):
    if rc == 0:
        return
    with open(log_path, errors="replace") as f:
        tail = f.read()[-2000:]
    if rc == -9:
        die("%s timed out after %g s; log tail:\n%s" % (what, timeout, tail))
    die("%s exited with %d; log tail:\n%s" % (what, rc, tail))


def run_measured(cmd, env, log_path, timeout):
    """Run CMD under /usr/bin/time and return (wall_s, cpu_s, maxrss_kib, rc).  The peak
    resident memory comes from /usr/bin/time, not from getrusage in this script: a child
    started by Python inherits Python's own high-water mark through vfork/exec."""
    rss_path = log_path + ".rss"
    # A blocking wait (Popen.wait with a timeout polls with sleeps of up to 50 ms, far coarser
    # than what is measured here); a timer kills the run's process group on timeout instead.
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    with open(log_path, "w") as log:
        p = subprocess.Popen(["/usr/bin/time", "-q", "-f", "%M", "-o", rss_path] + cmd, env=env,
                             stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        timer = threading.Timer(timeout, lambda: os.killpg(p.pid, signal.SIGKILL))
        timer.start()
        rc = p.wait()
        timer.cancel()
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    user, sys_ = after.ru_utime - before.ru_utime, after.ru_stime - before.ru_stime
    if rc == -signal.SIGKILL:
        rc = -9
    try:
        with open(rss_path) as f:
            rss = int(f.read().split()[-1])
    except (OSError, ValueError, IndexError):
        rss = float("nan")
    return wall, user + sys_, rss, rc


def fixed_cost_commands(args, workdir):
    """The fixed-cost rows: (label, {contestant: command}) with contestants prism, tachyon and,
    when given, baseline."""
    label, nff, _ = resolve_scene(args.small_scene, args.spd_dir, workdir)
    dat = os.path.join(workdir, label + "-small.dat")
    convert_to_tachyon(args.nff2tachyon, nff, dat)
    size = args.small_size

    def render(prism):
        return [prism, "render", nff, "-o", os.path.join(workdir, "small-%s.png" % os.path.basename(
            os.path.dirname(prism))), "--overwrite", "--threads", "1", "--width", str(size),
            "--height", str(size), "--spp", "1", "--max-depth", str(args.depth), "--quiet"]

    tachyon_render = [args.tachyon, dat, "-numthreads", "1", "-res", str(size), str(size), "-raydepth",
                      str(args.depth), "-aasamples", "0", "-format", "PNG", "-o",
                      os.path.join(workdir, "small-tachyon.png")]
    rows = [("start-up (prism --version, tachyon -version)",
             {"prism": [args.prism, "--version"], "tachyon": [args.tachyon, "-version"]}),
            ("%dx%d render of %s, to PNG" % (size, size, label),
             {"prism": render(args.prism), "tachyon": tachyon_render})]
    if args.baseline_prism:
        rows[0][1]["baseline"] = [args.baseline_prism, "--version"]
        rows[1][1]["baseline"] = render(args.baseline_prism)
    return rows


def bench_fixed(args, workdir, penv, tenv, writer):
    """Alternate every contestant of every fixed-cost row --fixed-runs times (the order rotates
    each round); return [(label, {contestant: [(wall, cpu, rss), ...]})]."""
    rows = fixed_cost_commands(args, workdir)
    results = [(label, {who: [] for who in cmds}) for label, cmds in rows]
    for i in range(args.fixed_runs):
        for (label, cmds), (_, res) in zip(rows, results):
            order = list(cmds)
            order = order[i % len(order):] + order[:i % len(order)]
            for who in order:
                log = os.path.join(workdir, "fixed-%s.log" % who)
                env = tenv if who == "tachyon" else penv
                wall, cpu, rss, rc = run_measured(cmds[who], env, log, args.timeout)
                if not (who == "tachyon" and cmds[who][-1] == "-version" and rc == 255):
                    # tachyon -version prints its version and exits with 255
                    check_rc("%s (%s, run %d)" % (who, label, i + 1), rc, log, args.timeout)
                res[who].append((wall, cpu, rss))
                if writer:
                    writer.writerow(["fixed: " + label, who, i + 1, "", "", "%.4f" % cpu, "%.4f" % wall,
                                     "", rc, rss])
    return results


def print_fixed_table(results, runs):
    print()
    print("Fixed costs: medians of %d alternating runs (min..max of wall time)" % runs)
    print()
    print("| what | program | wall ms (median, min..max) | CPU ms | peak RSS MiB | wall ratio Prism/Tachyon |")
    print("|---|---|---|---:|---:|---:|")
    for label, res in results:
        t_wall = statistics.median(w for w, _, _ in res["tachyon"])
        for who in [w for w in ("baseline", "prism", "tachyon") if w in res]:
            walls = [w * 1000 for w, _, _ in res[who]]
            cpu = statistics.median(c for _, c, _ in res[who]) * 1000
            rss = statistics.median(r for _, _, r in res[who]) / 1024.0
            wall = statistics.median(walls)
            ratio = "" if who == "tachyon" else "%.2f" % (wall / 1000 / t_wall)
            name = {"prism": "Prism", "baseline": "Prism (baseline)", "tachyon": "Tachyon"}[who]
            print("| %s | %s | %.1f (%.1f..%.1f) | %.1f | %.1f | %s |"
                  % (label, name, wall, min(walls), max(walls), cpu, rss, ratio))


# ------------------------------------------------------------------ report

def spread(values):
    return "%.3f..%.3f" % (min(values), max(values))


def geomean(xs):
    return math.exp(sum(math.log(x) for x in xs) / len(xs)) if xs else float("nan")


def print_table(rows, runs, p_start):
    print()
    print("| scene | NFF primitives | Prism CPU s (median, min..max) | Tachyon CPU s (median, min..max) "
          "| Prism/Tachyon | ratio less Prism start-up | Prism wall s | Tachyon wall s | target <= %.1f |"
          % TARGET_RATIO)
    print("|---|---:|---|---|---:|---:|---:|---:|---|")
    for r in rows:
        print("| %s | %d | %.3f (%s) | %.3f (%s) | %.2f | %.2f | %.3f | %.3f | %s |" % (
            r["scene"], r["prims"], r["p_med"], spread(r["p_cpu"]), r["t_med"], spread(r["t_cpu"]),
            r["ratio"], max(0.0, r["p_med"] - p_start) / r["t_med"],
            statistics.median(r["p_wall"]), statistics.median(r["t_wall"]),
            "met" if r["ratio"] <= TARGET_RATIO else "not met"))
    if rows and "b_cpu" in rows[0]:
        print()
        print("| scene | baseline Prism CPU s (median, min..max) | Prism CPU s | Prism/baseline |")
        print("|---|---|---:|---:|")
        for r in rows:
            b_med = statistics.median(r["b_cpu"])
            print("| %s | %.3f (%s) | %.3f | %.2f |" % (r["scene"], b_med, spread(r["b_cpu"]), r["p_med"],
                                                     r["p_med"] / b_med if b_med > 0 else float("inf")))
        print()
        print("geometric mean of Prism/baseline CPU-time ratios: %.2f"
              % geomean([r["p_med"] / statistics.median(r["b_cpu"]) for r in rows]))
    gm = geomean([r["ratio"] for r in rows])
    print()
    print("geometric mean of Prism/Tachyon CPU-time ratios over %d scenes: %.2f (target <= %.1f: %s); "
          "medians of %d runs each" % (len(rows), gm, TARGET_RATIO, "met" if gm <= TARGET_RATIO else "not met",
                                       runs))


def bench_scene(args, name, workdir, penv, tenv, writer):
    """Convert, warm up (writing the images), then time both renderers
    alternately on one scene; return the table row."""
    label, nff, origin = resolve_scene(name, args.spd_dir, workdir)
    prims, _ = count_primitives(nff)
    dat = os.path.join(workdir, label + ".dat")
    convert_to_tachyon(args.nff2tachyon, nff, dat)
    print("%-12s %7d primitives (%s) ..." % (label, prims, origin), end="", flush=True)

    # warm-up runs, also the images a person can compare
    p_png = os.path.join(args.images, label + "-prism.png")
    t_png = os.path.join(args.images, label + "-tachyon.png")
    log = os.path.join(workdir, label + "-prism-warmup.log")
    check_rc("prism on " + label, run_timed(prism_cmd(args, nff, p_png, quiet=False), penv, log,
                                            args.timeout)[3], log, args.timeout)
    shutil.copy(log, os.path.join(args.images, label + "-prism.txt"))
    log = os.path.join(workdir, label + "-tachyon-warmup.log")
    check_rc("tachyon on " + label, run_timed(tachyon_cmd(args, dat, t_png), tenv, log,
                                              args.timeout)[3], log, args.timeout)

    who_all = ("prism", "tachyon") + (("baseline",) if args.baseline_prism else ())
    if args.baseline_prism:  # its warm-up too, so its first timed run is not its first run
        log = os.path.join(workdir, label + "-baseline-warmup.log")
        png = os.path.join(workdir, label + "-baseline.png")
        check_rc("baseline prism on " + label,
                 run_timed(prism_cmd(args, nff, png, binary=args.baseline_prism), penv, log, args.timeout)[3],
                 log, args.timeout)
    res = {who: [] for who in who_all}
    p_start, t_start = [], []
    for i in range(args.runs):
        p_start.append(startup_cpu([args.prism, "--version"], penv, workdir, args.timeout))
        t_start.append(startup_cpu([args.tachyon, "-help"], tenv, workdir, args.timeout))
        if writer:
            writer.writerow([label, "prism-startup", i + 1, "", "", "%.4f" % p_start[-1], "", "", 0])
            writer.writerow([label, "tachyon-startup", i + 1, "", "", "%.4f" % t_start[-1], "", "", 0])
        order = who_all[i % len(who_all):] + who_all[:i % len(who_all)]  # rotates every round
        for who in order:
            log = os.path.join(workdir, "%s-%s-%d.log" % (label, who, i))
            png = os.path.join(workdir, "%s-%s.png" % (label, who))
            if who == "prism":
                cmd, env = prism_cmd(args, nff, png), penv
            elif who == "baseline":
                cmd, env = prism_cmd(args, nff, png, binary=args.baseline_prism), penv
            else:
                cmd, env = tachyon_cmd(args, dat, png), tenv
            user, sys_, wall, rc, _ = run_timed(cmd, env, log, args.timeout)
            check_rc("%s on %s (run %d)" % (who, label, i + 1), rc, log, args.timeout)
            trace = tachyon_trace_time(log) if who == "tachyon" else None
            res[who].append((user + sys_, wall))
            if writer:
                writer.writerow([label, who, i + 1, "%.4f" % user, "%.4f" % sys_, "%.4f" % (user + sys_),
                                 "%.4f" % wall, "" if trace is None else "%.4f" % trace, rc])
    row = {"scene": label, "prims": prims, "p_start": p_start, "t_start": t_start,
           "p_cpu": [c for c, _ in res["prism"]], "p_wall": [w for _, w in res["prism"]],
           "t_cpu": [c for c, _ in res["tachyon"]], "t_wall": [w for _, w in res["tachyon"]]}
    if "baseline" in res:
        row["b_cpu"] = [c for c, _ in res["baseline"]]
    row["p_med"] = statistics.median(row["p_cpu"])
    row["t_med"] = statistics.median(row["t_cpu"])
    row["ratio"] = row["p_med"] / row["t_med"] if row["t_med"] > 0 else float("inf")
    return row


# -------------------------------------------------------------------- main

def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 epilog=__doc__.split("\n\n", 1)[1],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--prism", default=DEFAULT_PRISM, help="Prism binary (default: %(default)s)")
    ap.add_argument("--tachyon", default=DEFAULT_TACHYON, help="Tachyon binary (default: %(default)s)")
    ap.add_argument("--tachyon-lib", default=DEFAULT_TACHYON_LIB,
                    help="Tachyon library flavour to load, must be the threaded one (default: %(default)s)")
    ap.add_argument("--nff2tachyon", default=DEFAULT_NFF2TACHYON, help="converter (default: %(default)s)")
    ap.add_argument("--spd-dir", default=DEFAULT_SPD_DIR, help="where SPD .nff files are looked up "
                    "(default: %(default)s)")
    ap.add_argument("--scenes", nargs="+", default=DEFAULT_SCENES, metavar="SCENE",
                    help="scenes to compare (default: %(default)s)")
    ap.add_argument("--runs", type=int, default=5, help="timed runs per renderer and scene (default: %(default)s)")
    ap.add_argument("--width", type=int, default=512, help="image width (default: %(default)s)")
    ap.add_argument("--height", type=int, default=512, help="image height (default: %(default)s)")
    ap.add_argument("--depth", type=int, default=5, help="maximum ray depth (default: %(default)s, SPD's rule)")
    ap.add_argument("--timeout", type=float, default=300.0, help="seconds before a run is killed "
                    "(default: %(default)s)")
    ap.add_argument("--images", default=os.path.join(REPO, "out", "tachyon-compare"),
                    help="folder for one PNG per renderer and scene (default: %(default)s)")
    ap.add_argument("--small-scene", default="balls-s2", help="scene of the small render among the fixed "
                    "costs (default: %(default)s)")
    ap.add_argument("--small-size", type=int, default=64, help="width and height of the small render "
                    "(default: %(default)s)")
    ap.add_argument("--fixed-runs", type=int, default=21, help="alternating runs of each fixed-cost row "
                    "(default: %(default)s; 0 skips them)")
    ap.add_argument("--fixed-only", action="store_true", help="measure the fixed costs only, no scenes")
    ap.add_argument("--baseline-prism", help="a second Prism binary timed alongside, in the fixed-cost rows and "
                    "on every scene (before/after in one run)")
    ap.add_argument("--csv", help="save every timed run to this CSV file")
    ap.add_argument("--keep-temp", action="store_true", help="keep the temp folder (converted scenes, logs)")
    args = ap.parse_args(argv)
    if args.runs < 1:
        ap.error("--runs must be at least 1")
    if args.fixed_only and args.fixed_runs < 1:
        ap.error("--fixed-only needs --fixed-runs of at least 1")
    if not os.access("/usr/bin/time", os.X_OK):
        ap.error("/usr/bin/time is needed for peak memory (Debian package time)")
    for exe in (args.prism, args.tachyon) + ((args.baseline_prism,) if args.baseline_prism else ()):
        if not (os.path.isfile(exe) and os.access(exe, os.X_OK)):
            ap.error("%s is not an executable file" % exe)
    if not os.path.isfile(args.nff2tachyon):
        ap.error("converter %s not found" % args.nff2tachyon)
    return args


def main(argv=None):
    args = parse_args(argv)
    workdir = tempfile.mkdtemp(prefix="tachyon_compare.")
    os.makedirs(args.images, exist_ok=True)
    csv_file = open(args.csv, "w", newline="") if args.csv else None
    writer = None
    if csv_file:
        writer = csv.writer(csv_file)
        writer.writerow(["scene", "renderer", "run", "cpu_user_s", "cpu_sys_s", "cpu_s", "wall_s",
                         "tachyon_trace_s", "returncode", "maxrss_kib"])
    try:
        tenv, tlib = setup_tachyon_flavour(args.tachyon, args.tachyon_lib, workdir)
        penv = dict(os.environ)
        prism_src = args.prism
        args.prism = snapshot_binary(args.prism, workdir)
        baseline_src = args.baseline_prism
        if args.baseline_prism:
            args.baseline_prism = snapshot_as(args.baseline_prism, workdir, "prism-baseline")
        print("date      %s" % datetime.datetime.now().astimezone().isoformat(timespec="seconds"))
        print("host      %s, %d CPUs, load average %.2f %.2f %.2f" % ((os.uname().nodename, os.cpu_count())
                                                                      + os.getloadavg()))
        print("prism     %s (copied before the runs; sha256 %s, built %s)"
              % (prism_src, sha256_of(args.prism)[:16],
                 datetime.datetime.fromtimestamp(os.path.getmtime(prism_src)).isoformat(timespec="seconds")))
        print("tachyon   %s with %s (threaded flavour, checked with ldd), -numthreads 1" % (args.tachyon, tlib))
        if baseline_src:
            print("baseline  %s (copied; sha256 %s)" % (baseline_src, sha256_of(args.baseline_prism)[:16]))
        if args.fixed_runs > 0:
            fixed = bench_fixed(args, workdir, penv, tenv, writer)
            print_fixed_table(fixed, args.fixed_runs)
            if args.fixed_only:
                print("load average at the end %.2f %.2f %.2f" % os.getloadavg())
                return
        print("settings  %dx%d, 1 spp, depth %d, one thread each, %d timed runs each, alternating"
              % (args.width, args.height, args.depth, args.runs))
        rows = []
        for name in args.scenes:
            row = bench_scene(args, name, workdir, penv, tenv, writer)
            if csv_file:
                csv_file.flush()
            rows.append(row)
            print(" prism %.3f s, tachyon %.3f s, ratio %.2f" % (row["p_med"], row["t_med"], row["ratio"]))
        print("load average at the end %.2f %.2f %.2f" % os.getloadavg())
        p_start = statistics.median(s for r in rows for s in r["p_start"])
        t_start = statistics.median(s for r in rows for s in r["t_start"])
        print("start-up: median CPU s of a run that only starts and exits (one per round, interleaved): "
              "prism --version %.3f, tachyon -help %.3f" % (p_start, t_start))
        print_table(rows, args.runs, p_start)
        print("\nimages in %s/ (Tachyon's are mirrored left-right: its camera is left-handed)" % args.images)
    finally:
        if csv_file:
            csv_file.close()
        if args.keep_temp:
            print("temp folder kept: %s" % workdir)
        else:
            shutil.rmtree(workdir, ignore_errors=True)


if __name__ == "__main__":
    main()
