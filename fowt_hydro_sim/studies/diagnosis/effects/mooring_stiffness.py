"""Mooring stiffness error and nonlinearity: the lines' axial stiffness scaled, an asymmetric
(quadratic) and a hardening (cubic) term of the surge restoring. With K_11 the scaled
lines' surge stiffness at rest and d = 5 m, the restoring force at offset x is
K_11 x (1 + asymmetry x / d + hardening x^2 / d^2): at +5 m it grows by asymmetry +
hardening, at -5 m by hardening - asymmetry. The cubic term acts in sway too; the quadratic
one in surge only (a layout mirrored about the x-z plane, such as three lines at 180 and
+-60 deg, has a sway curve symmetric in y)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from fowt_hydro_sim.physics.loads.extension import Extension
from fowt_hydro_sim.physics.platform_edits import scaled_mooring_stiffness
from fowt_hydro_sim.studies.diagnosis.effects.base import Effect, Parameter, linear_modes, scaled_term
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant

REFERENCE_OFFSET_M = 5.0


def nonlinear_terms(stiffness: np.ndarray, asymmetry: float, hardening: float) -> tuple[np.ndarray, np.ndarray]:
    """K2 (6,) and K3 (6,) of the restoring at rest ``stiffness`` (6,): K2 = asymmetry K_11 / d
    in surge, K3 = hardening K_ii / d^2 in surge and sway."""
    quadratic, cubic = np.zeros(6), np.zeros(6)
    quadratic[0] = asymmetry * stiffness[0] / REFERENCE_OFFSET_M
    cubic[0:2] = hardening * stiffness[0:2] / REFERENCE_OFFSET_M ** 2
    return quadratic, cubic


def apply(variant: Variant, run: MeasuredRun, values: dict[str, float]) -> Variant:
    platform = scaled_mooring_stiffness(variant.platform, values["line_stiffness_scale"])
    _, stiffness = linear_modes(platform)
    quadratic, cubic = nonlinear_terms(stiffness, values["asymmetry"], values["hardening"])
    return replace(variant, platform=platform, extension=variant.extension.plus(
        Extension(quadratic_stiffness=quadratic, cubic_stiffness=cubic)))


def term(values: dict[str, float]) -> str:
    """The fitted line stiffness in words, with the nonlinear terms the model's lines lack."""
    text = scaled_term("mooring line stiffness", values["line_stiffness_scale"], "too stiff", "too soft")
    extra = [f"{name} {values[name]:+.2g}" for name in ("hardening", "asymmetry") if abs(values[name]) >= 0.005]
    return text + (f", and its surge restoring lacks a {' and '.join(extra)} term" if extra else "")


EFFECT = Effect(
    "mooring_stiffness",
    "mooring line stiffness error, an asymmetric (quadratic) and a hardening (cubic) surge restoring",
    (Parameter("line_stiffness_scale", "-", start=1.15, low=0.3, high=3.0, off=1.0, plausible=(0.7, 1.3),
               why="a mooring's axial stiffness is known within about 30 %"),
     Parameter("hardening", "-", start=0.2, low=-0.5, high=5.0, plausible=(0.0, 2.0),
               why="catenary lines stiffen with offset: at 5 m by up to about twice, never soften"),
     Parameter("asymmetry", "-", start=0.05, low=-1.0, high=1.0, plausible=(-0.3, 0.3),
               why="a three-line catenary is stiffer moving away from its single line's anchor than from the "
                   "pair's: 0.09 to 0.17 for chain lines 0.4x to 3.7x the spring lines' stiffness in 200 m of "
                   "water (fitted over +-10 m), the sign the layout's")),
    apply, term=term)

# the benchmark's twin injects it at these values (one scenario each)
TWIN_INJECTIONS = ({"line_stiffness_scale": 1.4, "hardening": 0.0, "asymmetry": 0.0},
                   {"line_stiffness_scale": 0.7, "hardening": 1.0, "asymmetry": 0.0})
# none here: its independent form, chain lines' catenary curve (MoorPy, an optional
# dependency), is an independent-only form of the benchmark (benchmark.INDEPENDENT_ONLY)
INDEPENDENT_INJECTION = None
