"""Periodic tables sampled in time (the wave kinematics, load series), read by the compiled
kernel with cubic interpolation."""
from __future__ import annotations

import numpy as np
from numba import njit

from fowt_hydro_sim.physics.jit import step_loop


@njit(cache=True, inline="always")
def _lagrange(step_s: float, t: float, n: int) -> tuple[tuple[float, float, float, float], tuple[int, int, int, int]]:
    """The 4-point Lagrange weights and rows (periodic in n rows) at time t."""
    x = t / step_s
    i = int(np.floor(x))
    s = x - i
    w = (-s * (s - 1.0) * (s - 2.0) / 6.0, (s + 1.0) * (s - 1.0) * (s - 2.0) / 2.0,
         -(s + 1.0) * s * (s - 2.0) / 2.0, (s + 1.0) * s * (s - 1.0) / 6.0)
    return w, ((i - 1) % n, i % n, (i + 1) % n, (i + 2) % n)


@step_loop
def interpolate_series(series: np.ndarray, step_s: float, t: float, channel: int) -> float:
    """``interpolate_table`` of one channel of a periodic series (n, channels): a number, no
    array made (for the load components)."""
    w, rows = _lagrange(step_s, t, series.shape[0])
    return (w[0] * series[rows[0], channel] + w[1] * series[rows[1], channel]
            + w[2] * series[rows[2], channel] + w[3] * series[rows[3], channel])


@step_loop
def interpolate_into(table: np.ndarray, step_s: float, t: float, out: np.ndarray) -> None:
    """Cubic (4-point Lagrange) interpolation in a periodic table (n, points, channels) at
    time t, into ``out`` (points, channels); both C-contiguous (one flat loop, vectorised)."""
    n, n_points, n_channels = table.shape
    w, rows = _lagrange(step_s, t, n)
    flat = table.reshape((n, n_points * n_channels))
    r0, r1, r2, r3 = flat[rows[0]], flat[rows[1]], flat[rows[2]], flat[rows[3]]
    into = out.reshape(n_points * n_channels)
    for j in range(into.size):
        into[j] = w[0] * r0[j] + w[1] * r1[j] + w[2] * r2[j] + w[3] * r3[j]


@njit(cache=True)
def interpolate_table(table: np.ndarray, step_s: float, t: float) -> np.ndarray:
    """``interpolate_into`` a new array (points, channels)."""
    out = np.empty(table.shape[1:])
    interpolate_into(table, step_s, t, out)
    return out
