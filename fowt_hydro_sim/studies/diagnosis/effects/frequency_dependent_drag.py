"""Frequency-dependent drag (the seed paper's band-split Cd): the low-frequency band's Cd is
a ratio of the constant Cd, the other bands keep the constant Cd; drag model ``filtered``."""
from __future__ import annotations

from dataclasses import replace

from fowt_hydro_sim.physics.platform_edits import band_split
from fowt_hydro_sim.studies.diagnosis.effects.base import Effect, Parameter
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant


def apply(variant: Variant, run: MeasuredRun, values: dict[str, float]) -> Variant:
    return replace(variant, platform=band_split(variant.platform, values["low_frequency_cd_ratio"]),
                   drag_model="filtered")


EFFECT = Effect(
    "frequency_dependent_drag",
    "the low-frequency band's Cd differs from the wave band's (Butterworth band split)",
    (Parameter("low_frequency_cd_ratio", "-", start=0.6, low=0.05, high=4.0, off=1.0, plausible=(0.2, 2.0),
               why="the seed paper's tuned low-frequency Cds are 0.3 to 1.5 times the wave-band ones"),),
    apply)

# the benchmark's twin injects it at these values (one scenario each)
TWIN_INJECTIONS = ({"low_frequency_cd_ratio": 0.5}, {"low_frequency_cd_ratio": 0.3})
# none in the independent basin, whose strips have one Cd at every frequency
INDEPENDENT_INJECTION = None
