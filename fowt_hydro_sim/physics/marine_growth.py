"""Marine growth as HydroDyn applies it (``Morison.f90``: SetNodeMG, SetMemberProperties and the
marine-growth loads of CalcOutput), from the platform's ``marine_growth`` table (HydroDyn's
MGDepths: height z, thickness t, density rho_mg by row, highest first).

* Thickness and density at a height z: linear between the two rows around z, none outside the
  table (SetNodeMG), taken at the member's nodes as HydroDyn places them (ceil(L / MDivSize)
  equal elements, MDivSize the member's strip length), the grown radius R + t linear between
  them (HydroDyn's RMG): over the element that holds a table end it tapers from bare to grown,
  and that taper carries the tapered wall's axial terms (pressure, added mass AxCa, drag: the
  member's ``taper_axial``), as HydroDyn's dRdl_mg terms. A member is cut at the nodes where
  its thickness changes slope.
* The grown outer radius R + t replaces R in every load HydroDyn gives it to: drag, added
  mass, fluid inertia, and the hydrostatics (the buoyancy of the growth layer included, as
  HydroDyn's RMG in its buoyancy), the tapered wall's axial terms on d(R + t)/dl. Each piece
  is a (tapered) circular member of diameters D + 2 t at its ends, and takes the member's
  ``growth_zone`` coefficients (HydroDyn's CdMG, CaMG, CpMG ...) where it carries growth (the
  taper from bare to grown included: HydroDyn's coefficients there are per node), its own
  zones elsewhere.
* The growth's mass, rho_mg times the layer's volume (each element of the density at its
  lower node, as HydroDyn lumps it), and at each joint with end effects rho_mg t |An| (HydroDyn's
  Mass_MG_End, |An| the area of the joint's summed ends), is carried by the body: its weight
  -m g at the layer's centroid and its rigid-body inertia (HydroDyn's F_WMG and F_IMG: the
  growth moves with the member) belong to the hydrostatic load component (its row holds
  the weight, and the reaction -M a of the growth's mass matrix), as they belong to
  HydroDyn's output loads. Members modelled by potential flow (``drag_only``, PropPot) get
  the grown drag diameter but no growth mass (HydroDyn skips their growth loads too).

Circular members only; a rectangular member the growth reaches, or a MacCamy-Fuchs member
(its correction's ka takes the bare diameter), is refused in one line.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from fowt_hydro_sim.physics.config import ConfigError, EndPlate, MarineGrowthLevel, Member, Platform

# Gauss-Legendre nodes and weights on [0, 1] (exact to degree 9): the layer's mass, first
# and second moments along a piece (polynomials of degree <= 5 in the fraction)
_NODES, _WEIGHTS = (lambda x, w: ((x + 1) / 2, w / 2))(*np.polynomial.legendre.leggauss(5))


def thickness_and_density(table: tuple[MarineGrowthLevel, ...], z_m: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The growth's thickness and density at heights ``z_m``: linear between the rows around
    each height, 0 outside the table (HydroDyn's SetNodeMG)."""
    z = np.atleast_1d(np.asarray(z_m, dtype=float))
    if not table:
        return np.zeros_like(z), np.zeros_like(z)
    heights = np.array([r.z_m for r in table])[::-1]  # increasing
    inside = (z >= heights[0]) & (z <= heights[-1])
    t = np.interp(z, heights, [r.thickness_m for r in table][::-1])
    rho = np.interp(z, heights, [r.density_kg_m3 for r in table][::-1])
    return np.where(inside, t, 0.0), np.where(inside, rho, 0.0)


def _nodes(member: Member, table: tuple[MarineGrowthLevel, ...]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The member's nodes as HydroDyn places them, ceil(L / MDivSize) equal elements (MDivSize: the
    member's strip length): their fractions along the member from end a, and the growth's
    thickness and density at each (SetNodeMG)."""
    a, b = np.array(member.end_a_m), np.array(member.end_b_m)
    n = max(1, math.ceil(float(np.linalg.norm(b - a)) / member.strip_length_m - 1e-9))
    fractions = np.linspace(0.0, 1.0, n + 1)
    thickness, density = thickness_and_density(table, a[2] + fractions * (b[2] - a[2]))
    return fractions, thickness, density


def _grows(member: Member, table: tuple[MarineGrowthLevel, ...]) -> bool:
    """Whether the growth reaches any of the member's nodes."""
    return bool(np.any(_nodes(member, table)[1] > 0))


def grown_platform(platform: Platform) -> Platform:
    """The platform with each member the growth reaches cut at the table's rows into circular
    members of the grown diameters (the table kept; a platform without growth unchanged)."""
    table = platform.marine_growth
    if not table:
        return platform
    members = []
    for member in platform.members:
        if not _grows(member, table):
            members.append(member)
            continue
        if member.section != "circular":
            raise ConfigError(f"member {member.name}: marine growth on a rectangular member is not supported")
        if member.maccamy_fuchs:
            raise ConfigError(f"member {member.name}: marine growth on a MacCamy-Fuchs member is not supported")
        members.extend(_pieces(member, table))
    return dataclasses.replace(platform, members=tuple(members))


def _pieces(member: Member, table: tuple[MarineGrowthLevel, ...]) -> list[Member]:
    """The member cut where its nodal thickness changes slope: each piece's grown radius is
    linear, R + t between the nodes' thicknesses, as HydroDyn's RMG is between its nodes."""
    a, b = np.array(member.end_a_m), np.array(member.end_b_m)
    fractions, thickness, _ = _nodes(member, table)
    bends = np.abs(np.diff(thickness, 2)) > 1e-12  # at the inner nodes
    cuts = np.concatenate([[0], 1 + np.flatnonzero(bends), [fractions.size - 1]])
    pieces = []
    for k, (i, j) in enumerate(zip(cuts[:-1], cuts[1:])):
        s0, s1, t0, t1 = fractions[i], fractions[j], thickness[i], thickness[j]
        d0, d1 = member.diameter_at(s0) + 2 * t0, member.diameter_at(s1) + 2 * t1
        tapered = abs(d1 - d0) > 1e-12
        grown = max(t0, t1) > 0
        zones = (member.growth_zone,) if grown and member.growth_zone is not None else member.zones
        pieces.append(dataclasses.replace(
            member, name=f"{member.name}:{k + 1}", end_a_m=tuple(a + s0 * (b - a)), end_b_m=tuple(a + s1 * (b - a)),
            width_m=d0, height_m=d0, diameter_b_m=d1 if tapered else None, zones=zones,
            taper_axial=member.taper_axial if tapered else EndPlate(0.0, 1.0, 0.0), growth_zone=None,
            end_a_plate=member.end_a_plate if k == 0 else None,
            end_b_plate=member.end_b_plate if k == len(cuts) - 2 else None))
    return pieces


def _end_mass(member: Member, plate: EndPlate | None, end: np.ndarray, fraction: float,
              table: tuple[MarineGrowthLevel, ...]) -> float:
    """The growth's mass at a member end that carries a plate (HydroDyn's joint mass
    MGdens tMG |An|, ``Mass_MG_End``): the growth's density and thickness at the end times the
    area of the joint's summed ends (``joint_area_m2``) or of the end's own grown section."""
    if plate is None:
        return 0.0
    t, rho = (float(v[0]) for v in thickness_and_density(table, [end[2]]))
    if plate.joint_area_m2 is not None:
        area = float(np.linalg.norm(plate.joint_area_m2))
    else:
        area = math.pi * (member.diameter_at(fraction) / 2 + t) ** 2
    return rho * t * area


def growth_mass(platform: Platform) -> tuple[float, np.ndarray, np.ndarray]:
    """The growth's mass [kg], centroid (body frame) [m] and inertia about it [kg m^2] of the
    platform's members as given (not yet grown): the layer between R and R + t, t linear between
    the member's nodes, integrated element by element, each element of the density at its lower
    node (HydroDyn's MarineGrowthPartSegmentCyl takes MGDensity(i) for both halves of element i,
    its node i the lower), and at each member end with a plate (a joint's end effects) the
    joint's growth mass MGdens tMG |An| as a point mass (HydroDyn's Mass_MG_End; its small
    rotational inertia, I_MG_End, left out). A joint whose ends cancel has no plate and HydroDyn's
    |An| vanishes there; one whose axial coefficients are all 0 has no plate either, and its growth
    end mass is then not carried."""
    table = platform.marine_growth
    total, first, second = 0.0, np.zeros(3), np.zeros((3, 3))
    for member in platform.members:
        if not table or member.drag_only or member.section != "circular" or not _grows(member, table):
            continue
        a, b = np.array(member.end_a_m), np.array(member.end_b_m)
        length = float(np.linalg.norm(b - a))
        axis = (b - a) / length
        fractions, thickness, density = _nodes(member, table)
        for i in range(fractions.size - 1):
            s0, s1 = fractions[i], fractions[i + 1]
            s = s0 + _NODES * (s1 - s0)
            points = a + np.outer(s, b - a)
            t = thickness[i] + (thickness[i + 1] - thickness[i]) * _NODES
            rho = density[i] if a[2] <= b[2] else density[i + 1]
            r_in = np.array([member.diameter_at(x) / 2 for x in s])
            r_out = r_in + t
            dm = rho * math.pi * (r_out**2 - r_in**2) * _WEIGHTS * (s1 - s0) * length  # per node's share
            total += dm.sum()
            first += dm @ points
            # each slice: a ring (axial (Ro^2 + Ri^2)/2, transverse (Ro^2 + Ri^2)/4) at its point
            ring = dm * (r_out**2 + r_in**2) / 4
            local = np.sum(ring) * (np.eye(3) - np.outer(axis, axis)) + 2 * np.sum(ring) * np.outer(axis, axis)
            second += local + sum(m * (p @ p * np.eye(3) - np.outer(p, p)) for m, p in zip(dm, points))
        for plate, end, fraction in ((member.end_a_plate, a, 0.0), (member.end_b_plate, b, 1.0)):
            mass = _end_mass(member, plate, end, fraction, table)
            total += mass
            first += mass * end
            second += mass * (end @ end * np.eye(3) - np.outer(end, end))
    if total <= 0:
        return 0.0, np.zeros(3), np.zeros((3, 3))
    centroid = first / total
    inertia = second - total * (centroid @ centroid * np.eye(3) - np.outer(centroid, centroid))
    return total, centroid, inertia
