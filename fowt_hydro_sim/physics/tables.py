"""Periodic tables sampled in time (the wave kinematics, load series), read by the compiled
kernel with cubic interpolation."""
from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def interpolate_table(table: np.ndarray, step_s: float, t: float) -> np.ndarray:
    """Cubic (4-point Lagrange) interpolation in a periodic table (n, points, channels) at
    time t: (points, channels)."""
    n, n_points, n_channels = table.shape
    x = t / step_s
    i = int(np.floor(x))
    s = x - i
    w = (-s * (s - 1.0) * (s - 2.0) / 6.0, (s + 1.0) * (s - 1.0) * (s - 2.0) / 2.0,
         -(s + 1.0) * s * (s - 2.0) / 2.0, (s + 1.0) * s * (s - 1.0) / 6.0)
    rows = ((i - 1) % n, i % n, (i + 1) % n, (i + 2) % n)
    out = np.empty((n_points, n_channels))
    for p in range(n_points):
        for c in range(n_channels):
            out[p, c] = (w[0] * table[rows[0], p, c] + w[1] * table[rows[1], p, c]
                         + w[2] * table[rows[2], p, c] + w[3] * table[rows[3], p, c])
    return out
