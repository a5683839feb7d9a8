"""Plain columnar output of a run: ``timeseries.csv`` (one column per channel, SI units in
the names) and ``summary.json`` (configuration and statistics)."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from .dynamics import LOAD_COMPONENTS
from .model import DOF_NAMES, RunResult

_AXES = ("fx_n", "fy_n", "fz_n", "mx_nm", "my_nm", "mz_nm")
_MOTION_UNITS = ("m", "m", "m", "rad", "rad", "rad")


def column_names() -> list[str]:
    names = ["time_s"]
    names += [f"{d}_{u}" for d, u in zip(DOF_NAMES, _MOTION_UNITS)]
    names += [f"{d}_velocity_{u}_s" for d, u in zip(DOF_NAMES, _MOTION_UNITS)]
    names += [f"{d}_acceleration_{u}_s2" for d, u in zip(DOF_NAMES, _MOTION_UNITS)]
    names += [f"{c}_{a}" for c in LOAD_COMPONENTS for a in _AXES]
    names.append("wave_elevation_m")
    return names


def write_run(folder: Path, result: RunResult, summary: dict) -> None:
    folder.mkdir(parents=True, exist_ok=True)
    table = np.column_stack([result.time_s, result.motion, result.velocity, result.acceleration,
                             result.loads.reshape(len(result.time_s), -1), result.wave_elevation_m])
    np.savetxt(folder / "timeseries.csv", table, delimiter=",", header=",".join(column_names()),
               comments="", fmt="%.9g")
    (folder / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")


def read_run(folder: Path) -> dict[str, np.ndarray]:
    """The columns of a run's ``timeseries.csv`` by name."""
    data = np.loadtxt(Path(folder) / "timeseries.csv", delimiter=",", skiprows=1, ndmin=2)
    return dict(zip(column_names(), data.T))
