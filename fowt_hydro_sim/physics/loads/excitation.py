"""A potential-flow hull's first-order wave excitation (HydroDyn's ExctnMod 1, at the
undisplaced position): Re(sum_j a_j X(w_j, beta_j) e^{i (w_j t + phase_j)}) with the ``.3``
file's X interpolated in frequency and heading and the model's own wave components (those
the Morison strips see), sampled over the waves' repeat period and interpolated in time.
Zero for a platform without potential flow, in still water or with streamed waves."""
from __future__ import annotations

import numpy as np

from fowt_hydro_sim.physics.hydro.potential_flow import excitation_series, wamit_data
from fowt_hydro_sim.physics.jit import step_loop
from fowt_hydro_sim.physics.tables import interpolate_series


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[on, sample step] and the force samples (n, 6)."""
    flow, waves = inputs.platform.potential_flow, inputs.waves
    if flow is None or waves is None or waves.frequency_hz.size == 0:
        return np.array([0.0, 1.0]), np.zeros((4, 6))
    samples, step = excitation_series(wamit_data(flow, inputs.platform.environment), waves)
    return np.array([1.0, step]), samples


@step_loop
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    """The excitation at time t (world axes, reference point)."""
    if params[0] == 0.0:
        return
    for c in range(6):
        out[c] += interpolate_series(table, params[1], t, c)
