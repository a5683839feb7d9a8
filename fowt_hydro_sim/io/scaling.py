"""Froude scaling between a basin model and its full-scale platform.

A model at scale 1:lambda in water of density rho_m stands for the platform in water of
density rho_p; with gravity the same at both scales, Froude similitude multiplies a
quantity of dimension L^a T^b M^c by lambda^(a + b / 2 + 3 c) (rho_p / rho_m)^c: lengths by
lambda, times by sqrt(lambda), forces by lambda^3 rho_p / rho_m, moments by lambda^4
rho_p / rho_m. ``FROUDE`` holds each kind's exponents (of lambda, of the density ratio).
"""
from __future__ import annotations

from fowt_hydro_sim.errors import InputError

# kind -> (exponent of lambda, exponent of the density ratio rho_full / rho_model)
FROUDE: dict[str, tuple[float, float]] = {
    "length": (1.0, 0.0),
    "angle": (0.0, 0.0),
    "time": (0.5, 0.0),
    "frequency": (-0.5, 0.0),
    "velocity": (0.5, 0.0),
    "acceleration": (0.0, 0.0),
    "angular_velocity": (-0.5, 0.0),
    "angular_acceleration": (-1.0, 0.0),
    "mass": (3.0, 1.0),
    "force": (3.0, 1.0),
    "moment": (4.0, 1.0),
    "pressure": (1.0, 1.0),
    "power": (3.5, 1.0),
    "linear_stiffness": (2.0, 1.0),
    "rotational_stiffness": (4.0, 1.0),
}


def froude_factor(kind: str, scale: float, density_ratio: float = 1.0) -> float:
    """What a model-scale value of ``kind`` is multiplied by to give the full-scale value, for
    a model at 1:``scale`` and water densities full / model = ``density_ratio``."""
    if kind not in FROUDE:
        raise InputError(f"Froude scaling: unknown kind {kind!r} (kinds: {', '.join(FROUDE)})")
    if not scale > 0 or not density_ratio > 0:
        raise InputError(f"Froude scaling: scale and density ratio must be positive, got {scale}, {density_ratio}")
    length_exponent, density_exponent = FROUDE[kind]
    return scale**length_exponent * density_ratio**density_exponent


def to_full_scale(value: float, kind: str, scale: float, density_ratio: float = 1.0) -> float:
    """A model-scale value of ``kind`` at full scale."""
    return value * froude_factor(kind, scale, density_ratio)
