"""Frequency-dependent drag (the seed paper, eqs. 2-5): a bank of analog Butterworth filters on
each strip's transverse relative velocity, one drag coefficient per band, band forces summed.

For strip i, band b and transverse direction k (member frame, d1 and d2):

    v_b = H_b(s) v_rel,       F_k = sum_b 0.5 rho Cd_{b,k} D_k |v_b| v_{b,k}

where |v_b| is the magnitude of the band's whole transverse velocity, so that one all-pass
band gives back the constant-Cd model exactly. A direction without band Cds (the vertical
drag of the pontoons) keeps 0.5 rho Cd D_k |v_rel| v_{rel,k}.

Each band is realised as a cascade of first- and second-order sections (from the analog
zeros, poles and gain, never the ``ba`` polynomial form) in a continuous state-space form
whose states are integrated with the body by the same ABM4 step. The filter then sees the
relative velocity at every stage of the step, as the drag does, and a run stepped one dt at
a time stays equal to a batch run.
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from fowt_hydro_sim.physics.config import DragBand
from fowt_hydro_sim.physics.jit import step_loop


class StateSpace(NamedTuple):
    """x' = A x + B u, y = C x + D u; one output row per band for a bank."""

    a: np.ndarray  # (n, n)
    b: np.ndarray  # (n,)
    c: np.ndarray  # (n_out, n)
    d: np.ndarray  # (n_out,)

    @property
    def n_states(self) -> int:
        return self.b.size


def band_zpk(band: DragBand) -> tuple[np.ndarray, np.ndarray, float]:
    """Analog zeros, poles and gain of a band's filter (s in rad/s)."""
    import scipy.signal  # here: a filter design needs it, a run with constant Cds does not (0.8 s start-up)

    if band.kind in ("lowpass", "highpass"):
        btype = "low" if band.kind == "lowpass" else "high"
        return scipy.signal.butter(band.order, 2 * np.pi * band.cutoff_hz, btype, analog=True, output="zpk")
    if band.kind == "bandpass":
        # the paper's (wc/Q) s / (s^2 + (wc/Q) s + wc^2) is the first-order Butterworth band-pass
        # with edges w1 w2 = wc^2, w2 - w1 = wc/Q
        wc, q = 2 * np.pi * band.centre_hz, band.q
        half = wc / (2 * q)
        edges = [math.sqrt(wc**2 + half**2) - half, math.sqrt(wc**2 + half**2) + half]
        return scipy.signal.butter(1, edges, "bandpass", analog=True, output="zpk")
    if band.kind == "allpass":
        return np.zeros(0), np.zeros(0), 1.0
    raise ValueError(f"drag band {band.name}: unknown filter kind {band.kind!r}")


def _section(row: np.ndarray) -> StateSpace:
    """One analog section (b0 s^2 + b1 s + b2) / (a0 s^2 + a1 s + a2) with states scaled to
    the size of its input (for a second-order section: x1' = w x2, x2' = -w x1 - a1 x2 + w u)."""
    b0, b1, b2, a0, a1, a2 = row
    if a0 != 0.0:
        b0, b1, b2, a1, a2 = b0 / a0, b1 / a0, b2 / a0, a1 / a0, a2 / a0
        w = math.sqrt(a2)
        return StateSpace(np.array([[0.0, w], [-w, -a1]]), np.array([0.0, w]),
                          np.array([[(b2 - b0 * a2) / a2, (b1 - b0 * a1) / w]]), np.array([b0]))
    if b0 != 0.0:
        raise ValueError("improper filter section")
    pole = a2 / a1  # first order: (b1 s + b2) / (s + pole), after dividing by a1
    gain_s, gain_0 = b1 / a1, b2 / a1
    return StateSpace(np.array([[-pole]]), np.array([pole]), np.array([[(gain_0 - gain_s * pole) / pole]]),
                      np.array([gain_s]))


def _cascade(first: StateSpace, second: StateSpace) -> StateSpace:
    """``second`` driven by the output of ``first``."""
    n1, n2 = first.n_states, second.n_states
    a = np.zeros((n1 + n2, n1 + n2))
    a[:n1, :n1] = first.a
    a[n1:, :n1] = np.outer(second.b, first.c[0])
    a[n1:, n1:] = second.a
    b = np.concatenate([first.b, second.b * first.d[0]])
    c = np.concatenate([second.d[0] * first.c[0], second.c[0]])[None, :]
    return StateSpace(a, b, c, second.d * first.d[0])


def band_state_space(band: DragBand) -> StateSpace:
    """The band's filter as a cascade of sections in one state-space model."""
    import scipy.signal  # (see band_zpk)

    z, p, k = band_zpk(band)
    out = StateSpace(np.zeros((0, 0)), np.zeros(0), np.zeros((1, 0)), np.array([1.0]))
    if p.size == 0:
        return out._replace(d=np.array([float(k)]))
    for row in scipy.signal.zpk2sos(z, p, k, analog=True):
        out = _cascade(out, _section(row))
    return out


def bank_state_space(bands: tuple[DragBand, ...]) -> StateSpace:
    """All bands in parallel on one input: block-diagonal A, one output row per band."""
    parts = [band_state_space(b) for b in bands]
    n = sum(p.n_states for p in parts)
    a, b, c = np.zeros((n, n)), np.zeros(n), np.zeros((len(parts), n))
    start = 0
    for row, part in enumerate(parts):
        block = slice(start, start + part.n_states)
        a[block, block], b[block], c[row, block] = part.a, part.b, part.c[0]
        start += part.n_states
    return StateSpace(a, b, c, np.array([p.d[0] for p in parts]))


def state_response(bank: StateSpace, omega_rad_s: np.ndarray) -> np.ndarray:
    """Complex steady-state amplitude of the states per unit input e^{i w t}: (n_freq, n)."""
    n = bank.n_states
    system = 1j * np.asarray(omega_rad_s, dtype=float)[:, None, None] * np.eye(n) - bank.a
    return np.linalg.solve(system, np.broadcast_to(bank.b, (len(system), n))[..., None])[..., 0]


def frequency_response(bank: StateSpace, frequency_hz: np.ndarray) -> np.ndarray:
    """H_b(i w) of every band, (n_freq, n_bands), from the state-space realisation."""
    states = state_response(bank, 2 * np.pi * np.asarray(frequency_hz, dtype=float))
    return states @ bank.c.T + bank.d


def effective_drag_coefficient(band_cd: np.ndarray, response: np.ndarray) -> np.ndarray:
    """The constant Cd that dissipates, in a one-directional oscillation at each frequency,
    the same energy per cycle as the bank: sum_b Cd_b |H_b|^2 cos(arg H_b).

    (Over a cycle of u = U cos wt, |v_b| v_b with v_b = |H_b| U cos(wt + phi_b) does work
    (8/3) |H_b|^2 U^3 cos phi_b against u; a constant Cd does (8/3) U^3.)"""
    return np.sum(np.asarray(band_cd) * np.abs(response) ** 2 * np.cos(np.angle(response)), axis=-1)


# --------------------------------------------------------------------------- compiled kernels
def nonzero_entries(matrix: np.ndarray) -> np.ndarray:
    """(row, column) of the non-zero entries, (nnz, 2): the kernels skip the structural zeros
    of the bank's block-diagonal, cascade-triangular matrices. C order whether empty or not,
    so that both drag models call the kernels with the same types (one compilation)."""
    return np.ascontiguousarray(np.argwhere(matrix != 0.0), dtype=np.int64)


@step_loop
def filter_inputs(filter_strip: np.ndarray, v_rel: np.ndarray, out: np.ndarray) -> None:
    """The filtered strips' relative velocities (``v_rel`` (n_strips, 2) at rows ``filter_strip``)
    into ``out`` (2 m,), ordered (strip, direction): the filters' input."""
    for c in range(filter_strip.size):
        out[2 * c] = v_rel[filter_strip[c], 0]
        out[2 * c + 1] = v_rel[filter_strip[c], 1]


@step_loop
def band_velocities(states: np.ndarray, v_rel: np.ndarray, c: np.ndarray, c_nonzero: np.ndarray,
                    d: np.ndarray, out: np.ndarray) -> None:
    """Band velocities C x + D v_rel, ``out`` (n_bands, m), from the filter states
    (n_states, m) and the relative velocities (m,), ordered (strip, direction): ``filter_inputs``."""
    for b in range(d.size):
        for i in range(v_rel.size):
            out[b, i] = d[b] * v_rel[i]
    for e in range(c_nonzero.shape[0]):
        b, j = c_nonzero[e, 0], c_nonzero[e, 1]
        for i in range(v_rel.size):
            out[b, i] += c[b, j] * states[j, i]


@step_loop
def filter_rates(states: np.ndarray, v_rel: np.ndarray, a: np.ndarray, a_nonzero: np.ndarray,
                 b: np.ndarray, out: np.ndarray) -> None:
    """d(states)/dt = A x + B v_rel, ``out`` (n_states, m) like ``states``."""
    for r in range(b.size):
        for i in range(v_rel.size):
            out[r, i] = b[r] * v_rel[i]
    for e in range(a_nonzero.shape[0]):
        r, j = a_nonzero[e, 0], a_nonzero[e, 1]
        for i in range(v_rel.size):
            out[r, i] += a[r, j] * states[j, i]
