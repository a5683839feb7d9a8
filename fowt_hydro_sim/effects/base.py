"""What a candidate unmodelled effect is: named parameters with a value at which the
effect is off, and a pure function that turns a model variant into one with the effect."""
from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Callable, Iterator

import numpy as np

from ..model import PlatformModel
from ..config import platform_from_dict
from ..replay import MeasuredRun, Variant


@dataclass(frozen=True)
class Parameter:
    """One parameter: the fit starts at ``start`` within [low, high]; at ``off`` the
    effect is switched off."""

    name: str
    unit: str
    start: float
    low: float
    high: float
    off: float = 0.0

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
    quadratic in the elevation, whose low-frequency part is not coherent with it)."""

    name: str
    summary: str
    parameters: tuple[Parameter, ...]
    apply: Callable[[Variant, MeasuredRun, dict[str, float]], Variant]
    wave_coherent: bool = True

    def values(self, which: str = "start") -> dict[str, float]:
        return {p.name: getattr(p, which) for p in self.parameters}


# ---------------------------------------------------------------------- helpers for effects
def copied(document: dict) -> dict:
    """A deep copy in which YAML aliases no longer share mappings."""
    return json.loads(json.dumps(document))


def coefficient_holders(document: dict) -> Iterator[dict]:
    """Every mapping that holds hydrodynamic coefficients: member zones and end plates."""
    for member in document.get("members", []):
        yield from member.get("zones", [])
        for end in ("end_a_plate", "end_b_plate"):
            if member.get(end):
                yield member[end]


def scale_fields(document: dict, prefix: str, factor: float) -> dict:
    """A copy with every coefficient whose field name starts with ``prefix`` (``cd``, ``ca``)
    multiplied by ``factor``, in every band of a per-band coefficient."""
    document = copied(document)
    for holder in coefficient_holders(document):
        for key, value in holder.items():
            if key.startswith(prefix):
                holder[key] = ({band: factor * float(v) for band, v in value.items()} if isinstance(value, dict)
                               else factor * float(value))
    return document


def scale_mooring(document: dict, factor: float) -> dict:
    """A copy with the mooring lines' axial stiffness multiplied by ``factor``."""
    document = copied(document)
    document["mooring"]["stiffness_n_m"] = factor * float(document["mooring"]["stiffness_n_m"])
    return document


def linear_modes(document: dict) -> tuple[np.ndarray, np.ndarray]:
    """Diagonals of the mass (rigid + added) and restoring matrices at rest (6,), (6,)."""
    model = PlatformModel(platform_from_dict(document, "effect"))
    return np.diag(model.mass_matrix()), np.diag(model.restoring_matrix())


ANALYSED = (0, 2, 4)  # surge, heave, pitch: the DOFs whose per-DOF terms the effects fit
