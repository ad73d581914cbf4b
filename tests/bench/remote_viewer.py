#!/usr/bin/env python3
"""The remote viewer against the window beside the job, in one run (docs/viewer.md).

Runs `prism view --benchmark-moves` in process and `prism view --serve` + `prism connect
--benchmark-moves` over localhost TCP, alternating, for one process (2 threads) and 2 ranks
(1 thread each), and once more through a throttling proxy (default 2 MB/s each way). Prints
each run's frames/s and move-to-frame latency as the window measured them, the job's own frame
rate (`rendered` line) for the served runs, and the medians with the remote/in-process ratio.

  tests/bench/remote_viewer.py [--prism build/prism] [--runs 3] [--size 640x360]
                               [--moves 200] [--interval 10] [--rate 2e6]
"""
import argparse
import asyncio
import os
import re
import statistics
import subprocess
import sys
import tempfile
import threading
import time

SCENE = os.path.join(os.path.dirname(__file__), "..", "..", "scenes", "default.yaml")
ENV = dict(os.environ, QT_QPA_PLATFORM="offscreen", OMPI_ALLOW_RUN_AS_ROOT="1",
           OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def parse(output):
    fps = re.search(r"realtime  ([0-9.]+) frames/s", output)
    latency = re.search(r"latency    median ([0-9.e+-]+) ms", output)
    job = re.search(r"rendered   ([0-9.]+) frames/s", output)
    return (float(fps.group(1)) if fps else None, float(latency.group(1)) if latency else None,
            float(job.group(1)) if job else None)


def view_command(prism, ranks, size, extra):
    width, height = size.split("x")
    threads = "2" if ranks == 1 else "1"
    base = [prism, "view", SCENE, "-W", width, "-H", height, "--spp", "1", "--threads", threads,
            "--frame-time", "0"] + extra
    if ranks == 1:
        return base
    return ["mpiexec", "-n", str(ranks), "--oversubscribe"] + base


class Throttle:
    """A TCP proxy that carries at most `rate` bytes/s each way (a slow link)."""

    def __init__(self, target_port, rate):
        self.target_port, self.rate = target_port, rate
        self.loop = asyncio.new_event_loop()
        self.port = None
        ready = threading.Event()
        threading.Thread(target=self._run, args=(ready,), daemon=True).start()
        ready.wait()

    def _run(self, ready):
        asyncio.set_event_loop(self.loop)
        server = self.loop.run_until_complete(
            asyncio.start_server(self._serve, "127.0.0.1", 0))
        self.port = server.sockets[0].getsockname()[1]
        ready.set()
        self.loop.run_forever()

    async def _pipe(self, reader, writer):
        try:
            while True:
                data = await reader.read(16384)
                if not data:
                    break
                writer.write(data)
                await writer.drain()
                await asyncio.sleep(len(data) / self.rate)
        except (ConnectionError, OSError):
            pass
        writer.close()

    async def _serve(self, client_reader, client_writer):
        server_reader, server_writer = await asyncio.open_connection("127.0.0.1",
                                                                     self.target_port)
        await asyncio.gather(self._pipe(client_reader, server_writer),
                             self._pipe(server_reader, client_writer))


def run_local(args, ranks):
    command = view_command(args.prism, ranks, args.size,
                           ["--benchmark-moves", str(args.moves),
                            "--benchmark-interval", str(args.interval)])
    out = subprocess.run(command, env=ENV, capture_output=True, text=True, timeout=600)
    return parse(out.stdout + out.stderr)


def run_remote(args, ranks, rate=None):
    folder = tempfile.mkdtemp()
    connection = os.path.join(folder, "job")
    job = subprocess.Popen(view_command(args.prism, ranks, args.size,
                                        ["--serve", "0", "--connection-file", connection,
                                         "--exit-with-client"]),
                           env=ENV, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    while not os.path.exists(connection):
        if job.poll() is not None:
            sys.exit("the job ended before serving:\n" + job.stdout.read())
        time.sleep(0.05)
    target = connection
    env = ENV
    if rate:
        with open(connection) as f:
            fields = dict(line.strip().split("=", 1) for line in f if "=" in line)
        proxy = Throttle(int(fields["port"]), rate)
        target = "127.0.0.1:%d" % proxy.port
        env = dict(ENV, PRISM_TOKEN=fields["token"])
    desk = subprocess.run([args.prism, "connect", target, "--benchmark-moves", str(args.moves),
                           "--benchmark-interval", str(args.interval), "--frame-time", "0"],
                          env=env, capture_output=True, text=True, timeout=600)
    job_out = job.communicate(timeout=120)[0]
    fps, latency, _ = parse(desk.stdout + desk.stderr)
    job_fps = parse(job_out)[2]
    received = re.search(r"received   ([0-9]+) bytes", desk.stdout)
    return fps, latency, job_fps, int(received.group(1)) if received else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--prism", default="build/prism")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--size", default="640x360")
    parser.add_argument("--moves", type=int, default=200)
    parser.add_argument("--interval", type=float, default=10)
    parser.add_argument("--rate", type=float, default=2e6, help="throttled link, bytes/s")
    args = parser.parse_args()
    print("cpu:", subprocess.run("lscpu | sed -n 's/^Model name: *//p'", shell=True,
                                 capture_output=True, text=True).stdout.strip())
    results = {}
    for run in range(args.runs):
        for ranks in (1, 2):
            for name, measure in (("in process", lambda: run_local(args, ranks) + (None,)),
                                  ("localhost", lambda: run_remote(args, ranks))):
                r = measure()
                results.setdefault((name, ranks), []).append(r)
                print("run %d  %-10s %d rank(s): %s frames/s, latency %s ms, job %s frames/s%s"
                      % (run + 1, name, ranks, r[0], r[1], r[2],
                         ", %.1f MB received" % (r[3] / 1e6) if r[3] else ""), flush=True)
        r = run_remote(args, 1, args.rate)
        results.setdefault(("throttled", 1), []).append(r)
        print("run %d  throttled %.1f MB/s, 1 rank: %s frames/s, latency %s ms, job %s frames/s"
              % (run + 1, args.rate / 1e6, r[0], r[1], r[2]), flush=True)
    print("\nmedians (%s, %d moves every %g ms, %d runs)" % (args.size, args.moves,
                                                             args.interval, args.runs))

    def med(key, i):
        values = [r[i] for r in results[key] if r[i] is not None]
        return statistics.median(values) if values else float("nan")

    for ranks in (1, 2):
        local_fps, remote_fps = med(("in process", ranks), 0), med(("localhost", ranks), 0)
        local_lat, remote_lat = med(("in process", ranks), 1), med(("localhost", ranks), 1)
        print("%d rank(s): in process %.1f frames/s, %.1f ms; localhost %.1f frames/s, %.1f ms;"
              " ratio %.2f, added latency %.1f ms" % (ranks, local_fps, local_lat, remote_fps,
                                                     remote_lat, remote_fps / local_fps,
                                                     remote_lat - local_lat))
    print("throttled %.1f MB/s: %.1f frames/s shown, latency %.1f ms, job %.1f frames/s"
          % (args.rate / 1e6, med(("throttled", 1), 0), med(("throttled", 1), 1),
             med(("throttled", 1), 2)))


if __name__ == "__main__":
    main()
