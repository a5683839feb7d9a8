"""Second-order difference-frequency wave loads (slow drift), by Newman's approximation
with a constant drift coefficient: F(t) = C x [eta(t)^2 low-passed], along the wave
heading at the reference point. Its mean is the mean drift force C mean(eta^2)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from fowt_hydro_sim.physics.loads.extension import Extension
from fowt_hydro_sim.studies.diagnosis.effects.base import Effect, Parameter
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant

CUTOFF_HZ = 0.05  # difference frequencies kept


def drift_force(elevation_m: np.ndarray, step_s: float, coefficient_n_m2: float, heading_deg: float = 0.0,
                cutoff_hz: float = CUTOFF_HZ) -> np.ndarray:
    """(n, 6) wrench samples of the slow-drift force for a periodic elevation record."""
    squared = np.fft.rfft(np.asarray(elevation_m, dtype=float) ** 2)
    squared[np.fft.rfftfreq(len(elevation_m), step_s) > cutoff_hz] = 0.0
    force = coefficient_n_m2 * np.fft.irfft(squared, len(elevation_m))
    heading = np.deg2rad(heading_deg)
    out = np.zeros((len(elevation_m), 6))
    out[:, 0], out[:, 1] = force * np.cos(heading), force * np.sin(heading)
    return out


def apply(variant: Variant, run: MeasuredRun, values: dict[str, float]) -> Variant:
    force = drift_force(run.elevation_m, run.elevation_step_s, values["drift_coefficient_n_m2"], run.heading_deg)
    return replace(variant, extension=variant.extension.plus(Extension(force_n=force,
                                                                       force_step_s=run.elevation_step_s)))


EFFECT = Effect(
    "slow_drift",
    "second-order difference-frequency wave loads (Newman's approximation)",
    (Parameter("drift_coefficient_n_m2", "N/m^2", start=2.0e5, low=0.0, high=5.0e6, plausible=(0.0, 1.0e6),
               why="Newman drift of a 15 m column semisubmersible: a mean drift force of order 1 MN in an 11 m sea"),),
    apply, wave_coherent=False,
    signature={"surge.std.low_frequency": +1, "surge.offset": +1})
