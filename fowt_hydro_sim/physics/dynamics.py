"""6-DOF equations of motion and the fixed-step ABM4 integrator, compiled with numba.

State y = [x, y, z, roll, pitch, yaw, v_x, v_y, v_z, w_x, w_y, w_z] (world axes, reference
point), followed by the drag filter states, ordered (filter state, strip, direction); none
for the constant-Cd model. The right-hand side fills one row of loads per registered load
component (``physics.loads``): the Morison strip model's rows, then each module
component's. It solves (M + A(q) + sum M_c) [a; alpha] = F, with the strip added mass A and
any component's mass M_c on the left-hand side.

``integrate`` advances any number of steps in compiled code; a node stepping one dt at a
time and a batch run call the same function, so both give the same numbers, bit for bit.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit

from fowt_hydro_sim.physics.drag_filters import band_velocities, drag_per_length, filter_rates
from fowt_hydro_sim.physics.loads import FIRST_MODULE_ROW, N_LOADS, ROW, component_loads
from fowt_hydro_sim.physics.morison import (
    add_wet_added_mass,
    added_mass_about,
    deep_added_mass_about,
    end_plate_loads,
    lever_arms,
    relative_velocities,
    strip_loads,
    submerged_points,
    wetted_fractions,
)
from fowt_hydro_sim.physics.rigid_body import (
    euler_rates,
    mass_matrix_and_bias,
    matvec,
    rotate_inertia,
    rotation_matrix,
    solve_spd,
)
from fowt_hydro_sim.physics.tables import interpolate_table

N_BODY_STATES = 12
DRAG, INERTIA, ADDED_MASS = ROW["drag"], ROW["inertia"], ROW["added_mass"]  # the strip model's rows
N_MODULE_COMPONENTS = N_LOADS - FIRST_MODULE_ROW


class WaveTable(NamedTuple):
    values: np.ndarray  # (n_samples, n_points, 7) float64, periodic (a ring of blocks, or one period)
    step_s: float


class StripData(NamedTuple):
    """Strips (physics.strips) with their per-unit-length coefficients and 6x6 added mass."""

    centre: np.ndarray
    axis: np.ndarray
    directions: np.ndarray
    length: np.ndarray
    inertia: np.ndarray
    added_mass: np.ndarray
    added_mass_3x3: np.ndarray  # (n, 3, 3) per unit length, body axes
    added_mass_6x6: np.ndarray  # (n, 6, 6) per unit length, body axes, about the reference point
    drag: np.ndarray  # (n, 2): 0.5 rho Cd b, constant Cd (unfiltered directions)
    band_drag: np.ndarray  # (n, n_bands, 2): 0.5 rho Cd_b b per drag band; no bands: constant Cd
    filtered: np.ndarray  # (n, 2) bool: the direction's drag is summed over the bands
    point: np.ndarray  # (n,) index of the kinematics point
    deep: np.ndarray  # (n,) bool: fully wet at rest (morison.strip_loads)
    deep_added_mass_6x6: np.ndarray  # (6, 6) their added mass fully wet, body axes, about the reference point
    deep_moments: np.ndarray  # (13, 3, 3) moments of their 3x3 added mass (morison.added_mass_moments)


class PlateData(NamedTuple):
    centre: np.ndarray
    normal: np.ndarray
    pressure_area: np.ndarray
    added_mass: np.ndarray
    drag: np.ndarray
    added_mass_3x3: np.ndarray
    added_mass_6x6: np.ndarray
    point: np.ndarray


class HydroFlags(NamedTuple):
    """The kernel's form of ``config.HydroOptions`` (hydrostatics: the hydrostatic component's)."""

    fixed_directions: bool  # load directions at the undisplaced axes (else rotating with the body)
    undisplaced_wetting: bool  # wetted length of the undisplaced strips (else displaced)


class FilterBank(NamedTuple):
    """The drag filter bank (drag_filters.StateSpace), shared by every strip."""

    a: np.ndarray
    a_nonzero: np.ndarray  # (nnz, 2) int64 entries of A that are not zero
    b: np.ndarray
    c: np.ndarray
    c_nonzero: np.ndarray
    d: np.ndarray


class RigidBody(NamedTuple):
    mass: float
    cog: np.ndarray
    inertia_cog: np.ndarray


class KernelData(NamedTuple):
    """Everything the compiled right-hand side reads."""

    waves: WaveTable
    strips: StripData
    plates: PlateData
    filters: FilterBank
    body: RigidBody
    options: HydroFlags
    component_params: tuple  # (params, ...) of the module components, registry order
    component_tables: tuple  # (table, ...)
    still_surface: np.ndarray  # zeros (n_strips + n_plates): the water surface at z = 0 (no stretching)


@njit(cache=True)
def applied_loads(t: float, y: np.ndarray, d: KernelData, loads: np.ndarray, masses: np.ndarray,
                  filter_rates_out: np.ndarray, surface: np.ndarray) -> np.ndarray:
    """Fill ``loads`` (N_LOADS, 6; world axes, about the reference point) at state y and time
    t, with only the centripetal part in the added-mass row, the module components' masses
    (N_MODULE_COMPONENTS, 6, 6) and the drag filter states' rates; return the strips' 6x6
    added mass (world axes) that multiplies the body acceleration. ``surface`` (n_strips +
    n_plates) is the water surface height the strips and plates are wetted up to."""
    position, angles = y[0:3], y[3:6]
    velocity, omega = y[6:9], y[9:12]
    rotation = rotation_matrix(angles[0], angles[1], angles[2])
    kinematics = interpolate_table(d.waves.values, d.waves.step_s, t)
    s, plates, bank = d.strips, d.plates, d.filters

    if d.options.fixed_directions:  # world axes, lever arms R c
        frame = np.eye(3)
        arm, plate_arm = lever_arms(rotation, s.centre), lever_arms(rotation, plates.centre)
        plate_6x6 = added_mass_about(plate_arm, plates.added_mass_3x3)
        added_mass_body = deep_added_mass_about(rotation, s.deep_moments)
    else:  # body axes
        frame, arm, plate_arm = rotation, s.centre, plates.centre
        plate_6x6 = plates.added_mass_6x6
        added_mass_body = s.deep_added_mass_6x6.copy()
    wet_pose, wet_z = (np.eye(3), 0.0) if d.options.undisplaced_wetting else (rotation, position[2])
    body = np.zeros((3, 6))  # drag, inertia, centripetal added mass, frame axes
    n_strips = s.length.size
    wet, v_rel, a_fluid = np.empty(n_strips), np.empty((n_strips, 2)), np.empty((n_strips, 2))
    wetted_fractions(wet_pose, wet_z, s.centre, s.axis, s.length, surface[:n_strips], wet)
    submerged = np.empty(plates.centre.shape[0])
    submerged_points(wet_pose, wet_z, plates.centre, surface[n_strips:], submerged)
    relative_velocities(frame, velocity, omega, kinematics, arm, s.directions, s.point, v_rel, a_fluid)
    filter_states = y[N_BODY_STATES:].reshape((bank.b.size, 2 * n_strips))
    v_flat = v_rel.reshape(2 * n_strips)
    v_band = np.empty((bank.d.size, 2 * n_strips))
    band_velocities(filter_states, v_flat, bank.c, bank.c_nonzero, bank.d, v_band)
    filter_rates(filter_states, v_flat, bank.a, bank.a_nonzero, bank.b, filter_rates_out.reshape(filter_states.shape))
    drag = np.empty((n_strips, 2))
    drag_per_length(v_rel, v_band, s.band_drag, s.drag, s.filtered, drag)
    strip_loads(frame, omega, wet, a_fluid, drag, arm, s.directions, s.length, s.inertia, s.added_mass,
                body[0], body[1], body[2])
    add_wet_added_mass(wet, s.length, s.deep, s.added_mass_6x6, arm, s.added_mass_3x3, d.options.fixed_directions,
                       added_mass_body)
    end_plate_loads(frame, velocity, omega, kinematics, plate_arm, plates.normal, submerged, plates.pressure_area,
                    plates.added_mass, plates.drag, plate_6x6, plates.point, body[0], body[1], body[2],
                    added_mass_body)
    component_loads(t, y, rotation, d.component_params, d.component_tables, loads, masses)
    if d.options.fixed_directions:  # the frame is the world's
        for c, row in enumerate((DRAG, INERTIA, ADDED_MASS)):
            loads[row] = body[c]
        return added_mass_body
    for c, row in enumerate((DRAG, INERTIA, ADDED_MASS)):
        loads[row, 0:3] = matvec(frame, body[c, 0:3])
        loads[row, 3:6] = matvec(frame, body[c, 3:6])
    added_mass = np.empty((6, 6))
    for r in range(0, 6, 3):
        for c in range(0, 6, 3):
            added_mass[r:r + 3, c:c + 3] = rotate_inertia(frame, added_mass_body[r:r + 3, c:c + 3])
    return added_mass


@njit(cache=True)
def react(loads: np.ndarray, added_mass: np.ndarray, masses: np.ndarray, acceleration: np.ndarray) -> None:
    """Each left-hand-side mass's reaction -M a into its row."""
    _subtract_product(loads[ADDED_MASS], added_mass, acceleration)
    for k in range(masses.shape[0]):
        _subtract_product(loads[FIRST_MODULE_ROW + k], masses[k], acceleration)


@njit(cache=True, inline="always")
def _subtract_product(row: np.ndarray, matrix: np.ndarray, x: np.ndarray) -> None:
    """row -= matrix @ x (6x6), in place: no temporary in the step loop."""
    for i in range(6):
        for j in range(6):
            row[i] -= matrix[i, j] * x[j]


@njit(cache=True)
def derivative(t: float, y: np.ndarray, d: KernelData, loads: np.ndarray, masses: np.ndarray,
               out: np.ndarray) -> None:
    """Write dy/dt at time t to ``out`` (entries 6-12 are the accelerations); fill ``loads``,
    whose rows then include the reactions -M a of the masses on the left-hand side, and
    ``masses`` (N_MODULE_COMPONENTS, 6, 6; the caller's scratch) with the components' masses."""
    added_mass = applied_loads(t, y, d, loads, masses, out[N_BODY_STATES:], d.still_surface)
    rotation = rotation_matrix(y[3], y[4], y[5])
    mass6, bias = mass_matrix_and_bias(d.body.mass, d.body.cog, d.body.inertia_cog, rotation, y[9:12])
    total = -bias
    for c in range(N_LOADS):
        total += loads[c]
    lhs = mass6 + added_mass
    for k in range(N_MODULE_COMPONENTS):
        lhs += masses[k]
    acceleration = solve_spd(lhs, total)
    react(loads, added_mass, masses, acceleration)
    out[0:3] = y[6:9]
    out[3:6] = euler_rates(y[3], y[4], y[5], y[9:12])
    out[6:12] = acceleration


@njit(cache=True)
def prescribed_motion_loads(times: np.ndarray, states: np.ndarray, accelerations: np.ndarray,
                            d: KernelData, surfaces: np.ndarray, out_loads: np.ndarray) -> None:
    """Loads for a given motion (HydroDyn driver mode): states (n, 12), accelerations (n, 6),
    the water surface height over each strip and plate (n, n_strips + n_plates); for a model
    without drag filter states."""
    no_filter_states = np.empty(0)
    masses = np.empty((N_MODULE_COMPONENTS, 6, 6))
    for n in range(times.size):
        added_mass = applied_loads(times[n], states[n], d, out_loads[n], masses, no_filter_states, surfaces[n])
        react(out_loads[n], added_mass, masses, accelerations[n])


@njit(cache=True)
def _rk4(t: float, dt: float, y: np.ndarray, k1: np.ndarray, d: KernelData, loads: np.ndarray,
         masses: np.ndarray) -> None:
    k2, k3, k4 = np.empty_like(y), np.empty_like(y), np.empty_like(y)
    derivative(t + 0.5 * dt, y + 0.5 * dt * k1, d, loads, masses, k2)
    derivative(t + 0.5 * dt, y + 0.5 * dt * k2, d, loads, masses, k3)
    derivative(t + dt, y + dt * k3, d, loads, masses, k4)
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
    masses = np.empty((N_MODULE_COMPONENTS, 6, 6))
    predicted, fp = np.empty_like(y), np.empty_like(y)
    h = dt / 24.0
    written = 0
    for n in range(n_steps):
        t = (first_step + n) * dt
        t_next = (first_step + n + 1) * dt
        i0 = newest[0]
        f0, f1, f2, f3 = history[i0], history[(i0 + 3) % 4], history[(i0 + 2) % 4], history[(i0 + 1) % 4]
        if np.isnan(f3[0]):
            _rk4(t, dt, y, f0, d, loads, masses)
        else:
            for m in range(y.size):  # (loops: no temporaries over the filter states)
                predicted[m] = y[m] + h * (55.0 * f0[m] - 59.0 * f1[m] + 37.0 * f2[m] - 9.0 * f3[m])
            derivative(t_next, predicted, d, loads, masses, fp)
            for m in range(y.size):
                y[m] += h * (9.0 * fp[m] + 19.0 * f0[m] - 5.0 * f1[m] + f2[m])
        newest[0] = (i0 + 1) % 4  # the oldest row takes the new derivative
        derivative(t_next, y, d, loads, masses, history[newest[0]])
        if (n + 1) % record_every == 0:
            out_t[written] = t_next
            out_y[written] = y[:N_BODY_STATES]
            out_acceleration[written] = history[newest[0], 6:12]
            out_loads[written] = loads
            written += 1
    return written
