"""Additional linear damping in surge, heave and pitch, as fractions of each DOF's critical
damping 2 sqrt(K M) (diagonal mass with added mass, and restoring, at rest)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from fowt_hydro_sim.physics.loads.extension import Extension
from fowt_hydro_sim.studies.diagnosis.effects.base import ANALYSED, DAMPED, Effect, Parameter, linear_modes
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant

NAMES = ("surge_damping_ratio", "heave_damping_ratio", "pitch_damping_ratio")


def damping_matrix(mass: np.ndarray, stiffness: np.ndarray, ratios: dict[int, float]) -> np.ndarray:
    """Diagonal B1 (6, 6) with B_ii = ratio_i 2 sqrt(K_ii M_ii)."""
    out = np.zeros((6, 6))
    for dof, ratio in ratios.items():
        out[dof, dof] = ratio * 2.0 * np.sqrt(stiffness[dof] * mass[dof])
    return out


def apply(variant: Variant, run: MeasuredRun, values: dict[str, float]) -> Variant:
    mass, stiffness = linear_modes(variant.platform)
    damping = damping_matrix(mass, stiffness, {dof: values[name] for dof, name in zip(ANALYSED, NAMES)})
    return replace(variant, extension=variant.extension.plus(Extension(linear_damping=damping)))

WHY = "radiation and viscous damping beyond the strips' drag: a few percent of critical"

EFFECT = Effect(
    "linear_damping",
    "additional linear damping per DOF (e.g. radiation or viscous damping the strips miss)",
    tuple(Parameter(name, "of critical", start=0.02, low=0.0, high=0.5, plausible=(0.0, 0.1),
                    why=WHY) for name in NAMES),
    apply, signature=DAMPED)
