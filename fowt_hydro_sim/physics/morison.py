"""Strip-theory Morison loads in the relative form (HydroDyn's conventions; see strips.py).

Work is done in the axes of a ``frame``: the body axes when load directions rotate with the
body (frame = R; the strip geometry is constant there, fluid kinematics are rotated in and
loads rotated out once), the world axes when they stay at the undisplaced member and section
axes (HydroDyn's choice; frame = I and each strip's lever arm is R c). The added mass acts on
the body acceleration and is returned as a 6x6 matrix for the left-hand side; only its
velocity-dependent (centripetal) part is a force here.

A strip's loads act at its centre, scaled by its wetted fraction: the part of its displaced
(or undisplaced: HydroDyn's) length below the still water line, or with vertical wave
stretching below the instantaneous elevation over it, continuous as the strip crosses it.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from fowt_hydro_sim.physics.strips import Discretisation


@njit(cache=True)
def wetted_fraction(z_centre_m: float, axis_z: float, length_m: float) -> float:
    half = 0.5 * length_m * abs(axis_z)
    if half < 1e-9:
        return 1.0 if z_centre_m < 0.0 else 0.0
    return min(1.0, max(0.0, (half - z_centre_m) / (2.0 * half)))


@njit(cache=True, inline="always")
def _to_body(rotation: np.ndarray, x: float, y: float, z: float) -> tuple[float, float, float]:
    """R^T [x, y, z]: world axes to body axes."""
    return (rotation[0, 0] * x + rotation[1, 0] * y + rotation[2, 0] * z,
            rotation[0, 1] * x + rotation[1, 1] * y + rotation[2, 1] * z,
            rotation[0, 2] * x + rotation[1, 2] * y + rotation[2, 2] * z)


@njit(cache=True, inline="always")
def _cross(a: tuple, b: tuple) -> tuple[float, float, float]:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@njit(cache=True, inline="always")
def _add_wrench(out: np.ndarray, point: np.ndarray, f0: float, f1: float, f2: float) -> None:
    out[0] += f0
    out[1] += f1
    out[2] += f2
    out[3] += point[1] * f2 - point[2] * f1
    out[4] += point[2] * f0 - point[0] * f2
    out[5] += point[0] * f1 - point[1] * f0


@njit(cache=True, inline="always")
def _add_scaled(out: np.ndarray, scale: float, matrix: np.ndarray) -> None:
    for r in range(6):
        for c in range(6):
            out[r, c] += scale * matrix[r, c]


@njit(cache=True)
def wetted_fractions(rotation: np.ndarray, position_z_m: float, centre: np.ndarray, axis: np.ndarray,
                     length: np.ndarray, surface_m: np.ndarray, wet: np.ndarray) -> None:
    """Each strip's wetted fraction at the pose (rotation, heave) below the water surface at
    ``surface_m`` (per strip: 0, or the elevation with vertical stretching); identity and 0
    give the undisplaced wetted length."""
    for i in range(centre.shape[0]):
        c = centre[i]
        z = position_z_m + rotation[2, 0] * c[0] + rotation[2, 1] * c[1] + rotation[2, 2] * c[2] - surface_m[i]
        axis_z = rotation[2, 0] * axis[i, 0] + rotation[2, 1] * axis[i, 1] + rotation[2, 2] * axis[i, 2]
        wet[i] = wetted_fraction(z, axis_z, length[i])


@njit(cache=True)
def submerged_points(rotation: np.ndarray, position_z_m: float, centre: np.ndarray, surface_m: np.ndarray,
                     out: np.ndarray) -> None:
    """1 where a point (end plate centre) is below the water surface (``surface_m``, per point)
    at the pose, else 0."""
    for i in range(centre.shape[0]):
        c = centre[i]
        z = position_z_m + rotation[2, 0] * c[0] + rotation[2, 1] * c[1] + rotation[2, 2] * c[2] - surface_m[i]
        out[i] = 1.0 if z < 0.0 else 0.0


@njit(cache=True)
def lever_arms(rotation: np.ndarray, points: np.ndarray) -> np.ndarray:
    """R r of each body-frame point (n, 3): its world-axes offset from the reference point."""
    out = np.empty(points.shape)
    for i in range(points.shape[0]):
        for r in range(3):
            out[i, r] = rotation[r, 0] * points[i, 0] + rotation[r, 1] * points[i, 1] + rotation[r, 2] * points[i, 2]
    return out


@njit(cache=True)
def added_mass_about(arm: np.ndarray, mass_3x3: np.ndarray) -> np.ndarray:
    """6x6 added mass about the reference point of 3x3 added masses at points ``arm``:
    J^T A J = [[A, -A S], [S A, -S A S]] with S = skew(arm) (written out: no small-matrix
    products in the step loop)."""
    out = np.empty((arm.shape[0], 6, 6))
    sa, skew = np.empty((3, 3)), np.empty((3, 3))
    for i in range(arm.shape[0]):
        r, a = arm[i], mass_3x3[i]
        skew[0, 0], skew[0, 1], skew[0, 2] = 0.0, -r[2], r[1]
        skew[1, 0], skew[1, 1], skew[1, 2] = r[2], 0.0, -r[0]
        skew[2, 0], skew[2, 1], skew[2, 2] = -r[1], r[0], 0.0
        for j in range(3):
            for k in range(3):
                sa[j, k] = skew[j, 0] * a[0, k] + skew[j, 1] * a[1, k] + skew[j, 2] * a[2, k]
        for j in range(3):
            for k in range(3):
                out[i, j, k] = a[j, k]
                out[i, 3 + j, k] = sa[j, k]
                out[i, k, 3 + j] = sa[j, k]  # -(A S) = (S A)^T, A symmetric
                out[i, 3 + j, 3 + k] = -(sa[j, 0] * skew[0, k] + sa[j, 1] * skew[1, k] + sa[j, 2] * skew[2, k])
    return out


@njit(cache=True)
def relative_velocities(frame: np.ndarray, velocity: np.ndarray, omega: np.ndarray, kinematics: np.ndarray,
                        arm: np.ndarray, directions: np.ndarray, kinematics_point: np.ndarray,
                        v_rel: np.ndarray, a_fluid: np.ndarray) -> None:
    """Per strip: transverse relative velocity (d1, d2) and transverse fluid acceleration
    (d1, d2) in the frame's axes, written to ``v_rel`` and ``a_fluid``: the inputs of the drag
    and inertia terms. Dry strips get them too (with the kinematics at the water line), so
    that drag filters see a continuous input. ``arm``: the strips' centres in the frame."""
    v_body = _to_body(frame, velocity[0], velocity[1], velocity[2])
    w_body = _to_body(frame, omega[0], omega[1], omega[2])
    for i in range(arm.shape[0]):
        c = arm[i]
        p = kinematics_point[i]
        u = _to_body(frame, kinematics[p, 0], kinematics[p, 1], kinematics[p, 2])
        a = _to_body(frame, kinematics[p, 3], kinematics[p, 4], kinematics[p, 5])
        spin = _cross(w_body, (c[0], c[1], c[2]))
        vr0 = u[0] - v_body[0] - spin[0]
        vr1 = u[1] - v_body[1] - spin[1]
        vr2 = u[2] - v_body[2] - spin[2]
        for k in range(2):
            d = directions[i, k]
            v_rel[i, k] = vr0 * d[0] + vr1 * d[1] + vr2 * d[2]
            a_fluid[i, k] = a[0] * d[0] + a[1] * d[1] + a[2] * d[2]


@njit(cache=True)
def strip_loads(frame: np.ndarray, omega: np.ndarray, wet: np.ndarray, a_fluid: np.ndarray,
                drag_per_length: np.ndarray, arm: np.ndarray,
                directions: np.ndarray, length: np.ndarray, inertia: np.ndarray,
                added_mass: np.ndarray, added_mass_6x6: np.ndarray, deep: np.ndarray,
                out_drag: np.ndarray, out_inertia: np.ndarray, out_centripetal: np.ndarray,
                out_added_mass: np.ndarray) -> None:
    """Add the strips' drag, fluid-inertia and centripetal added-mass wrenches (frame axes,
    about the reference point) and their 6x6 added mass (frame axes) to the outputs.

    ``drag_per_length`` (n, 2) is the transverse drag per unit wetted length of the drag
    model (drag_filters.drag_per_length). ``out_added_mass`` comes holding the 6x6 added
    mass of the ``deep`` strips fully wet (``deep_added_mass``): a deep strip adds only its
    difference from that (none while it stays under water), so the step loop does not sum
    the 6x6 matrices of the strips that are always wet.
    """
    w_body = _to_body(frame, omega[0], omega[1], omega[2])
    for i in range(arm.shape[0]):
        if deep[i] and wet[i] != 1.0:
            _add_scaled(out_added_mass, (wet[i] - 1.0) * length[i], added_mass_6x6[i])
        if wet[i] == 0.0:
            continue
        c = arm[i]
        wet_length = wet[i] * length[i]
        centripetal = _cross(w_body, _cross(w_body, (c[0], c[1], c[2])))
        d1, d2 = directions[i, 0], directions[i, 1]
        drag1, drag2 = drag_per_length[i, 0] * wet_length, drag_per_length[i, 1] * wet_length
        fluid1, fluid2 = inertia[i, 0] * a_fluid[i, 0] * wet_length, inertia[i, 1] * a_fluid[i, 1] * wet_length
        spin1 = -added_mass[i, 0] * wet_length * (centripetal[0] * d1[0] + centripetal[1] * d1[1]
                                                   + centripetal[2] * d1[2])
        spin2 = -added_mass[i, 1] * wet_length * (centripetal[0] * d2[0] + centripetal[1] * d2[1]
                                                   + centripetal[2] * d2[2])
        # both directions' forces first, then one moment per wrench
        _add_wrench(out_drag, c, drag1 * d1[0] + drag2 * d2[0], drag1 * d1[1] + drag2 * d2[1],
                    drag1 * d1[2] + drag2 * d2[2])
        _add_wrench(out_inertia, c, fluid1 * d1[0] + fluid2 * d2[0], fluid1 * d1[1] + fluid2 * d2[1],
                    fluid1 * d1[2] + fluid2 * d2[2])
        _add_wrench(out_centripetal, c, spin1 * d1[0] + spin2 * d2[0], spin1 * d1[1] + spin2 * d2[1],
                    spin1 * d1[2] + spin2 * d2[2])
        if not deep[i]:
            _add_scaled(out_added_mass, wet_length, added_mass_6x6[i])


@njit(cache=True)
def deep_added_mass(length: np.ndarray, added_mass_6x6: np.ndarray, deep: np.ndarray) -> np.ndarray:
    """Sum of the ``deep`` strips' 6x6 added mass, fully wet (strip_loads' starting value)."""
    out = np.zeros((6, 6))
    for i in range(length.size):
        if deep[i]:
            _add_scaled(out, length[i], added_mass_6x6[i])
    return out


@njit(cache=True)
def end_plate_loads(frame: np.ndarray, velocity: np.ndarray, omega: np.ndarray, kinematics: np.ndarray,
                    arm: np.ndarray, normal: np.ndarray, submerged: np.ndarray, pressure_area: np.ndarray,
                    added_mass: np.ndarray, drag: np.ndarray, added_mass_6x6: np.ndarray,
                    kinematics_point: np.ndarray, out_drag: np.ndarray, out_inertia: np.ndarray,
                    out_centripetal: np.ndarray, out_added_mass: np.ndarray) -> None:
    """Axial end-plate terms (frame axes): dynamic pressure on the end area, added mass and
    scattering on a hemisphere, drag 0.25 rho Cd A |w| w; only for submerged ends."""
    v_body = _to_body(frame, velocity[0], velocity[1], velocity[2])
    w_body = _to_body(frame, omega[0], omega[1], omega[2])
    for i in range(arm.shape[0]):
        c, n = arm[i], normal[i]
        if submerged[i] == 0.0:
            continue
        p = kinematics_point[i]
        u = _to_body(frame, kinematics[p, 0], kinematics[p, 1], kinematics[p, 2])
        a = _to_body(frame, kinematics[p, 3], kinematics[p, 4], kinematics[p, 5])
        point = (c[0], c[1], c[2])
        spin = _cross(w_body, point)
        centripetal = _cross(w_body, spin)
        w_rel = ((u[0] - v_body[0] - spin[0]) * n[0] + (u[1] - v_body[1] - spin[1]) * n[1]
                 + (u[2] - v_body[2] - spin[2]) * n[2])
        a_n = a[0] * n[0] + a[1] * n[1] + a[2] * n[2]
        c_n = centripetal[0] * n[0] + centripetal[1] * n[1] + centripetal[2] * n[2]
        f_drag = drag[i] * abs(w_rel) * w_rel
        f_fluid = pressure_area[i] * kinematics[p, 6] + added_mass[i] * a_n
        f_spin = -added_mass[i] * c_n
        _add_wrench(out_drag, c, f_drag * n[0], f_drag * n[1], f_drag * n[2])
        _add_wrench(out_inertia, c, f_fluid * n[0], f_fluid * n[1], f_fluid * n[2])
        _add_wrench(out_centripetal, c, f_spin * n[0], f_spin * n[1], f_spin * n[2])
        _add_scaled(out_added_mass, 1.0, added_mass_6x6[i])


def added_mass_tensors(geometry: Discretisation) -> tuple[np.ndarray, np.ndarray]:
    """Body-axes 3x3 added mass of each strip per unit wetted length and of each end plate."""
    s, plates = geometry.strips, geometry.plates
    strip_3x3 = np.einsum("nk,nki,nkj->nij", s.added_mass_kg_m, s.directions, s.directions)
    plate_3x3 = np.einsum("n,ni,nj->nij", plates.added_mass_kg, plates.normal, plates.normal)
    return np.ascontiguousarray(strip_3x3), np.ascontiguousarray(plate_3x3.reshape(-1, 3, 3))
