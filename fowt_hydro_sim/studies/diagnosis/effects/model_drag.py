"""The model's own drag too strong or too weak: every Cd it has (strips, end plates, and each
band's of a platform with per-band Cds) times ``cd_scale``, the drag's form kept. A fit of 0.8
reads "the model's drag is 1.25 times too strong".

The form is kept because a band split is a term of its own, not a scale of one: the constant-Cd
model's drag 0.5 rho Cd D |v| v damps the slow motion through the waves' velocity in |v|, while
the split's low-frequency band, Cd |v_lf| v_lf, sees only the slow velocity. Splitting at equal
band Cds more than halves that damping (the surge low-frequency STD in LC5.2 goes from 1.9 m to
3.8 m), so a fitted pair of band scales jumps at the constant model instead of passing through
it. The band split, with its low-frequency Cd as a ratio of the wave band's, is
``frequency_dependent_drag``."""
from __future__ import annotations

from dataclasses import replace

from fowt_hydro_sim.physics.platform_edits import scaled_drag
from fowt_hydro_sim.studies.diagnosis.effects.base import MATERIAL_SCALE, Effect, Parameter, scaled_term
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant


def apply(variant: Variant, run: MeasuredRun, values: dict[str, float]) -> Variant:
    scale = values["cd_scale"]
    return variant if scale == 1.0 else replace(variant, platform=scaled_drag(variant.platform, scale))


def term(values: dict[str, float]) -> str:
    """The fitted scale in words: the model's drag too strong or too weak."""
    return scaled_term("drag", values["cd_scale"])


EFFECT = Effect(
    "model_drag",
    "the model's own drag coefficients too strong or too weak, every Cd alike",
    (Parameter("cd_scale", "-", start=1.2, low=0.2, high=4.0, off=1.0, plausible=(0.6, 1.6),
               why="handbook Morison Cds of columns and pontoons lie within about 40 % of those fitted to a "
                   "basin's wave-band response",
               material=MATERIAL_SCALE),),
    apply, term=term)

# the benchmark's twin injects it at these values (one scenario each)
TWIN_INJECTIONS = ({"cd_scale": 1.5}, {"cd_scale": 0.7})
# no injection in the independent basin: its Cd factor is a scenario baseline term there
# (split.yaml `baseline: {cd_factor: ...}`), scored by the fitted Cd scale
INDEPENDENT_INJECTION = None
