"""A potential-flow hull's radiation load (HydroDyn's RdtnMod 1): the infinite-frequency added
mass A_inf on the left-hand side of the equations of motion (this row then holds its
reaction -A_inf a) and the memory effect, the convolution

    F(t) = -int_0^T K(s) v(t - s) ds,   K(t) = (2/pi) int_0^inf B(w) cos(w t) dw

(``physics.hydro.radiation``; T = ``radiation_tmax_s``), by the trapezoidal rule on the
model's step over the reference point's velocities at the step times. The velocities are
kept in a ring (the last evaluation at each step time wins: the corrected state, as HydroDyn
keeps the velocity history at its own steps; step times no evaluation reached, as with a
prescribed motion sampled coarser than the step, are filled linearly between the evaluations
around them; a run starts with no history); the sum over the past steps is computed once
per step time, the current velocity's term at every evaluation. Only the couplings (i, j)
whose damping is not negligible are summed (``potential_flow.kernel_pairs``). Zero for a
platform without potential flow or with ``radiation: none`` (then A_inf alone)."""
from __future__ import annotations

import numpy as np
from numba import njit

from fowt_hydro_sim.physics.hydro.potential_flow import convolution_weights, wamit_data
from fowt_hydro_sim.physics.jit import step_loop

ON, DT, N, N_PAIRS, CACHED, LAST, PAST, A_INF, PAIRS = 0, 1, 2, 3, 4, 5, 6, 12, 48


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[on, dt, n, n_pairs, cached step, last step, past force (6), A_inf (36), pairs' i, pairs' j]
    and the table (n_pairs + 6, n): the weighted kernel of each pair, then the velocity ring of
    each DOF (one row each: the sums run along contiguous rows)."""
    flow = inputs.platform.potential_flow
    params = np.zeros(PAIRS)
    if flow is None:
        return params, np.zeros((1, 1))
    data = wamit_data(flow, inputs.platform.environment)
    params[ON] = 1.0
    params[CACHED] = params[LAST] = -1.0
    params[A_INF:A_INF + 36] = data.radiation.added_mass_inf_si.ravel()
    if flow.radiation == "none":
        return params, np.zeros((6, 1))
    weights, pairs = convolution_weights(flow, data, inputs.dt_s)
    params[DT], params[N], params[N_PAIRS] = inputs.dt_s, weights.shape[0], len(pairs)
    index = np.array([i for i, _ in pairs] + [j for _, j in pairs], float)
    return np.concatenate([params, index]), np.concatenate([weights.T, np.zeros((6, weights.shape[0]))])


@step_loop
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    """A_inf into ``mass``; the memory force into ``out``."""
    if params[ON] == 0.0:
        return
    for i in range(6):
        for j in range(6):
            mass[i, j] += params[A_INF + 6 * i + j]
    n, n_pairs = int(params[N]), int(params[N_PAIRS])
    if n == 0:
        return
    k = int(t / params[DT] + 0.5)
    last = int(params[LAST])
    if k < last:  # time went back: a new run, with no history before its first evaluation
        params[CACHED] = -1.0
        for c in range(6):
            for m in range(n):
                table[n_pairs + c, m] = 0.0
        last = -1
    slot = (n - k % n) % n  # the ring runs backwards in time: step k - m is at slot + m (mod n)
    if last >= 0 and k > last + 1:  # step times skipped (a prescribed motion sampled coarser than dt):
        before = (n - last % n) % n  # their velocities linear between the last evaluation's and this one
        for m in range(max(last + 1, k - n + 1), k):
            fraction = (m - last) / (k - last)
            at = (n - m % n) % n
            for c in range(6):
                v0 = table[n_pairs + c, before]
                table[n_pairs + c, at] = v0 + fraction * (y[6 + c] - v0)
    params[LAST] = k
    for c in range(6):
        table[n_pairs + c, slot] = y[6 + c]
    if params[CACHED] != k:  # the past steps' part, once per step time
        for c in range(6):
            params[PAST + c] = 0.0
        depth = min(n - 1, k)
        unwrapped = min(depth, n - 1 - slot)  # m = 1..unwrapped at slot + m, the rest at slot + m - n
        for p in range(n_pairs):
            i, j = int(params[PAIRS + p]), int(params[PAIRS + n_pairs + p])
            kernel, ring = table[p], table[n_pairs + j]
            acc = _dot(kernel, 1, ring, slot + 1, unwrapped)
            acc += _dot(kernel, unwrapped + 1, ring, slot + unwrapped + 1 - n, depth - unwrapped)
            params[PAST + i] -= acc
        params[CACHED] = k
    for c in range(6):
        out[c] += params[PAST + c]
    for p in range(n_pairs):
        i, j = int(params[PAIRS + p]), int(params[PAIRS + n_pairs + p])
        out[i] -= table[p, 0] * y[6 + j]


@njit(cache=True, inline="always")
def _dot(a: np.ndarray, a0: int, b: np.ndarray, b0: int, count: int) -> float:
    """sum_{m < count} a[a0 + m] b[b0 + m], in four interleaved sums (the loop vectorises)."""
    s0 = s1 = s2 = s3 = 0.0
    quads = count // 4
    for q in range(quads):
        m = 4 * q
        s0 += a[a0 + m] * b[b0 + m]
        s1 += a[a0 + m + 1] * b[b0 + m + 1]
        s2 += a[a0 + m + 2] * b[b0 + m + 2]
        s3 += a[a0 + m + 3] * b[b0 + m + 3]
    for m in range(4 * quads, count):
        s0 += a[a0 + m] * b[b0 + m]
    return (s0 + s1) + (s2 + s3)
