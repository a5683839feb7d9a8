"""6-DOF equations of motion and the fixed-step ABM4 integrator, compiled with numba.

State y = [x, y, z, roll, pitch, yaw, v_x, v_y, v_z, w_x, w_y, w_z] (world axes, reference
point), followed by the drag filter states, ordered (filter state, filtered strip,
direction): every strip's, or with strips wetted as at rest (the default) only those wet at
rest (a strip dry at rest never loads); none for the constant-Cd model. The right-hand side
fills one row of loads per registered load component (``physics.loads``): the Morison strip
model's rows, then each module component's. It solves (M + A(q) + sum M_c) [a; alpha] = F,
with the strip added mass A and any component's mass M_c on the left-hand side.

``integrate`` advances any number of steps in compiled code; a node stepping one dt at a
time and a batch run call the same function, so both give the same numbers, bit for bit.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np
from numba import njit

from fowt_hydro_sim.physics.drag_filters import band_velocities, filter_inputs, filter_rates
from fowt_hydro_sim.physics.jit import copy_into, step_loop
from fowt_hydro_sim.physics.loads import FIRST_MODULE_ROW, N_LOADS, ROW, component_loads
from fowt_hydro_sim.physics.morison import (
    add_wet_added_mass,
    added_mass_from_moments,
    centripetal_from_moments,
    end_plate_loads,
    lever_arms,
    relative_velocities,
    rotated_moments,
    strip_loads,
    submerged_points,
    wetted_fractions,
)
from fowt_hydro_sim.physics.rigid_body import (
    euler_rates,
    mass_matrix_and_bias,
    rotate_inertia,
    rotation_into,
    solve_spd,
    to_body,
)
from fowt_hydro_sim.physics.tables import interpolate_into

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
    filter_strip: np.ndarray  # (m,) int64: the strips with drag filter states (dynamics' docstring)
    filter_column: np.ndarray  # (n,) int64: the strip's filter inputs are columns 2 c, 2 c + 1; -1: none
    deep: np.ndarray  # (n,) bool: fully wet at rest (morison.strip_loads)
    deep_added_mass_6x6: np.ndarray  # (6, 6) their added mass fully wet, body axes, about the reference point
    deep_moments: np.ndarray  # (13, 3, 3) moments of their 3x3 added mass (morison.added_mass_moments)
    rest_wet: np.ndarray  # (n,) wetted fractions at rest: constant with the undisplaced wetted length
    rest_added_mass_6x6: np.ndarray  # (6, 6) all strips' added mass wetted as at rest, body axes
    rest_moments: np.ndarray  # (13, 3, 3) the moments of all strips' 3x3 added mass wetted as at rest


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


class Workspace(NamedTuple):
    """The right-hand side's scratch and outputs, made once per model (``workspace``): the step
    loop allocates nothing (it is compiled without numba's runtime: ``physics.jit``)."""

    loads: np.ndarray  # (N_LOADS, 6) the loads at the last evaluation
    identity: np.ndarray  # (3, 3)
    rotation: np.ndarray  # (3, 3) R at the last evaluation's state
    masses: np.ndarray  # (N_MODULE_COMPONENTS, 6, 6) the module components' left-hand-side masses
    kinematics: np.ndarray  # (n_points, 7) the wave kinematics at the evaluation's time
    wet: np.ndarray  # (n_strips,)
    v_rel: np.ndarray  # (n_strips, 2)
    a_fluid: np.ndarray  # (n_strips, 2)
    v_filtered: np.ndarray  # (2 m,) the filtered strips' relative velocities, the filters' input
    v_band: np.ndarray  # (n_bands, 2 m) their band velocities
    arm: np.ndarray  # (n_strips, 3) lever arms in the frame
    plate_arm: np.ndarray  # (n_plates, 3)
    submerged: np.ndarray  # (n_plates,)
    body: np.ndarray  # (3, 6) drag, inertia, centripetal added mass, frame axes
    first: np.ndarray  # (3, 3, 3) first moments of the strips' added mass (morison.rotated_moments)
    half: np.ndarray  # (3, 3, 3, 3)
    second: np.ndarray  # (3, 3, 3, 3) second moments
    spin: np.ndarray  # (6,) centripetal added-mass wrench from the moments
    added_mass: np.ndarray  # (6, 6) the strips' and plates' added mass, frame axes
    world_added_mass: np.ndarray  # (6, 6) the same in world axes: what multiplies the body acceleration
    system: np.ndarray  # (6, 6) the left-hand side
    factor: np.ndarray  # (6, 6) its Cholesky factor
    forces: np.ndarray  # (6,) the right-hand side
    bias: np.ndarray  # (6,) the rigid body's velocity terms
    trial_state: np.ndarray  # (n_states,) ABM4's predicted state, RK4's stage state
    trial_rates: np.ndarray  # (3, n_states) ABM4's predicted rates (row 0), RK4's k2, k3, k4


@njit(cache=True)
def workspace(d: KernelData) -> Workspace:
    """The scratch ``derivative`` and ``integrate`` work in, for kernel data ``d``."""
    n, m = d.strips.length.size, d.strips.filter_strip.size
    n_states = N_BODY_STATES + d.filters.b.size * 2 * m
    return Workspace(np.zeros((N_LOADS, 6)), np.eye(3), np.eye(3), np.zeros((N_MODULE_COMPONENTS, 6, 6)),
                     np.zeros(d.waves.values.shape[1:]), np.zeros(n), np.zeros((n, 2)), np.zeros((n, 2)),
                     np.zeros(2 * m), np.zeros((d.filters.d.size, 2 * m)),
                     d.strips.centre.copy(), d.plates.centre.copy(), np.zeros(d.plates.centre.shape[0]),
                     np.zeros((3, 6)), np.zeros((3, 3, 3)), np.zeros((3, 3, 3, 3)), np.zeros((3, 3, 3, 3)),
                     np.zeros(6), np.zeros((6, 6)), np.zeros((6, 6)), np.zeros((6, 6)), np.zeros((6, 6)),
                     np.zeros(6), np.zeros(6), np.zeros(n_states), np.zeros((3, n_states)))


@step_loop
def applied_loads(t: float, y: np.ndarray, d: KernelData, w: Workspace, filter_rates_out: np.ndarray,
                  surface: np.ndarray, constant_wetting: bool) -> None:
    """Fill ``w.loads`` (N_LOADS, 6; world axes, about the reference point) at state y and
    time t from the kinematics in ``w.kinematics`` (at t), with only the centripetal part in
    the added-mass row, ``w.masses`` with the module components' masses, ``w.rotation`` with
    R, ``w.world_added_mass`` with the strips' and plates' 6x6 added mass (world axes) that
    multiplies the body acceleration, and the drag filter states' rates. ``surface``
    (n_strips + n_plates) is the water surface height the strips and plates are wetted up
    to; ``constant_wetting``: the strips stay wetted as at rest (undisplaced wetted length,
    still surface), so the dry ones are skipped and the added mass and its centripetal
    wrench are sums of precomputed moments."""
    position, angles = y[0:3], y[3:6]
    velocity, omega = y[6:9], y[9:12]
    rotation_into(angles[0], angles[1], angles[2], w.rotation)
    rotation, identity = w.rotation, w.identity
    s, plates, bank = d.strips, d.plates, d.filters
    fixed = d.options.fixed_directions
    if constant_wetting:
        copy_into(s.rest_wet, w.wet)
    elif d.options.undisplaced_wetting:
        wetted_fractions(identity, 0.0, s.centre, s.axis, s.length, surface[:s.length.size], w.wet)
    else:
        wetted_fractions(rotation, position[2], s.centre, s.axis, s.length, surface[:s.length.size], w.wet)
    moments = s.rest_moments if constant_wetting else s.deep_moments
    if fixed:  # world axes, lever arms R c
        frame = identity
        lever_arms(rotation, s.centre, w.arm)
        lever_arms(rotation, plates.centre, w.plate_arm)
        rotated_moments(rotation, moments, w.first, w.half, w.second)
        added_mass_from_moments(moments[0], w.first, w.second, w.added_mass)
    else:  # body axes: w.arm and w.plate_arm hold the body-frame centres, the moments are at R = I
        frame = rotation
        if constant_wetting:  # (the centripetal wrench's; otherwise it is summed strip by strip)
            rotated_moments(identity, moments, w.first, w.half, w.second)
        copy_into(s.rest_added_mass_6x6 if constant_wetting else s.deep_added_mass_6x6, w.added_mass)
    if d.options.undisplaced_wetting:
        submerged_points(identity, 0.0, plates.centre, surface[s.length.size:], w.submerged)
    else:
        submerged_points(rotation, position[2], plates.centre, surface[s.length.size:], w.submerged)
    relative_velocities(frame, fixed, velocity, omega, w.kinematics, w.arm, s.directions, s.point, w.wet,
                        constant_wetting, w.v_rel, w.a_fluid)
    filter_states = y[N_BODY_STATES:].reshape((bank.b.size, w.v_filtered.size))
    filter_inputs(s.filter_strip, w.v_rel, w.v_filtered)
    band_velocities(filter_states, w.v_filtered, bank.c, bank.c_nonzero, bank.d, w.v_band)
    filter_rates(filter_states, w.v_filtered, bank.a, bank.a_nonzero, bank.b,
                 filter_rates_out.reshape(filter_states.shape))
    strip_loads(frame, omega, w.wet, w.v_rel, w.a_fluid, w.v_band, s.filter_column, w.arm, s.directions, s.length,
                s.inertia, s.added_mass, s.band_drag, s.drag, s.filtered, not constant_wetting, w.body)
    if constant_wetting:
        centripetal_from_moments(w.first, w.second, to_body(frame, omega[0], omega[1], omega[2]), w.spin)
        copy_into(w.spin, w.body[2])
    else:
        add_wet_added_mass(w.wet, s.length, s.deep, s.added_mass_6x6, w.arm, s.added_mass_3x3, fixed, w.added_mass)
    end_plate_loads(frame, velocity, omega, w.kinematics, w.plate_arm, plates.normal, w.submerged,
                    plates.pressure_area, plates.added_mass, plates.drag, plates.added_mass_6x6,
                    plates.added_mass_3x3, fixed, plates.point, w.body[0], w.body[1], w.body[2], w.added_mass)
    component_loads(t, y, rotation, d.component_params, d.component_tables, w.loads, w.masses)
    if fixed:  # the frame is the world's
        for c, row in enumerate((DRAG, INERTIA, ADDED_MASS)):
            copy_into(w.body[c], w.loads[row])
        copy_into(w.added_mass, w.world_added_mass)
        return
    for c, row in enumerate((DRAG, INERTIA, ADDED_MASS)):
        _rotate_wrench(frame, w.body[c], w.loads[row])
    for r in range(0, 6, 3):
        for c in range(0, 6, 3):
            rotate_inertia(frame, w.added_mass[r:r + 3, c:c + 3], w.world_added_mass[r:r + 3, c:c + 3])


@njit(cache=True, inline="always")
def _rotate_wrench(rotation: np.ndarray, wrench: np.ndarray, out: np.ndarray) -> None:
    """out = [R f; R m] of a body-axes wrench."""
    for i in range(3):
        out[i] = rotation[i, 0] * wrench[0] + rotation[i, 1] * wrench[1] + rotation[i, 2] * wrench[2]
        out[3 + i] = rotation[i, 0] * wrench[3] + rotation[i, 1] * wrench[4] + rotation[i, 2] * wrench[5]


@step_loop
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


@step_loop
def derivative(t: float, y: np.ndarray, d: KernelData, w: Workspace, out: np.ndarray) -> None:
    """Write dy/dt at time t to ``out`` (entries 6-12 are the accelerations); fill ``w.loads``,
    whose rows then include the reactions -M a of the masses on the left-hand side."""
    interpolate_into(d.waves.values, d.waves.step_s, t, w.kinematics)
    _derivative(t, y, d, w, out)


@step_loop
def _derivative(t: float, y: np.ndarray, d: KernelData, w: Workspace, out: np.ndarray) -> None:
    """``derivative`` with the kinematics at t already in ``w.kinematics``."""
    applied_loads(t, y, d, w, out[N_BODY_STATES:], d.still_surface, d.options.undisplaced_wetting)
    added_mass = w.world_added_mass
    mass_matrix_and_bias(d.body.mass, d.body.cog, d.body.inertia_cog, w.rotation, y[9:12], w.system, w.bias)
    for i in range(6):
        total = -w.bias[i]
        for c in range(N_LOADS):
            total += w.loads[c, i]
        w.forces[i] = total
        for j in range(6):
            w.system[i, j] += added_mass[i, j]
    for k in range(N_MODULE_COMPONENTS):
        for i in range(6):
            for j in range(6):
                w.system[i, j] += w.masses[k, i, j]
    acceleration = out[6:12]
    solve_spd(w.system, w.forces, w.factor, acceleration)
    react(w.loads, added_mass, w.masses, acceleration)
    copy_into(y[6:9], out[0:3])
    euler_rates(y[3], y[4], y[5], y[9:12], out[3:6])


@njit(cache=True)
def prescribed_motion_loads(times: np.ndarray, states: np.ndarray, accelerations: np.ndarray,
                            d: KernelData, surfaces: np.ndarray, out_loads: np.ndarray) -> None:
    """Loads for a given motion (HydroDyn driver mode): states (n, 12), accelerations (n, 6),
    the water surface height over each strip and plate (n, n_strips + n_plates); for a model
    without drag filter states."""
    no_filter_states = np.empty(0)
    w = workspace(d)
    for n in range(times.size):
        interpolate_into(d.waves.values, d.waves.step_s, times[n], w.kinematics)
        applied_loads(times[n], states[n], d, w, no_filter_states, surfaces[n], False)
        out_loads[n] = w.loads
        react(out_loads[n], w.world_added_mass, w.masses, accelerations[n])


@step_loop
def _rk4(t: float, dt: float, y: np.ndarray, k1: np.ndarray, d: KernelData, w: Workspace) -> None:
    """One RK4 step of y in place from its rate k1 at t (scratch: ``w.trial_state``, ``w.trial_rates``)."""
    stage, k = w.trial_state, w.trial_rates
    previous = k1
    for s, fraction in enumerate((0.5, 0.5, 1.0)):  # k2, k3, k4 at t + fraction dt
        rk4_stage(y, fraction, dt, previous, stage)
        derivative(t + fraction * dt, stage, d, w, k[s])
        previous = k[s]
    rk4_combine(y, dt, k1, k)


# the integrators' arithmetic, one definition for the compiled loop (inlined there) and the
# Python-level one (``integrate_stepwise``): compiled alike, so both give the same numbers
_step_arithmetic = njit(cache=True, _nrt=False, fastmath={"contract"}, inline="always")


@_step_arithmetic
def rk4_stage(y: np.ndarray, fraction: float, dt: float, rate: np.ndarray, stage: np.ndarray) -> None:
    """An RK4 stage state: stage = y + fraction dt rate."""
    for m in range(y.size):
        stage[m] = y[m] + fraction * dt * rate[m]


@_step_arithmetic
def rk4_combine(y: np.ndarray, dt: float, k1: np.ndarray, k: np.ndarray) -> None:
    """The RK4 step of y in place from its four rates (k1, and k2, k3, k4 as rows of k)."""
    for m in range(y.size):
        y[m] += (dt / 6.0) * (k1[m] + 2.0 * k[0, m] + 2.0 * k[1, m] + k[2, m])


@_step_arithmetic
def abm4_predict(y: np.ndarray, h: float, f0: np.ndarray, f1: np.ndarray, f2: np.ndarray, f3: np.ndarray,
                 predicted: np.ndarray) -> None:
    """Adams-Bashforth's prediction from the last four rates, newest first (h = dt / 24)."""
    for m in range(y.size):  # (loops: no temporaries over the filter states)
        predicted[m] = y[m] + h * (55.0 * f0[m] - 59.0 * f1[m] + 37.0 * f2[m] - 9.0 * f3[m])


@_step_arithmetic
def abm4_correct(y: np.ndarray, h: float, fp: np.ndarray, f0: np.ndarray, f1: np.ndarray, f2: np.ndarray) -> None:
    """Adams-Moulton's correction of y in place from the predicted rate fp and the last three."""
    for m in range(y.size):
        y[m] += h * (9.0 * fp[m] + 19.0 * f0[m] - 5.0 * f1[m] + f2[m])


# step_loop's options (physics.jit) and nogil: a node publishes the last batch while the next one runs
@njit(cache=True, nogil=True, _nrt=False, fastmath={"contract"})
def integrate(y: np.ndarray, first_step: int, dt: float, n_steps: int, record_every: int,
              d: KernelData, w: Workspace, refresh: bool, history: np.ndarray, newest: np.ndarray,
              out_t: np.ndarray, out_y: np.ndarray, out_acceleration: np.ndarray, out_loads: np.ndarray) -> int:
    """Advance ``n_steps`` steps of the 4th-order Adams-Bashforth-Moulton predictor-corrector
    (PECE, as OpenFAST's ElastoDyn), started with RK4 until four derivatives are known.

    y is updated in place. ``history`` (4, len(y)) is a ring of dy/dt at the last four steps:
    row ``newest[0]`` is the latest, the rows before it (cyclically) the older ones; rows
    not yet filled are marked by NaN. Time is counted in whole steps (t = step dt), so
    stepping one at a time and in a batch give the same numbers. The body state,
    accelerations and loads at every ``record_every``-th step end are written to the
    outputs; returns the number written. Both evaluations of a step are at its end time: the
    kinematics are interpolated once for them. ``refresh``: an input changed at the first
    step's start (the external wrench): the latest derivative is evaluated there again first.
    """
    predicted, fp = w.trial_state, w.trial_rates[0]
    h = dt / 24.0
    written = 0
    if refresh:
        derivative(first_step * dt, y, d, w, history[newest[0]])
    for n in range(n_steps):
        t = (first_step + n) * dt
        t_next = (first_step + n + 1) * dt
        i0 = newest[0]
        f0, f1, f2, f3 = history[i0], history[(i0 + 3) % 4], history[(i0 + 2) % 4], history[(i0 + 1) % 4]
        if np.isnan(f3[0]):
            _rk4(t, dt, y, f0, d, w)
            interpolate_into(d.waves.values, d.waves.step_s, t_next, w.kinematics)
        else:
            abm4_predict(y, h, f0, f1, f2, f3, predicted)
            interpolate_into(d.waves.values, d.waves.step_s, t_next, w.kinematics)
            _derivative(t_next, predicted, d, w, fp)
            abm4_correct(y, h, fp, f0, f1, f2)
        newest[0] = (i0 + 1) % 4  # the oldest row takes the new derivative
        _derivative(t_next, y, d, w, history[newest[0]])
        if (n + 1) % record_every == 0:
            out_t[written] = t_next
            copy_into(y[:N_BODY_STATES], out_y[written])
            copy_into(history[newest[0], 6:12], out_acceleration[written])
            copy_into(w.loads, out_loads[written])
            written += 1
    return written


def integrate_stepwise(rates: Callable[[float, np.ndarray, np.ndarray], None], y: np.ndarray, first_step: int,
                       dt: float, n_steps: int, record_every: int, w: Workspace, history: np.ndarray,
                       newest: np.ndarray, out_t: np.ndarray, out_y: np.ndarray, out_acceleration: np.ndarray,
                       out_loads: np.ndarray) -> int:
    """``integrate`` as a Python loop around ``rates(t, y, out)``, which writes dy/dt at (t, y)
    to ``out`` and the loads to ``w.loads`` (e.g. a Python force written into the kernel data,
    then ``derivative``): the same steps, evaluations and arithmetic, so that with rates that
    are ``derivative``'s the numbers are ``integrate``'s, bit for bit."""
    predicted, fp, stage, k = w.trial_state, w.trial_rates[0], w.trial_state, w.trial_rates
    h = dt / 24.0
    written = 0
    for n in range(n_steps):
        t = (first_step + n) * dt
        t_next = (first_step + n + 1) * dt
        i0 = int(newest[0])
        f0, f1, f2, f3 = history[i0], history[(i0 + 3) % 4], history[(i0 + 2) % 4], history[(i0 + 1) % 4]
        if np.isnan(f3[0]):
            previous = f0
            for s, fraction in enumerate((0.5, 0.5, 1.0)):
                rk4_stage(y, fraction, dt, previous, stage)
                rates(t + fraction * dt, stage, k[s])
                previous = k[s]
            rk4_combine(y, dt, f0, k)
        else:
            abm4_predict(y, h, f0, f1, f2, f3, predicted)
            rates(t_next, predicted, fp)
            abm4_correct(y, h, fp, f0, f1, f2)
        newest[0] = (i0 + 1) % 4
        rates(t_next, y, history[newest[0]])
        if (n + 1) % record_every == 0:
            out_t[written] = t_next
            out_y[written] = y[:N_BODY_STATES]
            out_acceleration[written] = history[newest[0], 6:12]
            out_loads[written] = w.loads
            written += 1
    return written
