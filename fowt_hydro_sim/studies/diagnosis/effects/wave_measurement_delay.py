"""Wave-measurement delay (a confounder, not physics): the elevation record's stamps are
late by ``delay_s``, so the model, driven by it, answers late. Corrected by shifting the
record back."""
from __future__ import annotations

from dataclasses import replace

from fowt_hydro_sim.studies.diagnosis.effects.base import Effect, Parameter
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant


def apply(variant: Variant, run: MeasuredRun, values: dict[str, float]) -> Variant:
    return replace(variant, elevation_shift_s=variant.elevation_shift_s - values["delay_s"])


EFFECT = Effect(
    "wave_measurement_delay",
    "the wave elevation's time stamps are late or early (probe clock, filtering)",
    (Parameter("delay_s", "s", start=0.5, low=-10.0, high=10.0, plausible=(-3.0, 3.0),
               why="a wave probe's and a motion tracker's clocks agree to a few seconds", grid_step=1.0),),
    apply)

# the benchmark's twin injects it at these values (one scenario each)
TWIN_INJECTIONS = ({"delay_s": 1.0}, {"delay_s": 2.5})
# none in the independent basin, whose wave probe's stamps are right
INDEPENDENT_INJECTION = None
