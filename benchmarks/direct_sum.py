"""Benchmark: prescribed-motion loads in wave components summed directly (a ``.Comp`` file whose
frequencies are on no common grid, the r-test's example.Comp: 76 components) against the same
components moved onto their 500 s grid (kinematics tables), on the r-test hd_WaveStMod3 column
(one member, 40 strips) at rest, 600 s at 0.1 s (6000 rows), HydroDyn's option set; in
process, numba kernel compiled beforehand, best of ``--repeats``.

Run: python benchmarks/direct_sum.py [--repeats N]
"""
from __future__ import annotations

import argparse
import dataclasses
import os
import tempfile
import time
from pathlib import Path

import numpy as np

from fowt_hydro_sim.cli import main
from fowt_hydro_sim.physics.config import HYDRODYN, load_platform
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import read_comp_file
from fowt_hydro_sim.testing import REPO

RTEST = REPO / "test" / "data" / "openfast_rtest"


def run(repeats: int) -> None:
    """Print the best time of each way of summing and their ratio."""
    with tempfile.TemporaryDirectory() as folder:
        platform_file = Path(folder) / "column.yaml"
        main(["platform", "import", str(RTEST / "hd_WaveStMod3" / "hydrodyn_input.dat"), "-o", str(platform_file),
              "--water-depth", "200"])
        platform = load_platform(platform_file)
    direct = read_comp_file(RTEST / "hd_WaveStMod2" / "example.Comp", direct_sum=True)
    gridded = dataclasses.replace(direct, frequency_hz=np.round(direct.frequency_hz * 500.0) / 500.0, period_s=500.0)
    t = np.arange(0.0, 600.0, 0.1)
    rest = np.zeros((t.size, 6))
    PlatformModel(platform, gridded, options=HYDRODYN).prescribed_motion_loads(t[:10], rest[:10], rest[:10], rest[:10])
    best = {}
    for name, waves in (("tables", gridded), ("direct sum", direct)):
        times = []
        for _ in range(repeats):
            start = time.perf_counter()
            PlatformModel(platform, waves, options=HYDRODYN).prescribed_motion_loads(t, rest, rest, rest)
            times.append(time.perf_counter() - start)
        best[name] = min(times)
        print(f"{name}: {best[name]:.2f} s for {t.size} rows, {direct.frequency_hz.size} components")
    print(f"direct sum / tables: {best['direct sum'] / best['tables']:.1f}x; load average {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=3)
    run(parser.parse_args().repeats)
