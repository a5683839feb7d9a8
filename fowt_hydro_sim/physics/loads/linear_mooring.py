"""A mooring given as a constant wrench at rest and a 6x6 stiffness about the reference point
(``Platform.linear_mooring``): F0 - K q (world axes, small motions), when the mooring in use is
``linear`` (the run may choose the platform's lines instead); zero otherwise."""
from __future__ import annotations

import numpy as np

from fowt_hydro_sim.physics.jit import add_force_minus_stiffness, step_loop


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[on, F0 (6), K (36)]; no table."""
    mooring = inputs.platform.linear_mooring
    if mooring is None or inputs.platform.mooring.model != "linear":
        return np.zeros(43), np.zeros((1, 1))
    return np.concatenate([[1.0], mooring.force_at_rest_n, np.ravel(mooring.stiffness)]), np.zeros((1, 1))


@step_loop
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    """F0 - K q."""
    if params[0] != 0.0:
        add_force_minus_stiffness(params, 1, y, out)
