"""Hub-height wind speed inputs: steady, step, ramp, or a measured or turbulent series
(a CSV of time and speed, or samples from a bag), each a function of time."""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.config import ConfigError

WIND_KINDS = ("steady", "step", "ramp", "file")
MAX_WIND_M_S = 80.0  # beyond: not a wind speed
DEFAULT_WIND_M_S = 13.0  # the one default hub-height wind speed (turbine node, closed loop): above rated


@dataclass(frozen=True)
class Wind:
    """``speed_m_s`` until ``start_s``; then a step to ``end_m_s`` or a ramp reaching it after
    ``ramp_s``; or the series (``time_s``, ``series_m_s``) interpolated, held at its ends."""

    kind: str = "steady"
    speed_m_s: float = DEFAULT_WIND_M_S
    end_m_s: float = DEFAULT_WIND_M_S
    start_s: float = 0.0
    ramp_s: float = 60.0
    time_s: tuple[float, ...] = ()
    series_m_s: tuple[float, ...] = ()

    def at(self, t_s: float) -> float:
        if self.kind == "file":
            return float(np.interp(t_s, self.time_s, self.series_m_s))
        if t_s < self.start_s or self.kind == "steady":
            return self.speed_m_s
        if self.kind == "step":
            return self.end_m_s
        fraction = min(1.0, (t_s - self.start_s) / self.ramp_s)
        return self.speed_m_s + fraction * (self.end_m_s - self.speed_m_s)


def check_series(time_s: np.ndarray, speed_m_s: np.ndarray, where: str) -> None:
    if time_s.size < 2:
        raise ConfigError(f"{where}: at least two samples are needed")
    if not (np.all(np.isfinite(time_s)) and np.all(np.isfinite(speed_m_s))):
        raise ConfigError(f"{where}: a time or speed is not a finite number")
    if np.any(np.diff(time_s) <= 0):
        raise ConfigError(f"{where}: times must increase")
    if np.any(speed_m_s < 0) or np.any(speed_m_s > MAX_WIND_M_S):
        raise ConfigError(f"{where}: wind speeds must be 0 to {MAX_WIND_M_S:g} m/s")


def read_series(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """A CSV of time [s] and hub-height wind speed [m/s] (a header line is allowed)."""
    try:
        text = Path(path).read_text()
    except OSError as exc:
        raise ConfigError(f"wind file {path}: cannot be read ({exc.strerror})") from None
    rows = []
    for number, line in enumerate(text.splitlines(), 1):
        cells = [c.strip() for c in line.split(",")]
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        try:
            if len(cells) != 2:
                raise ValueError
            rows.append((float(cells[0]), float(cells[1])))
        except ValueError:
            if rows or number > 1 and not line.strip().startswith(("t", "time")):
                raise ConfigError(f"wind file {path}: line {number}: expected 'time_s, speed_m_s', "
                                  f"got {line.strip()!r}") from None
    data = np.array(rows, dtype=float).reshape(-1, 2)
    check_series(data[:, 0], data[:, 1], f"wind file {path}")
    return data[:, 0], data[:, 1]


def series_wind(time_s: np.ndarray, speed_m_s: np.ndarray) -> Wind:
    return Wind("file", float(speed_m_s[0]), float(speed_m_s[-1]), time_s=tuple(map(float, time_s)),
                series_m_s=tuple(map(float, speed_m_s)))
