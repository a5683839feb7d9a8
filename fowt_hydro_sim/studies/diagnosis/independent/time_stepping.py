"""The independent simulator's time stepping, compiled with numba: RK4 of the Cummins
equation with the radiation memory as a trapezoidal convolution over the velocity history
(computed once per step, extrapolated linearly within it), the loads known in advance read
from a table on a uniform grid (linear interpolation; periodic or not), quadratic drag at the
undisplaced strip points, the spring lines on the displaced fairleads and an optional extra
surge restoring curve (a table against the surge offset). Shares nothing with physics/."""
from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True)
def _lookup(t, grid_start_s, grid_step_s, periodic, table):
    """Linear interpolation of ``table`` (n, ...) on the grid at time t (mod the grid's
    length when periodic, clamped to its ends otherwise): the two indices and the weight."""
    n = table.shape[0]
    u = (t - grid_start_s) / grid_step_s
    i = math.floor(u)
    w = u - i
    if periodic:
        i0 = i % n
        i1 = (i0 + 1) % n
    else:
        i0 = min(max(i, 0), n - 1)
        i1 = min(i0 + 1, n - 1)
    return i0, i1, w


@njit(cache=True)
def _rotation(r, p, y):
    cr, cp, cy = math.cos(r), math.cos(p), math.cos(y)
    sr, sp, sy = math.sin(r), math.sin(p), math.sin(y)
    out = np.empty((3, 3))
    out[0, 0], out[0, 1], out[0, 2] = cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr
    out[1, 0], out[1, 1], out[1, 2] = sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr
    out[2, 0], out[2, 1], out[2, 2] = -sp, cp * sr, cp * cr
    return out


@njit(cache=True)
def _mooring(x, fairlead, anchor, rest, pretension, stiffness, out):
    rot = _rotation(x[3], x[4], x[5])
    for line in range(fairlead.shape[0]):
        arm = rot @ fairlead[line]
        chord = anchor[line] - (x[:3] + arm)
        distance = math.sqrt(chord[0] ** 2 + chord[1] ** 2 + chord[2] ** 2)
        tension = max(0.0, pretension + stiffness * (distance - rest[line]))
        _add_force(arm, tension * chord / distance, out)


@njit(cache=True)
def _add_force(point, force, out):
    out[0] += force[0]
    out[1] += force[1]
    out[2] += force[2]
    out[3] += point[1] * force[2] - point[2] * force[1]
    out[4] += point[2] * force[0] - point[0] * force[2]
    out[5] += point[0] * force[1] - point[1] * force[0]


@njit(cache=True)
def _drag(v, fluid0, fluid1, w, points, n_circular, n_box, axis, circular_cda, box_direction, box_cda,
          plate_cda, rho, out):
    relative = np.empty(3)
    force = np.empty(3)
    for p in range(points.shape[0]):
        r = points[p]
        for k in range(3):
            relative[k] = (1.0 - w) * fluid0[p, k] + w * fluid1[p, k]
        relative[0] -= v[0] + v[4] * r[2] - v[5] * r[1]
        relative[1] -= v[1] + v[5] * r[0] - v[3] * r[2]
        relative[2] -= v[2] + v[3] * r[1] - v[4] * r[0]
        if p < n_circular:
            along = relative[0] * axis[p, 0] + relative[1] * axis[p, 1] + relative[2] * axis[p, 2]
            for k in range(3):
                force[k] = relative[k] - along * axis[p, k]
            speed = math.sqrt(force[0] ** 2 + force[1] ** 2 + force[2] ** 2)
            for k in range(3):
                force[k] *= 0.5 * rho * circular_cda[p] * speed
        elif p < n_circular + n_box:
            q = p - n_circular
            force[:] = 0.0
            for d in range(2):
                u = (relative[0] * box_direction[q, d, 0] + relative[1] * box_direction[q, d, 1]
                     + relative[2] * box_direction[q, d, 2])
                for k in range(3):
                    force[k] += 0.5 * rho * box_cda[q, d] * abs(u) * u * box_direction[q, d, k]
        else:
            force[0] = 0.0
            force[1] = 0.0
            force[2] = 0.25 * rho * plate_cda[p - n_circular - n_box] * abs(relative[2]) * relative[2]
        _add_force(r, force, out)


@njit(cache=True)
def integrate(steps, dt_s, start_s, x0, grid_start_s, grid_step_s, periodic, excitation, fluid,
              inverse_mass, stiffness, kernel_w, b1, b2, drag_on, rho, points, n_circular, n_box, axis,
              circular_cda, box_direction, box_cda, plate_cda, mooring_on, fairlead, anchor, rest, pretension,
              line_stiffness, curve_x_m, curve_force_n):
    """Positions and velocities at each step from ``start_s`` (n + 1, 6)."""
    nk = kernel_w.shape[0]
    moor0 = np.zeros(6)
    if mooring_on:
        _mooring(np.zeros(6), fairlead, anchor, rest, pretension, line_stiffness, moor0)
    curve0 = np.interp(0.0, curve_x_m, curve_force_n) if curve_x_m.size else 0.0
    history = np.zeros((steps + nk, 6))
    positions = np.empty((steps + 1, 6))
    velocities = np.empty((steps + 1, 6))
    x = x0.copy()
    v = np.zeros(6)
    positions[0], velocities[0] = x, v
    previous = np.zeros(6)
    memory = np.zeros(6)
    xs = np.empty((4, 6))
    vs = np.empty((4, 6))
    accelerations = np.empty((4, 6))
    load = np.empty(6)
    for n in range(steps):
        history[n + nk - 1] = v
        memory[:] = 0.0
        for k in range(nk):
            vk = history[n + nk - 1 - k]
            for i in range(6):
                acc = 0.0
                for j in range(6):
                    acc += kernel_w[k, i, j] * vk[j]
                memory[i] += acc
        slope = (memory - previous) / dt_s if n else np.zeros(6)
        previous[:] = memory
        t = start_s + n * dt_s
        for stage in range(4):
            if stage == 0:
                xs[0], vs[0], tau = x, v, 0.0
            elif stage < 3:
                xs[stage] = x + 0.5 * dt_s * vs[stage - 1]
                vs[stage] = v + 0.5 * dt_s * accelerations[stage - 1]
                tau = 0.5 * dt_s
            else:
                xs[3] = x + dt_s * vs[2]
                vs[3] = v + dt_s * accelerations[2]
                tau = dt_s
            xi, vi = xs[stage], vs[stage]
            i0, i1, w = _lookup(t + tau, grid_start_s, grid_step_s, periodic, excitation)
            for i in range(6):
                load[i] = ((1.0 - w) * excitation[i0, i] + w * excitation[i1, i] - memory[i] - tau * slope[i]
                           - b1[i] * vi[i] - b2[i] * abs(vi[i]) * vi[i])
                for j in range(6):
                    load[i] -= stiffness[i, j] * xi[j]
            if drag_on:
                _drag(vi, fluid[i0], fluid[i1], w, points, n_circular, n_box, axis, circular_cda, box_direction,
                      box_cda, plate_cda, rho, load)
            if mooring_on:
                load -= moor0
                _mooring(xi, fairlead, anchor, rest, pretension, line_stiffness, load)
            if curve_x_m.size:
                load[0] += np.interp(xi[0], curve_x_m, curve_force_n) - curve0
            accelerations[stage] = inverse_mass @ load
        x = x + dt_s / 6.0 * (vs[0] + 2 * vs[1] + 2 * vs[2] + vs[3])
        v = v + dt_s / 6.0 * (accelerations[0] + 2 * accelerations[1] + 2 * accelerations[2] + accelerations[3])
        positions[n + 1], velocities[n + 1] = x, v
    return positions, velocities
