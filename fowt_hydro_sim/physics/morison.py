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

import math

import numpy as np
from numba import njit

from fowt_hydro_sim.physics.jit import step_loop
from fowt_hydro_sim.physics.rigid_body import cross3, to_body
from fowt_hydro_sim.physics.strips import Discretisation


@step_loop
def wetted_fraction(z_centre_m: float, axis_z: float, length_m: float) -> float:
    half = 0.5 * length_m * abs(axis_z)
    if half < 1e-9:
        return 1.0 if z_centre_m < 0.0 else 0.0
    return min(1.0, max(0.0, (half - z_centre_m) / (2.0 * half)))


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


@step_loop
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


@step_loop
def submerged_points(rotation: np.ndarray, position_z_m: float, centre: np.ndarray, surface_m: np.ndarray,
                     out: np.ndarray) -> None:
    """1 where a point (end plate centre) is below the water surface (``surface_m``, per point)
    at the pose, else 0."""
    for i in range(centre.shape[0]):
        c = centre[i]
        z = position_z_m + rotation[2, 0] * c[0] + rotation[2, 1] * c[1] + rotation[2, 2] * c[2] - surface_m[i]
        out[i] = 1.0 if z < 0.0 else 0.0


@step_loop
def lever_arms(rotation: np.ndarray, points: np.ndarray, out: np.ndarray) -> None:
    """R r of each body-frame point (n, 3) into ``out`` (n, 3): its world-axes offset from the
    reference point."""
    for i in range(points.shape[0]):
        for r in range(3):
            out[i, r] = rotation[r, 0] * points[i, 0] + rotation[r, 1] * points[i, 1] + rotation[r, 2] * points[i, 2]


@njit(cache=True, inline="always")
def _add_mass_about(out: np.ndarray, scale: float, r: np.ndarray, a: np.ndarray) -> None:
    """out += scale J^T A J = scale [[A, -A S], [S A, -S A S]], S = skew(r): the 6x6 about the
    reference point of a symmetric 3x3 added mass A at lever arm r (written out: no
    small-matrix products in the step loop). Column k of S A is r x A[:, k]; row j of
    -S A S is r x (S A)[j, :]."""
    cols = (cross3((r[0], r[1], r[2]), (a[0, 0], a[1, 0], a[2, 0])),
            cross3((r[0], r[1], r[2]), (a[0, 1], a[1, 1], a[2, 1])),
            cross3((r[0], r[1], r[2]), (a[0, 2], a[1, 2], a[2, 2])))
    for j in range(3):
        row = (cols[0][j], cols[1][j], cols[2][j])  # (S A)[j, :]
        for k in range(3):
            out[j, k] += scale * a[j, k]
            out[3 + j, k] += scale * row[k]
            out[k, 3 + j] += scale * row[k]  # -(A S) = (S A)^T, A symmetric
        corner = cross3((r[0], r[1], r[2]), row)
        out[3 + j, 3] += scale * corner[0]
        out[3 + j, 4] += scale * corner[1]
        out[3 + j, 5] += scale * corner[2]


@njit(cache=True)
def added_mass_about(arm: np.ndarray, mass_3x3: np.ndarray) -> np.ndarray:
    """6x6 added mass about the reference point of 3x3 added masses at points ``arm``:
    J^T A J = [[A, -A S], [S A, -S A S]] with S = skew(arm)."""
    out = np.zeros((arm.shape[0], 6, 6))
    for i in range(arm.shape[0]):
        _add_mass_about(out[i], 1.0, arm[i], mass_3x3[i])
    return out


def added_mass_moments(centre: np.ndarray, mass_3x3: np.ndarray, wet_length: np.ndarray) -> np.ndarray:
    """Moments of the strips' 3x3 added mass (world-fixed: fixed directions) times their
    ``wet_length`` over their body-frame centres c: [sum L A, sum L c_n A (n = 0..2), sum L c_n
    c_q A (n, q = 0..2)], (13, 3, 3); ``deep_added_mass_about`` turns them into the strips'
    6x6 at any attitude without a sum over strips."""
    weight = wet_length[:, None, None] * mass_3x3
    first = np.einsum("in,ijk->njk", centre, weight)
    second = np.einsum("in,iq,ijk->nqjk", centre, centre, weight).reshape(9, 3, 3)
    return np.ascontiguousarray(np.concatenate([weight.sum(axis=0)[None], first, second]))


@njit(cache=True, inline="always")
def _levi(i: int, j: int, k: int) -> float:
    """The Levi-Civita symbol: skew(r)[i, k] = sum_j eps_ijk r_j."""
    return 0.5 * (i - j) * (j - k) * (k - i)


@step_loop
def rotated_moments(rotation: np.ndarray, moments: np.ndarray, first: np.ndarray, half: np.ndarray,
                    second: np.ndarray) -> None:
    """From ``added_mass_moments``, at lever arms r = R c: P_m = sum L r_m A = sum_n R_mn (sum L
    c_n A) into ``first`` (3, 3, 3) and Q_mp = sum L r_m r_p A = sum_nq R_mn R_pq (sum L c_n c_q
    A) into ``second`` (3, 3, 3, 3); ``half`` (3, 3, 3, 3) is scratch."""
    first[:] = 0.0
    half[:] = 0.0
    second[:] = 0.0
    for m in range(3):
        for n in range(3):
            rmn = rotation[m, n]
            for j in range(3):
                for k in range(3):
                    first[m, j, k] += rmn * moments[1 + n, j, k]
                    for q in range(3):
                        half[m, q, j, k] += rmn * moments[4 + 3 * n + q, j, k]
    for m in range(3):
        for p in range(3):
            for q in range(3):
                rpq = rotation[p, q]
                for j in range(3):
                    for k in range(3):
                        second[m, p, j, k] += rpq * half[m, q, j, k]


@step_loop
def added_mass_from_moments(total: np.ndarray, first: np.ndarray, second: np.ndarray, out: np.ndarray) -> None:
    """The strips' sum of L J^T A J = [[A, -A S], [S A, -S A S]] (S = skew(r), linear in r)
    into ``out`` (6, 6), from sum L A (``total``) and ``rotated_moments``' P and Q:
    (S A)[j, k] = eps_jml P_m[l, k], (S A S)[j, k] = eps_jml eps_pqk Q_mq[l, p]."""
    for j in range(3):
        for k in range(3):
            out[j, k] = total[j, k]
            sa, sas = 0.0, 0.0
            for m in range(3):
                for l in range(3):
                    e = _levi(j, m, l)
                    if e == 0.0:
                        continue
                    sa += e * first[m, l, k]
                    for q in range(3):
                        for p in range(3):
                            sas += e * _levi(p, q, k) * second[m, q, l, p]
            out[3 + j, k] = sa
            out[k, 3 + j] = sa
            out[3 + j, 3 + k] = -sas


@step_loop
def centripetal_from_moments(first: np.ndarray, second: np.ndarray, omega: tuple, out: np.ndarray) -> None:
    """The strips' centripetal added-mass wrench -sum L A w x (w x r) (moment about the
    reference point) into ``out`` (6,), from ``rotated_moments``' P and Q: with w x (w x r)
    = W r, W = w w^T - |w|^2 I, the force is -sum_kl W_kl P_l[:, k] and the moment
    -eps_jab sum_kl W_kl Q_al[b, k]; ``omega`` a 3-tuple in the moments' axes."""
    w2 = omega[0] ** 2 + omega[1] ** 2 + omega[2] ** 2
    for j in range(6):
        out[j] = 0.0
    for k in range(3):
        for l in range(3):
            w_kl = omega[k] * omega[l] - (w2 if k == l else 0.0)
            if w_kl == 0.0:
                continue
            for j in range(3):
                out[j] -= w_kl * first[l, j, k]
                for a in range(3):
                    for b in range(3):
                        e = _levi(j, a, b)
                        if e != 0.0:
                            out[3 + j] -= e * w_kl * second[a, l, b, k]


def deep_added_mass_about(rotation: np.ndarray, moments: np.ndarray) -> np.ndarray:
    """The strips' sum of L J^T A J with lever arms r = R c, (6, 6), from
    ``added_mass_moments`` (the deep strips', or all strips' wetted as at rest)."""
    first, half, second, out = np.empty((3, 3, 3)), np.empty((3, 3, 3, 3)), np.empty((3, 3, 3, 3)), np.empty((6, 6))
    rotated_moments(rotation, moments, first, half, second)
    added_mass_from_moments(moments[0], first, second, out)
    return out


@step_loop
def add_wet_added_mass(wet: np.ndarray, length: np.ndarray, deep: np.ndarray, added_mass_6x6: np.ndarray,
                       arm: np.ndarray, added_mass_3x3: np.ndarray, about_arm: bool, out: np.ndarray) -> None:
    """Add each strip's 6x6 added mass times its wetted length to ``out``, which comes holding
    the ``deep`` strips' fully wet (``deep_added_mass_about``; so a deep strip adds only its
    difference, none while it stays under water: the step loop does not sum the strips that
    are always wet). The strip's 6x6 is ``added_mass_6x6[i]`` (body axes, rotating
    directions) or, ``about_arm``, its 3x3 at lever arm ``arm[i]`` (world axes, fixed
    directions)."""
    for i in range(length.size):
        scale = (wet[i] - 1.0) * length[i] if deep[i] else wet[i] * length[i]
        if scale == 0.0:
            continue
        if about_arm:
            _add_mass_about(out, scale, arm[i], added_mass_3x3[i])
        else:
            _add_scaled(out, scale, added_mass_6x6[i])


@step_loop
def relative_velocities(frame: np.ndarray, world_axes: bool, velocity: np.ndarray, omega: np.ndarray,
                        kinematics: np.ndarray, arm: np.ndarray, directions: np.ndarray,
                        kinematics_point: np.ndarray, wet: np.ndarray, skip_dry: bool, v_rel: np.ndarray,
                        a_fluid: np.ndarray) -> None:
    """Per strip: transverse relative velocity (d1, d2) and transverse fluid acceleration
    (d1, d2) in the frame's axes, written to ``v_rel`` and ``a_fluid`` (n, 2): the inputs of
    the drag and inertia terms. ``arm``: the strips' centres in the frame; ``world_axes``: the
    frame is the identity (fixed directions), the kinematics are taken as they are. Dry strips
    (``wet`` 0) get them too, so that drag filters see a continuous input, unless
    ``skip_dry`` (strips wetted as at rest at every step: a dry strip never loads, its entries
    are left as they are and it has no filters: ``dynamics``)."""
    v_body = to_body(frame, velocity[0], velocity[1], velocity[2])
    w_body = to_body(frame, omega[0], omega[1], omega[2])
    for i in range(arm.shape[0]):
        if skip_dry and wet[i] == 0.0:
            continue
        p = kinematics_point[i]
        if world_axes:
            u = (kinematics[p, 0], kinematics[p, 1], kinematics[p, 2])
            a = (kinematics[p, 3], kinematics[p, 4], kinematics[p, 5])
        else:
            u = to_body(frame, kinematics[p, 0], kinematics[p, 1], kinematics[p, 2])
            a = to_body(frame, kinematics[p, 3], kinematics[p, 4], kinematics[p, 5])
        spin = cross3(w_body, (arm[i, 0], arm[i, 1], arm[i, 2]))
        vr0 = u[0] - v_body[0] - spin[0]
        vr1 = u[1] - v_body[1] - spin[1]
        vr2 = u[2] - v_body[2] - spin[2]
        for k in range(2):
            d0, d1, d2 = directions[i, k, 0], directions[i, k, 1], directions[i, k, 2]
            v_rel[i, k] = vr0 * d0 + vr1 * d1 + vr2 * d2
            a_fluid[i, k] = a[0] * d0 + a[1] * d1 + a[2] * d2


@njit(cache=True, inline="always")
def _plus_wrench(wrench: tuple, point: tuple, f0: float, f1: float, f2: float) -> tuple:
    """wrench + [f; point x f], as a 6-tuple (kept in registers over the strip loop)."""
    return (wrench[0] + f0, wrench[1] + f1, wrench[2] + f2, wrench[3] + (point[1] * f2 - point[2] * f1),
            wrench[4] + (point[2] * f0 - point[0] * f2), wrench[5] + (point[0] * f1 - point[1] * f0))


@step_loop
def strip_loads(frame: np.ndarray, omega: np.ndarray, wet: np.ndarray, v_rel: np.ndarray, a_fluid: np.ndarray,
                v_band: np.ndarray, filter_column: np.ndarray, arm: np.ndarray, directions: np.ndarray,
                length: np.ndarray, inertia: np.ndarray, added_mass: np.ndarray, band_drag: np.ndarray,
                constant_drag: np.ndarray, filtered: np.ndarray, with_centripetal: bool, out: np.ndarray) -> None:
    """The strips' drag, fluid-inertia and (``with_centripetal``) centripetal added-mass
    wrenches (frame axes, about the reference point) into ``out`` rows 0-2, each strip's
    loads times its wetted length (``wet`` x ``length``). Their 6x6 added mass:
    ``add_wet_added_mass``; without the centripetal wrench, ``centripetal_from_moments``
    gives it.

    Drag per wetted length (d1, d2): over the bands for filtered directions, 0.5 rho Cd_b D
    |v_b| v_b (``band_drag`` (n, n_bands, 2) = 0.5 rho Cd_b D; ``v_band`` (n_bands, 2 m), strip
    i's in columns 2 c, 2 c + 1 with c = ``filter_column[i]``: drag_filters), otherwise 0.5 rho Cd D |v_rel| v_rel
    (``constant_drag`` (n, 2)). No bands: the constant-Cd model. (Written out in the loop:
    an array handed to a helper per strip costs reference counting that is most of the loop.)"""
    w_body = to_body(frame, omega[0], omega[1], omega[2])
    drag = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    fluid = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    spin = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    for i in range(arm.shape[0]):
        if wet[i] == 0.0:
            continue
        c = (arm[i, 0], arm[i, 1], arm[i, 2])
        d1 = (directions[i, 0, 0], directions[i, 0, 1], directions[i, 0, 2])
        d2 = (directions[i, 1, 0], directions[i, 1, 1], directions[i, 1, 2])
        wet_length = wet[i] * length[i]
        v1, v2 = v_rel[i, 0], v_rel[i, 1]
        filtered1, filtered2 = filtered[i, 0], filtered[i, 1]
        drag1, drag2 = 0.0, 0.0
        if not (filtered1 and filtered2):
            speed = math.sqrt(v1 * v1 + v2 * v2)
            drag1 = 0.0 if filtered1 else constant_drag[i, 0] * speed * v1
            drag2 = 0.0 if filtered2 else constant_drag[i, 1] * speed * v2
        column = 2 * filter_column[i]
        for b in range(v_band.shape[0]):
            b1, b2 = v_band[b, column], v_band[b, column + 1]
            band_speed = math.sqrt(b1 * b1 + b2 * b2)
            if filtered1:
                drag1 += band_drag[i, b, 0] * band_speed * b1
            if filtered2:
                drag2 += band_drag[i, b, 1] * band_speed * b2
        drag1, drag2 = drag1 * wet_length, drag2 * wet_length
        fluid1, fluid2 = inertia[i, 0] * a_fluid[i, 0] * wet_length, inertia[i, 1] * a_fluid[i, 1] * wet_length
        # both directions' forces first, then one moment per wrench
        drag = _plus_wrench(drag, c, drag1 * d1[0] + drag2 * d2[0], drag1 * d1[1] + drag2 * d2[1],
                            drag1 * d1[2] + drag2 * d2[2])
        fluid = _plus_wrench(fluid, c, fluid1 * d1[0] + fluid2 * d2[0], fluid1 * d1[1] + fluid2 * d2[1],
                             fluid1 * d1[2] + fluid2 * d2[2])
        if with_centripetal:
            a_c = cross3(w_body, cross3(w_body, c))
            spin1 = -added_mass[i, 0] * wet_length * (a_c[0] * d1[0] + a_c[1] * d1[1] + a_c[2] * d1[2])
            spin2 = -added_mass[i, 1] * wet_length * (a_c[0] * d2[0] + a_c[1] * d2[1] + a_c[2] * d2[2])
            spin = _plus_wrench(spin, c, spin1 * d1[0] + spin2 * d2[0], spin1 * d1[1] + spin2 * d2[1],
                                spin1 * d1[2] + spin2 * d2[2])
    for k in range(6):
        out[0, k] = drag[k]
        out[1, k] = fluid[k]
        out[2, k] = spin[k]


@step_loop
def end_plate_loads(frame: np.ndarray, velocity: np.ndarray, omega: np.ndarray, kinematics: np.ndarray,
                    arm: np.ndarray, normal: np.ndarray, submerged: np.ndarray, pressure_area: np.ndarray,
                    added_mass: np.ndarray, drag: np.ndarray, added_mass_6x6: np.ndarray,
                    added_mass_3x3: np.ndarray, about_arm: bool, kinematics_point: np.ndarray,
                    out_drag: np.ndarray, out_inertia: np.ndarray, out_centripetal: np.ndarray,
                    out_added_mass: np.ndarray) -> None:
    """Axial end-plate terms (frame axes): dynamic pressure on the end area, added mass and
    scattering on a hemisphere, drag 0.25 rho Cd A |w| w; only for submerged ends. Their
    added mass is ``added_mass_6x6[i]`` (body axes) or, ``about_arm``, the 3x3 at the lever
    arm (world axes), as in ``add_wet_added_mass``."""
    v_body = to_body(frame, velocity[0], velocity[1], velocity[2])
    w_body = to_body(frame, omega[0], omega[1], omega[2])
    for i in range(arm.shape[0]):
        c, n = arm[i], normal[i]
        if submerged[i] == 0.0:
            continue
        p = kinematics_point[i]
        u = to_body(frame, kinematics[p, 0], kinematics[p, 1], kinematics[p, 2])
        a = to_body(frame, kinematics[p, 3], kinematics[p, 4], kinematics[p, 5])
        point = (c[0], c[1], c[2])
        spin = cross3(w_body, point)
        centripetal = cross3(w_body, spin)
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
        if about_arm:
            _add_mass_about(out_added_mass, 1.0, c, added_mass_3x3[i])
        else:
            _add_scaled(out_added_mass, 1.0, added_mass_6x6[i])


def added_mass_tensors(geometry: Discretisation) -> tuple[np.ndarray, np.ndarray]:
    """Body-axes 3x3 added mass of each strip per unit wetted length and of each end plate."""
    s, plates = geometry.strips, geometry.plates
    strip_3x3 = np.einsum("nk,nki,nkj->nij", s.added_mass_kg_m, s.directions, s.directions)
    plate_3x3 = np.einsum("n,ni,nj->nij", plates.added_mass_kg, plates.normal, plates.normal)
    return np.ascontiguousarray(strip_3x3), np.ascontiguousarray(plate_3x3.reshape(-1, 3, 3))
