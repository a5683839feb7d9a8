"""A potential-flow hull's data as the load components take it (HydroDyn's PotMod 1).

Conventions (HydroDyn's and WAMIT's): one body, its WAMIT origin at the platform's reference
point (the still-water line on the centre line for the packaged hulls), x along wave heading
0 deg, z up; the loads are in world axes about the reference point, linear in the body's
small displacement q = [x, y, z, roll, pitch, yaw] and velocity v:

- hydrostatics: rho g PtfmVol0 upward with its moment about the centre of buoyancy
  (PtfmCOBxt, PtfmCOByt), minus C q with C from the ``.hst`` file (which holds no gravity
  terms: the weight acts separately at the centre of gravity, the ``gravity`` component);
- radiation: A_inf on the left-hand side of the equations of motion (its reaction -A_inf a
  in the ``radiation`` row) and the memory -int_0^T K(s) v(t - s) ds, K from B(w) by the
  cosine transform (``physics.hydro.radiation``), the kernel's step the model's step;
- excitation: Re(sum_j a_j X(w_j, beta_j) e^{i (w_j t + phase_j)}) with the waves' own
  components (elevation at the origin a_j cos(w_j t + phase_j)), X interpolated linearly in
  frequency and heading, zero outside the file's frequencies;
- HydroDyn's additional matrices: AddF0 - AddCLin q - AddBLin v - AddBQuad (|v| v).
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from fowt_hydro_sim.physics.config import ConfigError, Environment, PotentialFlow
from fowt_hydro_sim.physics.hydro import wamit
from fowt_hydro_sim.physics.hydro.radiation import retardation_kernel

EXCITATION_STEP_S = 0.1  # force samples: cubic interpolation of 0.5 Hz content to ~1e-3


@lru_cache(maxsize=4)
def _read(root: str, rho: float, g: float, length_m: float) -> wamit.PotentialFlowData:
    try:
        data = wamit.read_potential_flow(root, rho, g, length_m)
    except wamit.WamitFormatError as exc:  # one line naming the file and the line
        raise ConfigError(str(exc)) from None
    if data.radiation.added_mass_inf_si.shape != (6, 6):
        raise ConfigError(f"{root}: {data.radiation.added_mass_inf_si.shape[0] // 6} WAMIT bodies: one body "
                          "(6 DOF) only")
    return data


def wamit_data(flow: PotentialFlow, environment: Environment) -> wamit.PotentialFlowData:
    """The hull's WAMIT files, redimensionalised with the platform's water density and gravity
    (read once per set of arguments)."""
    return _read(flow.wamit_root, environment.water_density_kg_m3, environment.gravity_m_s2, flow.wamit_length_m)


def excitation_coefficients(data: wamit.PotentialFlowData, omega_rad_s: np.ndarray,
                            heading_rad: np.ndarray) -> np.ndarray:
    """X (n, 6) at each (w, beta): linear in frequency (zero outside the table) and in heading
    (periodic over 360 deg)."""
    x = data.excitation
    headings = x.heading_deg
    table = x.force_per_amplitude_si
    if headings[-1] - headings[0] >= 360.0 - 1e-9:  # -180 and 180 both: drop the repeat
        headings, table = headings[:-1], table[:, :-1]
    extended = np.concatenate([headings, headings[:1] + 360.0])
    table = np.concatenate([table, table[:, :1]], axis=1)
    beta = (np.degrees(heading_rad) - headings[0]) % 360.0 + headings[0]
    k = np.clip(np.searchsorted(extended, beta, side="right") - 1, 0, len(extended) - 2)
    f = (beta - extended[k]) / (extended[k + 1] - extended[k])
    out = np.zeros((len(omega_rad_s), 6), complex)
    for n, (w, kk, ff) in enumerate(zip(omega_rad_s, k, f)):
        by_heading = (1 - ff) * table[:, kk] + ff * table[:, kk + 1]  # (n_freq, 6)
        if x.omega_rad_s[0] <= w <= x.omega_rad_s[-1]:
            out[n] = [np.interp(w, x.omega_rad_s, by_heading[:, i].real)
                      + 1j * np.interp(w, x.omega_rad_s, by_heading[:, i].imag) for i in range(6)]
    return out


def excitation_series(data: wamit.PotentialFlowData, waves) -> tuple[np.ndarray, float]:
    """(samples (n, 6) of the first-order excitation over the waves' repeat period, their step)."""
    omega = 2 * np.pi * waves.frequency_hz
    x = excitation_coefficients(data, omega, waves.direction_rad)
    n = max(int(math.ceil(waves.period_s / EXCITATION_STEP_S)), 2 * int(waves.harmonic.max()) + 2, 4)
    spectrum = np.zeros((n // 2 + 1, 6), complex)
    np.add.at(spectrum, waves.harmonic, (waves.amplitude_m * np.exp(1j * waves.phase_rad) * n / 2.0)[:, None] * x)
    return np.fft.irfft(spectrum, n, axis=0), waves.period_s / n


def kernel_pairs(damping_si: np.ndarray, tolerance: float = 1e-3) -> list[tuple[int, int]]:
    """The (i, j) couplings whose damping is not negligible anywhere: |B_ij| above
    ``tolerance`` sqrt(max|B_ii| max|B_jj|)."""
    peak = np.abs(damping_si).max(axis=0)
    scale = np.sqrt(np.outer(peak.diagonal(), peak.diagonal()))
    return [(i, j) for i in range(6) for j in range(6) if peak[i, j] > tolerance * scale[i, j]]


def convolution_weights(flow: PotentialFlow, data: wamit.PotentialFlowData, dt_s: float) -> tuple[
        np.ndarray, list[tuple[int, int]]]:
    """The radiation memory's weights (n, n_pairs): w_m K_ij(m dt) with the trapezoidal weights
    w_0 = w_{n-1} = dt/2, dt between, for the kernel of ``radiation_tmax_s`` at the model's
    step, and the pairs (i, j) they are for."""
    r = data.radiation
    omega_max = r.omega_rad_s[-1]
    if omega_max > np.pi / dt_s:
        raise ConfigError(f"potential flow: the damping table reaches {omega_max:g} rad/s, above pi/dt = "
                         f"{np.pi / dt_s:g} rad/s: take dt below {np.pi / omega_max:g} s")
    kernel = retardation_kernel(r.omega_rad_s, r.damping_si, flow.radiation_tmax_s, dt_s)
    pairs = kernel_pairs(r.damping_si)
    weights = np.full(len(kernel.time_s), dt_s)
    weights[[0, -1]] = dt_s / 2
    return np.stack([weights * kernel.kernel_si[:, i, j] for i, j in pairs], axis=1), pairs
