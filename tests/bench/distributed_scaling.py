#!/usr/bin/env python3
"""Parallel efficiency of Prism on this machine: best serial vs threads vs MPI ranks.

Renders one multi-second frame in each configuration, several times, alternating, and prints
median wall times of the render phase (Prism's own "render" time: tiles handed out until the
last one is back) and of the whole process, with speedup and efficiency against the best
serial run (1 process, 1 thread):

    serial      prism render SCENE --threads 1
    threads     prism render SCENE --threads 2
    ranks       mpirun -n 2 prism render SCENE --threads 1   (rank 0 renders and coordinates)

Efficiency E = T_serial / (p * T_p) with p = 2 cores. Points with more ranks x threads than
cores would be oversubscribed; this script never runs them.

usage: distributed_scaling.py [--runs N] [--scene FILE] [--spp N] [--prism PATH]
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


def run(command, env):
    start = time.monotonic()
    done = subprocess.run(command, env=env, capture_output=True, text=True, timeout=900)
    wall = time.monotonic() - start
    if done.returncode != 0:
        sys.exit("failed: %s\n%s%s" % (" ".join(command), done.stdout, done.stderr))
    match = re.search(r"^time\s+render ([0-9.]+) s", done.stdout, re.M)
    if not match:
        sys.exit("no render time in the output of %s:\n%s" % (" ".join(command), done.stdout))
    return float(match.group(1)), wall


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=5, help="runs per configuration (default 5)")
    parser.add_argument("--scene", default=os.path.join(REPO, "scenes", "default.yaml"))
    parser.add_argument("--spp", type=int, default=16, help="samples per pixel (default 16)")
    parser.add_argument("--prism", default=os.path.join(REPO, "build", "prism"))
    args = parser.parse_args()

    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    out = "/tmp/prism-scaling-%d.png" % os.getpid()
    base = [args.prism, "render", args.scene, "-o", out, "--overwrite", "--spp", str(args.spp)]
    configs = [
        ("serial: 1 process x 1 thread", 1, base + ["--threads", "1"]),
        ("threads: 1 process x 2 threads", 2, base + ["--threads", "2"]),
        ("ranks: 2 ranks x 1 thread", 2, ["mpirun", "-n", "2", "--bind-to", "core"] + base + ["--threads", "1"]),
    ]
    samples = {name: [] for name, _, _ in configs}
    for r in range(args.runs):
        order = configs if r % 2 == 0 else list(reversed(configs))
        for name, _, command in order:
            samples[name].append(run(command, env))
        print("round %d/%d done" % (r + 1, args.runs), file=sys.stderr)
    os.remove(out) if os.path.exists(out) else None

    serial_render = statistics.median(s[0] for s in samples[configs[0][0]])
    serial_wall = statistics.median(s[1] for s in samples[configs[0][0]])
    print("scene %s, %d spp, %d runs each, medians; load average at the end %s"
          % (os.path.relpath(args.scene, REPO), args.spp, args.runs,
             " ".join("%.2f" % x for x in os.getloadavg())))
    print()
    print("| configuration | cores p | render s (min..max) | speedup | efficiency | process wall s | efficiency (wall) |")
    print("|---|---:|---|---:|---:|---:|---:|")
    for name, p, _ in configs:
        renders = [s[0] for s in samples[name]]
        walls = [s[1] for s in samples[name]]
        render = statistics.median(renders)
        wall = statistics.median(walls)
        print("| %s | %d | %.3f (%.3f..%.3f) | %.2f | %.2f | %.3f | %.2f |"
              % (name, p, render, min(renders), max(renders), serial_render / render,
                 serial_render / (p * render), wall, serial_wall / (p * wall)))


if __name__ == "__main__":
    main()
