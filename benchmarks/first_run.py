"""Benchmark of a new user's first run: ``fowt-sim simulate`` in a fresh kernel cache
(NUMBA_CACHE_DIR pointing at an empty folder), without and with ``fowt-sim compile`` first.

Prints, for each drag model: the whole process's wall time, the model's set-up (which
includes compiling on a cold cache) and the time loop, for a cold cache, for the warm-up
command itself, and for the same run after it; then a 60 s run's whole process (an upper
bound of the time until a first run starts), with the load average beside each figure.

    python benchmarks/first_run.py [--duration 3600]
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from fowt_hydro_sim.testing import REPO


def fowt_sim(args: list[str], cache: Path) -> float:
    """Wall seconds of one command in a new process with this kernel cache."""
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "fowt_hydro_sim.cli", *args], check=True, cwd=REPO, capture_output=True,
                   env={**os.environ, "NUMBA_CACHE_DIR": str(cache)})
    return time.perf_counter() - start


def simulate(drag: str, duration_s: float, cache: Path, folder: Path) -> str:
    out = folder / f"{drag}_{duration_s:g}"
    wall = fowt_sim(["simulate", "--drag", drag, "--duration", str(duration_s), "-o", str(out), "--overwrite"], cache)
    perf = json.loads((out / "summary.json").read_text())["performance"]
    loop = perf["wall_time_s"] - perf["set_up_s"]
    return f"process {wall:6.1f} s, set-up {perf['set_up_s']:5.1f} s, loop {loop:5.1f} s, load {os.getloadavg()[0]:.1f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=3600.0)
    args = parser.parse_args()
    print(f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}; simulate lc5.3, {args.duration:g} s")
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        for drag in ("constant", "filtered"):
            print(f"cold cache, {drag:9s}: {simulate(drag, args.duration, folder / f'cold_{drag}', folder)}")
        cache = folder / "warm"
        print(f"fowt-sim compile       : process {fowt_sim(['compile'], cache):6.1f} s, load {os.getloadavg()[0]:.1f}")
        for drag in ("constant", "filtered"):
            print(f"after it, {drag:9s} : {simulate(drag, args.duration, cache, folder)}")
            print(f"after it, {drag:9s} : {simulate(drag, 60.0, cache, folder)} (60 s run)")


if __name__ == "__main__":
    main()
