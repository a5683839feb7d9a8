"""A potential-flow hull's hydrostatics as HydroDyn takes them from WAMIT (PotMod 1): the
buoyancy rho g PtfmVol0 at rest through the centre of buoyancy (PtfmCOBxt, PtfmCOByt), minus
the ``.hst`` restoring C q (q the displacement of the reference point, small angles). WAMIT's
C holds no gravity terms (the centre of gravity was put at the origin in the WAMIT run): the
weight acts separately at the centre of gravity (the ``gravity`` component). Zero for a
platform without potential flow."""
from __future__ import annotations

import numpy as np

from fowt_hydro_sim.physics.hydro.potential_flow import wamit_data
from fowt_hydro_sim.physics.jit import add_force_minus_stiffness, step_loop


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[on, W0 (6), C (36)]; no table."""
    flow, env = inputs.platform.potential_flow, inputs.platform.environment
    if flow is None:
        return np.zeros(43), np.zeros((1, 1))
    c = wamit_data(flow, env).hydrostatics.stiffness_si
    buoyancy = env.water_density_kg_m3 * env.gravity_m_s2 * flow.displaced_volume_m3
    x_cob, y_cob = flow.centre_of_buoyancy_xy_m
    w0 = np.array([0.0, 0.0, buoyancy, buoyancy * y_cob, -buoyancy * x_cob, 0.0])
    return np.concatenate([[1.0], w0, c.ravel()]), np.zeros((1, 1))


@step_loop
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    """W0 - C q."""
    if params[0] != 0.0:
        add_force_minus_stiffness(params, 1, y, out)
