"""The turbine on the platform, without ROS: the exchange the turbine node makes at each
platform odometry (``TurbineOnPlatform.answer``), and the coupled loop that steps the
platform model and the turbine in one process (``run_coupled``) with the same exchange in
the same order as the two nodes in lockstep:

    the platform's state at t (its body twist) -> the turbine advances to t in controller
    steps (the wind at each step, the hub's fore-aft velocity, the pitch and fore-aft
    accelerations as backward differences from the last answer) -> the rotor's wrench at t
    (thrust and shaft-torque reaction, frame ``hub``) -> the platform steps t -> t + period
    under that wrench -> its state at t + period ...

    platform = load_platform("volturnus_s")
    model = PlatformModel(platform, None, dt_s=0.05)
    rotor = turbine_on_platform("iea15_umaine", platform, Wind(speed_m_s=11.0))
    model.reset(motion=static_offset(model, rotor))
    parts = run_coupled(model, rotor, 600.0)   # CoupledPart: RunResult, line tensions, turbine channels
"""
from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import replace
from typing import NamedTuple

import numpy as np

from fowt_hydro_sim.physics.config import ConfigError, Platform
from fowt_hydro_sim.physics.loads import N_LOADS, RESTORING, ROW
from fowt_hydro_sim.physics.model import WAVE_BLOCK_S, PlatformModel, RunResult
from fowt_hydro_sim.turbine.description import TurbineDescription, load_turbine
from fowt_hydro_sim.turbine.performance import RotorCoefficients, read_table
from fowt_hydro_sim.turbine.rosco import Rosco, entry_name
from fowt_hydro_sim.turbine.rotor import HubMotion, TurbineModel, aero_loads, hub_motion, steady_operating_point
from fowt_hydro_sim.turbine.tower import TowerPoints, tower_drag
from fowt_hydro_sim.turbine.wind import Wind

STAMP_TOLERANCE_S = 1e-9  # platform times closer than this are the same time
# the turbine's channels, as the turbine node publishes them (/turbine/<name>) and timeseries.csv names them
CHANNELS = ("rotor_speed_rad_s", "generator_torque_nm", "generator_power_w", "blade_pitch_rad", "wind_speed_m_s",
            "relative_wind_speed_m_s", "thrust_n")


class TurbineOnPlatform:
    """A turbine model (rotor, drivetrain, actuator, controller) on a platform whose motion
    it is given at each platform output time: ``answer`` advances it there; ``hub_wrench``
    is then the wrench on the platform (frame ``hub``: the platform's hub point, body axes):
    the rotor's, and the wind's drag on the tower when the turbine has a tower table
    (``turbine.tower_aerodyn``), and ``channels`` its state. ``thrust_height_m`` is the thrust
    point's height above the platform's reference point; ``fixed`` ignores the platform's motion."""

    def __init__(self, turbine: TurbineDescription, coefficients: RotorCoefficients, model: TurbineModel,
                 wind: Wind, hub_point_m: np.ndarray, thrust_height_m: float = 0.0, fixed: bool = False):
        self.turbine, self.coefficients, self.model, self.wind = turbine, coefficients, model, wind
        self.hub_point_m = np.asarray(hub_point_m, dtype=float)
        self.thrust_height_m = thrust_height_m or float(self.hub_point_m[2])
        self.fixed = fixed
        self.last: HubMotion | None = None  # the hub's motion at the last time answered
        self.tower: TowerPoints | None = turbine.tower
        self.tower_load = (0.0, 0.0)  # the tower's drag [N] and its moment about the hub point [N m]

    @property
    def last_time_s(self) -> float | None:
        """The platform time last answered (None before the first)."""
        return None if self.last is None else self.last.time_s

    def answer(self, t: float, body_twist: np.ndarray) -> None:
        """Advance the turbine to the platform time ``t`` (later than the last answered) given
        the platform's body twist there ([v, omega], body axes): controller steps while one
        fits before ``t``; at the first time, the loads of the initial state.
        ``discon.ControllerError`` if the controller fails."""
        motion = hub_motion(t, body_twist, self.last, self.thrust_height_m, self.fixed)
        model, dt = self.model, self.model.dt_s
        while model.state.time_s + dt <= t + STAMP_TOLERANCE_S:
            model.step(self.wind.at(model.state.time_s + dt), motion.velocity_m_s, motion.pitch_acceleration_rad_s2,
                       fore_aft_acceleration_m_s2=motion.fore_aft_acceleration_m_s2)
        if self.last is None:  # the first time: the loads of the initial state
            s = model.state
            s.wind_m_s = self.wind.at(t)
            s.relative_wind_m_s = s.wind_m_s - motion.velocity_m_s
            s.thrust_n, s.aero_torque_nm = aero_loads(self.turbine, self.coefficients, s.relative_wind_m_s,
                                                      s.rotor_speed_rad_s, s.pitch_rad)
        if self.tower is not None:
            velocity = 0.0 if self.fixed else float(body_twist[0])
            self.tower_load = tower_drag(self.tower, self.turbine.air_density_kg_m3, model.state.wind_m_s, velocity,
                                         motion.pitch_rate_rad_s, float(self.hub_point_m[2]))
        self.last = motion

    def hub_wrench(self) -> np.ndarray:
        """[Fx, Fy, Fz, Mx, My, Mz] on the platform in frame ``hub``: the thrust along x, the
        shaft torque's reaction about it, the thrust's moment about the platform's hub
        point when the thrust point is elsewhere, and the tower's drag with its moment."""
        thrust, torque = self.model.hub_wrench()
        offset = self.thrust_height_m - float(self.hub_point_m[2])
        drag, moment = self.tower_load
        return np.array([thrust + drag, 0.0, 0.0, torque, offset * thrust + moment, 0.0])

    def channels(self) -> tuple[float, ...]:
        """The turbine's state, in the order of ``CHANNELS``."""
        s = self.model.state
        return (s.rotor_speed_rad_s, s.generator_torque_nm, self.model.generator_power_w(), s.pitch_rad, s.wind_m_s,
                s.relative_wind_m_s, s.thrust_n)

    def close(self, debug_dir: str | None = None) -> list:
        """End the controller's run (its debug files copied to ``debug_dir`` if given)."""
        return self.model.controller.close(debug_dir)


class HeldControls:
    """A controller that holds the generator torque [N m] and blade pitch [rad] it was
    given (the rotor in open loop, as a linearisation holds its inputs)."""

    def __init__(self, generator_torque_nm: float, pitch_rad: float):
        self.commands = (generator_torque_nm, pitch_rad)

    def step(self, *_measurements: float, **_more: float) -> tuple[float, float]:
        """The held generator torque and blade pitch, whatever is measured."""
        return self.commands

    def close(self, debug_dir: str | None = None) -> list:
        """Nothing to end; no debug files."""
        return []


class ControllerLimits(NamedTuple):
    """What of ROSCO's tuning bounds its steady operating point: the minimum rotor speed
    [rad/s] (``VS_MinOMSpd`` / ``WE_GearboxRatio``) and peak shaving's minimum blade pitch
    [rad] by wind speed [m/s] (``PS_WindSpeeds``, ``PS_BldPitchMin``; empty with ``PS_Mode`` 0)."""

    min_rotor_speed_rad_s: float
    shaving_wind_m_s: tuple[float, ...]
    shaving_pitch_rad: tuple[float, ...]

    def min_pitch_rad(self, wind_m_s: float) -> float:
        """Peak shaving's minimum pitch in ``wind_m_s`` (ROSCO interpolates its table, held at its ends)."""
        if not self.shaving_wind_m_s:
            return -math.inf
        return float(np.interp(wind_m_s, self.shaving_wind_m_s, self.shaving_pitch_rad))


def controller_limits(turbine: TurbineDescription) -> ControllerLimits:
    """The ``ControllerLimits`` of the turbine's DISCON.IN as its controller reads it (its
    ``discon_changes`` made); ConfigError naming a missing entry."""
    discon = turbine.discon_path
    values: dict[str, list[float]] = {}
    for line in turbine.controller_file().splitlines():
        name, numbers = entry_name(line)
        if name in ("VS_MinOMSpd", "WE_GearboxRatio", "PS_Mode", "PS_WindSpeeds", "PS_BldPitchMin"):
            try:
                values[name] = [float(v) for v in numbers.split()]
            except ValueError:
                raise ConfigError(f"{discon}: {name}: expected numbers, got {numbers.strip()!r}") from None
    missing = [n for n in ("VS_MinOMSpd", "WE_GearboxRatio", "PS_Mode") if not values.get(n)]
    if missing:
        raise ConfigError(f"{discon}: no {missing[0]}")
    shaving = values["PS_Mode"][0] != 0
    return ControllerLimits(values["VS_MinOMSpd"][0] / values["WE_GearboxRatio"][0],
                            tuple(values.get("PS_WindSpeeds", ())) if shaving else (),
                            tuple(values.get("PS_BldPitchMin", ())) if shaving else ())


def controlled_operating_point(turbine: TurbineDescription, coefficients: RotorCoefficients,
                               wind_m_s: float) -> tuple[float, float, float]:
    """Rotor speed, blade pitch and generator torque where the turbine with its ROSCO runs
    steadily in ``wind_m_s``: ``rotor.steady_operating_point`` within the controller's
    ``ControllerLimits`` (at least the minimum rotor speed, at least peak shaving's pitch),
    the generator torque balancing the rotor's torque there."""
    speed, pitch, torque = steady_operating_point(turbine, coefficients, wind_m_s)
    limits = controller_limits(turbine)
    bounded_speed, bounded_pitch = max(speed, limits.min_rotor_speed_rad_s), max(pitch, limits.min_pitch_rad(wind_m_s))
    if (bounded_speed, bounded_pitch) == (speed, pitch):
        return speed, pitch, torque
    aero = aero_loads(turbine, coefficients, wind_m_s, bounded_speed, bounded_pitch)[1]
    return bounded_speed, bounded_pitch, aero * turbine.gearbox_efficiency / turbine.gearbox_ratio


def turbine_on_platform(turbine: str, platform: Platform, wind: Wind, hub_height_m: float = 0.0,
                        rotor_start: tuple[float, float, float] | None = None, fixed: bool = False,
                        rosco_logging: int = 0, held: bool = False, discon_changes: str = "") -> TurbineOnPlatform:
    """The packaged turbine ``turbine`` (or a turbine YAML) with its ROSCO on ``platform``
    (``discon_changes``: entries of its DISCON.IN replaced, ``TurbineDescription.discon_changes``),
    starting at its steady operating point in the initial wind within its controller's
    limits (``controlled_operating_point``; or at ``rotor_start``: rotor
    speed [rad/s], blade pitch [rad], generator torque [N m]); ``held``: no controller, the
    generator torque and blade pitch held where they start (``HeldControls``)."""
    description = load_turbine(turbine, discon_changes=discon_changes)
    coefficients = RotorCoefficients(read_table(description.performance_path))
    start = rotor_start or controlled_operating_point(description, coefficients, wind.at(0.0))
    controller = (HeldControls(start[2], start[1]) if held else
                  Rosco(description.discon_path, description.controller_dt_s, description.generator_efficiency,
                        rosco_logging, pitch_rad=start[1], changes=description.changes))
    model = TurbineModel(description, coefficients, controller, *start)
    return TurbineOnPlatform(description, coefficients, model, wind, np.array(platform.hub_point_m), hub_height_m,
                             fixed)


def steady_wind_wrench(turbine: TurbineDescription, coefficients: RotorCoefficients, wind_m_s: float,
                       thrust_point_m: np.ndarray) -> np.ndarray:
    """The wind's steady wrench on the turbine in ``wind_m_s``, platform at rest: the rotor's
    thrust at its steady operating point (within its controller's limits,
    ``controlled_operating_point``) acting at ``thrust_point_m``, and the tower's drag when
    the turbine has a tower table; world axes, about the reference point."""
    speed, pitch, _ = controlled_operating_point(turbine, coefficients, wind_m_s)
    thrust, _ = aero_loads(turbine, coefficients, wind_m_s, speed, pitch)
    force = np.array([thrust, 0.0, 0.0])
    wrench = np.concatenate([force, np.cross(thrust_point_m, force)])
    if turbine.tower is not None:
        drag, moment = tower_drag(turbine.tower, turbine.air_density_kg_m3, wind_m_s, 0.0, 0.0, 0.0)
        wrench += np.array([drag, 0.0, 0.0, 0.0, moment, 0.0])
    return wrench


def restoring(model: PlatformModel, step: float = 1e-4) -> tuple[np.ndarray, np.ndarray]:
    """The wrench at rest (6: world axes, reference point) and the 6x6 restoring matrix there
    of every load that depends on the position alone (the registry's ``RESTORING``: the member or
    potential-flow hydrostatics, gravity, the mooring in any of its forms, HydroDyn's added
    stiffness), from the loads of a prescribed motion (the matrix by central differences; the
    moordyn lines: their quasi-static moorpy twin). A platform whose rest
    is its equilibrium has a zero wrench there."""
    platform, still = model.platform, model
    if platform.mooring.model == "moordyn" or model.filter_bank.n_states:  # (prescribed motion refuses them)
        if platform.mooring.model == "moordyn":
            platform = replace(platform, mooring=platform.mooring.chosen("moorpy"))
        still = PlatformModel(platform, None, dt_s=model.dt_s, options=model.options)
    rows = [ROW[name] for name in RESTORING]
    motion = np.zeros((13, 6))
    for j in range(6):
        motion[2 * j, j], motion[2 * j + 1, j] = step, -step
    loads = still.prescribed_motion_loads(np.zeros(13), motion, np.zeros((13, 6)), np.zeros((13, 6)))
    wrench = loads[:, rows].sum(axis=1)
    return wrench[12], -(wrench[0:12:2] - wrench[1:12:2]).T / (2 * step)


def static_offset(model: PlatformModel, rotor: TurbineOnPlatform) -> np.ndarray:
    """The platform's offset K^-1 (F0 + F) under the wind's steady wrench F in its initial
    wind (``steady_wind_wrench``; K, F0: the restoring matrix and the wrench at rest,
    ``restoring``), where a coupled run starts without a large start-up swing."""
    point = rotor.hub_point_m.copy()
    point[2] = rotor.thrust_height_m
    wrench = steady_wind_wrench(rotor.turbine, rotor.coefficients, rotor.wind.at(0.0), point)
    at_rest, stiffness = restoring(model)
    return np.linalg.solve(stiffness, at_rest + wrench)


class CoupledPart(NamedTuple):
    """A part of a coupled run: the platform's time series, each mooring line's tensions
    (n, lines, 2) and the turbine's channels (n, len(CHANNELS)) at the same rows."""

    result: RunResult
    tensions: np.ndarray
    turbine: np.ndarray


def body_twist(model: PlatformModel) -> np.ndarray:
    """The platform's [v, omega] in its body axes (R^T v, R^T omega), as its odometry
    carries them; written out in scalars (``frames.rotation_matrix``'s R): a coupled step's
    few microseconds."""
    roll, pitch, yaw = model.motion[3:].tolist()
    cr, sr, cp, sp, cy, sy = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch), math.cos(yaw), \
        math.sin(yaw)
    r = ((cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
         (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
         (-sp, cp * sr, cp * cr))
    v = model.velocity.tolist()
    return np.array([r[0][i] * v[k] + r[1][i] * v[k + 1] + r[2][i] * v[k + 2] for k in (0, 3) for i in range(3)])


def run_coupled(model: PlatformModel, rotor: TurbineOnPlatform, duration_s: float,
                output_interval_s: float | None = None, part_s: float = WAVE_BLOCK_S) -> Iterator[CoupledPart]:
    """Step ``model`` and ``rotor`` together for ``duration_s`` from the model's current
    state, exchanging every controller step (the model's dt must divide it), as the
    platform node in lockstep and the turbine node do; yield the run in parts of about
    ``part_s`` (whole output intervals; each part's first row is the previous part's last,
    as ``PlatformModel.run_parts``), one row every output interval (default every exchange)."""
    period = rotor.model.dt_s
    steps = int(round(period / model.dt_s))
    if steps < 1 or abs(steps * model.dt_s - period) > 1e-9 * period:
        raise ConfigError(f"coupled run: the model's step {model.dt_s:g} s must divide the controller's step "
                          f"{period:g} s")
    every = max(1, int(round((output_interval_s or period) / period)))
    n_periods = int(round(duration_s / period))
    part_rows = max(1, int(round(part_s / (every * period))))
    # MoorDyn's tensions exist at its latest step only: taken row by row; the other moorings' from the motion, per part
    lines_stepped = model.mooring_lines is not None
    rotor.answer(model.time_s, body_twist(model))

    def row() -> tuple:
        t, motion = model.time_s, model.motion
        tensions = model.mooring_tensions(np.array([t]), motion[None])[0] if lines_stepped else None
        return (t, motion, model.velocity, model.acceleration, model.loads, tensions,
                rotor.channels())

    rows, yielded = [row()], False
    for done in range(1, n_periods + 1):
        model.set_external_wrench(rotor.hub_wrench(), "hub")
        model.step(steps)
        rotor.answer(model.time_s, body_twist(model))
        if done % every == 0:
            rows.append(row())
        if len(rows) > part_rows or (done == n_periods and len(rows) > 1):
            yield _part(model, rows)
            rows, yielded = rows[-1:], True
    if not yielded:  # a run shorter than one output interval: its first row
        yield _part(model, rows)


def _part(model: PlatformModel, rows: list[tuple]) -> CoupledPart:
    t, motion, velocity, acceleration, loads, tensions, channels = zip(*rows)
    t, motion, velocity, acceleration, loads, channels = map(np.array, (t, motion, velocity, acceleration, loads,
                                                                       channels))
    tensions = np.array(tensions) if tensions[0] is not None else model.mooring_tensions(t, motion)
    loads = loads.reshape(len(t), N_LOADS, 6)
    result = RunResult(t, motion, velocity, acceleration, loads, model.wave_elevation(t))
    return CoupledPart(result, tensions.reshape(len(t), -1, 2), channels)
