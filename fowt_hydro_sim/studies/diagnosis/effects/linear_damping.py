"""Additional linear damping in surge, heave and pitch, as fractions of each DOF's critical
damping 2 sqrt(K M) (diagonal mass with added mass, and restoring, at rest)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from fowt_hydro_sim.physics.loads.extension import Extension
from fowt_hydro_sim.studies.diagnosis.effects.base import (DAMPED, Effect, Parameter, critical_damping, linear_modes,
                                                          per_dof)
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant

NAMES = ("surge_damping_ratio", "heave_damping_ratio", "pitch_damping_ratio")


def damping_matrix(mass: np.ndarray, stiffness: np.ndarray, ratios: dict[int, float]) -> np.ndarray:
    """Diagonal B1 (6, 6) with B_ii = ratio_i 2 sqrt(K_ii M_ii)."""
    critical = critical_damping(mass, stiffness, ratios)
    return np.diag([critical.get(dof, 0.0) for dof in range(6)])


def apply(variant: Variant, run: MeasuredRun, values: dict[str, float]) -> Variant:
    damping = damping_matrix(*linear_modes(variant.platform), per_dof(values, NAMES))
    return replace(variant, extension=variant.extension.plus(Extension(linear_damping=damping)))

WHY = "radiation and viscous damping beyond the strips' drag: a few percent of critical"

EFFECT = Effect(
    "linear_damping",
    "additional linear damping per DOF (e.g. radiation or viscous damping the strips miss)",
    tuple(Parameter(name, "of critical", start=0.02, low=0.0, high=0.5, plausible=(0.0, 0.1),
                    why=WHY) for name in NAMES),
    apply, signature=DAMPED)
