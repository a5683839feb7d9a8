"""Second-order difference-frequency wave loads (slow drift), by Newman's approximation with a
drift coefficient that may rise with the wave frequency, D(w) = (C / 2) (w / W_REF)^n
(held above W_MAX): F(t) = |sum_j a_j sqrt(D(w_j)) e^{i (w_j t + phase_j)}|^2, low-passed,
along the wave heading at the reference point. With n = 0 it is C x [eta(t)^2 low-passed],
whose mean is the mean drift force C mean(eta^2). A floating hull's mean-drift coefficient
rises through the wave band (from zero in long waves towards the short-wave reflection
limit), so one constant C cannot match the drift of several sea states at once: a long-period
sea drifts less per m^2 of wave than a short one."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from fowt_hydro_sim.physics.config import Platform
from fowt_hydro_sim.physics.loads import drift
from fowt_hydro_sim.physics.loads.extension import Extension
from fowt_hydro_sim.studies.diagnosis.effects.base import Effect, IndependentInjection, Parameter
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant

CUTOFF_HZ = 0.05  # difference frequencies kept
W_REF_RAD_S = 2.0 * math.pi / 10.0  # C is the coefficient of a 10 s wave
W_MAX_RAD_S = math.pi  # D held above 0.5 Hz: the seas end there, sensor noise above is not amplified


def drift_force(elevation_m: np.ndarray, step_s: float, coefficient_n_m2: float, heading_deg: float = 0.0,
                cutoff_hz: float = CUTOFF_HZ, exponent: float = 0.0) -> np.ndarray:
    """(n, 6) wrench samples of the slow-drift force for a periodic elevation record: the
    squared envelope of the elevation weighted by sqrt(D(w)/D(W_REF)), half of it (the
    low-passed eta^2 for n = 0), low-passed, times C."""
    eta = np.asarray(elevation_m, dtype=float)
    n = len(eta)
    spectrum = np.fft.rfft(eta)
    omega = 2.0 * np.pi * np.fft.rfftfreq(n, step_s)
    weight = np.zeros_like(omega)  # none at zero frequency (where a negative exponent would divide by 0)
    weight[1:] = (np.minimum(omega[1:], W_MAX_RAD_S) / W_REF_RAD_S) ** (0.5 * exponent)
    one_sided = np.zeros(n, dtype=complex)  # the analytic signal's spectrum
    one_sided[:spectrum.size] = 2.0 * spectrum * weight
    if n % 2 == 0:
        one_sided[n // 2] *= 0.5
    envelope = np.abs(np.fft.ifft(one_sided)) ** 2
    squared = np.fft.rfft(0.5 * envelope)
    squared[np.fft.rfftfreq(n, step_s) > cutoff_hz] = 0.0
    force = coefficient_n_m2 * np.fft.irfft(squared, n)
    heading = np.deg2rad(heading_deg)
    out = np.zeros((n, 6))
    out[:, 0], out[:, 1] = force * np.cos(heading), force * np.sin(heading)
    return out


def own_share(values: dict[str, float], run: MeasuredRun, platform: Platform) -> float:
    """The added mean drift force on a run's sea as a share of the model's own (its Newman
    drift from ``Platform.drift_coefficients_n_m2``, ``physics/loads/drift.py``): the
    added drift is the table D(w) = (C / 2) (w / W_REF)^n, so the share is
    sum a_j^2 (C / 2) (w_j / W_REF)^n / sum a_j^2 D_model(w_j) over the elevation's
    components. Infinite for a model without a drift table."""
    eta = np.asarray(run.elevation_m, dtype=float)
    power = np.abs(np.fft.rfft(eta - eta.mean()))[1:] ** 2
    omega = 2.0 * np.pi * np.fft.rfftfreq(eta.size, run.elevation_step_s)[1:]
    added = 0.5 * values["drift_coefficient_n_m2"] * (np.minimum(omega, W_MAX_RAD_S) / W_REF_RAD_S) ** values.get(
        "frequency_exponent", 0.0)
    own = float(np.sum(power * drift.coefficients(platform.drift_coefficients_n_m2, omega))
                if platform.drift_coefficients_n_m2 else 0.0)
    return float(np.sum(power * added)) / own if own > 0 else math.inf


def apply(variant: Variant, run: MeasuredRun, values: dict[str, float]) -> Variant:
    force = drift_force(run.elevation_m, run.elevation_step_s, values["drift_coefficient_n_m2"], run.heading_deg,
                        exponent=values.get("frequency_exponent", 0.0))
    return replace(variant, extension=variant.extension.plus(Extension(force_n=force,
                                                                       force_step_s=run.elevation_step_s)))


EFFECT = Effect(
    "slow_drift",
    "second-order difference-frequency wave loads (Newman's approximation)",
    (Parameter("drift_coefficient_n_m2", "N/m^2", start=2.0e5, low=0.0, high=5.0e6, plausible=(0.0, 1.0e6),
               why="Newman drift of a 15 m column semisubmersible: a mean drift force of order 1 MN in an 11 m sea"),
     Parameter("frequency_exponent", "-", start=1.0, low=-2.0, high=6.0, off=0.0, plausible=(-1.0, 4.0),
               why="a floating hull's mean-drift coefficient rises through the wave band, at most about as w^4 "
                   "(a small body in long waves), and falls only past a resonance")),
    apply, wave_coherent=False,
    signature={"surge.std.low_frequency": +1, "surge.offset": +1}, own_share=own_share)

# the benchmark's twin injects it at these values (one scenario each)
TWIN_INJECTIONS = ({"drift_coefficient_n_m2": 1.0e5}, {"drift_coefficient_n_m2": 3.0e5})
# in the independent basin: a Newman drift table steeper in frequency than the baseline's,
# times ``scale`` (basin.INJECTED_DRIFT)
INDEPENDENT_INJECTION = IndependentInjection("frequency_dependent_drift", ("slow_drift",),
                                             ({"scale": 1.0}, {"scale": 2.5}))
