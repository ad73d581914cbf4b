#!/usr/bin/env python3
"""Whole-job efficiency of 2 MPI ranks against one process, for one or more Prism builds.

The measure: a frame of a few seconds rendered by one process with one thread, and by
`mpirun -np 2` with one thread per rank; efficiency = one-process wall / (2 x job wall), both
whole processes (launch, MPI_Init, parse, broadcast, build, render, write, MPI_Finalize).
Each round runs the one-process render and then every variant's 2-rank job, in an order that
alternates between rounds; a round's efficiency uses that round's one-process time, and the
table gives each variant's median over the rounds with the spread. With --two-threads each round
also runs one process with 2 threads (no MPI): the machine's own ceiling for two workers, so
what the 2-rank jobs lose beyond it is MPI's and Prism's distribution.

A variant is NAME=PRISM, optionally followed by environment settings for mpirun:
    job_efficiency.py --variant before=/tmp/old/prism --variant now=build/prism \\
        --variant now+x=build/prism:OMPI_MCA_async_mpi_finalize=1

usage: job_efficiency.py [--rounds N] [--scene FILE] [-W W] [-H H] [--spp N] --variant ...
"""
import argparse
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


def timed(command, env):
    start = time.monotonic()
    done = subprocess.run(command, env=env, capture_output=True, text=True, timeout=900)
    wall = time.monotonic() - start
    if done.returncode != 0:
        sys.exit("failed: %s\n%s%s" % (" ".join(command), done.stdout, done.stderr))
    return wall


def parse_variant(text):
    name, _, rest = text.partition("=")
    if not name or not rest:
        sys.exit("a variant is NAME=PRISM[:VAR=VALUE...], not %r" % text)
    prism, *settings = rest.split(":")
    extra = {}
    for s in settings:
        key, _, value = s.partition("=")
        extra[key] = value
    return name, prism, extra


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=5, help="rounds (default 5)")
    parser.add_argument("--scene", default=os.path.join(REPO, "..", "shared", "scenes", "spd",
                                                        "balls-s4.nff"))
    parser.add_argument("-W", type=int, default=1024)
    parser.add_argument("-H", type=int, default=1024)
    parser.add_argument("--spp", type=int, default=6)
    parser.add_argument("--bind-to", default=None, help="mpirun --bind-to (default: mpirun's)")
    parser.add_argument("--two-threads", action="store_true",
                        help="also time one process with 2 threads each round (the ceiling)")
    parser.add_argument("--variant", action="append", required=True,
                        help="NAME=PRISM[:VAR=VALUE...]; the first one's PRISM renders alone")
    args = parser.parse_args()

    variants = [parse_variant(v) for v in args.variant]
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    out = "/tmp/prism-job-efficiency-%d.exr" % os.getpid()
    def render_args(threads):
        return ["render", args.scene, "--threads", str(threads), "-W", str(args.W), "-H",
                str(args.H), "--spp", str(args.spp), "-q", "--overwrite", "-o", out]
    render = render_args(1)
    mpirun = ["mpirun", "-np", "2"] + (["--bind-to", args.bind_to] if args.bind_to else [])
    serial = []
    ceiling = "one process, 2 threads (no MPI)"
    rows = [name for name, _, _ in variants] + ([ceiling] if args.two_threads else [])
    efficiency = {name: [] for name in rows}
    jobs = {name: [] for name in rows}
    for r in range(args.rounds):
        steps = [("one process", None)] + [(name, (prism, extra)) for name, prism, extra in variants]
        if args.two_threads:
            steps.append((ceiling, None))
        if r % 2:
            steps.reverse()
        times = {}
        for name, spec in steps:
            if name == ceiling:
                times[name] = timed([variants[0][1]] + render_args(2), env)
            elif spec is None:
                times[name] = timed([variants[0][1]] + render, env)
            else:
                prism, extra = spec
                times[name] = timed(mpirun + [prism] + render, dict(env, **extra))
        serial.append(times["one process"])
        for name in rows:
            jobs[name].append(times[name])
            efficiency[name].append(times["one process"] / (2 * times[name]))
        print("round %d/%d: one process %.3f s; %s" % (
            r + 1, args.rounds, times["one process"],
            ", ".join("%s %.3f s (%.3f)" % (n, times[n], efficiency[n][-1]) for n in rows)),
            file=sys.stderr)
    if os.path.exists(out):
        os.remove(out)

    print("%s %dx%d, %d spp, 1 thread per process, %d rounds; one process: median %.3f s; "
          "load average at the end %s" % (os.path.basename(args.scene), args.W, args.H, args.spp,
                                          args.rounds, statistics.median(serial),
                                          " ".join("%.2f" % x for x in os.getloadavg())))
    print()
    print("| variant | job s, median | efficiency per round | median |")
    print("|---|---:|---|---:|")
    for name in rows:
        print("| %s | %.3f | %s | %.3f |" % (
            name, statistics.median(jobs[name]), ", ".join("%.2f" % e for e in efficiency[name]),
            statistics.median(efficiency[name])))


if __name__ == "__main__":
    main()
