"""Additional quadratic damping -B2 |v| v in surge, heave and pitch. Each parameter is the
damping ratio it is equivalent to (Borgman linearisation, 8/(3 pi) B2 omega a) at an
oscillation of 1 m (1 deg) at the DOF's natural frequency."""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from fowt_hydro_sim.physics.loads.extension import Extension
from fowt_hydro_sim.studies.diagnosis.effects.base import (
    DAMPED,
    Effect,
    Parameter,
    added_term,
    critical_damping,
    linear_modes,
    per_dof,
)
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant

NAMES = ("surge_ratio_at_1m", "heave_ratio_at_1m", "pitch_ratio_at_1deg")
REFERENCE_AMPLITUDE = {0: 1.0, 2: 1.0, 4: np.deg2rad(1.0)}  # m, m, rad


def quadratic_coefficients(mass: np.ndarray, stiffness: np.ndarray, ratios: dict[int, float]) -> np.ndarray:
    """B2 (6,) with 8/(3 pi) B2 omega_n a_ref = ratio 2 sqrt(K M)."""
    out = np.zeros(6)
    for dof, linear in critical_damping(mass, stiffness, ratios).items():
        out[dof] = linear * 3.0 * np.pi / (8.0 * np.sqrt(stiffness[dof] / mass[dof]) * REFERENCE_AMPLITUDE[dof])
    return out


def apply(variant: Variant, run: MeasuredRun, values: dict[str, float]) -> Variant:
    b2 = quadratic_coefficients(*linear_modes(variant.platform), per_dof(values, NAMES))
    return replace(variant, extension=variant.extension.plus(Extension(quadratic_damping=b2)))

WHY = "viscous damping beyond the strips' drag at a 1 m (1 deg) motion: tens of percent at most"

EFFECT = Effect(
    "quadratic_damping",
    "additional quadratic (viscous) damping per DOF",
    tuple(Parameter(name, "of critical", start=0.05, low=0.0, high=2.0, plausible=(0.0, 0.5),
                    why=WHY) for name in NAMES),
    apply, signature=DAMPED,
    term=lambda values: added_term("quadratic damping", {name.split("_")[0]: values[name] for name in NAMES},
                                   "of critical at 1 m (1 deg)"))

# the benchmark's twin injects it at these values (one scenario each)
TWIN_INJECTIONS = ({"surge_ratio_at_1m": 0.1, "heave_ratio_at_1m": 0.0, "pitch_ratio_at_1deg": 0.1},
                   {"surge_ratio_at_1m": 0.3, "heave_ratio_at_1m": 0.0, "pitch_ratio_at_1deg": 0.3})
# none of its own in the independent basin: the basin's mixed damping (linear_damping's
# INDEPENDENT_INJECTION) is part quadratic, and this effect a right answer to it
INDEPENDENT_INJECTION = None
