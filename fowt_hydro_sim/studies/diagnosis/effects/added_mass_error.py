"""Added-mass / inertia error: every added-mass coefficient (Ca) scaled, which scales the
Morison inertia force's diffraction part (Cm = 1 + Ca) with it."""
from __future__ import annotations

from dataclasses import replace

from fowt_hydro_sim.physics.platform_edits import scaled_added_mass
from fowt_hydro_sim.studies.diagnosis.effects.base import Effect, Parameter, scaled_term
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant


def apply(variant: Variant, run: MeasuredRun, values: dict[str, float]) -> Variant:
    return replace(variant, platform=scaled_added_mass(variant.platform, values["added_mass_scale"]))


EFFECT = Effect(
    "added_mass_error",
    "added mass (Ca) and with it the inertia force's diffraction part in error",
    (Parameter("added_mass_scale", "-", start=1.1, low=0.3, high=2.0, off=1.0, plausible=(0.7, 1.3),
               why="strip-theory Ca of columns and pontoons lies within about 30 % of a BEM added mass"),),
    apply, term=lambda values: scaled_term("added mass", values["added_mass_scale"], "too large", "too small"))

# the benchmark's twin injects it at these values (one scenario each)
TWIN_INJECTIONS = ({"added_mass_scale": 0.7}, {"added_mass_scale": 1.35})
# none in the independent basin (its added mass is the BEM's, scaled only by the baseline spread)
INDEPENDENT_INJECTION = None
