"""Gravity: the platform's weight, acting at its centre of gravity."""
from __future__ import annotations

import numpy as np

from fowt_hydro_sim.physics.jit import step_loop


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[m g, centre of gravity (3, body frame)]."""
    p = inputs.platform
    return np.array([p.mass.mass_kg * p.environment.gravity_m_s2, *p.mass.cog_m]), np.zeros((1, 1))


@step_loop
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    # the weight (0, 0, -m g) at the centre of gravity R c (world axes)
    arm0 = rotation[0, 0] * params[1] + rotation[0, 1] * params[2] + rotation[0, 2] * params[3]
    arm1 = rotation[1, 0] * params[1] + rotation[1, 1] * params[2] + rotation[1, 2] * params[3]
    out[2] -= params[0]
    out[3] -= arm1 * params[0]
    out[4] += arm0 * params[0]
