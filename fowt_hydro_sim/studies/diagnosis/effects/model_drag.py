"""The model's own drag too strong or too weak, per band: every Cd (strips and end plates)
times ``wave_cd_scale`` in the wave band and ``low_frequency_cd_scale`` in the low-frequency
band (the ``filtered`` drag model's band split when the two differ; the ``constant`` model
when they are equal). Unlike ``frequency_dependent_drag``, whose low-frequency Cd is a ratio
of the unchanged wave-band Cd, both of the model's own drags are scaled: a fit of 0.6 and
1.0 reads "the model's wave-band drag is 1.7 times too strong, its low-frequency drag right"."""
from __future__ import annotations

from dataclasses import replace

from fowt_hydro_sim.physics.platform_edits import band_split, scaled_drag
from fowt_hydro_sim.studies.diagnosis.effects.base import MATERIAL_SCALE, Effect, Parameter, scaled_term
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant


def apply(variant: Variant, run: MeasuredRun, values: dict[str, float]) -> Variant:
    wave, low = values["wave_cd_scale"], values["low_frequency_cd_scale"]
    if wave == 1.0 and low == 1.0:
        return variant
    platform = scaled_drag(variant.platform, wave)
    if low == wave:
        return replace(variant, platform=platform)
    return replace(variant, platform=band_split(platform, low / wave), drag_model="filtered")


def term(values: dict[str, float]) -> str:
    """The fitted scales in words: each band's drag too strong or too weak."""
    wave = scaled_term("wave-band drag", values["wave_cd_scale"])
    low = scaled_term("low-frequency drag", values["low_frequency_cd_scale"])
    return wave + ", " + low.replace("the model's ", "its ", 1)


EFFECT = Effect(
    "model_drag",
    "the model's own drag coefficients too strong or too weak, in the wave and the low-frequency band",
    (Parameter("wave_cd_scale", "-", start=1.2, low=0.2, high=4.0, off=1.0, plausible=(0.6, 1.6),
               why="handbook Morison Cds of columns and pontoons lie within about 40 % of those fitted to a "
                   "basin's wave-band response",
               material=MATERIAL_SCALE),
     Parameter("low_frequency_cd_scale", "-", start=0.8, low=0.05, high=4.0, off=1.0, plausible=(0.3, 2.0),
               why="the seed paper's tuned low-frequency Cds are 0.3 to 1.5 times the wave-band ones, and up to "
                   "about twice in small seas",
               material=MATERIAL_SCALE)),
    apply, term=term)

# the benchmark's twin injects it at these values (one scenario each)
TWIN_INJECTIONS = ({"wave_cd_scale": 1.5, "low_frequency_cd_scale": 1.5},
                   {"wave_cd_scale": 0.7, "low_frequency_cd_scale": 0.4})
# no injection in the independent basin: its Cd factor is a scenario baseline term there
# (split.yaml `baseline: {cd_factor: ...}`), scored by the fitted Cd scales
INDEPENDENT_INJECTION = None
