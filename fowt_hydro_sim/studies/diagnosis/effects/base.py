"""What a candidate unmodelled effect is: named parameters with a value at which the
effect is off, and a pure function that turns a model variant into one with the effect;
and how the benchmark injects it into the independent simulator's runs."""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from fowt_hydro_sim.physics.config import Platform
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant


@dataclass(frozen=True)
class Parameter:
    """One parameter: the fit starts at ``start`` within [low, high]; at ``off`` the
    effect is switched off. ``plausible`` (default: [low, high]) is the range a real
    platform's value lies in, ``why`` says where that range comes from; a fit outside it, or
    at the edge of [low, high], is a sign that the parameter absorbs something else.
    ``grid_step``: a lag-type parameter, which the gaps follow in steps (a lag read from a
    cross-correlation peak is piecewise constant in a delay, so a forward difference sees
    no slope); it is fitted by a grid over its plausible range at this step, refined
    around the best point (``method.fit_effect``).
    ``material``: for a scale of one of the model's own terms, the smallest departure from
    ``off`` worth naming; a fit whose every such parameter lies closer to ``off`` says the
    term is right within what the diagnosis can attribute (``method.range_concerns``)."""

    name: str
    unit: str
    start: float
    low: float
    high: float
    off: float = 0.0
    plausible: tuple[float, float] | None = None
    why: str = ""
    grid_step: float | None = None
    material: float = 0.0

    @property
    def plausible_range(self) -> tuple[float, float]:
        return self.plausible or (self.low, self.high)

    @property
    def scale(self) -> float:
        """The parameter's typical size, for the fit's steps."""
        return abs(self.start - self.off)


@dataclass(frozen=True)
class Effect:
    """A switchable, parametrised extension of the model. ``apply(variant, run, values)``
    returns the variant with the effect at ``values`` (parameter name -> value) for
    ``run`` (effects may depend on the run's sea state or its elevation record).
    ``wave_coherent``: whether the loads it adds are linear in the waves (False for loads
    quadratic in the elevation, whose low-frequency part is not coherent with it).
    ``signature``: the direction in which switching the effect on (within its plausible
    range) moves the model's value of a gap metric ("std.low_frequency": -1, damping lowers
    the resonant response); it can close only gaps of the other sign. Metrics it can move
    either way are left out.
    ``term``: for an effect that scales (or adds to) a term the model already has, how a
    fit reads as that term's error, from the fitted values: "the model's slow drift is 2
    times too strong" (``scaled_term``); None for an effect the model lacks.
    ``own_share``: for an effect that adds to a term the model already has in another form
    (a drift of its own on top of the model's drift table), the added term's size as a share
    of the model's own on a run, from the fitted values and the platform; a fit under
    MATERIAL_SCALE of it on the tuning runs is no finding, as a scale of that term within
    MATERIAL_SCALE of 1 is not (``method.share_concern``)."""

    name: str
    summary: str
    parameters: tuple[Parameter, ...]
    apply: Callable[[Variant, MeasuredRun, dict[str, float]], Variant]
    wave_coherent: bool = True
    signature: dict[str, int] = field(default_factory=dict)
    term: Callable[[dict[str, float]], str] | None = None
    own_share: Callable[[dict[str, float], MeasuredRun, Platform], float] | None = None

    def values(self, which: str = "start") -> dict[str, float]:
        """Every parameter's ``start``, ``low``, ``high`` or ``off`` value, by name."""
        return {p.name: getattr(p, which) for p in self.parameters}


class IndependentInjection(NamedTuple):
    """An effect in the independent benchmark's basin (``independent/basin.py``): the
    ``form`` the basin injects (a name its ``effects`` knows; the scenarios are named after
    it), the catalogue effects that are a right answer to it, and the values of each strength
    in the form's own parameters."""

    form: str
    accepted: tuple[str, ...]
    strengths: tuple[dict[str, float], ...]


# A scale of one of the model's own terms closer to 1 than this is no finding (the drift's
# scale has a tighter bound of its own, ``model_slow_drift.MATERIAL_DRIFT_SCALE``), nor is an
# added term under this share of the model's own: the scored attribution is right within 25 %,
# and each basin baseline's Cds differ from the model's by a drawn share of 0.9-1.1 in every
# run (independent/basin.py), so a smaller departure is below what the fit can attribute to
# the term.
MATERIAL_SCALE = 0.2


# ---------------------------------------------------------------------- helpers for effects
def linear_modes(platform: Platform) -> tuple[np.ndarray, np.ndarray]:
    """Diagonals of the mass (rigid + added) and restoring matrices at rest (6,), (6,)."""
    model = PlatformModel(platform)
    return np.diag(model.mass_matrix()), np.diag(model.restoring_matrix())


# damping lowers the resonant responses: surge and pitch below 0.05 Hz, heave in the wave band
DAMPED = {"surge.std.low_frequency": -1, "pitch.std.low_frequency": -1, "heave.std.wave": -1}
ANALYSED = (0, 2, 4)  # surge, heave, pitch: the DOFs whose per-DOF terms the effects fit


def critical_damping(mass: np.ndarray, stiffness: np.ndarray, ratios: dict[int, float]) -> dict[int, float]:
    """Per DOF in ``ratios``: the ratio times its critical damping 2 sqrt(K M)."""
    return {dof: ratio * 2.0 * np.sqrt(stiffness[dof] * mass[dof]) for dof, ratio in ratios.items()}


def per_dof(values: dict[str, float], names: tuple[str, ...]) -> dict[int, float]:
    """The fitted values of per-DOF parameters, keyed by the analysed DOFs they belong to."""
    return {dof: values[name] for dof, name in zip(ANALYSED, names)}


def scaled_term(term: str, scale: float, strong: str = "too strong", weak: str = "too weak") -> str:
    """A fitted scale of one of the model's terms in words: the model's term is 1 / scale
    times ``strong`` (scale below 1) or scale times ``weak`` (above 1): 'the model's slow
    drift is 2 times too strong' for a scale of 0.5."""
    if scale <= 0.0:
        return f"the model's {term} is {strong} (the fit removes it)"
    if abs(scale - 1.0) < 0.005:
        return f"the model's {term} is right"
    factor, words = (1.0 / scale, strong) if scale < 1.0 else (scale, weak)
    return f"the model's {term} is {factor:.3g} times {words}"


def added_term(term: str, amounts: dict[str, float], unit: str) -> str:
    """Extra amounts of a term the model has, per DOF, in words: 'the model's damping is too
    weak by 0.04 of critical in surge, 0.03 in pitch' ('right' where every amount is 0)."""
    added = [(dof, value) for dof, value in amounts.items() if value != 0.0]
    if not added:
        return f"the model's {term} is right"
    first, *rest = added
    return (f"the model's {term} is too weak by {first[1]:.3g} {unit} in {first[0]}"
            + "".join(f", {value:.3g} in {dof}" for dof, value in rest))
