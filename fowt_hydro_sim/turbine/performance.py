"""Rotor performance tables (power, thrust and torque coefficients against blade pitch and
tip-speed ratio) in the text format ROSCO writes and ships (``Cp_Ct_Cq.*.txt``)."""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
from scipy.interpolate import RectBivariateSpline

from fowt_hydro_sim.physics.config import ConfigError

SECTIONS = ("power", "thrust", "torque")  # "# Power coefficient", "# Thrust coefficient", ...


@dataclass(frozen=True)
class PerformanceTable:
    pitch_rad: np.ndarray  # (n_pitch,)
    tsr: np.ndarray  # (n_tsr,)
    cp: np.ndarray  # (n_tsr, n_pitch)
    ct: np.ndarray
    cq: np.ndarray


def _numbers(line: str) -> list[float]:
    return [float(v) for v in line.split()]


def read_table(path: Path) -> PerformanceTable:
    """Parse a ROSCO performance file: pitch vector [deg], TSR vector, wind speed, then the
    Cp, Ct and Cq matrices (rows: TSR, columns: pitch)."""
    try:
        lines = Path(path).read_text().splitlines()
    except OSError as exc:
        raise ConfigError(f"performance table {path}: cannot be read ({exc.strerror})") from None
    vectors, matrices, current = {}, {}, None
    for i, line in enumerate(lines):
        low = " ".join(line.lower().split())
        if low.startswith("# pitch angle vector"):
            vectors["pitch"] = _numbers(lines[i + 1])
        elif low.startswith("# tsr vector"):
            vectors["tsr"] = _numbers(lines[i + 1])
        elif low.startswith("#"):
            current = next((s for s in SECTIONS if low.startswith(f"# {s} coefficient")), None)
            if current:
                matrices[current] = []
        elif current and line.strip():
            matrices[current].append(_numbers(line))
    missing = [s for s in ("pitch", "tsr") if s not in vectors] + [s for s in SECTIONS if not matrices.get(s)]
    if missing:
        raise ConfigError(f"performance table {path}: no {', '.join(missing)} section(s)")
    shape = (len(vectors["tsr"]), len(vectors["pitch"]))
    tables = {s: np.array(matrices[s]) for s in SECTIONS}
    for s, table in tables.items():
        if table.shape != shape:
            raise ConfigError(f"performance table {path}: {s} coefficients are {table.shape}, expected {shape} "
                              f"(TSR x pitch)")
    return PerformanceTable(np.deg2rad(vectors["pitch"]), np.array(vectors["tsr"]), tables["power"],
                            tables["thrust"], tables["torque"])


class RotorCoefficients:
    """Smooth (bicubic spline) interpolation of Cp and Ct at any pitch and tip-speed ratio,
    clamped to the table's range."""

    def __init__(self, table: PerformanceTable):
        self.table = table
        self._cp = RectBivariateSpline(table.pitch_rad, table.tsr, table.cp.T)
        self._ct = RectBivariateSpline(table.pitch_rad, table.tsr, table.ct.T)

    def _clamped(self, pitch_rad: float, tsr: float) -> tuple[float, float]:
        t = self.table
        return (min(max(pitch_rad, t.pitch_rad[0]), t.pitch_rad[-1]), min(max(tsr, t.tsr[0]), t.tsr[-1]))

    def cp(self, pitch_rad: float, tsr: float) -> float:
        return float(self._cp(*self._clamped(pitch_rad, tsr))[0, 0])

    def ct(self, pitch_rad: float, tsr: float) -> float:
        return float(self._ct(*self._clamped(pitch_rad, tsr))[0, 0])
