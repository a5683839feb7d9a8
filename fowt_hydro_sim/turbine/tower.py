"""The wind's drag on the tower, as AeroDyn's ``TwrAero`` computes it: per unit length
1/2 rho Cd D |u| u, u the wind at the height less the tower's fore-aft velocity there, the
wind at height z the hub's times (z / hub height)^alpha (InflowWind's power law, ``PLexp``).
The tower's table (heights above the platform's reference point, diameters and drag
coefficients, linear between its rows: ``io.aerodyn.tower_table``) is integrated by
Gauss-Legendre on each of its segments; its points are computed once (``tower_points``),
each step costs a few array operations (``tower_drag``)."""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from fowt_hydro_sim.io.aerodyn import TowerTable

GAUSS_POINTS = 8  # per segment of the table: a power law's integral within 1e-7 on a 117 m segment


class TowerPoints(NamedTuple):
    """The quadrature of the tower: heights [m] above the platform's reference point,
    weights Cd D dz [m^2] and the wind's profile (z / hub height)^alpha at each point."""

    heights_m: np.ndarray
    areas_m2: np.ndarray
    profile: np.ndarray


def tower_points(table: TowerTable, hub_height_m: float, shear_exponent: float) -> TowerPoints:
    """The quadrature points of ``table`` (``GAUSS_POINTS`` per segment; the diameter and the
    drag coefficient linear along each) with the wind profile of ``shear_exponent`` about the hub."""
    nodes, weights = np.polynomial.legendre.leggauss(GAUSS_POINTS)
    z0, z1 = table.heights_m[:-1, None], table.heights_m[1:, None]
    half = 0.5 * (z1 - z0)
    heights = (z0 + half * (nodes + 1.0)).ravel()
    cd_d = np.interp(heights, table.heights_m, table.diameters_m) * np.interp(heights, table.heights_m,
                                                                              table.drag_coefficients)
    areas = (half * weights).ravel() * cd_d
    profile = np.clip(heights / hub_height_m, 0.0, None) ** shear_exponent
    return TowerPoints(heights, areas, profile)


def tower_drag(points: TowerPoints, air_density_kg_m3: float, hub_wind_m_s: float, velocity_m_s: float,
               pitch_rate_rad_s: float, about_height_m: float) -> tuple[float, float]:
    """The tower's drag [N] along the wind (body x) and its moment [N m] about body y at
    ``about_height_m``, the platform moving at ``velocity_m_s`` (body x, at its reference
    point) and pitching at ``pitch_rate_rad_s``."""
    return _drag(points.heights_m, points.areas_m2, points.profile, 0.5 * air_density_kg_m3, hub_wind_m_s,
                 velocity_m_s, pitch_rate_rad_s, about_height_m)


@njit(cache=True)
def _drag(heights: np.ndarray, areas: np.ndarray, profile: np.ndarray, half_rho: float, wind: float,
          velocity: float, rate: float, about: float) -> tuple[float, float]:
    force, moment = 0.0, 0.0
    for k in range(heights.size):
        u = wind * profile[k] - velocity - rate * heights[k]
        f = half_rho * areas[k] * abs(u) * u
        force += f
        moment += f * (heights[k] - about)
    return force, moment

