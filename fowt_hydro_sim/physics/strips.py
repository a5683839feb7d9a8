"""Discretise the platform's members into Morison strips and end plates (body frame).

Each member is cut at its zone boundaries and at the still water line, then into equal
strips no longer than ``strip_length_m``. A strip carries its per-unit-length coefficients
in its two transverse directions: d1 (the section's width direction, horizontal for a
horizontal member) and d2 = axis x d1. Loads (HydroDyn's conventions, platform spec):

* fluid inertia   rho (A + Ca_k A_k) a_k      (Froude-Krylov + scattering, Cp = 1); for a member
                  flagged ``maccamy_fuchs``, rho A a_k with a the MacCamy-Fuchs acceleration
                  (waves/maccamy_fuchs.py: HydroDyn's Cp MCF)
* added mass      rho Ca_k A_k                 on the body acceleration
* drag            0.5 rho Cd_k b_k |v_perp| v_k   (per band for the filtered model: drag_filters.py)

with A the section area, A_k the added-mass reference area (pi D^2/4; pi h^2/4 for flow
along the width of a rectangle, pi w^2/4 along its height) and b_k the projected width
(D; h for flow along the width, w along the height). Cp (the zone's ``cp``, HydroDyn's) scales
the Froude-Krylov term: rho (Cp A + Ca_k A_k) a_k.

A rectangular section's width lies along d1 and its height along d2, both turned about the
axis by the member's ``spin_deg`` (d1 toward d2, HydroDyn's MSpinOrient): the drag and added-
mass directions turn with it.

A tapered circular member (diameter linear from end a to end b) takes each strip's diameter
at the strip's midpoint (HydroDyn takes it at its nodes; the two agree to second order in the
strip length), its end plates the end diameters, and its hydrostatic volume is the exact
frustum of each strip. The tapered side wall also carries axial loads (HydroDyn's, with the
member's axial coefficients ``taper_axial``), per unit length along the axis k:

* dynamic pressure  Cp_ax 2 pi R dR/dl p_dyn k   (the pressure on the slanted wall)
* added mass        2 rho Ca_ax pi R^2 |dR/dl| k k^T
* drag              0.5 rho Cd_ax pi R |dR/dl| |w| w k   (w: relative axial velocity)

They are applied as axial point terms at each strip's centre (the end plates' kernel: a
strip's ring is wet when its centre is below the water line). A tapered rectangular member
(width and height each linear from end a to end b) takes each strip's sides at its midpoint,
its hydrostatic volume is each strip's exact prismatoid, and its wall carries the dynamic
pressure term Cp_ax (dA/dl) p_dyn k (the pressure on the slanted walls projected on the axis;
2 pi R dR/dl for a circle); its axial added mass and drag are not implemented (config.py
refuses nonzero coefficients).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fowt_hydro_sim.physics.config import ConfigError, Member, Platform


@dataclass(frozen=True)
class Strips:
    centre_m: np.ndarray  # (n, 3) body frame, relative to the reference point
    axis: np.ndarray  # (n, 3) unit vector from end a to end b
    directions: np.ndarray  # (n, 2, 3) transverse unit vectors d1, d2
    length_m: np.ndarray  # (n,)
    area_m2: np.ndarray  # (n,) section area
    inertia_kg_m: np.ndarray  # (n, 2) fluid-inertia coefficient per unit length
    added_mass_kg_m: np.ndarray  # (n, 2)
    drag_kg_m2: np.ndarray  # (n, 2): 0.5 rho Cd b with the constant Cd, per direction
    band_drag_kg_m2: np.ndarray  # (n, n_bands, 2): 0.5 rho Cd b per drag band (zero if unfiltered)
    filtered: np.ndarray  # (n, 2) bool: the direction has band Cds
    member: np.ndarray  # (n,) index of the member
    zone: tuple[str, ...]  # zone name of each strip
    kinematics_point: np.ndarray  # (n,) index into Discretisation.points_m
    volume_m3: np.ndarray  # (n,) exact volume (a frustum for a tapered member)
    volume_centre_m: np.ndarray  # (n, 3) its centroid


@dataclass(frozen=True)
class EndPlates:
    centre_m: np.ndarray  # (m, 3)
    normal: np.ndarray  # (m, 3) unit vector from the end into the member
    pressure_area_m2: np.ndarray  # (m,) Cp A
    added_mass_kg: np.ndarray  # (m,) rho Ca (2/3) pi R^3
    drag_kg_m: np.ndarray  # (m,) 0.25 rho Cd A (HydroDyn's factor)
    kinematics_point: np.ndarray  # (m,)


@dataclass(frozen=True)
class Discretisation:
    strips: Strips
    plates: EndPlates
    points_m: np.ndarray  # (p, 3) undisplaced kinematics points, z <= 0 (unless points_above_water)
    maccamy_fuchs_diameter_m: np.ndarray  # (p,) > 0: the point's acceleration is MacCamy-Fuchs scaled for it


def transverse_directions(axis: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    d1 = np.cross([0.0, 0.0, 1.0], axis)
    if np.linalg.norm(d1) < 1e-9:  # a vertical member: width along x
        d1 = np.array([1.0, 0.0, 0.0])
    d1 /= np.linalg.norm(d1)
    return d1, np.cross(axis, d1)


def member_directions(member: Member) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Axis (end a to end b) and the section directions d1 (width), d2 (height) of a member,
    turned about the axis by its spin angle (d1 toward d2)."""
    axis = np.subtract(member.end_b_m, member.end_a_m, dtype=float)
    axis /= np.linalg.norm(axis)
    d1, d2 = transverse_directions(axis)
    if member.spin_deg:
        c, s = math.cos(math.radians(member.spin_deg)), math.sin(math.radians(member.spin_deg))
        d1, d2 = c * d1 + s * d2, -s * d1 + c * d2
    return axis, d1, d2


def _cuts(member: Member) -> np.ndarray:
    """Fractions along the member (0 at end a, 1 at end b) where strips must end."""
    a, b = np.array(member.end_a_m), np.array(member.end_b_m)
    levels = [0.0] + [z.below_z_m for z in member.zones if math.isfinite(z.below_z_m)]
    cuts = [0.0, 1.0]
    if abs(b[2] - a[2]) > 1e-12:
        cuts += [(lv - a[2]) / (b[2] - a[2]) for lv in levels]
    return np.unique(np.clip(cuts, 0.0, 1.0))


def _section(member: Member, fraction: float) -> tuple[float, tuple[float, float], tuple[float, float]]:
    """Section area, added-mass reference areas and projected widths per direction at
    ``fraction`` of the way from end a to end b."""
    if member.section == "circular":
        d = member.diameter_at(fraction)
        area = math.pi * d**2 / 4
        return area, (area, area), (d, d)
    w, h = member.sides_at(fraction)
    return w * h, (math.pi * h**2 / 4, math.pi * w**2 / 4), (h, w)


def prismatoid(member: Member, start: float, stop: float, length_m: float) -> tuple[float, float]:
    """Volume of a rectangular member between fractions ``start`` and ``stop`` (``length_m``
    long) and the distance of its centroid from ``start``: the area w h is quadratic along the
    axis, so Simpson's rule integrates the area and its first moment exactly."""
    areas = [math.prod(member.sides_at(start + u * (stop - start))) for u in (0.0, 0.5, 1.0)]
    volume = length_m * (areas[0] + 4 * areas[1] + areas[2]) / 6
    return volume, length_m * length_m * (2 * areas[1] + areas[2]) / 6 / volume


def frustum(radius_0_m: float, radius_1_m: float, length_m: float) -> tuple[float, float]:
    """Volume of a frustum and the distance of its centroid from the radius-0 end."""
    r0, r1 = radius_0_m, radius_1_m
    s = r0 * r0 + r0 * r1 + r1 * r1
    return math.pi * length_m * s / 3.0, length_m * (r0 * r0 + 2.0 * r0 * r1 + 3.0 * r1 * r1) / (4.0 * s)


def _taper_ring(rho: float, member: Member, fraction: float, length_m: float) -> tuple[float, float, float]:
    """A tapered wall's axial terms over ``length_m`` at ``fraction``: pressure area (signed,
    along a->b), added mass, drag factor (strips.py's docstring)."""
    full = float(np.linalg.norm(np.subtract(member.end_b_m, member.end_a_m)))
    ax = member.taper_axial
    if member.section == "rectangular":  # dA/dl = (w' h + w h') / L; ca = cd = 0 (config.py)
        (w, h), (w1, h1) = member.sides_at(fraction), member.sides_at(1.0)
        area_slope = ((w1 - member.width_m) * h + w * (h1 - member.height_m)) / full
        return ax.cp * area_slope * length_m, 0.0, 0.0
    radius = member.diameter_at(fraction) / 2
    slope = (member.diameter_at(1.0) - member.width_m) / 2 / full  # dR/dl
    return (ax.cp * 2 * math.pi * radius * slope * length_m,
            2 * rho * ax.ca * math.pi * radius**2 * abs(slope) * length_m,
            0.5 * rho * ax.cd * math.pi * radius * abs(slope) * length_m)


def discretise(platform: Platform, points_above_water: bool = False) -> Discretisation:
    """The platform's strips, end plates and kinematics points; the points above the still water
    line are one point at z = 0 unless ``points_above_water`` (Wheeler stretching)."""
    rho = platform.environment.water_density_kg_m3
    n_bands = len(platform.drag_bands)
    rows: dict[str, list] = {k: [] for k in ("centre", "axis", "dirs", "length", "area", "inertia",
                                               "added", "drag", "band_drag", "filtered", "member", "zone",
                                               "volume", "volume_centre", "mcf")}
    plates: dict[str, list] = {k: [] for k in ("centre", "normal", "pressure", "added", "drag")}
    for index, member in enumerate(platform.members):
        a, b = np.array(member.end_a_m), np.array(member.end_b_m)
        length = float(np.linalg.norm(b - a))
        axis, d1, d2 = member_directions(member)
        cuts = _cuts(member)
        rings = []
        for s0, s1 in zip(cuts[:-1], cuts[1:]):
            n = max(1, math.ceil((s1 - s0) * length / member.strip_length_m - 1e-9))
            for j in range(n):
                mid = s0 + (j + 0.5) * (s1 - s0) / n
                centre = a + mid * (b - a)
                area, am_area, width = _section(member, mid)
                strip_length = (s1 - s0) * length / n
                if member.section == "circular":
                    start = mid - 0.5 * (s1 - s0) / n
                    volume, offset = frustum(member.diameter_at(start) / 2,
                                             member.diameter_at(start + (s1 - s0) / n) / 2, strip_length)
                    volume_centre = a + start * (b - a) + offset * axis
                else:
                    start = mid - 0.5 * (s1 - s0) / n
                    volume, offset = prismatoid(member, start, start + (s1 - s0) / n, strip_length)
                    volume_centre = a + start * (b - a) + offset * axis
                if member.drag_only:  # HydroDyn's PropPot: the potential flow has the inertia and buoyancy
                    volume = 0.0
                rows["volume"].append(volume)
                rows["volume_centre"].append(volume_centre)
                if member.tapered:
                    rings.append((centre, _taper_ring(rho, member, mid, strip_length)))
                zone = next(z for z in member.zones if centre[2] < z.below_z_m or z is member.zones[-1])
                rows["centre"].append(centre)
                rows["axis"].append(axis)
                rows["dirs"].append([d1, d2])
                rows["length"].append(strip_length)
                rows["area"].append(area)
                keep = 0.0 if member.drag_only else 1.0
                if member.maccamy_fuchs:  # rho A on the scaled acceleration (waves/maccamy_fuchs.py)
                    rows["inertia"].append([rho * area, rho * area])
                else:
                    rows["inertia"].append([keep * rho * (zone.cp * area + zone.ca[k] * am_area[k]) for k in range(2)])
                rows["mcf"].append(member.width_m if member.maccamy_fuchs else 0.0)
                rows["added"].append([keep * rho * zone.ca[k] * am_area[k] for k in range(2)])
                rows["drag"].append([0.5 * rho * zone.cd[k].constant * width[k] for k in range(2)])
                rows["band_drag"].append([[0.5 * rho * (zone.cd[k].bands or (0.0,) * n_bands)[b] * width[k]
                                           for k in range(2)] for b in range(n_bands)])
                rows["filtered"].append([zone.cd[k].bands is not None for k in range(2)])
                rows["member"].append(index)
                rows["zone"].append(zone.name)
        keep = 0.0 if member.drag_only else 1.0
        for centre, (pressure, added, drag) in rings:
            plates["centre"].append(centre)
            plates["normal"].append(axis)
            plates["pressure"].append(keep * pressure)
            plates["added"].append(keep * added)
            plates["drag"].append(drag)
        for plate, end, normal, fraction in ((member.end_a_plate, a, axis, 0.0), (member.end_b_plate, b, -axis, 1.0)):
            if plate is None:
                continue
            if member.section != "circular":
                raise ConfigError(f"member {member.name}: end plates are supported on circular sections only")
            if plate.joint_area_m2 is not None:  # the joint's sums: inward normals, area then hemisphere
                area, volume = np.array(plate.joint_area_m2), np.array(plate.joint_volume_m3)
                for vector, scale in ((area, (plate.cp, 0.0, plate.cd)), (volume, (0.0, plate.ca, 0.0))):
                    size = float(np.linalg.norm(vector))
                    if size > 0.0:
                        plates["centre"].append(end)
                        plates["normal"].append(-vector / size)
                        plates["pressure"].append(keep * scale[0] * size)
                        plates["added"].append(keep * rho * scale[1] * size)
                        plates["drag"].append(0.25 * rho * scale[2] * size)
                continue
            radius = member.diameter_at(fraction) / 2
            plates["centre"].append(end)
            plates["normal"].append(normal)
            plates["pressure"].append(keep * plate.cp * math.pi * radius**2)
            plates["added"].append(keep * rho * plate.ca * 2.0 / 3.0 * math.pi * radius**3)
            plates["drag"].append(0.25 * rho * plate.cd * math.pi * radius**2)

    strip_centres = np.array(rows["centre"]).reshape(-1, 3)  # (none: a potential-flow hull)
    plate_centres = np.array(plates["centre"]).reshape(-1, 3)
    undisplaced = np.round(np.vstack([strip_centres, plate_centres]), 9)
    if not points_above_water:  # kinematics above the water line are those at z = 0: one point
        undisplaced[:, 2] = np.minimum(undisplaced[:, 2], 0.0)
    # a MacCamy-Fuchs strip's point is its own (its acceleration is scaled for its diameter)
    scaled_for = np.concatenate([np.array(rows["mcf"], dtype=float), np.zeros(len(plate_centres))])
    keys, index = np.unique(np.column_stack([undisplaced, scaled_for]), axis=0, return_inverse=True)
    points, index = keys[:, 0:3], index.ravel()
    n = len(strip_centres)
    strips = Strips(
        centre_m=strip_centres, axis=np.array(rows["axis"]).reshape(-1, 3),
        directions=np.array(rows["dirs"]).reshape(-1, 2, 3),
        length_m=np.array(rows["length"], dtype=float), area_m2=np.array(rows["area"], dtype=float),
        inertia_kg_m=np.array(rows["inertia"]).reshape(-1, 2), added_mass_kg_m=np.array(rows["added"]).reshape(-1, 2),
        drag_kg_m2=np.array(rows["drag"]).reshape(-1, 2),
        band_drag_kg_m2=np.array(rows["band_drag"]).reshape(n, n_bands, 2),
        filtered=np.array(rows["filtered"], dtype=bool).reshape(-1, 2), member=np.array(rows["member"], dtype=int),
        zone=tuple(rows["zone"]), kinematics_point=index[:n], volume_m3=np.array(rows["volume"]),
        volume_centre_m=np.array(rows["volume_centre"]).reshape(-1, 3))
    end_plates = EndPlates(
        centre_m=plate_centres, normal=np.array(plates["normal"]).reshape(-1, 3),
        pressure_area_m2=np.array(plates["pressure"], dtype=float),
        added_mass_kg=np.array(plates["added"], dtype=float),
        drag_kg_m=np.array(plates["drag"], dtype=float), kinematics_point=index[n:])
    return Discretisation(strips, end_plates, np.ascontiguousarray(points), keys[:, 3].copy())
