"""Hydrostatics from the member geometry, linear or nonlinear (``HydroOptions.hydrostatics``).

Linear: the buoyancy wrench is W0 - C q, W0 the static buoyancy (rho g V at the centre of
buoyancy) and C the buoyancy part of the restoring matrix (waterplane and centre-of-
buoyancy terms, WAMIT's convention).

Nonlinear (HydroDyn's member hydrostatics): rho g V_sub upward through the centroid of the
displaced members' part below z = 0, every member a closed prism or, tapered, a closed
frustum (end plates included). Each member's section is sampled by a quadrature (polar
Gauss for a circle, tensor Gauss for a rectangle); a sample's line runs from end a to end b
at the same fraction of the local radius (parallel to the axis for a prism), the local
area weight grows with the radius squared, and the submerged part of each line and the
integrals along it are exact. Wherever the water plane cuts the side wall only, the
integrand over the section is a polynomial of degree 3 at most, which the quadrature
integrates exactly, so volume and centroid are exact; where it also cuts an end, the error
is the quadrature's on a kinked integrand.

The step evaluates this member by member (``members_submerged_volume``): a member whose end
faces are all below the water plane adds its whole volume and moment (computed once), one
all above adds nothing, an untapered one cut through its side wall only uses a small rule
(``COARSE``: the integrands are then of degree 2, so it is exact too), any other the full
quadrature.

The nonlinear hydrostatics stop at the seabed (z = -water_depth_m), as HydroDyn's member
hydrostatics do (Morison.f90: no loads on a member's part below the seabed; a member that
crosses it, or ends on it from below, keeps only its upper end plate): a member's part below
the seabed displaces nothing, and the section where a member enters the seabed carries no
pressure (it is on the soil), so the buoyancy of that section, rho g depth times its
horizontal area, is taken off at it. A vertical pile through the seabed with its top at z_t
below the water line is thus pushed down by rho g A |z_t|, its top plate's pressure alone.
Where the model and HydroDyn part: a member whose bottom end sits exactly on the seabed with
no pile under it has no bottom-plate buoyancy here (HydroDyn applies that plate; here it
returns as soon as the bottom is above the seabed), and the cut is horizontal, so a pile
tilted from the vertical is exact only where HydroDyn's cut, normal to its axis, agrees (the
OC3 tripod's piles are vertical). The linear model's volume and the free-surface
hydrostatics take no seabed.

A rectangular member may taper (width and height each linear from end a to end b) and be
spun about its axis: its lines run at fixed fractions of the local half-sides along the spun
section directions, and the area weight grows as (1 + c_w f)(1 + c_h f) along the line (f
from 0 at end a to 1 at end b); where c_w != c_h that quadratic is three table rows on the same
line, the kernel's (1 + c f)^2 weights with c = 0, 1, -1. For a member tilted from the
vertical and tapered, the submerged length of a line is a rational function over the
section, not a polynomial: the quadrature is then not exact by construction, but the tests
find it at rounding (5e-15 against a direct integration) while the water plane cuts the side
walls only, and within 6.3e-3 where it also cuts the ends (the r-test's member).

The linear model's volume and centre of buoyancy are the strips' exact (frustum, prismatoid)
volumes. Its waterplane is that of vertical members crossing the water line (any section,
spin or taper); a platform with a tilted member through the water line has none, and asking
for linear hydrostatics then fails in one line (nonlinear and free_surface need none).

Gravity acts separately at the centre of gravity.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from fowt_hydro_sim.physics.config import ConfigError, Member, Platform
from fowt_hydro_sim.physics.fill import FILL_RECORD, fill_mass, fill_records, fill_wrench
from fowt_hydro_sim.physics.jit import step_loop
from fowt_hydro_sim.physics.strips import Strips, member_directions

N_RADIAL, N_ANGULAR, N_SIDE = 6, 24, 8  # section quadrature (circle: radial x angular; rectangle: side^2)
# where the water plane cuts a prism's side wall only, the integrands over the section are of
# degree 2 at most: a Gauss rule exact to degree 3 is exact there (circle: 3 Gauss radii x 4
# angles; rectangle: 2 x 2)
COARSE = (3, 4, 2)


@dataclass(frozen=True)
class Hydrostatics:
    displaced_volume_m3: float
    centre_of_buoyancy_m: np.ndarray
    waterplane_area_m2: float
    waterplane_first_moment_m3: np.ndarray  # (int x dA, int y dA)
    waterplane_second_moment_m4: np.ndarray  # [[int y^2, int xy], [int xy, int x^2]]
    buoyancy_wrench: np.ndarray  # (6,) at rest, about the reference point
    stiffness: np.ndarray  # (6, 6) buoyancy restoring matrix (NaN without a waterplane)
    waterplane_error: str | None = None  # why the platform has no linear waterplane, if it has none
    # marine growth's mass [kg], centroid (body) [m] and inertia about it [kg m^2] (physics/marine_growth.py)
    growth: tuple[float, np.ndarray, np.ndarray] = (0.0, np.zeros(3), np.zeros((3, 3)))
    # the fill's mass [kg], centroid (body) [m], inertia about it [kg m^2] and end-cap records (physics/fill.py)
    fill: tuple[float, np.ndarray, np.ndarray] = (0.0, np.zeros(3), np.zeros((3, 3)))
    fill_records: np.ndarray = field(default_factory=lambda: np.zeros((0, FILL_RECORD)))
    gravity_m_s2: float = 9.80665


def _waterplane(platform: Platform) -> tuple[float, np.ndarray, np.ndarray]:
    """Area, first moments (x, y) and second moments [[int y^2, int xy], [int xy, int x^2]]
    of the sections of the vertical members crossing z = 0; ConfigError for a tilted one."""
    area, first, second = 0.0, np.zeros(2), np.zeros((2, 2))
    for m in platform.members:
        if m.drag_only:  # its buoyancy is the potential flow's
            continue
        za, zb = m.end_a_m[2], m.end_b_m[2]
        if min(za, zb) >= 0.0 or max(za, zb) <= 0.0:
            continue
        if any(abs(a - b) > 1e-9 for a, b in zip(m.end_a_m[:2], m.end_b_m[:2])):
            raise ConfigError(f"member {m.name} crosses the water line tilted from the vertical: the linear "
                              "waterplane takes vertical members only")
        x, y = m.end_a_m[:2]
        w, h = m.sides_at(za / (za - zb))  # at z = 0
        if m.section == "circular":
            a = math.pi * w**2 / 4
            i_uu = i_vv = math.pi * w**4 / 64
        else:  # int u^2 dA (u along the width direction d1), int v^2 dA (v along d2)
            a = w * h
            i_uu, i_vv = h * w**3 / 12, w * h**3 / 12
        _, d1, d2 = member_directions(m)  # horizontal for a vertical member
        i_xx = d1[0] ** 2 * i_uu + d2[0] ** 2 * i_vv  # int x'^2 dA about the section's centre
        i_yy = d1[1] ** 2 * i_uu + d2[1] ** 2 * i_vv
        i_xy = d1[0] * d1[1] * i_uu + d2[0] * d2[1] * i_vv
        area += a
        first += a * np.array([x, y])
        second += np.array([[i_yy + a * y * y, i_xy + a * x * y], [i_xy + a * x * y, i_xx + a * x * x]])
    return area, first, second


def hydrostatics(platform: Platform, strips: Strips, growth: tuple[float, np.ndarray, np.ndarray] | None = None,
                 filled: Platform | None = None) -> Hydrostatics:
    """The platform's displaced volume, centre of buoyancy, waterplane and restoring matrix
    (strips: its discretisation); ``growth``: its marine growth's mass properties, and
    ``filled``: the platform whose fill groups the component carries (physics/fill.py; the
    platform before its members were grown)."""
    growth = growth or (0.0, np.zeros(3), np.zeros((3, 3)))
    carried = {"growth": growth, "gravity_m_s2": platform.environment.gravity_m_s2}
    if filled is not None and filled.fill_groups:
        carried.update(fill=fill_mass(filled), fill_records=fill_records(filled))
    env = platform.environment
    rho_g = env.water_density_kg_m3 * env.gravity_m_s2
    submerged = strips.centre_m[:, 2] < 0.0  # strips are cut at the water line
    volumes = strips.volume_m3[submerged]
    volume = float(volumes.sum())
    # (a potential-flow hull without Morison members displaces nothing here)
    centre = volumes @ strips.volume_centre_m[submerged] / volume if volume > 0 else np.zeros(3)
    try:
        area, first, second = _waterplane(platform)
    except ConfigError as exc:  # refused where linear hydrostatics are asked for (parameters)
        force = np.array([0.0, 0.0, rho_g * volume])
        return Hydrostatics(volume, centre, math.nan, np.full(2, math.nan), np.full((2, 2), math.nan),
                            np.concatenate([force, np.cross(centre, force)]), np.full((6, 6), math.nan), str(exc),
                            **carried)
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
    return Hydrostatics(volume, centre, area, first, second, wrench, c, None, **carried)


def section_quadrature(member: Member, fraction: float = 0.0,
                       sizes: tuple[int, int, int] = (N_RADIAL, N_ANGULAR, N_SIDE)) -> tuple[np.ndarray, np.ndarray]:
    """Offsets (k, 3; body frame, from the member's axis) and area weights (k,) of the
    section quadrature ``fraction`` of the way from end a to end b (the same points, scaled
    with the section): exact for polynomials of degree 3 over the section."""
    _, d1, d2 = member_directions(member)
    width, height = member.sides_at(fraction)
    if member.section == "circular":
        radius = width / 2
        n_radial, n_angular, n_side = sizes
        x, w = np.polynomial.legendre.leggauss(n_radial)
        r = radius * (x + 1) / 2
        theta = 2 * np.pi * (np.arange(n_angular) + 0.5) / n_angular
        u, v = np.outer(r, np.cos(theta)).ravel(), np.outer(r, np.sin(theta)).ravel()
        weights = np.outer(w * r * radius / 2, np.full(n_angular, 2 * np.pi / n_angular)).ravel()
    else:  # width along d1, height along d2 (strips.py), both spun
        n_side = sizes[2]
        x, w = np.polynomial.legendre.leggauss(n_side)
        u = np.repeat(x * width / 2, n_side)
        v = np.tile(x * height / 2, n_side)
        weights = np.outer(w * width / 2, w * height / 2).ravel()
    return np.outer(u, d1) + np.outer(v, d2), weights


def weight_rows(growth_width: float, growth_height: float) -> list[tuple[float, float]]:
    """(weight factor, ratio) rows whose (1 + (ratio - 1) f)^2 terms sum to the area growth
    (1 + c_w f)(1 + c_h f) along a line: one row if c_w = c_h (a circle, a uniform taper),
    else three with ratios 1, 2, 0 (1, (1 + f)^2, (1 - f)^2 span the quadratics)."""
    if growth_width == growth_height:
        return [(1.0, 1.0 + growth_width)]
    p1, p2 = growth_width + growth_height, growth_width * growth_height
    return [(1.0 - p2, 1.0), (p1 / 4 + p2 / 2, 2.0), (p2 / 2 - p1 / 4, 0.0)]


def member_lines(member: Member, sizes: tuple[int, int, int] = (N_RADIAL, N_ANGULAR, N_SIDE)) -> np.ndarray:
    """A member's quadrature lines as rows [start (3), start to end (3), axial length, area
    weight at end a, ratio], body frame. A line runs at a fixed fraction of the local radius
    (half-sides), so it is parallel to the axis unless the member is tapered; its area weight
    grows as (1 + (ratio - 1) f)^2 (``weight_rows``)."""
    a, b = np.array(member.end_a_m), np.array(member.end_b_m)
    (w0, h0), (w1, h1) = member.sides_at(0.0), member.sides_at(1.0)
    offsets_a, weights = section_quadrature(member, 0.0, sizes)
    offsets_b, _ = section_quadrature(member, 1.0, sizes)
    growth = weight_rows(w1 / w0 - 1.0, h1 / h0 - 1.0)
    return np.array([[*(a + offset_a), *(b + offset_b - a - offset_a), float(np.linalg.norm(b - a)), factor * weight,
                      ratio]
                     for offset_a, offset_b, weight in zip(offsets_a, offsets_b, weights) for factor, ratio in growth])


def _reach(member: Member) -> float:
    """The largest distance of a point of an end face from the member's axis."""
    return max(math.hypot(*member.sides_at(f)) if member.section == "rectangular" else member.sides_at(f)[0]
               for f in (0.0, 1.0)) / 2


# a member's record in the nonlinear hydrostatics' parameters
FIRST_FINE, N_FINE, FIRST_COARSE, N_COARSE, END_A, END_B, REACH, VOLUME, MOMENT, SEABED = (0, 1, 2, 3, 4, 7, 10, 11,
                                                                                         12, 15)
RECORD = 16


def member_records(platform: Platform) -> tuple[np.ndarray, np.ndarray]:
    """Per member, a record (RECORD floats: where its fine and coarse lines are in the table,
    its end centres, reach, whole volume and its first moment, body frame, and the seabed's z,
    world) and the table of every member's fine then coarse lines (a tapered member's coarse
    lines are its fine ones: its integrands are not polynomials)."""
    records, tables, first = [], [], 0
    for m in platform.members:
        if m.drag_only:  # its buoyancy is the potential flow's
            continue
        fine = member_lines(m)
        coarse = fine if m.tapered else member_lines(m, COARSE)
        volume, moment = submerged_volume(np.eye(3), -np.inf, fine)  # wholly under water
        record = np.zeros(RECORD)
        record[[FIRST_FINE, N_FINE]] = first, len(fine)
        record[[FIRST_COARSE, N_COARSE]] = (first, len(fine)) if m.tapered else (first + len(fine), len(coarse))
        record[END_A:END_A + 3], record[END_B:END_B + 3] = m.end_a_m, m.end_b_m
        record[REACH], record[VOLUME], record[MOMENT:MOMENT + 3] = _reach(m), volume, moment
        record[SEABED] = -platform.environment.water_depth_m
        records.append(record)
        tables += [fine] if m.tapered else [fine, coarse]
        first += len(fine) + (0 if m.tapered else len(coarse))
    if not records:  # no member: nothing displaced
        return np.zeros(0), np.zeros((1, 9))
    return np.concatenate(records), np.concatenate(tables)


@njit(cache=True, inline="always")
def _weight_integrals(c: float, f: float) -> tuple[float, float]:
    """int_0^f (1 + c u)^2 du and int_0^f u (1 + c u)^2 du."""
    return (f + c * f * f + c * c * f * f * f / 3.0,
            f * f / 2.0 + 2.0 * c * f * f * f / 3.0 + c * c * f * f * f * f / 4.0)


@njit(cache=True)
def submerged_volume(rotation: np.ndarray, position_z_m: float, lines: np.ndarray) -> tuple[float, np.ndarray]:
    """Volume below z = 0 of the quadrature lines' members at the pose, and its first moment
    (body frame); no seabed."""
    volume, m0, m1, m2 = _add_lines(rotation, position_z_m, lines, 0, lines.shape[0], (0.0, 0.0, 0.0, 0.0), -np.inf)
    return volume, np.array([m0, m1, m2])


@njit(cache=True)
def members_submerged_volume(rotation: np.ndarray, position_z_m: float, records: np.ndarray,
                             lines: np.ndarray) -> tuple[float, np.ndarray]:
    """``submerged_volume`` member by member (``member_records``), between the seabed and z = 0:
    a member whose end faces are all between them adds its whole volume, one all above the
    water plane or all below the seabed nothing, one cut through its side wall by the water
    plane only its coarse lines, any other its fine lines. Where a member enters the seabed,
    the section it is cut by there carries no pressure (soil, not water, is under it): its
    buoyancy is taken off as a negative volume, the seabed's depth times the cut's area, at the
    cut (``_add_lines``)."""
    volume, moment = _members_volume(rotation, position_z_m, records, lines)
    return volume, np.array(moment)


@step_loop
def _members_volume(rotation: np.ndarray, position_z_m: float, records: np.ndarray,
                    lines: np.ndarray) -> tuple[float, tuple[float, float, float]]:
    """``members_submerged_volume`` with the moment as a tuple (no array made)."""
    total = (0.0, 0.0, 0.0, 0.0)  # volume and first moment
    for k in range(records.size // RECORD):
        r = records[k * RECORD:(k + 1) * RECORD]
        z_a = position_z_m + rotation[2, 0] * r[END_A] + rotation[2, 1] * r[END_A + 1] + rotation[2, 2] * r[END_A + 2]
        z_b = position_z_m + rotation[2, 0] * r[END_B] + rotation[2, 1] * r[END_B + 1] + rotation[2, 2] * r[END_B + 2]
        reach, seabed = r[REACH], r[SEABED]
        low, high = min(z_a, z_b), max(z_a, z_b)
        if high + reach < 0.0 and low - reach > seabed:
            total = (total[0] + r[VOLUME], total[1] + r[MOMENT], total[2] + r[MOMENT + 1], total[3] + r[MOMENT + 2])
        elif low - reach > 0.0 or high + reach < seabed:
            continue
        elif low + reach < 0.0 and high - reach > 0.0 and low - reach > seabed:
            total = _add_lines(rotation, position_z_m, lines, int(r[FIRST_COARSE]), int(r[N_COARSE]), total, seabed)
        else:
            total = _add_lines(rotation, position_z_m, lines, int(r[FIRST_FINE]), int(r[N_FINE]), total, seabed)
    return total[0], (total[1], total[2], total[3])


@step_loop
def _add_lines(rotation: np.ndarray, position_z_m: float, lines: np.ndarray, first: int, count: int,
               total: tuple[float, float, float, float], seabed_z_m: float) -> tuple[float, float, float, float]:
    """``total`` (volume, first moment) plus the volume of lines[first:first + count] between
    the seabed (z = seabed_z_m; -inf: none) and z = 0 and its first moment (the lines' volume
    summed on its own first). A line that starts (or ends) at or below the seabed and reaches
    above it adds minus the seabed's depth times its horizontal area there, at that point: the
    pressure on the seabed cut, which is on the soil, taken off."""
    volume, (m0, m1, m2) = 0.0, total[1:]
    free = seabed_z_m == -np.inf
    for q in range(first, first + count):
        line = lines[q]
        z0 = position_z_m + rotation[2, 0] * line[0] + rotation[2, 1] * line[1] + rotation[2, 2] * line[2]
        rise = rotation[2, 0] * line[3] + rotation[2, 1] * line[4] + rotation[2, 2] * line[5]  # over the line
        cut = -1.0  # the fraction along the line where it enters the seabed, if it does
        if abs(rise) < 1e-12:
            low, high = (0.0, 1.0) if z0 < 0.0 and (free or z0 > seabed_z_m) else (0.0, 0.0)
        elif rise > 0.0:
            low, high = 0.0, min(1.0, max(0.0, -z0 / rise))
            if not free and z0 <= seabed_z_m:
                low = cut = min(1.0, (seabed_z_m - z0) / rise)
        else:
            low, high = min(1.0, max(0.0, -z0 / rise)), 1.0
            if not free and z0 + rise <= seabed_z_m:
                high = cut = max(0.0, (seabed_z_m - z0) / rise)
        if high <= low:
            continue
        c = line[8] - 1.0  # the radius grows as 1 + c f along the line, the area weight as its square
        v_high, m_high = _weight_integrals(c, high)
        v_low, m_low = _weight_integrals(c, low)
        scale = line[6] * line[7]
        wet, first_moment = scale * (v_high - v_low), scale * (m_high - m_low)
        volume += wet
        m0 += wet * line[0] + first_moment * line[3]
        m1 += wet * line[1] + first_moment * line[4]
        m2 += wet * line[2] + first_moment * line[5]
        if cut >= 0.0:  # depth times the horizontal area of the line's tube at the cut (its volume per unit rise)
            plate = seabed_z_m * scale * (1.0 + c * cut) ** 2 / abs(rise)
            volume += plate
            m0 += plate * (line[0] + cut * line[3])
            m1 += plate * (line[1] + cut * line[4])
            m2 += plate * (line[2] + cut * line[5])
    return total[0] + volume, m0, m1, m2


# --------------------------------------------------------------------------- load component
# free_surface: the kernel computes the linear load; PlatformModel.prescribed_motion_loads replaces it
MODES = {"linear": 0.0, "nonlinear": 1.0, "free_surface": 0.0}


GROWTH = 44  # params[44:61]: the carried mass (marine growth and fill): mass, the growth's weight, the mass's
# centroid (3), its inertia about it (9), the growth's centroid (3, where its weight acts)
FILL = 61  # params[61]: the number of filled members, then their records (physics/fill.py)


@njit(cache=True, inline="always")
def records_start(params: np.ndarray) -> int:
    """Where the nonlinear hydrostatics' member records start in the parameters."""
    return FILL + 1 + FILL_RECORD * int(params[FILL])


def carried_mass(h: Hydrostatics) -> np.ndarray:
    """The marine growth and the fill as one rigid body, and the growth's weight: the
    parameters' block at GROWTH."""
    (mg, cg, ig), (mf, cf, i_f) = h.growth, h.fill
    mass = mg + mf
    if mass <= 0.0:
        return np.zeros(FILL - GROWTH)
    centre = (mg * cg + mf * cf) / mass
    inertia = np.zeros((3, 3))
    for m, c, i in ((mg, cg, ig), (mf, cf, i_f)):
        d = np.asarray(c) - centre
        inertia += i + m * (d @ d * np.eye(3) - np.outer(d, d))
    return np.concatenate([[mass, mg * h.gravity_m_s2], centre, np.ravel(inertia), cg])


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[mode (0 linear, 1 nonlinear), rho g, W0 (6), C (36), the carried mass (17), the fill's
    records (a count, then FILL_RECORD each), and, nonlinear, the member records] and,
    nonlinear, the quadrature lines (member_records)."""
    h, env = inputs.hydrostatics, inputs.platform.environment
    mode = inputs.options.hydrostatics
    if mode == "linear" and h.waterplane_error:
        raise ConfigError(f"hydrostatics 'linear': {h.waterplane_error}; use nonlinear or free_surface")
    linear = (h.buoyancy_wrench, h.stiffness.ravel()) if mode == "linear" else (np.zeros(6), np.zeros(36))
    fill = [[len(h.fill_records)], np.ravel(h.fill_records)]
    params = np.concatenate([[MODES[mode], env.water_density_kg_m3 * env.gravity_m_s2], *linear, carried_mass(h),
                             *fill])
    if mode != "nonlinear":
        return params, np.zeros((1, 1))
    records, lines = member_records(inputs.platform)
    return np.concatenate([params, records]), lines


@njit(cache=True)
def carried_wrench(y: np.ndarray, rotation: np.ndarray, params: np.ndarray, out: np.ndarray,
                   mass: np.ndarray) -> None:
    """The marine growth's weight and the fill's end-cap loads (physics/fill.py) into ``out``,
    and the rigid-body mass of both (HydroDyn's F_IMG and F_If) into ``mass`` with its
    velocity terms into ``out``; ``params`` the hydrostatic component's."""
    if params[GROWTH] > 0.0:
        growth_wrench(y, rotation, params[GROWTH:FILL], out, mass)
    if params[FILL] > 0.0:
        fill_wrench(y, rotation, params[FILL + 1:records_start(params)], out)


@njit(cache=True)
def growth_wrench(y: np.ndarray, rotation: np.ndarray, growth: np.ndarray, out: np.ndarray,
                  mass: np.ndarray) -> None:
    """The carried mass's rigid-body mass matrix about the reference point (world axes) into
    ``mass`` and its velocity terms (-bias) into ``out``, and the marine growth's weight at its
    displaced centroid: HydroDyn's F_WMG, F_IMG and F_If. (Written out: no temporaries in the
    step loop.)"""
    m, weight = growth[0], growth[1]
    g0 = rotation[0, 0] * growth[2] + rotation[0, 1] * growth[3] + rotation[0, 2] * growth[4]
    g1 = rotation[1, 0] * growth[2] + rotation[1, 1] * growth[3] + rotation[1, 2] * growth[4]
    g2 = rotation[2, 0] * growth[2] + rotation[2, 1] * growth[3] + rotation[2, 2] * growth[4]
    p0 = rotation[0, 0] * growth[14] + rotation[0, 1] * growth[15] + rotation[0, 2] * growth[16]
    p1 = rotation[1, 0] * growth[14] + rotation[1, 1] * growth[15] + rotation[1, 2] * growth[16]
    w0, w1, w2 = y[9], y[10], y[11]
    for i in range(3):  # R I_c R^T into the rotational block
        for j in range(3):
            acc = 0.0
            for k in range(3):
                for n in range(3):
                    acc += rotation[i, k] * growth[5 + 3 * k + n] * rotation[j, n]
            mass[3 + i, 3 + j] = acc
    iw0 = mass[3, 3] * w0 + mass[3, 4] * w1 + mass[3, 5] * w2
    iw1 = mass[4, 3] * w0 + mass[4, 4] * w1 + mass[4, 5] * w2
    iw2 = mass[5, 3] * w0 + mass[5, 4] * w1 + mass[5, 5] * w2
    skew = ((0.0, -g2, g1), (g2, 0.0, -g0), (-g1, g0, 0.0))
    for i in range(3):
        for j in range(3):
            mass[i, j] = m if i == j else 0.0
            mass[i, 3 + j] = -m * skew[i][j]
            mass[3 + i, j] = m * skew[i][j]
            mass[3 + i, 3 + j] -= m * (skew[i][0] * skew[0][j] + skew[i][1] * skew[1][j] + skew[i][2] * skew[2][j])
    # centripetal w x (w x g), gyroscopic w x (I w), and g x centripetal; the weight at the growth's centroid
    wg0, wg1, wg2 = w1 * g2 - w2 * g1, w2 * g0 - w0 * g2, w0 * g1 - w1 * g0
    c0, c1, c2 = w1 * wg2 - w2 * wg1, w2 * wg0 - w0 * wg2, w0 * wg1 - w1 * wg0
    out[0] -= m * c0
    out[1] -= m * c1
    out[2] -= m * c2 + weight
    out[3] -= (w1 * iw2 - w2 * iw1) + m * (g1 * c2 - g2 * c1) + p1 * weight
    out[4] -= (w2 * iw0 - w0 * iw2) + m * (g2 * c0 - g0 * c2) - p0 * weight
    out[5] -= (w0 * iw1 - w1 * iw0) + m * (g0 * c1 - g1 * c0)


@step_loop
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    """Linear: W0 - C q about the undisplaced position. Nonlinear: rho g V_sub through the
    displaced centre of buoyancy, about the displaced reference point. Either with the marine
    growth's weight, the fill's end-cap loads and their mass, if any."""
    carried_wrench(y, rotation, params, out, mass)
    if params[0] == 0.0:
        for i in range(6):  # written out: no temporaries in the step loop
            acc = params[2 + i]
            for j in range(6):
                acc -= params[8 + 6 * i + j] * y[j]
            out[i] += acc
        return
    volume, moment = _members_volume(rotation, y[2], params[records_start(params):], table)
    if volume <= 0.0:
        return
    force = params[1] * volume
    # the centre of buoyancy's lever arm R m / V (world axes) crossed with (0, 0, force)
    arm0 = (rotation[0, 0] * moment[0] + rotation[0, 1] * moment[1] + rotation[0, 2] * moment[2]) / volume
    arm1 = (rotation[1, 0] * moment[0] + rotation[1, 1] * moment[1] + rotation[1, 2] * moment[2]) / volume
    out[2] += force
    out[3] += arm1 * force
    out[4] -= arm0 * force
