"""Drag that depends on the sea state: every Cd scaled by (KC / KC_ref)^exponent, with the
run's Keulegan-Carpenter number at the surface KC = pi Hs / D (D the widest circular
member, at least ``KC_FLOOR``) and KC_ref = 1. A free decay (calm water) keeps the platform's
Cds: the form says how they change with the sea, not with the body's own motion."""
from __future__ import annotations

import math
from dataclasses import replace

from fowt_hydro_sim.physics.config import Platform
from fowt_hydro_sim.physics.platform_edits import scaled_drag, widest_circular_diameter_m
from fowt_hydro_sim.studies.diagnosis.effects.base import Effect, Parameter
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant

KC_REFERENCE = 1.0
KC_FLOOR = 0.05  # still water would otherwise give a Cd of 0 (or infinity)


def keulegan_carpenter(hs_m: float, platform: Platform) -> float:
    return max(KC_FLOOR, math.pi * hs_m / widest_circular_diameter_m(platform))


def apply(variant: Variant, run: MeasuredRun, values: dict[str, float]) -> Variant:
    if run.decay_dof is not None:
        return variant
    factor = (keulegan_carpenter(run.hs_m, variant.platform) / KC_REFERENCE) ** values["kc_exponent"]
    return replace(variant, platform=scaled_drag(variant.platform, factor))


EFFECT = Effect(
    "kc_dependent_drag",
    "drag coefficients that change with the sea state (Keulegan-Carpenter number)",
    (Parameter("kc_exponent", "-", start=0.3, low=-2.0, high=2.0, plausible=(-1.0, 1.0),
               why="measured Cd(KC) of cylinders varies at most about as KC to the power +-1 over these seas"),),
    apply)

# the benchmark's twin injects it at these values (one scenario each)
TWIN_INJECTIONS = ({"kc_exponent": 0.5}, {"kc_exponent": -0.5})
# none in the independent basin, whose Cds do not change with the sea state
INDEPENDENT_INJECTION = None
