"""Mooring stiffness error and nonlinearity: the lines' axial stiffness scaled, and a cubic
hardening of the horizontal restoring, K3 = hardening x K_11 / (5 m)^2 in surge and sway
(the restoring force grows by that fraction at 5 m offset)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from fowt_hydro_sim.physics.loads.extension import Extension
from fowt_hydro_sim.physics.platform_edits import scaled_mooring_stiffness
from fowt_hydro_sim.studies.diagnosis.effects.base import Effect, Parameter, linear_modes
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant

HARDENING_OFFSET_M = 5.0


def apply(variant: Variant, run: MeasuredRun, values: dict[str, float]) -> Variant:
    platform = scaled_mooring_stiffness(variant.platform, values["line_stiffness_scale"])
    _, stiffness = linear_modes(platform)
    cubic = np.zeros(6)
    cubic[0:2] = values["hardening"] * stiffness[0:2] / HARDENING_OFFSET_M ** 2
    return replace(variant, platform=platform, extension=variant.extension.plus(Extension(cubic_stiffness=cubic)))


EFFECT = Effect(
    "mooring_stiffness",
    "mooring line stiffness error and a hardening (cubic) horizontal restoring",
    (Parameter("line_stiffness_scale", "-", start=1.15, low=0.3, high=3.0, off=1.0, plausible=(0.7, 1.3),
               why="a mooring's axial stiffness is known within about 30 %"),
     Parameter("hardening", "-", start=0.2, low=-0.5, high=5.0, plausible=(0.0, 2.0),
               why="catenary lines stiffen with offset: at 5 m by up to about twice, never soften")),
    apply)
