"""Member hydrostatics up to the instantaneous free surface: HydroDyn's MHstLMod 2 (rectangular
members; circular members flagged ``hydrostatics_by_section``) and MHstLMod 1 with wave
stretching (the other circular members).

The pressure is the still-water hydrostatic pressure p = -rho g z (z up from the still water
line; negative, a suction, between z = 0 and a crest), integrated over the part of each member
surface below the free surface. As HydroDyn does, the free surface is a plane near each piece
of surface, through (x, y, eta(x, y)) and normal to the wave surface there (central
differences of eta); A load F = -int p n dA acts on each wetted face, moments about the origin.

Rectangular members (MHstLMod 2): for the side walls of each element (the member cut into
``n_elements`` equal lengths) the plane at the element's midpoint; for each end plate the plane
at its end node. Each face is a planar polygon (the side walls of an element are planar
quadrilaterals) clipped by its plane; the pressure is linear in z, so the force and moment
integrands are at most quadratic and the edge-midpoint rule on a fan of triangles integrates
them exactly. This is an independent computation of what HydroDyn's
``getElementHstLds_Mod2_Rec`` and ``GetEndPlateHstLds_Rec`` integrate in closed form along the
element (adaptive Simpson, relative tolerance 1e-6).

Circular members, possibly tapered, MHstLMod 2 (HydroDyn's ``getElementHstLds_Mod2_Cyl``): each
element, whatever its nodes' depths, takes the plane at its midpoint (the elevation there, the
normal from central differences over the element's mean radius), and each cross-section of its
side wall is wetted on the arc of its rim below that plane (a circular segment of the section:
the whole rim, none of it, or the arc between the two points where the plane cuts the rim).
The load per unit length of a section is closed form in the arc's end angles (int z n R dt
with n = u - (dR/ds) k, u the rim's unit radius); it is integrated here along the element by
Gauss-Legendre in a cosine-stretched variable (48 points) on the pieces between the sections
where the plane starts and stops cutting the rim (both linear in the axial coordinate, so found
in closed form), which takes the square-root behaviour of the arc there, where HydroDyn refines
Simpson's rule adaptively (relative tolerance 1e-6, absolute 1e-8 N, and always across a piece
that goes from wetted whole to dry). HydroDyn's section load (``GetSectionHstLds_Cyl``) takes
the term R^2 cos(phi) int sin t cos t dt of the side force along the section's horizontal axis
y with the sign opposite to the pressure integral's (phi the member's inclination from the
horizontal): the model follows it (``_wall_sections``' ``cross_sign``). The term vanishes
wherever the surface plane is level across the section (still water, or a wave running along
the member) and where the plane cuts the section through its centre; on a small surface slope s
across the section the two signs differ by 2 rho g R^2 s sin(2 beta) per unit length (2 beta
the angle of the rim's dry arc), a side force of at most 2 rho g R^2 |s|. The end plates: as
for MHstLMod 1, below.

Circular members, possibly tapered, MHstLMod 1 with stretching (HydroDyn's
``getElementHstLds_Mod1``): an element whose two nodes are below the elevation over them is
wetted whole (its whole side wall, whatever the surface between); an element whose lower node
is below and upper node above is wetted up to the plane through the point where its axis
crosses the surface (found by linear interpolation of z - eta between the nodes), normal to the
surface there (central differences over the section's radius at that point), from its lower
node up, past its upper node if the tilted plane reaches beyond it; where the plane dips below
the lower node, the part of the wall there above the plane is taken off (HydroDyn's closed form
for the truncated cone counts it negative: with the element below wetted whole, the two give
the wall below the plane); an element whose lower node is dry carries no load. The end plates
take the plane at their node (central differences over their radius), the part of the disc
below it (a circular segment). Whole walls and discs are closed forms (Archimedes for the
frustum less its end discs); a cut wall is integrated here along the axis as MHstLMod 2's
(the exact pressure integral, with the pieces split where the plane meets the sections' rims),
where HydroDyn writes the element's load in closed form (the truncated cone's volume and
waterplane ellipse).

Pure numpy and scipy, no numba (about 1 ms per element and time step): ``HydroOptions(
hydrostatics="free_surface")`` for a prescribed motion (``fowt-sim loads``), not a
time-stepping path.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from fowt_hydro_sim.frames import rotation_matrix as rotation_matrices

Elevation = Callable[[float, float, float], float]
"""eta(t, x, y) in m."""


@dataclass(frozen=True)
class RectangularMember:
    """A straight rectangular member: side A along ``x_hat``, side B along ``y_hat`` (both
    normal to the axis), each varying linearly from end a to end b."""

    end_a_m: tuple[float, float, float]
    end_b_m: tuple[float, float, float]
    side_a_m: tuple[float, float]
    side_b_m: tuple[float, float]
    spin_deg: float
    n_elements: int


@dataclass(frozen=True)
class CircularMember:
    """A straight circular member, its diameter varying linearly from end a to end b; its
    elements wetted as HydroDyn's MHstLMod ``mhstlmod`` (1 or 2) wets them."""

    end_a_m: tuple[float, float, float]
    end_b_m: tuple[float, float, float]
    diameter_m: tuple[float, float]
    n_elements: int
    mhstlmod: int = 1


def section_axes(end_a: np.ndarray, end_b: np.ndarray, spin_deg: float) -> tuple[np.ndarray, ...]:
    """Axis k and section axes (x_hat along side A, y_hat along side B) as HydroDyn's
    Morison_DirCosMtrx: for a non-vertical member x_hat is horizontal before the spin."""
    d = end_b - end_a
    length = float(np.linalg.norm(d))
    horizontal = float(np.hypot(d[0], d[1]))
    if horizontal < 1e-12 * length:
        sign = 1.0 if d[2] > 0 else -1.0
        d1, d2 = np.array([1.0, 0.0, 0.0]), np.array([0.0, sign, 0.0])
    else:
        d1 = np.array([d[1] / horizontal, -d[0] / horizontal, 0.0])
        d2 = np.array([d[0] * d[2] / (horizontal * length), d[1] * d[2] / (horizontal * length),
                       -horizontal / length])
    c, s = np.cos(np.radians(spin_deg)), np.sin(np.radians(spin_deg))
    return d / length, c * d1 + s * d2, -s * d1 + c * d2


def clip_below(polygon: np.ndarray, point: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """The part of a convex planar polygon (n, 3) on the water side of the plane through
    ``point`` with upward ``normal``: (r - point) . normal <= 0 (Sutherland-Hodgman)."""
    height = (polygon - point) @ normal
    out = []
    n = len(polygon)
    for i in range(n):
        a, b, ha, hb = polygon[i], polygon[(i + 1) % n], height[i], height[(i + 1) % n]
        if ha <= 0.0:
            out.append(a)
        if (ha <= 0.0) != (hb <= 0.0):
            out.append(a + (b - a) * (ha / (ha - hb)))
    return np.array(out).reshape(-1, 3)


def pressure_wrench(polygon: np.ndarray, rho_g: float) -> np.ndarray:
    """Force and moment about the origin of p = -rho g z on a planar polygon whose vertex order
    makes its area vector point out of the body: F = rho g int z n dA, M = rho g int z r x n dA."""
    out = np.zeros(6)
    for j in range(1, len(polygon) - 1):
        a, b, c = polygon[0], polygon[j], polygon[j + 1]
        area = 0.5 * np.cross(b - a, c - a)
        mids = np.array([(a + b) / 2, (b + c) / 2, (c + a) / 2])
        z_mean = mids[:, 2].mean()
        zr_mean = (mids[:, 2:3] * mids).mean(axis=0)
        out[:3] += rho_g * z_mean * area
        out[3:] += rho_g * np.cross(zr_mean, area)
    return out


def surface_plane(eta: Elevation, t: float, x: float, y: float, step_m: float) -> tuple[np.ndarray, np.ndarray]:
    """The free-surface plane at (x, y): the point (x, y, eta) and the unit normal from the
    elevation's central differences over +-step_m (as HydroDyn's WaveField_GetNodeWaveNormal)."""
    dx = (eta(t, x + step_m, y) - eta(t, x - step_m, y)) / (2 * step_m)
    dy = (eta(t, x, y + step_m) - eta(t, x, y - step_m)) / (2 * step_m)
    normal = np.array([-dx, -dy, 1.0])
    return np.array([x, y, eta(t, x, y)]), normal / np.linalg.norm(normal)


def _section(centre: np.ndarray, x_hat: np.ndarray, y_hat: np.ndarray, sa: float, sb: float) -> np.ndarray:
    """Section corners in HydroDyn's order (-,-), (+,-), (+,+), (-,+) along (x_hat, y_hat)."""
    signs = ((-1, -1), (1, -1), (1, 1), (-1, 1))
    return np.array([centre + 0.5 * (i * sa * x_hat + j * sb * y_hat) for i, j in signs])


def _outward(polygon: np.ndarray, inside: np.ndarray) -> np.ndarray:
    """The polygon ordered so that its area vector points away from ``inside``."""
    area = np.cross(polygon[1] - polygon[0], polygon[2] - polygon[0])
    return polygon if area @ (polygon.mean(axis=0) - inside) > 0 else polygon[::-1]


def member_wrench(member: RectangularMember, eta: Elevation, t: float, rho: float, g: float,
                  rotation: np.ndarray | None = None, position_m: np.ndarray | None = None) -> np.ndarray:
    """Hydrostatic wrench (6,) about the origin on a member up to the free surface; the member
    is displaced by x -> position + rotation x (at rest by default)."""
    rotation = np.eye(3) if rotation is None else rotation
    position_m = np.zeros(3) if position_m is None else position_m
    a, b = np.asarray(member.end_a_m, float), np.asarray(member.end_b_m, float)
    k, x_hat, y_hat = section_axes(a, b, member.spin_deg)
    s = np.linspace(0.0, 1.0, member.n_elements + 1)
    body_centres = a + s[:, None] * (b - a)
    sa = member.side_a_m[0] + s * (member.side_a_m[1] - member.side_a_m[0])
    sb = member.side_b_m[0] + s * (member.side_b_m[1] - member.side_b_m[0])
    sections = [position_m + _section(c, x_hat, y_hat, p, q) @ rotation.T for c, p, q in zip(body_centres, sa, sb)]
    centres, k = position_m + body_centres @ rotation.T, rotation @ k
    rho_g, out = rho * g, np.zeros(6)
    for i in range(member.n_elements):
        mid = 0.5 * (centres[i] + centres[i + 1])
        point, normal = surface_plane(eta, t, mid[0], mid[1], max(0.5 * (sa[i] + sa[i + 1]), 0.5 * (sb[i] + sb[i + 1])))
        lo, hi = sections[i], sections[i + 1]
        for j in range(4):
            face = _outward(np.array([lo[j], lo[(j + 1) % 4], hi[(j + 1) % 4], hi[j]]), mid)
            wet = clip_below(face, point, normal)
            if len(wet) >= 3:
                out += pressure_wrench(wet, rho_g)
    for end, section, size in ((0, sections[0], max(sa[0], sb[0])), (-1, sections[-1], max(sa[-1], sb[-1]))):
        centre = centres[end]
        point, normal = surface_plane(eta, t, centre[0], centre[1], size)
        wet = clip_below(_outward(section, centre + (k if end == 0 else -k)), point, normal)
        if len(wet) >= 3:
            out += pressure_wrench(wet, rho_g)
    return out


# ------------------------------------------------------------------ circular members
def _circle_axes(k: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors normal to the axis k: a horizontal one and one with z >= 0."""
    y = np.array([0.0, 1.0, 0.0]) if abs(k[2]) > 1.0 - 1e-12 else np.array([-k[1], k[0], 0.0]) / math.hypot(k[0], k[1])
    z = np.cross(k, y)
    return (-y, -z) if z[2] < 0 else (y, z)


def _wet_arcs(centres: np.ndarray, radii: np.ndarray, y: np.ndarray, z: np.ndarray, point: np.ndarray,
              normal: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For sections (n, 3) of radii (n,), the angles theta1, theta2 of the rim part
    centre + radius (cos t y + sin t z) below the plane through ``point`` with upward ``normal``
    (an empty arc: theta1 == theta2)."""
    a, b = radii * (y @ normal), radii * (z @ normal)
    c = (point - centres) @ normal  # wet where a cos t + b sin t <= c
    m = np.hypot(a, b)
    phi = np.arctan2(b, a)
    beta = np.arccos(np.clip(c / np.where(m > 0, m, 1.0), -1.0, 1.0))
    whole, dry = c >= m, c <= -m
    t1 = np.where(whole | dry, 0.0, phi + beta)
    t2 = np.where(whole, 2 * np.pi, np.where(dry, 0.0, phi + 2 * np.pi - beta))
    return t1, t2


def _wall_sections(centres: np.ndarray, radii: np.ndarray, taper: float, k: np.ndarray, y: np.ndarray,
                   z: np.ndarray, t1: np.ndarray, t2: np.ndarray, cross_sign: float = 1.0) -> np.ndarray:
    """(n, 6): d(wrench)/ds / (rho g) of p = -rho g z on the arcs [t1, t2] of the side wall at
    sections (n, 3) of radii (n,): int z (n, r x n) dA with n dA = (u - taper k) R dt ds,
    u = cos t y + sin t z, r = centre + R u. ``cross_sign`` -1 takes the term
    R z_z int sin t cos t dt of int z cos t dt with the opposite sign, as HydroDyn's
    GetSectionHstLds_Cyl does (its C1); the term vanishes where the surface plane is level
    across the section (the arc symmetric about -z)."""
    s1, s2, c1, c2 = np.sin(t1), np.sin(t2), np.cos(t1), np.cos(t2)
    dt, d2 = t2 - t1, 0.25 * (np.sin(2 * t2) - np.sin(2 * t1))
    one, cos, sin = dt, s2 - s1, c1 - c2
    cos2, sincos, sin2 = 0.5 * dt + d2, 0.5 * (s2 * s2 - s1 * s1), 0.5 * dt - d2
    z0, zy, zz = centres[:, 2], radii * y[2], radii * z[2]  # z on the rim: z0 + zy cos + zz sin
    z_u = ((z0 * cos + zy * cos2 + cross_sign * zz * sincos)[:, None] * y
           + (z0 * sin + zy * sincos + zz * sin2)[:, None] * z)  # int z u dt
    z_1 = z0 * one + zy * cos + zz * sin  # int z dt
    along = z_u - taper * z_1[:, None] * k
    force = radii[:, None] * along
    # r x n = centre x (u - taper k) - R taper u x k
    moment = radii[:, None] * (np.cross(centres, along) - (radii * taper)[:, None] * np.cross(z_u, k))
    return np.hstack([force, moment])


# Gauss-Legendre nodes on [0, 1], used through s = s0 + (s1 - s0) (1 - cos(pi tau)) / 2, which
# smooths the square-root behaviour of the wetted arc where the plane meets a section's rim
_TAU, _WEIGHT = np.polynomial.legendre.leggauss(48)
_TAU, _WEIGHT = 0.5 * (_TAU + 1.0), 0.5 * _WEIGHT


def _full_disc(centre: np.ndarray, radius: float, outward: np.ndarray) -> np.ndarray:
    """int z (n, r x n) dA over a whole disc: z linear over it, int u u^T dA = pi R^4 / 4 (1 - n n^T)."""
    area = math.pi * radius * radius
    return np.concatenate([area * centre[2] * outward,
                           area * centre[2] * np.cross(centre, outward)
                           + 0.25 * area * radius * radius * np.cross([0.0, 0.0, 1.0], outward)])


def _disc_wrench(centre: np.ndarray, radius: float, outward: np.ndarray, y: np.ndarray, z: np.ndarray,
                 point: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """int z (n, r x n) dA / 1 over the part of the disc (centre, radius, in the plane of y, z)
    below the plane through ``point`` with upward ``normal``; n the disc's outward normal."""
    n_in = normal - (normal @ outward) * outward  # the plane's normal within the disc
    size = float(np.linalg.norm(n_in))
    height = (point - centre) @ normal
    if size < 1e-12:
        if height < 0.0:
            return np.zeros(6)
        e, limit = y, radius  # whole disc
    else:
        e, limit = n_in / size, height / size  # wet where u . e <= limit
    if limit >= radius:
        return _full_disc(centre, radius, outward)
    if limit <= -radius:
        return np.zeros(6)
    v_dir = np.cross(outward, e)
    w_z, v_z = e[2], v_dir[2]

    def slab(u: float) -> np.ndarray:  # int over v in the chord at u of z (1, r)
        half = math.sqrt(max(radius * radius - u * u, 0.0))
        zc = centre[2] + u * w_z  # z at v = 0; z = zc + v v_z
        length, v2 = 2 * half, 2 * half**3 / 3
        first = zc * length * (centre + u * e) + v_z * v2 * v_dir
        return np.concatenate([[zc * length], first])

    from scipy import integrate  # imported when used: it costs a model's import 0.3-0.5 s
    moments, _ = integrate.quad_vec(slab, -radius, limit, epsabs=0.0, epsrel=1e-12)
    return np.concatenate([moments[0] * outward, np.cross(moments[1:], outward)])


def _circular_element(lower: np.ndarray, k: np.ndarray, r_lower: float, taper: float, s_end: float,
                      plane: tuple[np.ndarray, np.ndarray] | None) -> np.ndarray:
    """int z (n, r x n) dA over an element's side wall from its lower section along k: up to
    s_end whole (plane None), or below the plane, from s = 0 up to where it leaves the cone."""
    y, z = _circle_axes(k)
    if plane is None:  # the frustum's Archimedes load less its two end discs
        r0, r1 = r_lower, r_lower + taper * s_end
        sum_r = r0 * r0 + r0 * r1 + r1 * r1
        volume = math.pi * s_end * sum_r / 3
        centroid = lower + k * s_end * (r0 * r0 + 2 * r0 * r1 + 3 * r1 * r1) / (4 * sum_r)
        solid = np.concatenate([[0.0, 0.0, volume], volume * np.cross(centroid, [0.0, 0.0, 1.0])])
        return solid - _full_disc(lower, r0, -k) - _full_disc(lower + s_end * k, r1, k)
    point, normal = plane
    whole, dry = _rim_roots(lower, k, r_lower, taper, point, normal)
    top = s_end if dry is None else max(dry, 0.0)
    bottom = 0.0 if whole is None else min(whole, 0.0)
    breaks = sorted({bottom, 0.0, top, *([whole] if whole is not None and 0.0 < whole < top else [])})
    total = np.zeros(6)
    for s0, s1 in zip(breaks[:-1], breaks[1:]):
        if s1 <= s0:
            continue
        # below the lower section: minus the part above the plane
        total += _wall_piece(s0, s1, lower, k, r_lower, taper, y, z, plane, minus_whole=s1 <= 0.0)
    return total


def _rim_roots(start: np.ndarray, k: np.ndarray, r_start: float, taper: float, point: np.ndarray,
               normal: np.ndarray) -> tuple[float | None, float | None]:
    """Along the axis from the section at ``start`` (s, radius r_start + taper s), where the
    plane through ``point`` with upward ``normal`` stops wetting the whole section and where it
    stops wetting any of it: (whole, dry), None for one that never changes."""
    # g(s) = (point - c(s)) . n and the rim's reach m(s) = R(s) |n_perp|, both linear in s: the
    # section is wet whole while g >= m, dry once g <= -m
    kn, g0 = k @ normal, (point - start) @ normal
    perp = math.sqrt(max(1.0 - kn * kn, 0.0))

    def root(sign: float) -> float | None:  # g - sign m = 0
        slope = -kn - sign * taper * perp
        return None if abs(slope) < 1e-12 else (sign * r_start * perp - g0) / slope

    return root(1.0), root(-1.0)


def _wall_piece(s0: float, s1: float, start: np.ndarray, k: np.ndarray, r_start: float, taper: float,
                y: np.ndarray, z: np.ndarray, plane: tuple[np.ndarray, np.ndarray], minus_whole: bool = False,
                cross_sign: float = 1.0) -> np.ndarray:
    """int z (n, r x n) dA over the side wall below the plane between s0 and s1 along the axis
    from the section at ``start`` (Gauss-Legendre in a cosine-stretched variable), less the whole
    wall there with ``minus_whole``; ``cross_sign`` as ``_wall_sections``."""
    point, normal = plane
    half = 0.5 * (s1 - s0)
    at = s0 + half * (1.0 - np.cos(np.pi * _TAU))
    weight = _WEIGHT * half * np.pi * np.sin(np.pi * _TAU)
    centres, radii = start + np.outer(at, k), r_start + taper * at
    wet = _wall_sections(centres, radii, taper, k, y, z, *_wet_arcs(centres, radii, y, z, point, normal),
                         cross_sign=cross_sign)
    if minus_whole:
        full = np.full(at.size, 2 * np.pi)
        wet = wet - _wall_sections(centres, radii, taper, k, y, z, np.zeros(at.size), full)
    return weight @ wet


def _sectioned_element(start: np.ndarray, k: np.ndarray, r_start: float, taper: float, length: float,
                       plane: tuple[np.ndarray, np.ndarray], cross_sign: float = -1.0) -> np.ndarray:
    """int z (n, r x n) dA over an element's side wall (s from 0 to ``length`` along k from its
    section at ``start``) below the plane, each section wetted on its own arc, as HydroDyn's
    MHstLMod 2 integrates it (``cross_sign`` -1, its C1 sign; +1 the pressure integral's:
    ``_wall_sections``); split where a section becomes wet whole or dry."""
    y, z = _circle_axes(k)
    inside = [s for s in _rim_roots(start, k, r_start, taper, *plane) if s is not None and 0.0 < s < length]
    breaks = sorted({0.0, length, *inside})
    total = np.zeros(6)
    for s0, s1 in zip(breaks[:-1], breaks[1:]):
        total += _wall_piece(s0, s1, start, k, r_start, taper, y, z, plane, cross_sign=cross_sign)
    return total


def _cut_elements(nodes: np.ndarray, radii: np.ndarray, k: np.ndarray, taper: float, dl: float, eta: Elevation,
                  t: float) -> np.ndarray:
    """int z (n, r x n) dA over the side walls of a member's elements (nodes (n + 1, 3) along k,
    lower first) as HydroDyn's MHstLMod 1 with stretching wets them: whole, cut by the plane
    where the axis crosses the surface, or dry (module docstring)."""
    zeta = np.array([eta(t, n[0], n[1]) for n in nodes])
    out = np.zeros(6)
    for i in range(len(nodes) - 1):
        wet_lower, wet_upper = nodes[i, 2] < zeta[i], nodes[i + 1, 2] < zeta[i + 1]
        if wet_lower and wet_upper:
            out += _circular_element(nodes[i], k, radii[i], taper, dl, None)
        elif wet_lower:
            ratio = (zeta[i] - nodes[i, 2]) / ((zeta[i] - nodes[i, 2]) - (zeta[i + 1] - nodes[i + 1, 2]))
            crossing = nodes[i] + ratio * dl * k
            _, normal = surface_plane(eta, t, crossing[0], crossing[1], radii[i] + taper * ratio * dl)
            out += _circular_element(nodes[i], k, radii[i], taper, dl, (crossing, normal))
    return out


def circular_member_wrench(member: CircularMember, eta: Elevation, t: float, rho: float, g: float,
                           rotation: np.ndarray | None = None, position_m: np.ndarray | None = None) -> np.ndarray:
    """Hydrostatic wrench (6,) about the origin on a circular member up to the free surface as
    HydroDyn's MHstLMod 1 with stretching or MHstLMod 2 wets it (``member.mhstlmod``, module
    docstring); the member is displaced by x -> position + rotation x (at rest by default)."""
    rotation = np.eye(3) if rotation is None else rotation
    position_m = np.zeros(3) if position_m is None else position_m
    a = position_m + rotation @ np.asarray(member.end_a_m, float)
    b = position_m + rotation @ np.asarray(member.end_b_m, float)
    length = float(np.linalg.norm(b - a))
    k = (b - a) / length
    dl = length / member.n_elements
    r_a, r_b = 0.5 * member.diameter_m[0], 0.5 * member.diameter_m[1]
    taper = (r_b - r_a) / length
    nodes = a + np.outer(np.arange(member.n_elements + 1) * dl, k)
    radii = r_a + taper * np.arange(member.n_elements + 1) * dl
    out = np.zeros(6)
    if member.mhstlmod == 2:  # each element below the surface plane at its midpoint
        for i in range(member.n_elements):
            mid = 0.5 * (nodes[i] + nodes[i + 1])
            plane = surface_plane(eta, t, mid[0], mid[1], 0.5 * (radii[i] + radii[i + 1]))
            out += _sectioned_element(nodes[i], k, radii[i], taper, dl, plane)
    else:
        out += _cut_elements(nodes, radii, k, taper, dl, eta, t)
    y, z = _circle_axes(k)
    for node, radius, outward in ((nodes[0], radii[0], -k), (nodes[-1], radii[-1], k)):
        point, normal = surface_plane(eta, t, node[0], node[1], radius)
        out += _disc_wrench(node, radius, outward, y, z, point, normal)
    return rho * g * out


def platform_members(platform) -> list[RectangularMember | CircularMember]:
    """The platform's members for these hydrostatics (rectangular: width = HydroDyn's side A,
    along the section's direction d1 before the spin, height = side B; taper and spin as the
    platform gives them; circular: the diameters at both ends and MHstLMod 2 where the member is
    ``hydrostatics_by_section``, 1 otherwise; one element per strip length, HydroDyn's MDivSize)."""
    members = []
    for m in platform.members:
        if m.drag_only:  # its buoyancy is the potential flow's
            continue
        length = math.dist(m.end_a_m, m.end_b_m)
        n = max(1, math.ceil(length / m.strip_length_m - 1e-9))
        if m.section == "circular":
            members.append(CircularMember(m.end_a_m, m.end_b_m, (m.diameter_at(0.0), m.diameter_at(1.0)), n,
                                          2 if m.hydrostatics_by_section else 1))
            continue
        (w0, h0), (w1, h1) = m.sides_at(0.0), m.sides_at(1.0)
        members.append(RectangularMember(m.end_a_m, m.end_b_m, (w0, w1), (h0, h1), m.spin_deg, n))
    return members


def prescribed_motion_wrenches(members: list[RectangularMember | CircularMember], eta: Elevation, time_s: np.ndarray,
                               motion: np.ndarray, rho: float, g: float) -> np.ndarray:
    """(n, 6) hydrostatic loads along a prescribed motion (n, 6: x y z, roll pitch yaw), global
    axes, moments about the displaced reference point."""
    rotations = rotation_matrices(motion[:, 3], motion[:, 4], motion[:, 5])
    out = np.zeros((len(time_s), 6))
    for i, t in enumerate(time_s):
        position = np.asarray(motion[i, 0:3], float)
        total = sum((circular_member_wrench if isinstance(m, CircularMember) else member_wrench)(
            m, eta, float(t), rho, g, rotations[:, :, i], position) for m in members)
        out[i, 0:3] = total[0:3]
        out[i, 3:6] = total[3:6] - np.cross(position, total[0:3])
    return out


def wave_elevation(waves, depth_m: float, gravity_m_s2: float) -> Elevation:
    """eta(t, x, y) of a set of wave components (none: still water)."""
    if waves is None or waves.frequency_hz.size == 0:
        return lambda t, x, y: 0.0
    return lambda t, x, y: float(waves.elevation(x, y, np.array([t]), depth_m, gravity_m_s2)[0])


def regular_wave(amplitude_m: float, omega_rad_s: float, wavenumber_rad_m: float, heading_deg: float,
                 phase_rad: float) -> Elevation:
    """eta = A cos(omega t - k (x cos beta + y sin beta) + phase): a wave travelling toward beta."""
    cb, sb = np.cos(np.radians(heading_deg)), np.sin(np.radians(heading_deg))

    def eta(t: float, x: float, y: float) -> float:
        return amplitude_m * np.cos(omega_rad_s * t - wavenumber_rad_m * (x * cb + y * sb) + phase_rad)

    return eta


def on_grid(eta: Elevation, spacing_x_m: float, spacing_y_m: float) -> Elevation:
    """eta interpolated bilinearly between the nodes of a horizontal grid through the origin, as
    SeaState stores and interpolates the elevation (dX = X_HalfWidth / (NX - 1))."""

    def gridded(t: float, x: float, y: float) -> float:
        i, j = np.floor(x / spacing_x_m), np.floor(y / spacing_y_m)
        fx, fy = x / spacing_x_m - i, y / spacing_y_m - j
        x0, y0 = i * spacing_x_m, j * spacing_y_m
        x1, y1 = x0 + spacing_x_m, y0 + spacing_y_m
        return ((1 - fx) * (1 - fy) * eta(t, x0, y0) + fx * (1 - fy) * eta(t, x1, y0)
                + (1 - fx) * fy * eta(t, x0, y1) + fx * fy * eta(t, x1, y1))

    return gridded
