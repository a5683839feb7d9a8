"""Benchmark of ``fowt-sim sweep`` on 1, 2 and 4 workers of a LocalCluster (one thread each).

The same table of runs (load cases x seeds, constant drag, the packaged platform) is swept
once per worker count into a fresh folder (the first sweep also warms the kernel cache,
which is not timed: a one-run sweep goes first). Prints, per worker count: wall time, runs
per minute, speed-up over one worker and parallel efficiency (speed-up / workers), with the
machine's core count and load average beside them.

    python benchmarks/sweep.py [--runs 24] [--hours 3] [--workers 1 2 4]
"""
from __future__ import annotations

import argparse
import logging
import os
import tempfile
import time
from pathlib import Path

from fowt_hydro_sim.physics.config import RunConfig
from fowt_hydro_sim.studies.sweep import Sweep, run_sweep

CASES = ("lc5.0", "lc5.1", "lc5.2", "lc5.3", "lc5.4", "lc6.1")


def table(runs: int, hours: float) -> Sweep:
    """``runs`` runs of ``hours``: the six load cases, seeds 1, 2, ... as many as needed."""
    cases = CASES[: min(runs, len(CASES))]
    if runs % len(cases):
        raise SystemExit(f"--runs must be a multiple of {len(cases)}")
    return Sweep(cases, tuple(range(1, runs // len(cases) + 1)), run=RunConfig(duration_s=3600.0 * hours),
                 transient_s=600.0)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=24)
    parser.add_argument("--hours", type=float, default=3.0, help="simulated hours per run")
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2, 4])
    args = parser.parse_args()
    logging.basicConfig(level=logging.WARNING)
    sweep = table(args.runs, args.hours)
    with tempfile.TemporaryDirectory() as folder:
        run_sweep(Sweep(("lc5.3",), (1,), run=RunConfig(duration_s=60.0)), Path(folder) / "warm", workers=1)
        print(f"{args.runs} runs of {args.hours:g} h (dt {sweep.run.dt_s:g} s, constant drag), "
              f"{os.cpu_count()} cores, load average before {os.getloadavg()[0]:.1f}")
        print(f"{'workers':>8s}{'wall [s]':>10s}{'runs/min':>10s}{'sim x real':>12s}{'speed-up':>10s}"
              f"{'efficiency':>12s}{'load':>7s}")
        base = None
        for workers in args.workers:
            start = time.perf_counter()
            outcome = run_sweep(sweep, Path(folder) / f"w{workers}", workers=workers)
            wall = time.perf_counter() - start
            base = base or wall * args.workers[0]
            speed_up = base / wall
            print(f"{workers:8d}{wall:10.1f}{60 * outcome['runs'] / wall:10.2f}"
                  f"{outcome['runs'] * sweep.run.duration_s / wall:12.0f}{speed_up:10.2f}"
                  f"{speed_up / workers:12.2f}{os.getloadavg()[0]:7.1f}", flush=True)


if __name__ == "__main__":
    main()
