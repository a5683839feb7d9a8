"""The turbine model: a rigid rotor in the relative wind at the hub (thrust and aerodynamic
torque from the Cp/Ct tables), a 1-DOF drivetrain (rotor + generator inertia, gearbox),
a blade-pitch actuator with position and rate limits, and the controller called every
step. The rotor speed advances by explicit Euler at the controller step, as in ROSCO's own
simple simulator (``rosco.toolbox.sim.Sim``)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from fowt_hydro_sim.turbine.description import TurbineDescription
from fowt_hydro_sim.turbine.performance import RotorCoefficients

MIN_RELATIVE_WIND_M_S = 0.1  # below: no aerodynamic load (the tip-speed ratio has no meaning)


@dataclass
class TurbineState:
    time_s: float = 0.0
    rotor_speed_rad_s: float = 0.0
    pitch_rad: float = 0.0
    generator_torque_nm: float = 0.0
    wind_m_s: float = 0.0  # free wind at the hub
    relative_wind_m_s: float = 0.0  # free wind minus the hub's fore-aft velocity
    thrust_n: float = 0.0
    aero_torque_nm: float = 0.0

    def generator_speed_rad_s(self, gearbox_ratio: float) -> float:
        return self.rotor_speed_rad_s * gearbox_ratio


@dataclass(frozen=True)
class HubMotion:
    """The thrust point's motion at one odometry: what the rotor and ROSCO see."""

    time_s: float
    pitch_rate_rad_s: float  # the platform's body pitch rate
    velocity_m_s: float  # fore-aft (body x) velocity of the thrust point
    pitch_acceleration_rad_s2: float  # the platform's pitch acceleration (ROSCO's NacIMU_FA_RAcc)
    fore_aft_acceleration_m_s2: float  # fore-aft acceleration of the thrust point (ROSCO's FA_Acc_TT)


def hub_motion(t: float, twist: np.ndarray, last: HubMotion | None, thrust_height_m: float,
               fixed: bool = False) -> HubMotion:
    """The thrust point's motion from the platform's body twist (v, omega) at time ``t``: its
    fore-aft velocity, body x of v + omega x r (r = (0, 0, ``thrust_height_m``)), and the pitch
    and fore-aft accelerations as backward differences from the ``last`` odometry answered
    (zero at the first one); all zero with ``fixed`` (a fixed foundation)."""
    if fixed:
        return HubMotion(t, 0.0, 0.0, 0.0, 0.0)
    rate = float(twist[4])
    velocity = float(twist[0]) + rate * thrust_height_m  # body x of v + omega x r, r = (0, 0, h)
    if last is None or t <= last.time_s:
        return HubMotion(t, rate, velocity, 0.0, 0.0)
    dt = t - last.time_s
    return HubMotion(t, rate, velocity, (rate - last.pitch_rate_rad_s) / dt, (velocity - last.velocity_m_s) / dt)


def aero_loads(turbine: TurbineDescription, coefficients: RotorCoefficients, relative_wind_m_s: float,
               rotor_speed_rad_s: float, pitch_rad: float) -> tuple[float, float]:
    """Rotor thrust [N] and aerodynamic torque [N m]: 1/2 rho A U^2 Ct and 1/2 rho A R U^2 Cp/TSR."""
    u = relative_wind_m_s
    if u < MIN_RELATIVE_WIND_M_S:
        return 0.0, 0.0
    r = turbine.rotor_radius_m
    tsr = rotor_speed_rad_s * r / u
    pressure = 0.5 * turbine.air_density_kg_m3 * math.pi * r ** 2 * u ** 2
    thrust = pressure * coefficients.ct(pitch_rad, tsr)
    torque = pressure * r * coefficients.cp(pitch_rad, tsr) / tsr if tsr > 0 else 0.0
    return thrust, torque


def steady_operating_point(turbine: TurbineDescription, coefficients: RotorCoefficients,
                           wind_m_s: float) -> tuple[float, float, float]:
    """Rotor speed, blade pitch and generator torque where the rotor runs steadily in
    ``wind_m_s``: below rated at the optimal tip-speed ratio (up to rated speed) and the
    lowest pitch; above rated at rated speed and torque, the pitch balancing them."""
    speed = min(turbine.rated_rotor_speed_rad_s, turbine.optimal_tsr * wind_m_s / turbine.rotor_radius_m)
    shaft = turbine.rated_generator_torque_nm * turbine.gearbox_ratio / turbine.gearbox_efficiency

    def surplus(pitch_rad: float) -> float:
        return aero_loads(turbine, coefficients, wind_m_s, speed, pitch_rad)[1] - shaft

    pitch = turbine.min_pitch_rad
    if speed >= turbine.rated_rotor_speed_rad_s and surplus(pitch) > 0:
        pitch = brentq(surplus, pitch, min(turbine.max_pitch_rad, float(coefficients.table.pitch_rad[-1])))
    torque = aero_loads(turbine, coefficients, wind_m_s, speed, pitch)[1]
    return speed, pitch, torque * turbine.gearbox_efficiency / turbine.gearbox_ratio


def actuate_pitch(turbine: TurbineDescription, pitch_rad: float, command_rad: float, dt_s: float) -> float:
    """The blade pitch after one step towards the command, within rate and position limits."""
    most = turbine.max_pitch_rate_rad_s * dt_s
    moved = pitch_rad + min(max(command_rad - pitch_rad, -most), most)
    return min(max(moved, turbine.min_pitch_rad), turbine.max_pitch_rad)


def drivetrain_step(turbine: TurbineDescription, rotor_speed_rad_s: float, aero_torque_nm: float,
                    generator_torque_nm: float, dt_s: float) -> float:
    """The rotor speed after one explicit Euler step of J dw/dt = Q_aero - N Q_gen / eta."""
    shaft = turbine.gearbox_ratio * generator_torque_nm / turbine.gearbox_efficiency
    return max(0.0, rotor_speed_rad_s + dt_s * (aero_torque_nm - shaft) / turbine.drivetrain_inertia_kg_m2)


class TurbineModel:
    """The turbine stepped at its controller step; ``controller`` has ROSCO's ``step``."""

    def __init__(self, turbine: TurbineDescription, coefficients: RotorCoefficients, controller,
                 rotor_speed_rad_s: float, pitch_rad: float = 0.0, generator_torque_nm: float = 0.0):
        self.turbine, self.coefficients, self.controller = turbine, coefficients, controller
        self.state = TurbineState(rotor_speed_rad_s=rotor_speed_rad_s, pitch_rad=pitch_rad,
                                  generator_torque_nm=generator_torque_nm)

    @property
    def dt_s(self) -> float:
        return self.turbine.controller_dt_s

    def step(self, wind_m_s: float, hub_velocity_m_s: float = 0.0, pitch_acceleration_rad_s2: float = 0.0,
             last: bool = False, fore_aft_acceleration_m_s2: float = 0.0) -> TurbineState:
        """Advance one controller step to ``time_s + dt``: the wind there (``wind_m_s``) and the
        hub's fore-aft velocity give the loads on the rotor, the drivetrain accelerates, ROSCO
        answers (also given the platform's pitch acceleration and the hub's fore-aft
        acceleration, for its floating feedback and tower damper), the actuator moves the blades."""
        s, t = self.state, self.turbine
        time_s = s.time_s + self.dt_s
        relative = wind_m_s - hub_velocity_m_s
        thrust, torque = aero_loads(t, self.coefficients, relative, s.rotor_speed_rad_s, s.pitch_rad)
        speed = drivetrain_step(t, s.rotor_speed_rad_s, torque, s.generator_torque_nm, self.dt_s)
        generator_torque, command = self.controller.step(
            time_s, relative, speed, speed * t.gearbox_ratio, s.pitch_rad, s.generator_torque_nm,
            pitch_acceleration_rad_s2, last, fore_aft_acceleration_m_s2=fore_aft_acceleration_m_s2)
        self.state = TurbineState(time_s, speed, actuate_pitch(t, s.pitch_rad, command, self.dt_s),
                                  generator_torque, wind_m_s, relative, thrust, torque)
        return self.state

    def generator_power_w(self) -> float:
        s, t = self.state, self.turbine
        return s.generator_speed_rad_s(t.gearbox_ratio) * s.generator_torque_nm * t.generator_efficiency

    def hub_wrench(self) -> tuple[float, float]:
        """Thrust [N] along the rotor axis (x, downwind) and the shaft torque's reaction on the
        nacelle [N m] about it: the rotor turns clockwise seen from upwind (spin along +x), and
        the generator holding it back pushes the nacelle the way the rotor turns."""
        s, t = self.state, self.turbine
        return s.thrust_n, t.gearbox_ratio * s.generator_torque_nm / t.gearbox_efficiency
