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
platform without potential flow or with ``radiation: none`` (then A_inf alone).

With ``radiation: state_space`` (HydroDyn's RdtnMod 2) the memory is ``F = C x``,
``dx/dt = A x + B v``, with A, B, C from the WAMIT ``.ss`` file next to the other WAMIT files
(``physics.hydro.wamit.read_ss``), x = 0 at a run's first step (HydroDyn starts so). The
states advance on the model's step by the exact solution for a velocity linear between step
times (``physics.hydro.radiation.first_order_hold``: x_{k+1} = Phi x_k + G0 v_k + G1 v_{k+1},
Phi block-diagonal as A): the part from the last step time's final state and velocity,
Phi x_k + G0 v_k, once per step time, G1 v and C x at every evaluation, with the velocity of
that evaluation (the last evaluation at each step time wins, as for the convolution; step
times no evaluation reached take velocities linear between the evaluations around them)."""
from __future__ import annotations

from functools import lru_cache

import numpy as np
from numba import njit

from fowt_hydro_sim.physics.config import ConfigError, PotentialFlow
from fowt_hydro_sim.physics.hydro import wamit
from fowt_hydro_sim.physics.hydro.potential_flow import convolution_weights, wamit_data
from fowt_hydro_sim.physics.hydro.radiation import diagonal_blocks, first_order_hold
from fowt_hydro_sim.physics.jit import step_loop

ON, DT, N, N_PAIRS, CACHED, LAST, PAST, A_INF, STATES, BASE, PRE_STEP, DATA = 0, 1, 2, 3, 4, 5, 6, 12, 48, 49, 50, 51
# the state-space form's blocks after the header, in this order: Phi (ns x ns), each row's first and
# end column of Phi's block (ns each), G0 and G1 (ns x 6 each), the first and end velocity each
# state's row of G0 and G1 reads (ns each), C (6 x ns), the first and end load row each state's
# column of C feeds (ns each), the states at the base step and the trial states (ns each),
# Phi x + G0 v of the base step (ns), the velocities at the base step and at the last evaluation
# (6 each), a scratch column (ns). (SS_Fitting's states each read one velocity and feed one load:
# the ranges keep the products to the nonzero terms.)
SS_BLOCKS = ("phi", "lo", "hi", "g0", "g1", "in_lo", "in_hi", "c", "out_lo", "out_hi", "x_base", "x_trial", "pre",
             "u_base", "u_last", "scratch")


def _nonzero_range(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For each row of ``rows``, the first and end index of its nonzero entries (0, 0 if none)."""
    lo, hi = np.zeros(len(rows)), np.zeros(len(rows))
    for r, row in enumerate(rows):
        nonzero = np.flatnonzero(row)
        if nonzero.size:
            lo[r], hi[r] = nonzero[0], nonzero[-1] + 1
    return lo, hi


def state_space_offsets(ns: int) -> dict[str, int]:
    """Where each of ``SS_BLOCKS`` starts in params for ``ns`` states, and ``end``."""
    sizes = (ns * ns, ns, ns, ns * 6, ns * 6, ns, ns, 6 * ns, ns, ns, ns, ns, ns, 6, 6, ns)
    out, start = {}, DATA
    for name, size in zip(SS_BLOCKS, sizes):
        out[name] = start
        start += size
    out["end"] = start
    return out


@lru_cache(maxsize=4)
def _read_ss(path: str) -> wamit.StateSpaceRadiation:
    try:
        ss = wamit.read_ss(path)
    except wamit.WamitFormatError as exc:  # one line naming the file and the line
        raise ConfigError(str(exc)) from None
    growth = float(np.linalg.eigvals(ss.a).real.max())
    if growth >= 0.0:
        raise ConfigError(f"{path}: its A matrix has an eigenvalue with real part {growth:g} >= 0: the radiation "
                          "memory would not decay")
    return ss


def state_space_data(flow: PotentialFlow) -> wamit.StateSpaceRadiation:
    """The hull's ``.ss`` matrices (the WAMIT root + ``.ss``), read once per file."""
    return _read_ss(flow.wamit_root + ".ss")


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[on, dt, n, n_pairs, cached step, last step, past force (6), A_inf (36), n_states, base step,
    step of the cached Phi x + G0 v], then for the convolution the pairs' i and j and the table
    (n_pairs + 6, n): the weighted kernel of each pair, then the velocity ring of each DOF (one
    row each: the sums run along contiguous rows); for the state-space form the blocks of
    ``state_space_offsets`` and no table."""
    flow = inputs.platform.potential_flow
    params = np.zeros(DATA)
    if flow is None:
        return params, np.zeros((1, 1))
    data = wamit_data(flow, inputs.platform.environment)
    params[ON] = 1.0
    params[CACHED] = params[LAST] = params[BASE] = params[PRE_STEP] = -1.0
    params[A_INF:A_INF + 36] = data.radiation.added_mass_inf_si.ravel()
    if flow.radiation == "none":
        return params, np.zeros((6, 1))
    if flow.radiation == "state_space":
        ss = state_space_data(flow)
        ns = ss.a.shape[0]
        phi, g0, g1 = first_order_hold(ss.a, ss.b, inputs.dt_s)
        lo, hi = np.zeros(ns), np.zeros(ns)
        inputs_read = np.zeros((ns, 6), bool)
        for start, end in diagonal_blocks(ss.a):  # a block's states read the velocities its B rows read
            lo[start:end], hi[start:end] = start, end
            inputs_read[start:end] = (ss.b[start:end] != 0.0).any(axis=0)
        g0[~inputs_read], g1[~inputs_read] = 0.0, 0.0  # zero in exact arithmetic
        in_lo, in_hi = _nonzero_range(inputs_read)
        out_lo, out_hi = _nonzero_range(ss.c.T)
        at = state_space_offsets(ns)
        params = np.concatenate([params, np.zeros(at["end"] - DATA)])
        params[DT], params[STATES] = inputs.dt_s, ns
        for name, block in (("phi", phi), ("lo", lo), ("hi", hi), ("g0", g0), ("g1", g1), ("in_lo", in_lo),
                            ("in_hi", in_hi), ("c", ss.c), ("out_lo", out_lo), ("out_hi", out_hi)):
            params[at[name]:at[name] + block.size] = np.ravel(block)
        return params, np.zeros((1, 1))
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
    if params[STATES] > 0.0:
        _state_space(t, y, params, out)
        return
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
            i, j = int(params[DATA + p]), int(params[DATA + n_pairs + p])
            kernel, ring = table[p], table[n_pairs + j]
            acc = _dot(kernel, 1, ring, slot + 1, unwrapped)
            acc += _dot(kernel, unwrapped + 1, ring, slot + unwrapped + 1 - n, depth - unwrapped)
            params[PAST + i] -= acc
        params[CACHED] = k
    for c in range(6):
        out[c] += params[PAST + c]
    for p in range(n_pairs):
        i, j = int(params[DATA + p]), int(params[DATA + n_pairs + p])
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


@step_loop
def _state_space(t: float, y: np.ndarray, params: np.ndarray, out: np.ndarray) -> None:
    """The state-space memory C x into ``out``, the states advanced to this evaluation's step."""
    ns = int(params[STATES])
    # the block offsets (as ``state_space_offsets``)
    at_phi = DATA
    at_lo = at_phi + ns * ns
    at_hi = at_lo + ns
    at_g0 = at_hi + ns
    at_g1 = at_g0 + ns * 6
    at_in_lo = at_g1 + ns * 6
    at_in_hi = at_in_lo + ns
    at_c = at_in_hi + ns
    at_out_lo = at_c + 6 * ns
    at_out_hi = at_out_lo + ns
    at_x_base = at_out_hi + ns
    at_x_trial = at_x_base + ns
    at_pre = at_x_trial + ns
    at_u_base = at_pre + ns
    at_u_last = at_u_base + 6
    at_scratch = at_u_last + 6
    k = int(t / params[DT] + 0.5)
    base, last = int(params[BASE]), int(params[LAST])
    if base < 0 or k < last or k == base:  # a new run (or its first step again): no memory yet
        for r in range(ns):
            params[at_x_base + r] = 0.0
        for c in range(6):
            params[at_u_base + c] = y[6 + c]
        params[BASE] = params[LAST] = k
        params[PRE_STEP] = -1.0
        base = last = k
    if k > last:  # a new step time: the last one's velocity is final, its trial states become the base
        if last > base:
            for r in range(ns):
                params[at_x_base + r] = params[at_x_trial + r]
            for c in range(6):
                params[at_u_base + c] = params[at_u_last + c]
            params[BASE] = last
            base = last
        params[LAST] = k
    for c in range(6):
        params[at_u_last + c] = y[6 + c]
    if k == base:
        for r in range(ns):
            params[at_x_trial + r] = params[at_x_base + r]
    elif k == base + 1:
        if params[PRE_STEP] != base:  # Phi x + G0 v of the base step, once per step time
            for r in range(ns):
                acc = 0.0
                for j in range(int(params[at_lo + r]), int(params[at_hi + r])):
                    acc += params[at_phi + ns * r + j] * params[at_x_base + j]
                for c in range(int(params[at_in_lo + r]), int(params[at_in_hi + r])):
                    acc += params[at_g0 + 6 * r + c] * params[at_u_base + c]
                params[at_pre + r] = acc
            params[PRE_STEP] = base
        for r in range(ns):
            acc = params[at_pre + r]
            for c in range(int(params[at_in_lo + r]), int(params[at_in_hi + r])):
                acc += params[at_g1 + 6 * r + c] * y[6 + c]
            params[at_x_trial + r] = acc
    else:  # step times skipped (a prescribed motion sampled coarser than dt): velocities linear between
        for r in range(ns):
            params[at_x_trial + r] = params[at_x_base + r]
        steps = k - base
        for m in range(1, steps + 1):
            for r in range(ns):
                acc = 0.0
                for j in range(int(params[at_lo + r]), int(params[at_hi + r])):
                    acc += params[at_phi + ns * r + j] * params[at_x_trial + j]
                for c in range(6):
                    start = params[at_u_base + c]
                    ua = start + (m - 1) / steps * (y[6 + c] - start)
                    ub = start + m / steps * (y[6 + c] - start)
                    acc += params[at_g0 + 6 * r + c] * ua + params[at_g1 + 6 * r + c] * ub
                params[at_scratch + r] = acc
            for r in range(ns):
                params[at_x_trial + r] = params[at_scratch + r]
    for r in range(ns):
        state = params[at_x_trial + r]
        for i in range(int(params[at_out_lo + r]), int(params[at_out_hi + r])):
            out[i] += params[at_c + ns * i + r] * state
