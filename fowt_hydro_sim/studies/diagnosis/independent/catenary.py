"""A catenary mooring for the independent benchmark: the surge restoring curve of three chain
lines solved by MoorPy's quasi-static catenary (with seabed contact), at the platform's
fairleads and along its lines' directions, less the platform's spring lines' curve: the
extra surge force the "basin" has and the model does not (``cummins.Effects.mooring_curve_n``).
Needs ``moorpy`` (the ``benchmark`` extra)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fowt_hydro_sim.physics.config import Platform
from fowt_hydro_sim.studies.diagnosis.independent.cummins import mooring_wrench


@dataclass(frozen=True)
class ChainLines:
    """Three (or as many as the platform's lines) identical chain lines: anchor on the seabed
    ``anchor_distance_m`` from its fairlead, horizontally along the line's direction."""

    anchor_distance_m: float = 800.0
    length_m: float = 825.0
    weight_n_m: float = 1500.0  # submerged weight per metre
    axial_stiffness_n: float = 8.0e8  # EA


def surge_force_n(platform: Platform, lines: ChainLines, surge_m: float) -> float:
    """The catenary lines' surge force on the platform displaced by ``surge_m``."""
    from moorpy.Catenary import catenary
    depth = platform.environment.water_depth_m
    total = 0.0
    for line in platform.mooring.lines:
        fairlead = np.asarray(line.fairlead_m, float)
        direction = np.asarray(line.anchor_m, float)[:2] - fairlead[:2]
        direction /= np.linalg.norm(direction)
        anchor = fairlead[:2] + direction * lines.anchor_distance_m
        span = anchor - (fairlead[:2] + (surge_m, 0.0))
        distance = float(np.linalg.norm(span))
        result = catenary(distance, depth + fairlead[2], lines.length_m, lines.axial_stiffness_n, lines.weight_n_m,
                          CB=0)
        total += abs(result[2]) * span[0] / distance  # the fairlead's horizontal tension, towards the anchor
    return total


def surge_curve(platform: Platform, lines: ChainLines = ChainLines(),
                offsets_m: np.ndarray | None = None) -> tuple[tuple[float, float], ...]:
    """(surge offset, catenary force - spring lines' force) pairs, both zero-referenced, at
    ``offsets_m`` (default -40 to 40 m in 2 m steps)."""
    import warnings
    if offsets_m is None:
        offsets_m = np.linspace(-40.0, 40.0, 41)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        catenary_n = np.array([surge_force_n(platform, lines, x) for x in offsets_m])
    spring_n = np.array([mooring_wrench(platform, np.array([x, 0.0, 0.0, 0.0, 0.0, 0.0]))[0] for x in offsets_m])
    extra = (catenary_n - surge_force_n(platform, lines, 0.0)) - (spring_n - mooring_wrench(platform, np.zeros(6))[0])
    return tuple((float(x), float(f)) for x, f in zip(offsets_m, extra))
