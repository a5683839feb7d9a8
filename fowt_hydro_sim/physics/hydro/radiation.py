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

Arrays carry the frequency or time axis first and any trailing shape (a 6x6 matrix, say).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

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
