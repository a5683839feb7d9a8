"""HydroDyn's additional preload, stiffness and damping of a potential-flow hull (AddF0,
AddCLin, AddBLin, AddBQuad): AddF0 - AddCLin q - AddBLin v - AddBQuad (|v| v), q and v the
reference point's displacement and velocity (world axes, small angles), (|v| v)_j = |v_j| v_j.
Zero for a platform without potential flow; without AddBQuad where the band-split AddBQuad
(``added_quadratic_bands``) replaces it."""
from __future__ import annotations

import numpy as np

from fowt_hydro_sim.physics.jit import step_loop
from fowt_hydro_sim.physics.loads import added_quadratic_bands


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[on, AddF0 (6), AddCLin (36), AddBLin (36), AddBQuad (36)]; no table."""
    flow = inputs.platform.potential_flow
    if flow is None:
        return np.zeros(115), np.zeros((1, 1))
    quadratic = np.zeros(36) if added_quadratic_bands.active(inputs) else np.ravel(flow.added_quadratic_damping)
    return np.concatenate([[1.0], flow.added_force_n, np.ravel(flow.added_stiffness),
                           np.ravel(flow.added_linear_damping), quadratic]), np.zeros((1, 1))


@step_loop
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    """AddF0 - AddCLin q - AddBLin v - AddBQuad |v| v."""
    if params[0] == 0.0:
        return
    for i in range(6):
        acc = params[1 + i]
        for j in range(6):
            v = y[6 + j]
            acc -= (params[7 + 6 * i + j] * y[j] + params[43 + 6 * i + j] * v
                    + params[79 + 6 * i + j] * abs(v) * v)
        out[i] += acc
