"""The turbine side of a coupled run: its channels' statistics, spectra and fatigue, and the
tower-base fore-aft bending moment from the rigid-body loads.

The tower-base moment is what the rigid structure above the tower base (tower, yaw bearing,
nacelle, hub, parked blades: mass m, centre of mass c, pitch inertia I about c, from the
platform's OpenFAST ElastoDyn deck, ``above_tower_base``) puts on the base, about the body
y axis (positive as a downwind thrust bends it), in the fore-aft plane:

    M = T (h_z - z_b) + (c_z - z_b) m (g sin(theta) - a_x) - c_x m (-g cos(theta) - a_z) - I theta''

with T the rotor thrust along the body x axis at the thrust point h, z_b the tower base's
height above the platform's reference point, theta the platform pitch and (a_x, a_z) the
centre of mass's acceleration in body axes: (cos(theta) x'' - sin(theta) z'' + c_z theta''
- c_x theta'^2, sin(theta) x'' + cos(theta) z'' - c_x theta'' - c_z theta'^2). In a steady
thrust with the platform at rest it is T (h_z - z_b) + m g c_x. Left out: the tower's and
blades' elastic deflection (the structure is rigid), roll and yaw, the rotor's gyroscopic
and aerodynamic moments other than the thrust.

A channel's damage-equivalent load (DEL) is ``studies.tensions.damage_equivalent_load``
(rainflow, 1 Hz equivalent cycles over the analysed time) with S-N slope ``TOWER_SN_SLOPE``,
m = 10, that of welded steel in the tower (the mooring tensions use m = 3).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from fowt_hydro_sim.physics.config import Platform
from fowt_hydro_sim.studies.tensions import DEL_FREQUENCY_HZ, damage_equivalent_load

if TYPE_CHECKING:
    from fowt_hydro_sim.studies.coupled_run import CoupledRecord

TOWER_SN_SLOPE = 10.0  # S-N slope of the steel tower's DEL


@dataclass(frozen=True)
class AboveTowerBase:
    """The rigid structure above the tower base: the base's height above the platform's
    reference point, its mass, centre of mass (x, z from the reference point) and pitch
    inertia about it."""

    base_height_m: float
    mass_kg: float
    cog_x_m: float
    cog_z_m: float
    iyy_kg_m2: float


def elastodyn_deck(platform: Platform) -> Path | None:
    """The platform's OpenFAST ElastoDyn deck: ``*_ElastoDyn.dat`` in the folder of its
    potential-flow data's folder (the OpenFAST model's folder, as ``volturnus_s`` ships it);
    None if it has none."""
    if platform.potential_flow is None:
        return None
    decks = sorted(Path(platform.potential_flow.wamit_root).parent.parent.glob("*_ElastoDyn.dat"))
    return decks[0] if decks else None


def above_tower_base(platform: Platform) -> AboveTowerBase | None:
    """The structure above the tower base from the platform's ElastoDyn deck
    (``io.elastodyn.system_mass_properties`` less the platform's own mass); None without a
    deck."""
    from fowt_hydro_sim.io.elastodyn import deck_fields, deck_number, system_mass_properties
    deck = elastodyn_deck(platform)
    if deck is None:
        return None
    fields, _ = deck_fields(deck)
    num = lambda name: deck_number(fields, name, deck)  # noqa: E731
    ref = np.array([num("PtfmRefxt"), num("PtfmRefyt"), num("PtfmRefzt")])
    blade = deck.parent / Path(fields["BldFile1"]).name  # the blade file kept beside the deck (its PROVENANCE)
    whole = system_mass_properties(deck, blade if blade.is_file() else None)
    total, centre = whole.mass_kg, np.array(whole.cog_m)
    own, at = num("PtfmMass"), np.array([num("PtfmCMxt"), num("PtfmCMyt"), num("PtfmCMzt")]) - ref
    mass = total - own
    cog = (total * centre - own * at) / mass
    about_origin = (whole.inertia_about_cog_kg_m2[1][1] + total * (centre[0] ** 2 + centre[2] ** 2)
                    - num("PtfmPIner") - own * (at[0] ** 2 + at[2] ** 2))
    return AboveTowerBase(num("TowerBsHt") - float(ref[2]), float(mass), float(cog[0]), float(cog[2]),
                          float(about_origin - mass * (cog[0] ** 2 + cog[2] ** 2)))


def tower_base_moment(motion: np.ndarray, velocity: np.ndarray, acceleration: np.ndarray, thrust_n: np.ndarray,
                      above: AboveTowerBase, thrust_point_m: tuple[float, float], gravity_m_s2: float = 9.80665,
                      ) -> np.ndarray:
    """The tower-base fore-aft bending moment [N m] at each row (module docstring) from the
    platform's motion, velocity and acceleration (n, 6: surge ... yaw, angles in rad), the
    thrust [N] at ``thrust_point_m`` (x, z from the reference point, body axes)."""
    theta, rate, spin = motion[:, 4], velocity[:, 4], acceleration[:, 4]
    cos, sin = np.cos(theta), np.sin(theta)
    cx, cz, zb, m, g = above.cog_x_m, above.cog_z_m, above.base_height_m, above.mass_kg, gravity_m_s2
    ax = cos * acceleration[:, 0] - sin * acceleration[:, 2] + cz * spin - cx * rate**2
    az = sin * acceleration[:, 0] + cos * acceleration[:, 2] - cx * spin - cz * rate**2
    return (thrust_n * (thrust_point_m[1] - zb) + (cz - zb) * m * (g * sin - ax) - cx * m * (-g * cos - az)
            - above.iyy_kg_m2 * spin)


def channel_row(name: str, x: np.ndarray, duration_s: float, slope: float = TOWER_SN_SLOPE) -> dict:
    """A channel's mean, STD, maximum and DEL (S-N slope ``slope``, 1 Hz equivalent over
    ``duration_s``)."""
    return {"quantity": name, "mean": float(x.mean()), "std": float(x.std()), "max": float(x.max()),
            "del": damage_equivalent_load(x, duration_s, slope), "sn_slope": slope,
            "del_frequency_hz": DEL_FREQUENCY_HZ, "analysed_s": duration_s}


# a sweep row's tower-base moment columns
TOWER_METRICS = ("tower_base_moment_mean_nm", "tower_base_moment_std_nm", "tower_base_moment_max_nm",
                 "tower_base_moment_del_nm")


def tower_base_metrics(time_s: np.ndarray, rows: CoupledRecord, platform: Platform, thrust_height_m: float,
                       transient_s: float) -> dict[str, float]:
    """A sweep row's tower-base moment columns (``TOWER_METRICS``): mean, STD,
    maximum and DEL after ``transient_s``; NaN for a platform without an ElastoDyn deck."""
    from fowt_hydro_sim.turbine.coupled import CHANNELS
    above = above_tower_base(platform)
    if above is None:
        return dict.fromkeys(TOWER_METRICS, math.nan)
    moment = tower_base_moment(rows.motion.motion, rows.velocity, rows.acceleration,
                               rows.channels[:, CHANNELS.index("thrust_n")], above,
                               (platform.hub_point_m[0], thrust_height_m), platform.environment.gravity_m_s2)
    keep = time_s >= time_s[0] + transient_s
    row = channel_row("tower_base_moment", moment[keep], float(time_s[keep][-1] - time_s[keep][0]))
    return dict(zip(TOWER_METRICS, (row["mean"], row["std"], row["max"], row["del"])))
