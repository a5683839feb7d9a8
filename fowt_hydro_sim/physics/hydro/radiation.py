"""The radiation retardation kernel and its transforms (Cummins' equation).

The radiation load on a body moving with velocity ``v(t)`` is, in the time domain,

    F_rad(t) = -A_inf dv/dt - int_0^t K(t - s) v(s) ds,

with the retardation (impulse-response) kernel ``K`` and the frequency-domain damping ``B`` and
added mass ``A`` related by (Ogilvie 1964)

    K(t) = (2/pi) int_0^inf B(w) cos(w t) dw,
    B(w) = int_0^inf K(t) cos(w t) dt,
    A(w) = A_inf - (1/w) int_0^inf K(t) sin(w t) dt.

Sign convention: ``K`` enters the load with a minus sign (as in HydroDyn's ``Conv_Radiation``:
``F_Rdtn = -sum K(t - s) v(s) ds``), so a positive ``B`` gives ``K(0) > 0``.

:func:`retardation_kernel` follows HydroDyn's ``Conv_Rdtn_Init`` (RdtnMod 1, kernel from the
damping): time step ``RdtnDT``, ``NStepRdtn = ceil(RdtnTMax / RdtnDT)`` rounded up to an odd
number ``2 m + 1`` with ``m`` a product of the primes up to 23, frequency step
``pi / ((NStepRdtn - 1) RdtnDT)``; ``B`` at those frequencies is interpolated linearly in the
table, taken as zero at w = 0 and above the highest tabulated frequency (HydroDyn puts the
zero-damping infinite-frequency row just above it and holds end values); the cosine transform is
the trapezoidal rule (a type-I discrete cosine transform, FFTPACK's COST, normalised by
``1/(NStepRdtn - 1)``). HydroDyn refuses a table whose highest frequency exceeds ``pi / RdtnDT``;
so does this function.

The state-space form (HydroDyn's RdtnMod 2, the ``.ss`` file) has its impulse response and
frequency response here, and its exact step for a velocity linear between step times (the
kernel integrates it so: :func:`first_order_hold`).

Arrays carry the frequency or time axis first and any trailing shape (a 6x6 matrix, say).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm

# the first nine primes: HydroDyn's PSF(N, 9)
_SMALL_PRIMES = (2, 3, 5, 7, 11, 13, 17, 19, 23)


@dataclass(frozen=True)
class RetardationKernel:
    """A retardation kernel on a uniform time grid.

    ``time_s``: (N,) from 0 in steps ``dt_s``; ``kernel_si``: (N, ...) in N/m, N/rad, N m/m,
    N m/rad (load per unit velocity, per second of the convolution); ``omega_rad_s`` and
    ``damping_si``: the frequency grid the transform used and the damping interpolated onto it."""

    time_s: np.ndarray
    kernel_si: np.ndarray
    omega_rad_s: np.ndarray
    damping_si: np.ndarray

    @property
    def dt_s(self) -> float:
        """The kernel's time step (s)."""
        return float(self.time_s[1] - self.time_s[0])


def product_of_small_primes(n: int, n_primes: int = 9) -> int:
    """The smallest integer >= ``n`` whose prime factors are all among the first ``n_primes``
    primes (HydroDyn's ``PSF``)."""
    if n < 1:
        raise ValueError(f"n must be >= 1, not {n}")
    primes = _SMALL_PRIMES[:n_primes]
    m = n
    while True:
        rest = m
        for p in primes:
            while rest % p == 0:
                rest //= p
        if rest == 1:
            return m
        m += 1


def kernel_steps(rdtn_tmax_s: float, rdtn_dt_s: float) -> int:
    """HydroDyn's number of kernel samples ``NStepRdtn`` for ``RdtnTMax`` and ``RdtnDT``: odd,
    at least ``RdtnTMax / RdtnDT``, with ``NStepRdtn - 1`` twice a product of small primes."""
    if not rdtn_dt_s > 0 or not rdtn_tmax_s > 0:
        raise ValueError(f"RdtnTMax and RdtnDT must be positive, not {rdtn_tmax_s!r} and {rdtn_dt_s!r}")
    n = int(np.ceil(rdtn_tmax_s / rdtn_dt_s))
    if n % 2 == 0:
        n += 1
    half = max((n - 1) // 2, 1)
    return 2 * product_of_small_primes(half) + 1


def _dct1(values: np.ndarray) -> np.ndarray:
    """Type-I discrete cosine transform along axis 0, unnormalised:
    ``y_k = x_0 + (-1)^k x_{N-1} + 2 sum_{n=1}^{N-2} x_n cos(pi k n / (N - 1))``."""
    extended = np.concatenate([values, values[-2:0:-1]], axis=0)
    return np.fft.rfft(extended, axis=0).real


def interpolate_damping(omega_rad_s: np.ndarray, damping_si: np.ndarray, omega_out: np.ndarray) -> np.ndarray:
    """``B`` at ``omega_out`` as HydroDyn extends and interpolates the table: linear between the
    tabulated frequencies, from zero at w = 0 to the first one, zero above the last one."""
    omega = np.asarray(omega_rad_s, float)
    damping = np.asarray(damping_si, float)
    if omega.ndim != 1 or omega.size < 1 or damping.shape[0] != omega.size:
        raise ValueError("omega_rad_s must be 1-D with one entry per row of damping_si")
    if omega[0] <= 0 or np.any(np.diff(omega) <= 0):
        raise ValueError("omega_rad_s must be positive and strictly ascending")
    grid = np.concatenate([[0.0], omega, [omega[-1] * (1 + np.finfo(float).eps)]])
    table = np.concatenate([np.zeros((1, *damping.shape[1:])), damping, np.zeros((1, *damping.shape[1:]))])
    flat = table.reshape(len(grid), -1)
    out = np.stack([np.interp(omega_out, grid, flat[:, k]) for k in range(flat.shape[1])], axis=-1)
    return out.reshape(len(omega_out), *damping.shape[1:])


def retardation_kernel(omega_rad_s: np.ndarray, damping_si: np.ndarray, rdtn_tmax_s: float = 60.0,
                       rdtn_dt_s: float = 0.025) -> RetardationKernel:
    """The retardation kernel ``K(t) = (2/pi) int_0^inf B(w) cos(w t) dw`` from a damping table
    (finite frequencies, ascending; ``damping_si`` (n, ...)), as HydroDyn computes it for
    ``RdtnTMax`` and ``RdtnDT`` (see the module docstring)."""
    omega = np.asarray(omega_rad_s, float)
    if omega.size and omega[-1] > np.pi / rdtn_dt_s:
        raise ValueError(f"the table reaches {omega[-1]:g} rad/s, above pi/RdtnDT = {np.pi / rdtn_dt_s:g} rad/s: "
                         f"RdtnDT must be below {np.pi / omega[-1]:g} s")
    n = kernel_steps(rdtn_tmax_s, rdtn_dt_s)
    d_omega = np.pi / ((n - 1) * rdtn_dt_s)
    grid = np.arange(n) * d_omega
    damping = interpolate_damping(omega, damping_si, grid)
    kernel = _dct1(damping) / (rdtn_dt_s * (n - 1))
    return RetardationKernel(time_s=np.arange(n) * rdtn_dt_s, kernel_si=kernel, omega_rad_s=grid,
                             damping_si=damping)


def _trapezoid_weights(time_s: np.ndarray) -> np.ndarray:
    dt = np.diff(time_s)
    weights = np.zeros_like(time_s)
    weights[:-1] += dt / 2
    weights[1:] += dt / 2
    return weights


def damping_from_kernel(time_s: np.ndarray, kernel_si: np.ndarray, omega_rad_s: np.ndarray) -> np.ndarray:
    """``B(w) = int_0^T K(t) cos(w t) dt`` (trapezoidal rule on the kernel's grid) at each of
    ``omega_rad_s``; returns (len(omega), ...)."""
    t = np.asarray(time_s, float)
    weighted = _trapezoid_weights(t).reshape(-1, *([1] * (np.ndim(kernel_si) - 1))) * kernel_si
    return np.tensordot(np.cos(np.outer(omega_rad_s, t)), weighted, axes=(1, 0))


def added_mass_from_kernel(time_s: np.ndarray, kernel_si: np.ndarray, added_mass_inf_si: np.ndarray,
                           omega_rad_s: np.ndarray) -> np.ndarray:
    """Ogilvie's relation ``A(w) = A_inf - (1/w) int_0^T K(t) sin(w t) dt`` (trapezoidal rule) at
    each of ``omega_rad_s``; at w = 0 its limit ``A_inf - int_0^T t K(t) dt``. Returns
    (len(omega), ...)."""
    t = np.asarray(time_s, float)
    omega = np.asarray(omega_rad_s, float)
    weighted = _trapezoid_weights(t).reshape(-1, *([1] * (np.ndim(kernel_si) - 1))) * kernel_si
    with np.errstate(invalid="ignore", divide="ignore"):
        sinc_t = np.where(omega[:, None] == 0, t[None, :], np.sin(np.outer(omega, t)) / omega[:, None])
    return np.asarray(added_mass_inf_si) - np.tensordot(sinc_t, weighted, axes=(1, 0))


# --------------------------------------------------------------------------- state-space form
# HydroDyn's RdtnMod 2: the memory load F = C x with dx/dt = A x + B v (the .ss file of WAMIT's
# SS_Fitting; ``physics.hydro.wamit.read_ss``). C exp(A t) B stands for -K(t).

def state_space_impulse_response(a: np.ndarray, b: np.ndarray, c: np.ndarray, time_s: np.ndarray) -> np.ndarray:
    """``-C exp(A t) B`` at each of ``time_s`` (uniformly spaced from its first value): the
    retardation kernel the state-space form stands for, (len(time_s), 6, 6), in the sign of
    :func:`retardation_kernel`."""
    t = np.asarray(time_s, float)
    out = np.zeros((t.size, c.shape[0], b.shape[1]))
    if t.size == 0:
        return out
    state = expm(a * t[0]) @ b
    step = expm(a * (t[1] - t[0])) if t.size > 1 else np.eye(a.shape[0])
    for k in range(t.size):
        out[k] = -c @ state
        state = step @ state
    return out


def state_space_coefficients(a: np.ndarray, b: np.ndarray, c: np.ndarray,
                             omega_rad_s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The damping B(w) and the added mass less its infinite-frequency limit, A(w) - A_inf,
    that the state-space form gives at each of ``omega_rad_s`` (> 0): with
    ``H(w) = C (i w I - A)^-1 B`` the memory load of v e^{i w t} is H v e^{i w t}
    = -(B(w) + i w (A(w) - A_inf)) v e^{i w t}. Returns ((n, 6, 6), (n, 6, 6))."""
    omega = np.asarray(omega_rad_s, float)
    identity = np.eye(a.shape[0])
    response = np.array([c @ np.linalg.solve(1j * w * identity - a, b) for w in omega])
    return -response.real, -response.imag / omega[:, None, None]


def diagonal_blocks(a: np.ndarray) -> list[tuple[int, int]]:
    """The smallest contiguous diagonal blocks [start, end) of ``a`` outside which it is zero
    (SS_Fitting's A is block-diagonal, one block per DOF; a full matrix is one block)."""
    n = a.shape[0]
    nonzero = a != 0.0
    blocks, start = [], 0
    while start < n:
        end = start + 1
        while end < n and (nonzero[start:end, end:].any() or nonzero[end:, start:end].any()):
            end += 1
        blocks.append((start, end))
        start = end
    return blocks


def first_order_hold(a: np.ndarray, b: np.ndarray, dt_s: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The exact step of ``dx/dt = A x + B u`` over ``dt_s`` for an input linear between the
    step times (a first-order hold): ``x_{k+1} = Phi x_k + G0 u_k + G1 u_{k+1}``. Computed
    block by block (:func:`diagonal_blocks`; the blocks do not couple), each from one matrix
    exponential of ``[[A dt, B dt, 0], [0, 0, I], [0, 0, 0]]``, whose first block row is
    ``[Phi, P1, P2]`` with ``P1 = int_0^dt e^{A (dt - s)} B ds``, ``P2 = int_0^dt e^{A (dt - s)} B s/dt ds``;
    ``G0 = P1 - P2``, ``G1 = P2``. Returns (Phi (n, n), G0 (n, m), G1 (n, m))."""
    if not dt_s > 0:
        raise ValueError(f"the step must be positive, not {dt_s!r}")
    n, m = b.shape
    phi, g0, g1 = np.zeros((n, n)), np.zeros((n, m)), np.zeros((n, m))
    for start, end in diagonal_blocks(a):
        size = end - start
        augmented = np.zeros((size + 2 * m, size + 2 * m))
        augmented[:size, :size] = a[start:end, start:end] * dt_s
        augmented[:size, size:size + m] = b[start:end] * dt_s
        augmented[size:size + m, size + m:] = np.eye(m)
        e = expm(augmented)
        phi[start:end, start:end] = e[:size, :size]
        p1, p2 = e[:size, size:size + m], e[:size, size + m:]
        g0[start:end], g1[start:end] = p1 - p2, p2
    return phi, g0, g1
