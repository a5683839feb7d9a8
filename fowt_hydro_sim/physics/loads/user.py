"""A force computed in Python: the callable passed as ``PlatformModel(user_force=...)``.

The compiled kernel cannot call Python, so the model steps through a Python-level loop when
it has one (``dynamics.integrate_stepwise``), writing the callable's wrench at each
evaluation's time and state into this component's params before the compiled right-hand
side reads them. Without a callable the params stay zero and the compiled loop runs alone.
"""
from __future__ import annotations

import numpy as np

from fowt_hydro_sim.physics.jit import step_loop


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[wrench (6), world axes, about the reference point]; zero until the model writes it."""
    return np.zeros(6), np.zeros((1, 1))


@step_loop
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    """The wrench last written."""
    for i in range(6):
        out[i] += params[i]
