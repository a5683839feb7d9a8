"""The catalogue of candidate unmodelled effects for the gap diagnosis: one module each,
registered here. An effect is a parametrised, switchable change of a model variant
(base.Effect); adding one is a new module and one entry in ``CATALOGUE``."""
from __future__ import annotations

from fowt_hydro_sim.studies.diagnosis.effects import (
               added_mass_error,
               frequency_dependent_drag,
               kc_dependent_drag,
               linear_damping,
               mooring_stiffness,
               quadratic_damping,
               slow_drift,
               wave_measurement_delay,
)
from fowt_hydro_sim.studies.diagnosis.effects.base import Effect, Parameter

CATALOGUE: dict[str, Effect] = {effect.name: effect for effect in (
    frequency_dependent_drag.EFFECT,
    slow_drift.EFFECT,
    linear_damping.EFFECT,
    quadratic_damping.EFFECT,
    mooring_stiffness.EFFECT,
    added_mass_error.EFFECT,
    kc_dependent_drag.EFFECT,
    wave_measurement_delay.EFFECT,
)}

__all__ = ["CATALOGUE", "Effect", "Parameter"]
