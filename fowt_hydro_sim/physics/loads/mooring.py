"""The paper's mooring: massless linear springs from body fairleads to fixed anchors.

Tension T = T0 + k (L - L0) along the line toward the anchor, L the current fairlead-to-
anchor distance, so the geometry (and the pretension's geometric stiffness) follows the
body's motion.
"""
from __future__ import annotations

import numpy as np

from fowt_hydro_sim.physics.jit import step_loop


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[k, T0, L0, fairleads (3 n, body frame), anchors (3 n, world frame)]."""
    mooring = inputs.platform.mooring
    return np.concatenate([[mooring.stiffness_n_m, mooring.pretension_n, mooring.unstretched_length_m],
                           np.ravel([line.fairlead_m for line in mooring.lines]),
                           np.ravel([line.anchor_m for line in mooring.lines])]), np.zeros((1, 1))


@step_loop
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    """Force and moment (world axes, about the reference point) of all lines."""
    stiffness, pretension, unstretched = params[0], params[1], params[2]
    n = (params.size - 3) // 6
    for i in range(n):  # written out: no temporaries in the step loop
        f, a = 3 + 3 * i, 3 + 3 * n + 3 * i  # the fairlead (body frame) and anchor (world frame)
        r0 = rotation[0, 0] * params[f] + rotation[0, 1] * params[f + 1] + rotation[0, 2] * params[f + 2]
        r1 = rotation[1, 0] * params[f] + rotation[1, 1] * params[f + 1] + rotation[1, 2] * params[f + 2]
        r2 = rotation[2, 0] * params[f] + rotation[2, 1] * params[f + 1] + rotation[2, 2] * params[f + 2]
        l0, l1, l2 = params[a] - y[0] - r0, params[a + 1] - y[1] - r1, params[a + 2] - y[2] - r2
        length = np.sqrt(l0 * l0 + l1 * l1 + l2 * l2)
        scale = (pretension + stiffness * (length - unstretched)) / length
        f0, f1, f2 = scale * l0, scale * l1, scale * l2
        out[0] += f0
        out[1] += f1
        out[2] += f2
        out[3] += r1 * f2 - r2 * f1
        out[4] += r2 * f0 - r0 * f2
        out[5] += r0 * f1 - r1 * f0
