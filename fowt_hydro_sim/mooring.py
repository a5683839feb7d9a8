"""The paper's mooring: massless linear springs from body fairleads to fixed anchors.

Tension T = T0 + k (L - L0) along the line toward the anchor, L the current fairlead-to-
anchor distance, so the geometry (and the pretension's geometric stiffness) follows the
body's motion.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .rigid_body import cross


@njit(cache=True)
def mooring_wrench(position: np.ndarray, rotation: np.ndarray, fairleads_body: np.ndarray,
                   anchors: np.ndarray, stiffness_n_m: float, pretension_n: float,
                   unstretched_length_m: float) -> np.ndarray:
    """Force and moment (world axes, about the reference point) of all lines."""
    out = np.zeros(6)
    for i in range(fairleads_body.shape[0]):
        r = rotation @ fairleads_body[i]
        line = anchors[i] - (position + r)
        length = np.sqrt(line @ line)
        tension = pretension_n + stiffness_n_m * (length - unstretched_length_m)
        force = tension * line / length
        out[0:3] += force
        out[3:6] += cross(r, force)
    return out
