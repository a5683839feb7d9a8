"""The paper's mooring: massless linear springs from body fairleads to fixed anchors.

Tension T = T0 + k (L - L0) along the line toward the anchor, L the current fairlead-to-
anchor distance, so the geometry (and the pretension's geometric stiffness) follows the
body's motion.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from fowt_hydro_sim.physics.rigid_body import cross, matvec


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[k, T0, L0, fairleads (3 n, body frame), anchors (3 n, world frame)]."""
    mooring = inputs.platform.mooring
    return np.concatenate([[mooring.stiffness_n_m, mooring.pretension_n, mooring.unstretched_length_m],
                           np.ravel([line.fairlead_m for line in mooring.lines]),
                           np.ravel([line.anchor_m for line in mooring.lines])]), np.zeros((1, 1))


@njit(cache=True)
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    """Force and moment (world axes, about the reference point) of all lines."""
    stiffness, pretension, unstretched = params[0], params[1], params[2]
    n = (params.size - 3) // 6
    fairleads = params[3:3 + 3 * n].reshape((n, 3))
    anchors = params[3 + 3 * n:].reshape((n, 3))
    position = y[0:3]
    for i in range(n):
        r = matvec(rotation, fairleads[i])
        line = anchors[i] - (position + r)
        length = np.sqrt(line[0] * line[0] + line[1] * line[1] + line[2] * line[2])
        tension = pretension + stiffness * (length - unstretched)
        force = tension * line / length
        out[0:3] += force
        out[3:6] += cross(r, force)
