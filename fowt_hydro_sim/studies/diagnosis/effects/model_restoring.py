"""The model's own heave and pitch restoring (hydrostatic; the mooring's share is under 1 %)
too stiff or too soft: a linear stiffness (scale - 1) x C_ii added in heave and pitch, C the model's
restoring matrix at rest. A fit of 1.05 in pitch reads "the model's pitch restoring is 5 %
too soft" (a centre of gravity placed too high, a waterplane too small)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from fowt_hydro_sim.physics.loads.extension import Extension
from fowt_hydro_sim.studies.diagnosis.effects.base import Effect, Parameter, linear_modes, scaled_term
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant

HEAVE, PITCH = 2, 4


def apply(variant: Variant, run: MeasuredRun, values: dict[str, float]) -> Variant:
    scales = {HEAVE: values["heave_restoring_scale"], PITCH: values["pitch_restoring_scale"]}
    if all(s == 1.0 for s in scales.values()):
        return variant
    _, restoring = linear_modes(variant.platform)
    stiffness = np.zeros((6, 6))
    for dof, scale in scales.items():
        stiffness[dof, dof] = (scale - 1.0) * restoring[dof]
    return replace(variant, extension=variant.extension.plus(Extension(stiffness=stiffness)))


def term(values: dict[str, float]) -> str:
    """The fitted scales in words: each restoring too stiff or too soft."""
    heave, pitch = (scaled_term(f"{dof} restoring", values[f"{dof}_restoring_scale"], "too stiff", "too soft")
                    for dof in ("heave", "pitch"))
    return heave + ", " + pitch.replace("the model's ", "its ", 1)


EFFECT = Effect(
    "model_restoring",
    "the model's own heave and pitch restoring (hydrostatics and mooring) too stiff or too soft",
    (Parameter("heave_restoring_scale", "-", start=1.03, low=0.5, high=1.5, off=1.0, plausible=(0.95, 1.05),
               why="a column semisubmersible's waterplane area is known within a few per cent (as built, draft)"),
     Parameter("pitch_restoring_scale", "-", start=1.05, low=0.5, high=1.5, off=1.0, plausible=(0.85, 1.15),
               why="the pitch restoring rho g (I_wp + V z_B) - m g z_G moves by about 4 % per 0.5 m of the "
                   "centre of gravity's height (windmoor12), rarely known better than 1 m in a basin model")),
    apply, term=term)

# the benchmark's twin injects it at these values (one scenario each)
TWIN_INJECTIONS = ({"heave_restoring_scale": 1.0, "pitch_restoring_scale": 0.88},
                   {"heave_restoring_scale": 1.04, "pitch_restoring_scale": 1.1})
# none in the independent basin yet (its hydrostatics are the BEM geometry's)
INDEPENDENT_INJECTION = None
