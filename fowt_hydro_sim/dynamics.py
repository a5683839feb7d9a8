"""6-DOF equations of motion and the fixed-step ABM4 integrator, compiled with numba.

State y = [x, y, z, roll, pitch, yaw, v_x, v_y, v_z, w_x, w_y, w_z] (world axes, reference
point), followed by the drag filter states, ordered (filter state, strip, direction); none
for the constant-Cd model. The right-hand side sums the load components of ``LOAD_COMPONENTS`` and
solves (M + A(q) + M_x) [a; alpha] = F with the strip added mass A and the extension's mass M_x
on the left-hand side. The ``extension`` component (extension.py) holds loads beyond the
Morison model that the gap diagnosis switches on (zero otherwise).

``integrate`` advances any number of steps in compiled code; a node stepping one dt at a
time and a batch run call the same function, so both give the same numbers, bit for bit.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from .drag_filters import band_velocities, drag_per_length, filter_rates
from .morison import end_plate_loads, relative_velocities, strip_loads
from .mooring import mooring_wrench
from .rigid_body import cross, euler_rates, mass_matrix_and_bias, rotate_inertia, rotation_matrix, solve_spd

LOAD_COMPONENTS = ("drag", "inertia", "added_mass", "hydrostatic", "mooring", "gravity", "external", "extension")
N_LOADS = len(LOAD_COMPONENTS)
N_BODY_STATES = 12


class KernelData(NamedTuple):
    """Everything the compiled right-hand side reads (arrays and scalars only)."""

    wave_table: np.ndarray  # (n_samples, n_points, 7) float32, periodic
    wave_table_step_s: float
    strip_centre: np.ndarray
    strip_axis: np.ndarray
    strip_directions: np.ndarray
    strip_length: np.ndarray
    strip_inertia: np.ndarray
    strip_added_mass: np.ndarray
    strip_added_mass_6x6: np.ndarray
    strip_drag: np.ndarray  # (n, 2): 0.5 rho Cd b, constant Cd (unfiltered directions)
    band_drag: np.ndarray  # (n, n_bands, 2): 0.5 rho Cd_b b per drag band; no bands: constant Cd
    strip_filtered: np.ndarray  # (n, 2) bool: the direction's drag is summed over the bands
    filter_a: np.ndarray  # the filter bank (drag_filters.StateSpace), shared by every strip
    filter_a_nonzero: np.ndarray  # (nnz, 2) int64 entries of A that are not zero
    filter_b: np.ndarray
    filter_c: np.ndarray
    filter_c_nonzero: np.ndarray
    filter_d: np.ndarray
    strip_point: np.ndarray
    plate_centre: np.ndarray
    plate_normal: np.ndarray
    plate_pressure_area: np.ndarray
    plate_added_mass: np.ndarray
    plate_drag: np.ndarray
    plate_added_mass_6x6: np.ndarray
    plate_point: np.ndarray
    mass: float
    cog: np.ndarray
    inertia_cog: np.ndarray
    gravity: float
    buoyancy_wrench: np.ndarray
    hydrostatic_stiffness: np.ndarray
    fairleads: np.ndarray
    anchors: np.ndarray
    line_stiffness: float
    line_pretension: float
    line_length: float
    external_world: np.ndarray  # (6,) world axes, about the reference point
    external_body: np.ndarray  # (6,) body axes, about external_point
    external_point: np.ndarray  # (3,) body frame
    extension_force_table: np.ndarray  # (n_samples, 1, 6) world wrench at the reference point, periodic
    extension_force_step_s: float
    extension_linear_damping: np.ndarray  # (6, 6) on the reference point's world-axes velocity
    extension_quadratic_damping: np.ndarray  # (6,) per DOF: -B2 |v| v
    extension_stiffness: np.ndarray  # (6, 6) on the 6-DOF offset
    extension_cubic_stiffness: np.ndarray  # (6,) per DOF: -K3 q^3
    extension_mass: np.ndarray  # (6, 6) added to the mass matrix (world axes, reference point)


@njit(cache=True)
def interpolate_table(table: np.ndarray, step_s: float, t: float) -> np.ndarray:
    """Cubic (4-point Lagrange) interpolation in a periodic table at time t."""
    n, n_points, n_channels = table.shape
    x = t / step_s
    i = int(np.floor(x))
    s = x - i
    w = (-s * (s - 1.0) * (s - 2.0) / 6.0, (s + 1.0) * (s - 1.0) * (s - 2.0) / 2.0,
         -(s + 1.0) * s * (s - 2.0) / 2.0, (s + 1.0) * s * (s - 1.0) / 6.0)
    rows = ((i - 1) % n, i % n, (i + 1) % n, (i + 2) % n)
    out = np.empty((n_points, n_channels))
    for p in range(n_points):
        for c in range(n_channels):
            out[p, c] = (w[0] * table[rows[0], p, c] + w[1] * table[rows[1], p, c]
                         + w[2] * table[rows[2], p, c] + w[3] * table[rows[3], p, c])
    return out


@njit(cache=True)
def applied_loads(t: float, y: np.ndarray, d: KernelData, loads: np.ndarray,
                  filter_rates_out: np.ndarray) -> np.ndarray:
    """Fill ``loads`` (N_LOADS, 6; world axes, about the reference point) at state y and time
    t, with only the centripetal part in the added-mass row, and the drag filter states'
    rates; return the 6x6 added mass (world axes) that multiplies the body acceleration."""
    position, angles = y[0:3], y[3:6]
    velocity, omega = y[6:9], y[9:12]
    rotation = rotation_matrix(angles[0], angles[1], angles[2])
    kinematics = interpolate_table(d.wave_table, d.wave_table_step_s, t)

    body = np.zeros((3, 6))  # drag, inertia, centripetal added mass, body axes
    added_mass_body = np.zeros((6, 6))
    n_strips = d.strip_length.size
    wet, v_rel, a_fluid = np.empty(n_strips), np.empty((n_strips, 2)), np.empty((n_strips, 2))
    relative_velocities(rotation, position, velocity, omega, kinematics, d.strip_centre,
                        d.strip_axis, d.strip_directions, d.strip_length, d.strip_point,
                        wet, v_rel, a_fluid)
    filter_states = y[N_BODY_STATES:].reshape((d.filter_b.size, 2 * n_strips))
    v_flat = v_rel.reshape(2 * n_strips)
    v_band = np.empty((d.filter_d.size, 2 * n_strips))
    band_velocities(filter_states, v_flat, d.filter_c, d.filter_c_nonzero, d.filter_d, v_band)
    filter_rates(filter_states, v_flat, d.filter_a, d.filter_a_nonzero, d.filter_b,
                 filter_rates_out.reshape(filter_states.shape))
    drag = np.empty((n_strips, 2))
    drag_per_length(v_rel, v_band, d.band_drag, d.strip_drag, d.strip_filtered, drag)
    strip_loads(rotation, omega, wet, a_fluid, drag, d.strip_centre,
                d.strip_directions, d.strip_length, d.strip_inertia, d.strip_added_mass,
                d.strip_added_mass_6x6, body[0], body[1], body[2], added_mass_body)
    end_plate_loads(rotation, position, velocity, omega, kinematics, d.plate_centre, d.plate_normal,
                    d.plate_pressure_area, d.plate_added_mass, d.plate_drag, d.plate_added_mass_6x6,
                    d.plate_point, body[0], body[1], body[2], added_mass_body)
    for c in range(3):
        loads[c, 0:3] = rotation @ body[c, 0:3]
        loads[c, 3:6] = rotation @ body[c, 3:6]
    loads[3] = d.buoyancy_wrench - d.hydrostatic_stiffness @ y[0:6]
    loads[4] = mooring_wrench(position, rotation, d.fairleads, d.anchors, d.line_stiffness,
                              d.line_pretension, d.line_length)
    r_g = rotation @ d.cog
    weight = np.array([0.0, 0.0, -d.mass * d.gravity])
    loads[5, 0:3] = weight
    loads[5, 3:6] = cross(r_g, weight)
    force_body = rotation @ d.external_body[0:3]
    loads[6, 0:3] = d.external_world[0:3] + force_body
    loads[6, 3:6] = (d.external_world[3:6] + rotation @ d.external_body[3:6]
                     + cross(rotation @ d.external_point, force_body))
    loads[7] = extension_wrench(t, y, d)
    added_mass = np.empty((6, 6))
    for r in range(0, 6, 3):
        for c in range(0, 6, 3):
            added_mass[r:r + 3, c:c + 3] = rotate_inertia(rotation, added_mass_body[r:r + 3, c:c + 3])
    return added_mass


@njit(cache=True)
def extension_wrench(t: float, y: np.ndarray, d: KernelData) -> np.ndarray:
    """The extension's load at time t and state y, without its mass term."""
    q, v = y[0:6], y[6:12]
    wrench = interpolate_table(d.extension_force_table, d.extension_force_step_s, t)[0]
    wrench -= d.extension_linear_damping @ v + d.extension_stiffness @ q
    wrench -= d.extension_quadratic_damping * np.abs(v) * v + d.extension_cubic_stiffness * q ** 3
    return wrench


@njit(cache=True)
def derivative(t: float, y: np.ndarray, d: KernelData, loads: np.ndarray, out: np.ndarray) -> None:
    """Write dy/dt at time t to ``out`` (entries 6-12 are the accelerations); fill ``loads``,
    whose added-mass row then includes the reaction -A a."""
    added_mass = applied_loads(t, y, d, loads, out[N_BODY_STATES:])
    rotation = rotation_matrix(y[3], y[4], y[5])
    mass6, bias = mass_matrix_and_bias(d.mass, d.cog, d.inertia_cog, rotation, y[9:12])
    total = -bias
    for c in range(N_LOADS):
        total += loads[c]
    acceleration = solve_spd(mass6 + added_mass + d.extension_mass, total)
    loads[2] -= added_mass @ acceleration
    loads[7] -= d.extension_mass @ acceleration
    out[0:3] = y[6:9]
    out[3:6] = euler_rates(y[3], y[4], y[5], y[9:12])
    out[6:12] = acceleration


@njit(cache=True)
def prescribed_motion_loads(times: np.ndarray, states: np.ndarray, accelerations: np.ndarray,
                            d: KernelData, out_loads: np.ndarray) -> None:
    """Loads for a given motion (HydroDyn driver mode): states (n, 12), accelerations (n, 6);
    for a model without drag filter states."""
    no_filter_states = np.empty(0)
    for n in range(times.size):
        added_mass = applied_loads(times[n], states[n], d, out_loads[n], no_filter_states)
        out_loads[n, 2] -= added_mass @ accelerations[n]
        out_loads[n, 7] -= d.extension_mass @ accelerations[n]


@njit(cache=True)
def _rk4(t: float, dt: float, y: np.ndarray, k1: np.ndarray, d: KernelData, loads: np.ndarray) -> None:
    k2, k3, k4 = np.empty_like(y), np.empty_like(y), np.empty_like(y)
    derivative(t + 0.5 * dt, y + 0.5 * dt * k1, d, loads, k2)
    derivative(t + 0.5 * dt, y + 0.5 * dt * k2, d, loads, k3)
    derivative(t + dt, y + dt * k3, d, loads, k4)
    y += (dt / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4)


@njit(cache=True, nogil=True)  # a node publishes the last batch while the next one runs
def integrate(y: np.ndarray, first_step: int, dt: float, n_steps: int, record_every: int,
              d: KernelData, history: np.ndarray, newest: np.ndarray, out_t: np.ndarray,
              out_y: np.ndarray, out_acceleration: np.ndarray, out_loads: np.ndarray) -> int:
    """Advance ``n_steps`` steps of the 4th-order Adams-Bashforth-Moulton predictor-corrector
    (PECE, as OpenFAST's ElastoDyn), started with RK4 until four derivatives are known.

    y is updated in place. ``history`` (4, len(y)) is a ring of dy/dt at the last four steps:
    row ``newest[0]`` is the latest, the rows before it (cyclically) the older ones; rows
    not yet filled are marked by NaN. Time is counted in whole steps (t = step dt), so
    stepping one at a time and in a batch give the same numbers. The body state,
    accelerations and loads at every ``record_every``-th step end are written to the
    outputs; returns the number written.
    """
    loads = np.zeros((N_LOADS, 6))
    predicted, fp = np.empty_like(y), np.empty_like(y)
    h = dt / 24.0
    written = 0
    for n in range(n_steps):
        t = (first_step + n) * dt
        t_next = (first_step + n + 1) * dt
        i0 = newest[0]
        f0, f1, f2, f3 = history[i0], history[(i0 + 3) % 4], history[(i0 + 2) % 4], history[(i0 + 1) % 4]
        if np.isnan(f3[0]):
            _rk4(t, dt, y, f0, d, loads)
        else:
            for m in range(y.size):  # (loops: no temporaries over the filter states)
                predicted[m] = y[m] + h * (55.0 * f0[m] - 59.0 * f1[m] + 37.0 * f2[m] - 9.0 * f3[m])
            derivative(t_next, predicted, d, loads, fp)
            for m in range(y.size):
                y[m] += h * (9.0 * fp[m] + 19.0 * f0[m] - 5.0 * f1[m] + f2[m])
        newest[0] = (i0 + 1) % 4  # the oldest row takes the new derivative
        derivative(t_next, y, d, loads, history[newest[0]])
        if (n + 1) % record_every == 0:
            out_t[written] = t_next
            out_y[written] = y[:N_BODY_STATES]
            out_acceleration[written] = history[newest[0], 6:12]
            out_loads[written] = loads
            written += 1
    return written
