"""Gravity: the platform's weight, acting at its centre of gravity."""
from __future__ import annotations

import numpy as np
from numba import njit

from fowt_hydro_sim.physics.rigid_body import cross, matvec


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[m g, centre of gravity (3, body frame)]."""
    p = inputs.platform
    return np.array([p.mass.mass_kg * p.environment.gravity_m_s2, *p.mass.cog_m]), np.zeros((1, 1))


@njit(cache=True)
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    weight = np.array([0.0, 0.0, -params[0]])
    out[0:3] += weight
    out[3:6] += cross(matvec(rotation, params[1:4]), weight)
