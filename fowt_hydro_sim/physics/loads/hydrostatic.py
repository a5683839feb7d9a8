"""Hydrostatics: linear about the undisplaced position, from the member geometry.

The buoyancy wrench is W0 - C q: W0 the static buoyancy (rho g V at the centre of
buoyancy) and C the buoyancy part of the restoring matrix (waterplane and centre-of-
buoyancy terms, WAMIT's convention); gravity acts separately at the centre of gravity.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from fowt_hydro_sim.physics.config import ConfigError, Platform
from fowt_hydro_sim.physics.strips import Strips


@dataclass(frozen=True)
class Hydrostatics:
    displaced_volume_m3: float
    centre_of_buoyancy_m: np.ndarray
    waterplane_area_m2: float
    waterplane_first_moment_m3: np.ndarray  # (int x dA, int y dA)
    waterplane_second_moment_m4: np.ndarray  # [[int y^2, int xy], [int xy, int x^2]]
    buoyancy_wrench: np.ndarray  # (6,) at rest, about the reference point
    stiffness: np.ndarray  # (6, 6) buoyancy restoring matrix


def _waterplane(platform: Platform) -> tuple[float, np.ndarray, np.ndarray]:
    area, first, second = 0.0, np.zeros(2), np.zeros((2, 2))
    for m in platform.members:
        za, zb = m.end_a_m[2], m.end_b_m[2]
        if min(za, zb) >= 0.0 or max(za, zb) <= 0.0:
            continue
        if any(abs(a - b) > 1e-9 for a, b in zip(m.end_a_m[:2], m.end_b_m[:2])):
            raise ConfigError(f"member {m.name}: only vertical members may cross the water line")
        x, y = m.end_a_m[:2]
        if m.section == "circular":
            a = math.pi * m.width_m**2 / 4
            i_xx = i_yy = math.pi * m.width_m**4 / 64
        else:  # width along x, height along y for a vertical member
            a = m.width_m * m.height_m
            i_xx, i_yy = m.width_m * m.height_m**3 / 12, m.height_m * m.width_m**3 / 12
        area += a
        first += a * np.array([x, y])
        second += np.array([[i_xx + a * y * y, a * x * y], [a * x * y, i_yy + a * x * x]])
    return area, first, second


def hydrostatics(platform: Platform, strips: Strips) -> Hydrostatics:
    env = platform.environment
    rho_g = env.water_density_kg_m3 * env.gravity_m_s2
    submerged = strips.centre_m[:, 2] < 0.0  # strips are cut at the water line
    volumes = strips.area_m2[submerged] * strips.length_m[submerged]
    volume = float(volumes.sum())
    centre = volumes @ strips.centre_m[submerged] / volume
    area, first, second = _waterplane(platform)
    c = np.zeros((6, 6))
    c[2, 2] = rho_g * area
    c[2, 3] = c[3, 2] = rho_g * first[1]
    c[2, 4] = c[4, 2] = -rho_g * first[0]
    c[3, 3] = rho_g * (second[0, 0] + volume * centre[2])
    c[3, 4] = c[4, 3] = -rho_g * second[0, 1]
    c[4, 4] = rho_g * (second[1, 1] + volume * centre[2])
    c[3, 5] = -rho_g * volume * centre[0]
    c[4, 5] = -rho_g * volume * centre[1]
    force = np.array([0.0, 0.0, rho_g * volume])
    wrench = np.concatenate([force, np.cross(centre, force)])
    return Hydrostatics(volume, centre, area, first, second, wrench, c)


# --------------------------------------------------------------------------- load component
def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[W0 (6), C (36)]."""
    h = inputs.hydrostatics
    return np.concatenate([h.buoyancy_wrench, h.stiffness.ravel()]), np.zeros((1, 1))


@njit(cache=True)
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    """W0 - C q, linear about the undisplaced position."""
    stiffness = params[6:42].reshape((6, 6))
    out += params[0:6] - stiffness @ y[0:6]
