"""The seed paper's frequency-dependent drag on a potential-flow hull: HydroDyn's additional
quadratic damping AddBQuad split into the platform's drag bands. The reference point's velocity
v (world axes, six DOFs) goes through each band's analog Butterworth filter H_b (the same
filters as the Morison strips' band split, ``physics.drag_filters``), and

    F = - sum_b AddBQuad_b (|v_b| v_b),   v_b = H_b(s) v,   (|v_b| v_b)_j = |v_b,j| v_b,j

with one 6x6 matrix per band (``potential_flow.added_quadratic_damping_bands``). Active with
the ``filtered`` drag model when the platform gives the band matrices; the plain AddBQuad
(``added_matrices``) is then off. One all-pass band gives back the plain AddBQuad.

The filters run on the model's step: their states are advanced by the trapezoidal (Tustin)
rule from one step time to the next, over the velocities at the step times (the last
evaluation at each step time wins, the corrected state, as the radiation memory keeps its
velocities; step times no evaluation reached, as with a prescribed motion sampled coarser
than the step, take velocities linear between the evaluations around them). A run starts with
the filters in the steady state of its first velocity. Zero otherwise."""
from __future__ import annotations

import numpy as np

from fowt_hydro_sim.physics.drag_filters import bank_state_space
from fowt_hydro_sim.physics.jit import step_loop

ON, NB, NS, BASE, LAST, DT, HEADER = 0, 1, 2, 3, 4, 5, 6
# params blocks after the header, in this order: P (ns x ns) and Q (ns) of the Tustin step
# x' = P x + Q (u + u'), C (nb x ns) and D (nb) of the bands' outputs, AddBQuad_b (nb x 36), the
# states at the base step and the trial states (ns x 6 each, one column per DOF), the velocities at
# the base step and at the last evaluation (6 each), the steady-state gain 2 (I - P)^-1 (ns x ns)
# and a scratch column (ns)
BLOCKS = ("p", "q", "c", "d", "bquad", "x_base", "x_trial", "u_base", "u_last", "steady", "scratch")


def offsets(nb: int, ns: int) -> dict[str, int]:
    """Where each of ``BLOCKS`` starts in params, and ``end``."""
    sizes = (ns * ns, ns, nb * ns, nb, nb * 36, ns * 6, ns * 6, 6, 6, ns * ns, ns)
    out, start = {}, HEADER
    for name, size in zip(BLOCKS, sizes):
        out[name] = start
        start += size
    out["end"] = start
    return out


def active(inputs) -> bool:
    """Whether the band split replaces the plain AddBQuad in this model."""
    flow = inputs.platform.potential_flow
    return flow is not None and bool(flow.added_quadratic_damping_bands) and inputs.drag_model == "filtered"


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[on, n_bands, n_states, base step, last step, dt] and the blocks of ``offsets``; no table."""
    if not active(inputs):
        return np.zeros(HEADER), np.zeros((1, 1))
    bank = bank_state_space(inputs.platform.drag_bands)
    nb, ns, dt = bank.d.size, bank.n_states, inputs.dt_s
    left = np.eye(ns) - 0.5 * dt * bank.a
    p = np.linalg.solve(left, np.eye(ns) + 0.5 * dt * bank.a)
    q = np.linalg.solve(left, 0.5 * dt * bank.b)
    steady = 2.0 * np.linalg.inv(np.eye(ns) - p) if ns else np.zeros((0, 0))  # x = (I - P)^-1 2 Q u
    at = offsets(nb, ns)
    params = np.zeros(at["end"])
    params[ON], params[NB], params[NS], params[BASE], params[LAST], params[DT] = 1.0, nb, ns, -1.0, -1.0, dt
    blocks = {"p": p, "q": q, "c": bank.c, "d": bank.d, "steady": steady,
              "bquad": np.array(inputs.platform.potential_flow.added_quadratic_damping_bands, dtype=float)}
    for name, block in blocks.items():
        params[at[name]:at[name] + block.size] = np.ravel(block)
    return params, np.zeros((1, 1))


@step_loop
def _advance(params: np.ndarray, ns: int, at_p: int, at_q: int, at_x: int, at_scratch: int,
             at_u0: int, u1: np.ndarray, steps: int) -> None:
    """The states at ``at_x`` (ns x 6) ``steps`` Tustin steps on, the velocity going linearly from
    params[at_u0:at_u0 + 6] (the states' step) to ``u1`` (the last step's)."""
    for m in range(1, steps + 1):
        for c in range(6):
            start, end = params[at_u0 + c], u1[c]
            ua = start + (m - 1) / steps * (end - start)
            ub = start + m / steps * (end - start)
            for r in range(ns):
                acc = params[at_q + r] * (ua + ub)
                for j in range(ns):
                    acc += params[at_p + ns * r + j] * params[at_x + 6 * j + c]
                params[at_scratch + r] = acc
            for r in range(ns):
                params[at_x + 6 * r + c] = params[at_scratch + r]


@step_loop
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    """- sum_b AddBQuad_b |v_b| v_b, the band velocities from the filters at the step time."""
    if params[ON] == 0.0:
        return
    nb, ns = int(params[NB]), int(params[NS])
    # the block offsets (as ``offsets``)
    at_p = HEADER
    at_q = at_p + ns * ns
    at_c = at_q + ns
    at_d = at_c + nb * ns
    at_bquad = at_d + nb
    at_x_base = at_bquad + nb * 36
    at_x_trial = at_x_base + ns * 6
    at_u_base = at_x_trial + ns * 6
    at_u_last = at_u_base + 6
    at_steady = at_u_last + 6
    at_scratch = at_steady + ns * ns
    k = int(t / params[DT] + 0.5)
    base, last = int(params[BASE]), int(params[LAST])
    if base < 0 or k < last or k == base:  # a new run (or its first step again): filters in steady state
        for c in range(6):
            params[at_u_base + c] = y[6 + c]
            params[at_u_last + c] = y[6 + c]
            for r in range(ns):
                acc = 0.0
                for j in range(ns):
                    acc += params[at_steady + ns * r + j] * params[at_q + j] * y[6 + c]
                params[at_x_base + 6 * r + c] = acc
        params[BASE] = params[LAST] = k
        base = last = k
    if k > last:  # a new step time: the last one's velocity is final, its states become the base
        if last > base:
            _advance(params, ns, at_p, at_q, at_x_base, at_scratch, at_u_base, params[at_u_last:at_u_last + 6],
                     last - base)
            for c in range(6):
                params[at_u_base + c] = params[at_u_last + c]
            params[BASE] = last
            base = last
        params[LAST] = k
    for c in range(6):
        params[at_u_last + c] = y[6 + c]
        for r in range(ns):
            params[at_x_trial + 6 * r + c] = params[at_x_base + 6 * r + c]
    if k > base:
        _advance(params, ns, at_p, at_q, at_x_trial, at_scratch, at_u_base, y[6:12], k - base)
    for b in range(nb):
        for j in range(6):
            vb = params[at_d + b] * y[6 + j]
            for r in range(ns):
                vb += params[at_c + ns * b + r] * params[at_x_trial + 6 * r + j]
            q = abs(vb) * vb
            for i in range(6):
                out[i] -= params[at_bquad + 36 * b + 6 * i + j] * q
