"""Benchmark: ``fowt-sim loads --hydrodyn`` on the full windmoor12 hull (0.5 m strips) along the
HydroDyn reference's 600 s prescribed motion, in a fresh process each time (start-up, numba
cache load, set-up, loads, CSV), in still water and in the reference's 169 JONSWAP
components, against the HydroDyn v5 driver's wall times on this kind of machine (62 s still
water, 103 s waves; reference READMEs).

Prints the wall time of each case (best of ``--repeats``) and HydroDyn's time over ours.
Run: python benchmarks/hydrodyn_loads.py [--repeats N]
"""
from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import yaml

from fowt_hydro_sim.physics.config import platform_document
from fowt_hydro_sim.testing import REPO
from fowt_hydro_sim.testing.references import hydrodyn_case

HYDRODYN_WALL_S = {"still water": 62.0, "waves": 103.0}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    sys.path.insert(0, str(REPO / "test"))
    from test_hydrodyn_moving import hydrodyn_hull, reference_motion

    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        np.savetxt(folder / "prp.dat", reference_motion(), fmt="%.6f" + " %.12e" * 18)
        (folder / "hull.yaml").write_text(yaml.safe_dump(platform_document(hydrodyn_hull()), sort_keys=False))
        comp = hydrodyn_case("windmoor12_fixed_waves") / "waves_jonswap_Hs11_Tp12_g4.9.Comp"
        command = [sys.executable, "-m", "fowt_hydro_sim.cli", "loads", "--platform", str(folder / "hull.yaml"),
                   "--motion", str(folder / "prp.dat"), "--hydrodyn", "--overwrite", "-o", str(folder / "out.csv")]
        cases = {"still water": ["--still-water"], "waves": ["--waves-comp", str(comp), "--wave-table-dt", "0.05"]}
        subprocess.run(command + cases["waves"], check=True, cwd=REPO, capture_output=True)  # fill the numba cache
        for name, extra in cases.items():
            best = float("inf")
            for _ in range(args.repeats):
                start = time.perf_counter()
                subprocess.run(command + extra, check=True, cwd=REPO, capture_output=True)
                best = min(best, time.perf_counter() - start)
            print(f"{name:12s} fowt-sim loads {best:6.2f} s wall (fresh process), HydroDyn "
                  f"{HYDRODYN_WALL_S[name]:.0f} s: {HYDRODYN_WALL_S[name] / best:5.1f}x faster")


if __name__ == "__main__":
    main()
