#!/usr/bin/env python3
"""Where the caustic map of a distributed render should be built: on every rank, or once on
rank 0 and sent. Renders one caustic-map frame with 1 process and with 2 MPI ranks (1 thread
each, so 2 ranks use this machine's 2 cores), alternating, and prints medians of

    build   rank 0's map build (its run summary)
    frame   tiles handed out until the last one is back
    total   the whole run as rank 0 reports it (scene, map, frame, image)

for each binary given (e.g. the current build and one built from an older commit). The cost of
building once and broadcasting instead is estimated from the bytes a slave would need for its
lookups (a receiver texel and an irradiance per texel) over the link bandwidth `prism speedup`
measures (--bandwidth, MB/s).

usage: caustic_map_ranks.py [--prism PATH ...] [--runs N] [--resolution N] [--bandwidth MB/s]
"""
import argparse
import os
import re
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
SCENE = os.path.join(REPO, "scenes", "caustic-glass-sphere.yaml")
# position, normal (3 floats each), distance, cosine, valid (padded): 36 B; irradiance: 12 B.
BYTES_PER_TEXEL = 48


def mpi_env():
    env = dict(os.environ)
    if os.geteuid() == 0:
        env["OMPI_ALLOW_RUN_AS_ROOT"] = "1"
        env["OMPI_ALLOW_RUN_AS_ROOT_CONFIRM"] = "1"
    return env


def run(prism, ranks, resolution, out):
    args = [prism, "render", SCENE, "--caustics", "map", "--map-resolution", str(resolution),
            "--width", "640", "--height", "480", "--spp", "4", "--threads", "1", "-o", out, "--overwrite"]
    if ranks > 1:
        args = ["mpiexec", "-n", str(ranks), "--bind-to", "none"] + args
    done = subprocess.run(args, env=mpi_env(), capture_output=True, text=True, timeout=600)
    if done.returncode != 0:
        sys.exit("failed: %s\n%s%s" % (" ".join(args), done.stdout, done.stderr))
    text = done.stdout
    build = re.search(r"\(build ([0-9.]+) ms\)", text)
    times = re.search(r"^time\s+render ([0-9.]+) s.*total ([0-9.]+) s", text, re.M)
    if not build or not times:
        sys.exit("no build or time line in:\n" + text)
    return float(build.group(1)) / 1e3, float(times.group(1)), float(times.group(2))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--prism", action="append", help="binary (repeatable)")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--resolution", type=int, default=1024)
    parser.add_argument("--bandwidth", type=float, default=1026.0,
                        help="MB/s from rank 0 to a slave (prism speedup's link probe)")
    a = parser.parse_args()
    binaries = a.prism or [os.path.join(REPO, "build", "prism")]
    out = "/tmp/caustic_map_ranks.png"
    samples = {(b, r): [] for b in binaries for r in (1, 2)}
    for i in range(a.runs):
        for b in binaries:
            for r in (1, 2):
                samples[(b, r)].append(run(b, r, a.resolution, out))
                print("run %d/%d done: %s, %d rank(s)" % (i + 1, a.runs, b, r), file=sys.stderr)
    print("caustic map %d², scenes/caustic-glass-sphere.yaml, 640x480, 4 spp, 1 thread per "
          "rank, medians of %d\n" % (a.resolution, a.runs))
    print("| binary | ranks | build s | frame s | total s (min..max) |")
    print("|---|---|---|---|---|")
    for (b, r), s in samples.items():
        med = [statistics.median(x[k] for x in s) for k in range(3)]
        totals = [x[2] for x in s]
        print("| %s | %d | %.3f | %.3f | %.3f (%.3f..%.3f) |"
              % (b, r, med[0], med[1], med[2], min(totals), max(totals)))
    megabytes = a.resolution * a.resolution * BYTES_PER_TEXEL / 1e6
    print("\nbuild once and send: %.1f MB per slave, %.3f s at %.0f MB/s"
          % (megabytes, megabytes / a.bandwidth, a.bandwidth))


if __name__ == "__main__":
    main()
