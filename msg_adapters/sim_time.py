"""Simulation time in float seconds to and from ROS stamp parts and bag log times (ns);
no ROS imports."""
from __future__ import annotations

import math

import numpy as np

NS_PER_S = 10**9


def nanoseconds(time_s: float) -> int:
    """A non-negative simulation time in integer ns, rounded to the nearest ns."""
    if not math.isfinite(time_s):
        raise ValueError(f"time must be finite, got {time_s}")
    if time_s < 0.0:
        raise ValueError(f"time must be non-negative for a ROS stamp, got {time_s} s")
    whole = math.floor(time_s)
    return whole * NS_PER_S + round((time_s - whole) * 1e9)  # split: t * 1e9 loses ns above ~1e7 s


def nanoseconds_array(time_s: np.ndarray) -> np.ndarray:
    """``nanoseconds`` of each time (int64), the same rounding; ValueError names a time that
    is not finite or negative."""
    time_s = np.asarray(time_s, dtype=float)
    bad = ~np.isfinite(time_s) | (time_s < 0.0)
    if np.any(bad):
        nanoseconds(float(time_s[bad][0]))  # raises, naming it
    whole = np.floor(time_s)
    return whole.astype(np.int64) * NS_PER_S + np.rint((time_s - whole) * 1e9).astype(np.int64)


def stamp_parts(time_s: float) -> tuple[int, int]:
    """(sec, nanosec) of a simulation time in seconds, rounded to the nearest nanosecond."""
    return divmod(nanoseconds(time_s), NS_PER_S)
