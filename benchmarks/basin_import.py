"""Benchmark of ``fowt-sim measured import``: a 3-hour full-scale run at 1:50 (25.5 minutes
of model time sampled at 100 Hz, 152,736 rows), two probes, six DOFs and three line
tensions, written as a model-scale CSV, an HDF5 and a MATLAB file, each imported by the
command in a fresh process (reading, checks, Froude scaling, the probe clock check, the bag).

Prints: each file's size and the command's wall time.

    python benchmarks/basin_import.py [--repeat 3]
"""
from __future__ import annotations

import argparse
import csv
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import h5py
import numpy as np
import scipy.io
import yaml

SCALE = 50.0
RATE_HZ = 100.0
DURATION_S = 10800.0  # full scale


def channels() -> dict[str, np.ndarray]:
    """Model-scale channels of a synthetic run (sums of sines; SI units but mm for lengths)."""
    t = np.arange(0.0, DURATION_S / np.sqrt(SCALE), 1.0 / RATE_HZ)
    rng = np.random.default_rng(1)
    out = {"Time": t}
    for name in ("WP1", "Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw", "T1", "T2", "T3"):
        f, phase = rng.uniform(0.3, 1.5, 20), rng.uniform(0, 2 * np.pi, 20)
        out[name] = np.sin(2 * np.pi * f[:, None] * t[None, :] + phase[:, None]).sum(axis=0)
    out["WP2"] = out["WP1"]  # beside it, across the waves' direction
    return out


def column_map() -> dict:
    probes = {"WP1": [0.0, 0.0], "WP2": [0.0, 1.0]}
    spec = {name: {"quantity": "elevation", "unit": "mm", "position_m": xy} for name, xy in probes.items()}
    spec.update({name: {"quantity": name.lower(), "unit": "mm"} for name in ("Surge", "Sway", "Heave")})
    spec.update({name: {"quantity": name.lower(), "unit": "deg"} for name in ("Roll", "Pitch", "Yaw")})
    spec.update({name: {"quantity": "tension", "unit": "N", "line": name} for name in ("T1", "T2", "T3")})
    return {"scale": SCALE, "density_ratio": 1.025, "time": {"channel": "Time"}, "channels": spec}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=3, help="imports per file (the best is reported)")
    args = parser.parse_args()
    data = channels()
    with tempfile.TemporaryDirectory() as folder:
        root = Path(folder)
        (root / "map.yaml").write_text(yaml.safe_dump(column_map()))
        with open(root / "run.csv", "w", newline="") as stream:
            writer = csv.writer(stream)
            writer.writerow(list(data))
            writer.writerows(np.column_stack(list(data.values())).tolist())
        with h5py.File(root / "run.h5", "w") as stream:
            for name, values in data.items():
                stream.create_dataset(name, data=values)
        scipy.io.savemat(root / "run.mat", data)
        print(f"{data['Time'].size} rows x {len(data)} channels, {DURATION_S:g} s full scale at 1:{SCALE:g}")
        for name in ("run.csv", "run.h5", "run.mat"):
            walls = []
            for _ in range(args.repeat):
                start = time.perf_counter()
                done = subprocess.run([sys.executable, "-m", "fowt_hydro_sim.cli", "measured", "import",
                                       str(root / name), "--map", str(root / "map.yaml"), "-o", str(root / "bags"),
                                       "--overwrite"], capture_output=True, text=True)
                if done.returncode:
                    sys.exit(done.stderr)
                walls.append(time.perf_counter() - start)
            size = (root / name).stat().st_size / 1e6
            print(f"{name}: {size:.1f} MB, import {min(walls):.2f} s wall (best of {args.repeat})")


if __name__ == "__main__":
    main()
