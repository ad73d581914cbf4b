#!/usr/bin/env python3
"""Log-log convergence slopes of a `prism sweep` CSV: for each family (curve), the least-squares
slope of log error against log time over its points, for the caustic region's relative RMSE and
MRSE, against wall and CPU seconds. A slope of −0.5 is an error that halves when the time
quadruples (Monte Carlo noise); 0, an error no budget moves.

  tests/bench/sweep_slopes.py SWEEP.csv [SWEEP.csv ...]

Python 3 standard library only; the slope is caustic_convergence.py's.
"""
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from caustic_convergence import slope  # noqa: E402


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    print("| sweep | family | points | time span s | rel. RMSE | MRSE | rel. RMSE (CPU s) | MRSE (CPU s) |")
    print("|---|---|---:|---|---:|---:|---:|---:|")
    for path in sys.argv[1:]:
        families = {}
        with open(path) as f:
            for row in csv.DictReader(f):
                families.setdefault((row["family"], row["method"]), []).append(row)
        for (family, method), rows in families.items():
            wall = [float(r["seconds_median"]) for r in rows]
            cpu = [float(r["cpu_seconds_median"]) for r in rows]
            rel = [float(r["region_rel_rmse"]) for r in rows]
            mrse = [float(r["region_mrse"]) for r in rows]
            print("| %s | %s: %s | %d | %.2f..%.2f | %.2f | %.2f | %.2f | %.2f |" % (
                os.path.basename(path), method, family, len(rows), min(wall), max(wall),
                slope(list(zip(wall, rel))), slope(list(zip(wall, mrse))),
                slope(list(zip(cpu, rel))), slope(list(zip(cpu, mrse)))))


if __name__ == "__main__":
    main()
