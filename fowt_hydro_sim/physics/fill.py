"""Filled (flooded) members as HydroDyn computes them (``Morison.f90``: SetMemberProperties_Cyl,
and Morison_CalcOutput's filled-buoyancy end loads and flooded-ballast inertia), from the
platform's ``fill_groups`` (HydroDyn's FillMList, FillFSLoc, FillDens) and each member's wall
(``wall_thickness_m``, HydroDyn's PropThck).

* The fill's extent: HydroDyn takes a member's lower end as its first node (the lower z; on a
  level member the lower x, then y) and its inner radius Rin = D / 2 - t, linear between the
  ends. A member whose top is at or below the fill's free surface z_f is filled whole
  (HydroDyn's memfloodstatus 1; its overfill z_ov = z_f - z_top); one whose bottom is at or
  above it holds none; in between it is filled from its bottom to l_fill = (z_f - z_bottom) /
  cos(phi) along its axis (memfloodstatus 2: the fill ends in a section normal to the axis).
* Its weight, as HydroDyn applies it: the fill's pressure on the inside of the member's end
  caps only (the side walls' share, the fill's weight across the axis, is not applied: its
  formula is commented out in that source). On the bottom cap the axial force
  -rho_f g pi Rin1^2 h along the member's axis k (h: the fill's height above the bottom's
  centre: z_ov + max(z_top - z_bottom, 0) at the displaced pose for a whole-filled member,
  l_fill k_z for a partly filled one) and the moment of the pressure's gradient across the
  tilted cap, rho_f g pi Rin1^4 / 4 (z x k); on the top cap of a whole-filled member
  +rho_f g pi Rin2^2 (z_ov + max(z_bottom - z_top, 0)) along k and -rho_f g pi Rin2^4 / 4 (z x k).
  A vertical member thus carries its fill's weight exactly, a tilted one the weight's
  component along its axis (times cos(phi)), a level one none. These loads follow the pose
  (``fill_wrench``) and belong to the hydrostatic load component, as the marine growth's
  weight does.
* Its inertia: the fill moves with the member (HydroDyn's F_If, the flooded ballast's mass
  and inertia lumped at the nodes, with the nodes' accelerations): its mass, centroid and
  inertia (``fill_mass``) join the marine growth's rigid-body mass on the hydrostatic
  component (the reaction -M a on the equations' mass side). HydroDyn's partly filled
  element takes its fill's length as the vertical z_f - z_node, not along the axis; here the
  fill is the frustum of length l_fill (the same on a vertical member).

Rectangular members cannot be filled (refused where the platform is read); members modelled by
potential flow (``drag_only``) are filled as any other, as HydroDyn fills them.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from fowt_hydro_sim.physics.config import Member, Platform

# a filled member's record: [whole (1) or partly (0) filled, bottom end (3), top end (3), body frame,
# rho_f g pi Rin^2 at the bottom and the top, rho_f g pi Rin^4 / 4 at the bottom and the top,
# the overfill z_ov (whole) and the fill's length along the axis l_fill (partly)]
FILL_RECORD = 13
_NODES, _WEIGHTS = (lambda x, w: ((x + 1) / 2, w / 2))(*np.polynomial.legendre.leggauss(5))


def _bottom_first(member: Member) -> tuple[np.ndarray, np.ndarray, float, float]:
    """The member's ends as HydroDyn orders them, lower first (z, then x, then y), and the
    inner radius at each."""
    a, b = np.array(member.end_a_m), np.array(member.end_b_m)
    ra, rb = member.inner_radius_at(0.0), member.inner_radius_at(1.0)
    if (a[2], a[0], a[1]) > (b[2], b[0], b[1]):
        return b, a, rb, ra
    return a, b, ra, rb


def filled_members(platform: Platform) -> list[tuple[Member, float, float]]:
    """(member, the fill's free-surface z [m], density [kg/m^3]) of every member of a fill group."""
    by_name = {m.name: m for m in platform.members}
    return [(by_name[name], group.free_surface_z_m, group.density_kg_m3)
            for group in platform.fill_groups for name in group.members]


def fill_extent(member: Member, free_surface_z_m: float) -> tuple[int, float, float]:
    """HydroDyn's flood status of a member (1: whole, 2: partly, 0: empty), its overfill z_ov
    [m] (whole) and the fill's length from the bottom along the axis l_fill [m]."""
    bottom, top, _, _ = _bottom_first(member)
    length = float(np.linalg.norm(top - bottom))
    if free_surface_z_m >= top[2]:
        return 1, free_surface_z_m - top[2], length
    if bottom[2] >= free_surface_z_m:
        return 0, 0.0, 0.0
    return 2, 0.0, (free_surface_z_m - bottom[2]) / ((top[2] - bottom[2]) / length)


def fill_records(platform: Platform) -> np.ndarray:
    """(n, FILL_RECORD): one record per member holding fill (``fill_wrench``'s)."""
    g = platform.environment.gravity_m_s2
    records = []
    for member, z_f, rho in filled_members(platform):
        status, overfill, length = fill_extent(member, z_f)
        if status == 0:
            continue
        bottom, top, r1, r2 = _bottom_first(member)
        records.append([1.0 if status == 1 else 0.0, *bottom, *top, rho * g * math.pi * r1**2,
                        rho * g * math.pi * r2**2, rho * g * math.pi * r1**4 / 4, rho * g * math.pi * r2**4 / 4,
                        overfill, length])
    return np.array(records, dtype=float).reshape(-1, FILL_RECORD)


def fill_mass(platform: Platform) -> tuple[float, np.ndarray, np.ndarray]:
    """The fill's mass [kg], centroid (body frame) [m] and inertia about it [kg m^2]: each
    member's fill a solid frustum of its inner radius from its bottom to l_fill, of the group's
    density."""
    total, first, second = 0.0, np.zeros(3), np.zeros((3, 3))
    for member, z_f, rho in filled_members(platform):
        status, _, length = fill_extent(member, z_f)
        if status == 0:
            continue
        bottom, top, r1, r2 = _bottom_first(member)
        full = float(np.linalg.norm(top - bottom))
        axis = (top - bottom) / full
        s = _NODES * length  # along the axis from the bottom
        points = bottom + np.outer(s, axis)
        r = r1 + (r2 - r1) * s / full
        dm = rho * math.pi * r**2 * _WEIGHTS * length
        total += dm.sum()
        first += dm @ points
        disc = dm * r**2 / 4  # a disc's inertia about a diameter; about its axis twice that
        second += np.sum(disc) * (np.eye(3) + np.outer(axis, axis))
        second += sum(m * (p @ p * np.eye(3) - np.outer(p, p)) for m, p in zip(dm, points))
    if total <= 0:
        return 0.0, np.zeros(3), np.zeros((3, 3))
    centroid = first / total
    return total, centroid, second - total * (centroid @ centroid * np.eye(3) - np.outer(centroid, centroid))


@njit(cache=True)
def fill_wrench(y: np.ndarray, rotation: np.ndarray, records: np.ndarray, out: np.ndarray) -> None:
    """The fill's pressure on the end caps (HydroDyn's F_BF_End) at state ``y``, world axes,
    about the displaced reference point, added to ``out``; ``records`` flat (FILL_RECORD each).
    (Written out: no temporaries in the step loop.)"""
    for k in range(records.size // FILL_RECORD):
        r = records[k * FILL_RECORD:(k + 1) * FILL_RECORD]
        b0 = rotation[0, 0] * r[1] + rotation[0, 1] * r[2] + rotation[0, 2] * r[3]
        b1 = rotation[1, 0] * r[1] + rotation[1, 1] * r[2] + rotation[1, 2] * r[3]
        b2 = rotation[2, 0] * r[1] + rotation[2, 1] * r[2] + rotation[2, 2] * r[3]
        t0 = rotation[0, 0] * r[4] + rotation[0, 1] * r[5] + rotation[0, 2] * r[6]
        t1 = rotation[1, 0] * r[4] + rotation[1, 1] * r[5] + rotation[1, 2] * r[6]
        t2 = rotation[2, 0] * r[4] + rotation[2, 1] * r[5] + rotation[2, 2] * r[6]
        length = math.sqrt((t0 - b0) ** 2 + (t1 - b1) ** 2 + (t2 - b2) ** 2)
        k0, k1, k2 = (t0 - b0) / length, (t1 - b1) / length, (t2 - b2) / length
        rise = t2 - b2  # z_top - z_bottom at the pose
        if r[0] > 0.0:  # whole: both caps, the head from the overfill
            f_bottom = -r[7] * (r[11] + max(rise, 0.0))
            f_top = r[8] * (r[11] + max(-rise, 0.0))
            couple = r[9] - r[10]
        else:  # partly: the bottom cap under the fill's height l_fill k_z
            f_bottom = -r[7] * r[12] * k2
            f_top = 0.0
            couple = r[9]
        f = f_bottom + f_top
        out[0] += f * k0
        out[1] += f * k1
        out[2] += f * k2
        # r x (f k) at each cap, and the caps' couples c (z x k) = c (-k1, k0, 0)
        out[3] += f_bottom * (b1 * k2 - b2 * k1) + f_top * (t1 * k2 - t2 * k1) - couple * k1
        out[4] += f_bottom * (b2 * k0 - b0 * k2) + f_top * (t2 * k0 - t0 * k2) + couple * k0
        out[5] += f_bottom * (b0 * k1 - b1 * k0) + f_top * (t0 * k1 - t1 * k0)
