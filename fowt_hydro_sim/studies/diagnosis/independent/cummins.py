"""A linear 6-DOF Cummins time-domain model of the hull, independent of the project's model:

    (M + A_inf) x'' + int_0^t K(t - tau) x'(tau) dtau + C x = F_exc + F_drag + F_moor + F_effects

about the reference point (0, 0, 0), with A_inf, K (from B(w) by a cosine transform) and
the excitation X(w) from the capytaine database (bem.py), its own wave synthesis (JONSWAP,
by FFT over the sea's repeat period), quadratic Morison drag at the undisplaced strip points,
the mooring's spring lines evaluated on the displaced fairleads, and a fixed-step RK4 whose
memory term is the trapezoidal convolution over the velocity history, extrapolated linearly
within a step (time_stepping.py, numba). Runs may start a pre-roll before the record, in the sea's
periodic extension (a basin runs before it records). Injectable effects (in forms the
diagnosis catalogue does not use): extra damping, linear plus quadratic per DOF; a slow
surge drift force from a frequency-dependent mean-drift coefficient by Newman's
approximation; an extra surge restoring curve (a catenary's); harmonic loads."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from fowt_hydro_sim.physics.config import Platform
from fowt_hydro_sim.studies.diagnosis.independent import time_stepping
from fowt_hydro_sim.studies.diagnosis.independent.bem import (
    FREQUENCIES_HZ,
    HydroDatabase,
)
from fowt_hydro_sim.studies.replay import MeasuredRun

ELEVATION_STEP_S = 0.1
MOTION_STEP_S = 0.25
KERNEL_LENGTH_S = 60.0


# --------------------------------------------------------------------------- waves
@dataclass(frozen=True)
class Waves:
    """Long-crested linear waves: eta(x, y, t) = sum a cos(w t - k (x cos b + y sin b) + phase)."""

    omega_rad_s: np.ndarray
    amplitude_m: np.ndarray
    phase_rad: np.ndarray
    heading_deg: float = 0.0
    period_s: float | None = None  # the repeat period, when every frequency is a multiple of its inverse


def wavenumber(omega_rad_s: np.ndarray, depth_m: float, g: float) -> np.ndarray:
    """k from w^2 = g k tanh(k h), by Newton from the deep-water guess."""
    omega = np.atleast_1d(np.asarray(omega_rad_s, float))
    k = np.maximum(omega ** 2 / g, 1e-12)
    for _ in range(50):
        f = g * k * np.tanh(k * depth_m) - omega ** 2
        df = g * np.tanh(k * depth_m) + g * k * depth_m / np.cosh(k * depth_m) ** 2
        k = k - f / df
    return k


def jonswap_waves(hs_m: float, tp_s: float, gamma: float, period_s: float, seed: int,
                  heading_deg: float = 0.0, band_tp: tuple[float, float] = (0.5, 4.0),
                  f_max_hz: float = float(FREQUENCIES_HZ[-1])) -> Waves:
    """Random-phase components at f = i / period_s between band_tp x the peak frequency (and
    at most f_max_hz, the BEM's highest by default), amplitudes sqrt(2 S df) from the JONSWAP
    spectrum (Goda's form), scaled to the Hs."""
    fp = 1.0 / tp_s
    top = min(band_tp[1] * fp, f_max_hz)
    f = np.arange(math.ceil(band_tp[0] * fp * period_s), math.floor(top * period_s + 1e-9) + 1) / period_s
    sigma = np.where(f <= fp, 0.07, 0.09)
    shape = f ** -5 * np.exp(-1.25 * (fp / f) ** 4) * gamma ** np.exp(-((f / fp - 1.0) ** 2) / (2 * sigma ** 2))
    amplitude = np.sqrt(2.0 * shape / period_s)
    amplitude *= hs_m / (4.0 * math.sqrt(0.5 * np.sum(amplitude ** 2)))
    phase = np.random.default_rng(seed).uniform(0.0, 2.0 * math.pi, f.size)
    return Waves(2.0 * math.pi * f, amplitude, phase, heading_deg, period_s)


def elevation(waves: Waves, time_s: np.ndarray, x_m: float, y_m: float, depth_m: float, g: float) -> np.ndarray:
    k = wavenumber(waves.omega_rad_s, depth_m, g)
    b = math.radians(waves.heading_deg)
    phase = waves.phase_rad - k * (x_m * math.cos(b) + y_m * math.sin(b))
    if waves.period_s:  # one period by FFT, then its periodic extension
        step = ELEVATION_STEP_S
        n = round(waves.period_s / step)
        if abs(n * step - waves.period_s) < 1e-6 and np.allclose(time_s / step, np.rint(time_s / step), atol=1e-6):
            period = synthesis(waves.amplitude_m * np.exp(1j * phase), waves, np.arange(n) * step)
            return period[np.rint(time_s / step).astype(int) % n]
    return np.cos(np.outer(time_s, waves.omega_rad_s) + phase) @ waves.amplitude_m


def _harmonic_sum(coefficients: np.ndarray, omega: np.ndarray, time_s: np.ndarray, chunk: int = 2000) -> np.ndarray:
    """Re(sum_j c_j e^{i w_j t}) for coefficients (n_components, ...) -> (n_t, ...)."""
    flat = coefficients.reshape(coefficients.shape[0], -1)
    out = np.empty((time_s.size, flat.shape[1]))
    for start in range(0, time_s.size, chunk):
        phasors = np.exp(1j * np.outer(time_s[start:start + chunk], omega))
        out[start:start + chunk] = (phasors @ flat).real
    return out.reshape((time_s.size,) + coefficients.shape[1:])


# --------------------------------------------------------------------------- hull description
@dataclass(frozen=True)
class Strips:
    """Drag points at the undisplaced hull. Circular strips: drag on the velocity normal to
    the axis, 0.5 rho Cd D L |u_n| u_n. Rectangular strips: per transverse direction,
    0.5 rho Cd A |u_d| u_d. Keel plates: 0.25 rho Cd A |w| w (HydroDyn's convention)."""

    circular_point_m: np.ndarray  # (p, 3)
    circular_axis: np.ndarray  # (p, 3)
    circular_cda_m2: np.ndarray  # (p,) Cd x D x L
    box_point_m: np.ndarray  # (q, 3)
    box_direction: np.ndarray  # (q, 2, 3)
    box_cda_m2: np.ndarray  # (q, 2)
    plate_point_m: np.ndarray  # (r, 3)
    plate_cda_m2: np.ndarray  # (r,) Cd x A (the 0.25 factor applied in the force)

    @property
    def points_m(self) -> np.ndarray:
        return np.vstack([self.circular_point_m, self.box_point_m, self.plate_point_m])


def _zone_cd(member, z_m: float) -> tuple[float, float]:
    for zone in member.zones:
        if z_m < zone.below_z_m or zone is member.zones[-1]:
            return zone.cd[0].constant, zone.cd[1].constant
    raise ValueError(f"{member.name}: no zone")


def strips(platform: Platform, cd_scale: float = 1.0, strip_length_m: float | None = None) -> Strips:
    """The immersed members cut into strips no longer than ``strip_length_m`` (default each
    member's own), with the constant (case 1) Cds times ``cd_scale``."""
    circ, box, plate = ([], [], []), ([], [], []), ([], [])
    for member in platform.members:
        a, b = np.asarray(member.end_a_m, float), np.asarray(member.end_b_m, float)
        if a[2] > 0.0 and b[2] > 0.0:
            continue
        if b[2] > 0.0:
            b = a + (b - a) * (0.0 - a[2]) / (b[2] - a[2])
        elif a[2] > 0.0:
            a = b + (a - b) * (0.0 - b[2]) / (a[2] - b[2])
        length = float(np.linalg.norm(b - a))
        axis = (b - a) / length
        n = max(1, math.ceil(length / (strip_length_m or member.strip_length_m) - 1e-9))
        dl = length / n
        for i in range(n):
            centre = a + axis * (i + 0.5) * dl
            cd_1, cd_2 = _zone_cd(member, float(centre[2]))
            if member.section == "circular":
                circ[0].append(centre), circ[1].append(axis), circ[2].append(cd_scale * cd_1 * member.width_m * dl)
            else:
                side = np.cross(axis, (0.0, 0.0, 1.0))
                side /= np.linalg.norm(side)
                up = np.cross(side, axis)
                box[0].append(centre), box[1].append((side, up))
                box[2].append((cd_scale * cd_1 * member.height_m * dl, cd_scale * cd_2 * member.width_m * dl))
        if member.end_a_plate is not None and member.section == "circular":
            bottom = a if a[2] < b[2] else b
            plate[0].append(bottom)
            plate[1].append(cd_scale * member.end_a_plate.cd * math.pi * member.width_m ** 2 / 4.0)
    array = lambda items, shape: np.asarray(items, float).reshape(shape)
    return Strips(array(circ[0], (-1, 3)), array(circ[1], (-1, 3)), array(circ[2], (-1,)),
                  array(box[0], (-1, 3)), array(box[1], (-1, 2, 3)), array(box[2], (-1, 2)),
                  array(plate[0], (-1, 3)), array(plate[1], (-1,)))


def rigid_body_mass(platform: Platform) -> np.ndarray:
    """The 6x6 mass matrix about (0, 0, 0)."""
    m = platform.mass.mass_kg
    r = np.asarray(platform.mass.cog_m, float)
    skew = _skew(r)
    inertia = np.asarray(platform.mass.inertia_about_cog_kg_m2, float) + m * (r @ r * np.eye(3) - np.outer(r, r))
    return np.block([[m * np.eye(3), -m * skew], [m * skew, inertia]])


def _skew(r: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])


def rotation(angles_rad: np.ndarray) -> np.ndarray:
    """R = Rz(yaw) Ry(pitch) Rx(roll)."""
    (cr, cp, cy), (sr, sp, sy) = np.cos(angles_rad), np.sin(angles_rad)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def mooring_wrench(platform: Platform, x: np.ndarray) -> np.ndarray:
    """Force and moment about the displaced reference point of the spring lines: tension
    pretension + k (d - d_rest) along the fairlead-anchor chord (never below zero)."""
    mooring = platform.mooring
    out = np.zeros(6)
    rot = rotation(x[3:])
    for line in mooring.lines:
        fairlead_body = np.asarray(line.fairlead_m, float)
        anchor = np.asarray(line.anchor_m, float)
        rest = float(np.linalg.norm(anchor - fairlead_body))
        arm = rot @ fairlead_body
        chord = anchor - (x[:3] + arm)
        distance = float(np.linalg.norm(chord))
        tension = max(0.0, mooring.pretension_n + mooring.stiffness_n_m * (distance - rest))
        force = tension * chord / distance
        out[:3] += force
        out[3:] += np.cross(arm, force)
    return out


# --------------------------------------------------------------------------- radiation
def retardation(database: HydroDatabase, dt_s: float, length_s: float = KERNEL_LENGTH_S,
                added_mass_scale: float = 1.0) -> np.ndarray:
    """K(t_k) = 2/pi int_0^w_max B(w) cos(w t_k) dw on t_k = k dt (k = 0..length/dt), with B
    linear between the BEM frequencies and B(0) = 0; shape (n, 6, 6)."""
    omega = np.concatenate([[0.0], database.omega_rad_s])
    damping = np.concatenate([np.zeros((1, 6, 6)), database.damping]) * added_mass_scale
    fine = np.linspace(0.0, omega[-1], 4000)
    b_fine = np.stack([np.interp(fine, omega, damping[:, i, j]) for i in range(6) for j in range(6)], axis=-1)
    t = np.arange(0.0, length_s + 0.5 * dt_s, dt_s)
    weights = np.full(fine.size, fine[1] - fine[0])
    weights[[0, -1]] *= 0.5
    kernel = (2.0 / math.pi) * (np.cos(np.outer(t, fine)) * weights) @ b_fine
    return kernel.reshape(t.size, 6, 6)


def added_mass_from_kernel(kernel: np.ndarray, dt_s: float, added_mass_inf: np.ndarray,
                           omega_rad_s: float) -> np.ndarray:
    """A(w) = A_inf - 1/w int_0^inf K(t) sin(w t) dt: the kernel's consistency with the BEM."""
    t = np.arange(kernel.shape[0]) * dt_s
    weights = np.full(t.size, dt_s)
    weights[[0, -1]] *= 0.5
    return added_mass_inf - np.tensordot(weights * np.sin(omega_rad_s * t), kernel, axes=1) / omega_rad_s


# --------------------------------------------------------------------------- options
Table = tuple[tuple[float, float], ...]


@dataclass(frozen=True)
class Baseline:
    """The independent simulator's own baseline differences from the platform description,
    and its physical slow drift (a surge mean-drift coefficient table D(w), (rad/s, N/m^2)
    pairs, by Newman's approximation; the project's model has none)."""

    cd_scale: float = 1.0
    added_mass_scale: float = 1.0  # scales A_inf and the radiation kernel
    strip_length_m: float | None = None  # None: the platform's
    drag: bool = True
    mooring: bool = True
    drift_coefficient_n_m2: Table = ()


@dataclass(frozen=True)
class Effects:
    """Injected effects: extra damping F = -(b1 v + b2 |v| v) per DOF; a surge drift force
    F(t) = |sum_j a_j sqrt(D(w_j)) e^{i theta_j(t)}|^2 (Newman), D from (w, D) pairs; an extra
    surge restoring force against the surge offset (m, N) pairs (a catenary's curve less the
    spring lines'); harmonic loads (DOF, amplitude N or N m, frequency Hz)."""

    linear_damping: tuple[float, ...] = (0.0,) * 6
    quadratic_damping: tuple[float, ...] = (0.0,) * 6
    drift_coefficient_n_m2: Table = field(default=())
    mooring_curve_n: Table = field(default=())
    harmonic_load: tuple[tuple[int, float, float], ...] = field(default=())

    def drift_force_n(self, waves: Waves, time_s: np.ndarray) -> np.ndarray:
        return drift_force_n(self.drift_coefficient_n_m2, waves, time_s)


def drift_force_n(table: Table, waves: Waves, time_s: np.ndarray) -> np.ndarray:
    """Newman's slow drift force in surge of a mean-drift coefficient table."""
    if not table:
        return np.zeros(time_s.size)
    table = np.asarray(table, float)
    coefficient = np.interp(waves.omega_rad_s, table[:, 0], table[:, 1], left=table[0, 1], right=table[-1, 1])
    if np.any(coefficient < 0.0):
        raise ValueError("drift coefficient must be >= 0 (Newman's approximation)")
    c = waves.amplitude_m * np.sqrt(coefficient) * np.exp(1j * waves.phase_rad)
    return np.abs(synthesis(c, waves, time_s, real=False)) ** 2


def synthesis(coefficients: np.ndarray, waves: Waves, time_s: np.ndarray, real: bool = True) -> np.ndarray:
    """sum_j c_j e^{i w_j t} (its real part if ``real``) for coefficients (n_components, ...):
    by FFT over the waves' repeat period when ``time_s`` is that period's uniform grid from
    0, else by direct sum."""
    n = time_s.size
    if waves.period_s and n > 1 and abs(time_s[0]) < 1e-9 and abs(n * (time_s[1] - time_s[0]) - waves.period_s) < 1e-6:
        index = np.rint(waves.omega_rad_s * waves.period_s / (2.0 * math.pi)).astype(int)
        flat = coefficients.reshape(coefficients.shape[0], -1)
        out = np.empty((n, flat.shape[1]), float if real else complex)
        for start in range(0, flat.shape[1], 64):
            spectrum = np.zeros((n, min(64, flat.shape[1] - start)), complex)
            np.add.at(spectrum, index, flat[:, start:start + 64])
            values = n * np.fft.ifft(spectrum, axis=0)
            out[:, start:start + 64] = values.real if real else values
        return out.reshape((n,) + coefficients.shape[1:])
    if real:
        return _harmonic_sum(coefficients, waves.omega_rad_s, time_s)
    return _harmonic_sum(coefficients, waves.omega_rad_s, time_s) + 1j * _harmonic_sum(
        -1j * coefficients, waves.omega_rad_s, time_s)


# --------------------------------------------------------------------------- the model
FORCING_STEP_S = 0.1  # the grid the loads known in advance are tabulated on


@dataclass(frozen=True)
class Forcing:
    """Everything known in advance on a time grid: excitation (+ drift + harmonic loads),
    fluid velocity at the strip points (float32)."""

    time_s: np.ndarray
    excitation: np.ndarray  # (n, 6)
    fluid_velocity_m_s: np.ndarray  # (n, points, 3)


def forcing(database: HydroDatabase, platform: Platform, hull: Strips, waves: Waves, time_s: np.ndarray,
            effects: Effects, baseline: Baseline = Baseline()) -> Forcing:
    env = platform.environment
    x_table = database.excitation_at(waves.heading_deg)
    omega = waves.omega_rad_s
    if omega.max() > database.omega_rad_s[-1] or omega.min() < database.omega_rad_s[0]:
        raise ValueError(f"wave frequencies {omega.min():.3f}-{omega.max():.3f} rad/s outside the BEM's "
                         f"{database.omega_rad_s[0]:.3f}-{database.omega_rad_s[-1]:.3f}")
    x_w = np.stack([np.interp(omega, database.omega_rad_s, x_table[:, i].real)
                    + 1j * np.interp(omega, database.omega_rad_s, x_table[:, i].imag) for i in range(6)], axis=1)
    amplitude = waves.amplitude_m * np.exp(1j * waves.phase_rad)
    excitation = synthesis(amplitude[:, None] * x_w, waves, time_s)
    excitation[:, 0] += effects.drift_force_n(waves, time_s) + drift_force_n(baseline.drift_coefficient_n_m2, waves,
                                                                             time_s)
    for dof, load, frequency_hz in effects.harmonic_load:
        excitation[:, dof] += load * np.sin(2.0 * math.pi * frequency_hz * time_s)
    k = wavenumber(omega, env.water_depth_m, env.gravity_m_s2)
    b = math.radians(waves.heading_deg)
    points = hull.points_m
    h = env.water_depth_m
    kz = np.outer(k, points[:, 2] + h)
    local = amplitude[:, None] * np.exp(-1j * np.outer(k, points[:, 0] * math.cos(b) + points[:, 1] * math.sin(b)))
    horizontal = local * omega[:, None] * np.cosh(kz) / np.sinh(k * h)[:, None]
    vertical = -1j * local * omega[:, None] * np.sinh(kz) / np.sinh(k * h)[:, None]
    coefficients = np.stack([horizontal * math.cos(b), horizontal * math.sin(b), vertical], axis=-1)
    return Forcing(time_s, excitation, synthesis(coefficients, waves, time_s).astype(np.float32))


def drag_wrench(hull: Strips, rho: float, velocity: np.ndarray, fluid: np.ndarray) -> np.ndarray:
    """Quadratic drag on the relative velocity at the undisplaced strips (``fluid``: (n, 3) at
    ``hull.points_m``); force and moment about (0,0,0): the time stepping's own drag."""
    out = np.zeros(6)
    fluid = np.asarray(fluid, float)
    time_stepping._drag(np.asarray(velocity, float), fluid, fluid, 0.0, hull.points_m, len(hull.circular_point_m),
                        len(hull.box_point_m), hull.circular_axis, hull.circular_cda_m2, hull.box_direction,
                        hull.box_cda_m2, hull.plate_cda_m2, rho, out)
    return out


@dataclass(frozen=True)
class Trajectory:
    time_s: np.ndarray
    position: np.ndarray  # (n, 6) m, rad
    velocity: np.ndarray  # (n, 6)


def _forcing_grid(waves: Waves, start_s: float, end_s: float) -> tuple[np.ndarray, bool]:
    """The loads' grid: one repeat period from 0 (periodic) when the waves repeat on it, else
    the run's span."""
    if waves.period_s:
        n = round(waves.period_s / FORCING_STEP_S)
        if abs(n * FORCING_STEP_S - waves.period_s) < 1e-6:
            return np.arange(n) * FORCING_STEP_S, True
    n = math.ceil((end_s - start_s) / FORCING_STEP_S) + 2
    return start_s + np.arange(n) * FORCING_STEP_S, False


def integrate(platform: Platform, database: HydroDatabase, waves: Waves | None, duration_s: float,
              dt_s: float = 0.05, baseline: Baseline = Baseline(), effects: Effects = Effects(),
              initial: np.ndarray | None = None, preroll_s: float = 0.0) -> Trajectory:
    """RK4 at dt_s of the Cummins equation (time_stepping.py), from ``-preroll_s`` (in the waves'
    periodic extension) to ``duration_s``; the trajectory from 0."""
    env = platform.environment
    steps = round((duration_s + preroll_s) / dt_s)
    hull = strips(platform, baseline.cd_scale, baseline.strip_length_m)
    waves = waves or Waves(np.array([1.0]), np.zeros(1), np.zeros(1))
    grid, periodic = _forcing_grid(waves, -preroll_s, duration_s)
    force = forcing(database, platform, hull, waves, grid, effects, baseline)
    mass = rigid_body_mass(platform) + baseline.added_mass_scale * database.added_mass_inf
    kernel = retardation(database, dt_s, added_mass_scale=baseline.added_mass_scale)
    weights = np.full(kernel.shape[0], dt_s)
    weights[[0, -1]] *= 0.5
    mooring = platform.mooring
    fairlead = np.array([line.fairlead_m for line in mooring.lines], float).reshape(-1, 3)
    anchor = np.array([line.anchor_m for line in mooring.lines], float).reshape(-1, 3)
    curve = np.asarray(effects.mooring_curve_n, float).reshape(-1, 2)
    x0 = np.zeros(6) if initial is None else np.asarray(initial, float)
    positions, velocities = time_stepping.integrate(
        steps, dt_s, -preroll_s, x0, float(grid[0]), FORCING_STEP_S, periodic, force.excitation,
        force.fluid_velocity_m_s, np.linalg.inv(mass), database.hydrostatic_stiffness,
        kernel * weights[:, None, None], np.asarray(effects.linear_damping, float),
        np.asarray(effects.quadratic_damping, float), baseline.drag, env.water_density_kg_m3, hull.points_m,
        len(hull.circular_point_m), len(hull.box_point_m), hull.circular_axis, hull.circular_cda_m2,
        hull.box_direction, hull.box_cda_m2, hull.plate_cda_m2, baseline.mooring, fairlead, anchor,
        np.linalg.norm(anchor - fairlead, axis=1), mooring.pretension_n, mooring.stiffness_n_m,
        np.ascontiguousarray(curve[:, 0]), np.ascontiguousarray(curve[:, 1]))
    keep = round(preroll_s / dt_s)
    return Trajectory(np.arange(steps + 1 - keep) * dt_s, positions[keep:], velocities[keep:])


def measured_run(platform: Platform, database: HydroDatabase, waves: Waves, duration_s: float, name: str,
                 dt_s: float = 0.05, baseline: Baseline = Baseline(), effects: Effects = Effects(),
                 preroll_s: float = 0.0) -> MeasuredRun:
    """A "measured" run for the diagnosis: elevation at (0, 0) every 0.1 s, motion every 0.25 s."""
    trajectory = integrate(platform, database, waves, duration_s, dt_s, baseline, effects, preroll_s=preroll_s)
    env = platform.environment
    elevation_time = np.arange(0.0, duration_s + 1e-9, ELEVATION_STEP_S)
    motion_time = np.arange(0.0, duration_s + 1e-9, MOTION_STEP_S)
    motion = np.stack([np.interp(motion_time, trajectory.time_s, trajectory.position[:, i]) for i in range(6)], axis=1)
    return MeasuredRun(name, elevation_time, elevation(waves, elevation_time, 0.0, 0.0, env.water_depth_m,
                                                       env.gravity_m_s2),
                       (0.0, 0.0), motion_time, motion, waves.heading_deg)
