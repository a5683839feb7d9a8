"""Benchmark: ``fowt-sim loads --hydrodyn`` on the full windmoor12 hull (0.5 m strips) along the
HydroDyn reference's 600 s prescribed motion, in a fresh process each time (start-up, numba
cache load, set-up, loads, CSV), in still water and in the reference's 169 JONSWAP
components, against the HydroDyn v5 driver's wall times on this kind of machine (62 s still
water, 103 s waves; reference READMEs).

Prints the wall and CPU (user + system) time of each case (best of ``--repeats``), HydroDyn's
time over each, and the load average: on a shared machine the wall time grows with the other
users' load, the CPU time much less.
Run: python benchmarks/hydrodyn_loads.py [--repeats N]
"""
from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import yaml

from fowt_hydro_sim.physics.config import platform_document
from fowt_hydro_sim.testing import REPO
from fowt_hydro_sim.testing.references import hydrodyn_case, hydrodyn_hull, reference_motion

HYDRODYN_WALL_S = {"still water": 62.0, "waves": 103.0}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        np.savetxt(folder / "prp.dat", reference_motion(), fmt="%.6f" + " %.12e" * 18)
        (folder / "hull.yaml").write_text(yaml.safe_dump(platform_document(hydrodyn_hull()), sort_keys=False))
        comp = hydrodyn_case("windmoor12_fixed_waves") / "waves_jonswap_Hs11_Tp12_g4.9.Comp"
        command = [sys.executable, "-m", "fowt_hydro_sim.cli", "loads", "--platform", str(folder / "hull.yaml"),
                   "--motion", str(folder / "prp.dat"), "--hydrodyn", "--overwrite", "-o", str(folder / "out.csv")]
        cases = {"still water": ["--still-water"], "waves": ["--waves-comp", str(comp), "--wave-table-dt", "0.05"]}
        subprocess.run(command + cases["waves"], check=True, cwd=REPO, capture_output=True)  # fill the numba cache
        print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
        for name, extra in cases.items():
            wall, cpu = float("inf"), float("inf")
            for _ in range(args.repeats):
                before, start = resource.getrusage(resource.RUSAGE_CHILDREN), time.perf_counter()
                subprocess.run(command + extra, check=True, cwd=REPO, capture_output=True)
                after = resource.getrusage(resource.RUSAGE_CHILDREN)
                wall = min(wall, time.perf_counter() - start)
                cpu = min(cpu, after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
            hd = HYDRODYN_WALL_S[name]
            print(f"{name:12s} fowt-sim loads {wall:6.2f} s wall, {cpu:5.2f} s CPU (fresh process), HydroDyn "
                  f"{hd:.0f} s: {hd / wall:5.1f}x on wall, {hd / cpu:5.1f}x on CPU")
        print(f"load average {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
