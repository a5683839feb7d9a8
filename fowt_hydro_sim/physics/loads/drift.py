"""Second-order slow drift: the difference-frequency wave force by Newman's approximation from
the platform's mean-drift coefficient table D(w) (``Platform.drift_coefficients_n_m2``,
N per m^2 of wave amplitude, e.g. a BEM's far-field mean drift of the floating hull):

    F(t) = |sum_j a_j sqrt(D(w_j)) e^{i (w_j t + phase_j)}|^2

along the sea's mean heading (weighted by a^2 D), at the reference point. Its mean is the
mean drift sum a_j^2 D(w_j) = 2 int S D dw; a regular wave gives a constant a^2 D(w).

This is the second-order force that strip theory with HydroDyn's kinematic choices
(undisplaced wetted length, fixed directions) does not have: the consistent combination is
that set plus this component (``HydroOptions.slow_drift``). The table is for head seas on the
undisplaced hull and is applied whatever the heading and the yaw; the force series is built
once from the model's wave components over their repeat period (none in still water or with
streamed waves)."""
from __future__ import annotations

import math

import numpy as np

from fowt_hydro_sim.physics.jit import step_loop
from fowt_hydro_sim.physics.tables import interpolate_series

STEP_S = 0.5  # force samples; the slow drift lies below 0.05 Hz, the envelope below ~0.5 Hz


def coefficients(table: tuple[tuple[float, float], ...], omega_rad_s: np.ndarray) -> np.ndarray:
    """D(w): linear in the table, 0 at w = 0, held at the last value above it."""
    pairs = np.asarray(table, float).reshape(-1, 2)
    return np.interp(omega_rad_s, np.concatenate([[0.0], pairs[:, 0]]), np.concatenate([[0.0], pairs[:, 1]]))


def newman_force(waves, table: tuple[tuple[float, float], ...], step_s: float = STEP_S) -> tuple[np.ndarray, float]:
    """(samples (n, 2) of the force's x and y over the waves' repeat period, their step)."""
    d = coefficients(table, 2.0 * np.pi * waves.frequency_hz)
    harmonic = waves.harmonic - waves.harmonic.min()  # |envelope| does not change with a common shift
    n = max(int(math.ceil(waves.period_s / step_s)), int(harmonic.max()) + 1, 4)
    spectrum = np.zeros(n, complex)
    np.add.at(spectrum, harmonic, waves.amplitude_m * np.sqrt(d) * np.exp(1j * waves.phase_rad))
    magnitude = np.abs(np.fft.ifft(spectrum) * n) ** 2
    weight = waves.amplitude_m ** 2 * d
    heading = math.atan2(np.sum(weight * np.sin(waves.direction_rad)), np.sum(weight * np.cos(waves.direction_rad)))
    return np.stack([magnitude * math.cos(heading), magnitude * math.sin(heading)], axis=1), waves.period_s / n


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[sample step] and the force samples (n, 2); zeros when off, in still water or without a table."""
    waves, table = inputs.waves, inputs.platform.drift_coefficients_n_m2
    if inputs.options.slow_drift == "none" or not table or waves is None or waves.frequency_hz.size == 0:
        return np.array([1.0]), np.zeros((4, 2))
    samples, step = newman_force(waves, table)
    return np.array([step]), samples


@step_loop
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    """The slow-drift force F(t) (world x, y) at the reference point."""
    out[0] += interpolate_series(table, params[0], t, 0)
    out[1] += interpolate_series(table, params[0], t, 1)
