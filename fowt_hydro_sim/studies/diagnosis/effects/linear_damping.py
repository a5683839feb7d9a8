"""Additional linear damping in surge, heave and pitch, as fractions of each DOF's critical
damping 2 sqrt(K M) (diagonal mass with added mass, and restoring, at rest)."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from fowt_hydro_sim.physics.loads.extension import Extension
from fowt_hydro_sim.studies.diagnosis.effects.base import (
    DAMPED,
    Effect,
    IndependentInjection,
    Parameter,
    added_term,
    critical_damping,
    linear_modes,
    per_dof,
)
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
    apply, signature=DAMPED,
    term=lambda values: added_term("linear damping", {name.split("_")[0]: values[name] for name in NAMES},
                                   "of critical"))

# the benchmark's twin injects it at these values (one scenario each)
TWIN_INJECTIONS = ({"surge_damping_ratio": 0.04, "heave_damping_ratio": 0.0, "pitch_damping_ratio": 0.03},
                   {"surge_damping_ratio": 0.10, "heave_damping_ratio": 0.0, "pitch_damping_ratio": 0.08})
# in the independent basin: damping part linear, part quadratic in surge and pitch, which
# linear or quadratic damping both answer rightly (critical damping is about 2.8e6 N s/m in
# surge and 1.4e10 N m s in pitch)
INDEPENDENT_INJECTION = IndependentInjection(
    "mixed_damping", ("linear_damping", "quadratic_damping"),
    ({"surge_linear_n_s_m": 1.4e5, "surge_quadratic_n_s2_m2": 7.0e5,
      "pitch_linear_n_m_s": 5.6e8, "pitch_quadratic_n_m_s2": 1.1e11},
     {"surge_linear_n_s_m": 2.8e5, "surge_quadratic_n_s2_m2": 1.4e6,
      "pitch_linear_n_m_s": 1.1e9, "pitch_quadratic_n_m_s2": 2.2e11}))
