"""Member hydrostatics up to the instantaneous free surface, HydroDyn's MHstLMod 2.

The pressure is the still-water hydrostatic pressure p = -rho g z (z up from the still water
line; negative, a suction, between z = 0 and a crest), integrated over the part of each member
surface below the free surface. As HydroDyn does, the free surface is a plane near each piece
of surface: for the side walls of each element (the member cut into ``n_elements`` equal
lengths) the plane through (x, y, eta(x, y)) at the element's midpoint, normal to the wave
surface there; for each end plate the plane at its end node. A load F = -int p n dA acts on
each wetted face, moments about the origin.

Here each face is a planar polygon (rectangular, possibly tapered, members: the side walls of
an element are planar quadrilaterals) clipped by its plane; the pressure is linear in z, so
the force and moment integrands are at most quadratic and the edge-midpoint rule on a fan of
triangles integrates them exactly. This is an independent computation of what HydroDyn's
``getElementHstLds_Mod2_Rec`` and ``GetEndPlateHstLds_Rec`` integrate in closed form along the
element (adaptive Simpson, relative tolerance 1e-6).

Pure numpy, no numba (about 1 ms per element and time step): ``HydroOptions(hydrostatics=
"free_surface")`` for a prescribed motion (``fowt-sim loads``), not a time-stepping path.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from fowt_hydro_sim.frames import rotation_matrix as rotation_matrices
from fowt_hydro_sim.physics.config import ConfigError

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


def platform_members(platform) -> list[RectangularMember]:
    """The platform's members for these hydrostatics (width = HydroDyn's side A, along the
    section's direction d1 before the spin, height = side B; taper and spin as the platform
    gives them; one element per strip length, HydroDyn's MDivSize); ConfigError naming a
    circular member (not implemented)."""
    members = []
    for m in platform.members:
        if m.drag_only:  # its buoyancy is the potential flow's
            continue
        if m.section != "rectangular":
            raise ConfigError(f"hydrostatics 'free_surface': member {m.name} is {m.section}: implemented for "
                              "rectangular members only")
        length = math.dist(m.end_a_m, m.end_b_m)
        (w0, h0), (w1, h1) = m.sides_at(0.0), m.sides_at(1.0)
        members.append(RectangularMember(m.end_a_m, m.end_b_m, (w0, w1), (h0, h1), m.spin_deg,
                                         max(1, math.ceil(length / m.strip_length_m - 1e-9))))
    return members


def prescribed_motion_wrenches(members: list[RectangularMember], eta: Elevation, time_s: np.ndarray,
                               motion: np.ndarray, rho: float, g: float) -> np.ndarray:
    """(n, 6) hydrostatic loads along a prescribed motion (n, 6: x y z, roll pitch yaw), global
    axes, moments about the displaced reference point."""
    rotations = rotation_matrices(motion[:, 3], motion[:, 4], motion[:, 5])
    out = np.zeros((len(time_s), 6))
    for i, t in enumerate(time_s):
        position = np.asarray(motion[i, 0:3], float)
        total = sum(member_wrench(m, eta, float(t), rho, g, rotations[:, :, i], position) for m in members)
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
