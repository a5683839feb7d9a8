"""``fowt-sim turbine``: the wind turbine on the platform, driven by NREL's ROSCO.

Each platform odometry (stamped t) advances the turbine model (``fowt_hydro_sim.turbine``)
to t in controller steps, in the relative wind at the hub, and answers with the rotor's
thrust and shaft-torque reaction as the platform's external wrench (frame ``hub``, stamped
t: a lockstep platform node steps on it), and the turbine's state on ``/turbine/*``
(geometry_msgs/Vector3Stamped stamped t, the value in x, SI units). Runs on simulation time.
"""
from __future__ import annotations

import logging
import time
from dataclasses import dataclass

import numpy as np
import rclpy
from geometry_msgs.msg import Vector3Stamped, WrenchStamped
from nav_msgs.msg import Odometry
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.qos import QoSProfile, ReliabilityPolicy

import msg_adapters as adapt
from fowt_hydro_sim.physics.config import ConfigError, RunConfig, load_platform
from fowt_hydro_sim.ros import parameters
from fowt_hydro_sim.ros.startup import init_ros
from fowt_hydro_sim.rosbag.reader import Bag
from fowt_hydro_sim.settings import like, setting
from fowt_hydro_sim.turbine.description import load_turbine
from fowt_hydro_sim.turbine.discon import ControllerError
from fowt_hydro_sim.turbine.performance import RotorCoefficients, read_table
from fowt_hydro_sim.turbine.rosco import Rosco
from fowt_hydro_sim.turbine.rotor import HubMotion, TurbineModel, aero_loads, hub_motion, steady_operating_point
from fowt_hydro_sim.turbine.wind import DEFAULT_WIND_M_S, WIND_KINDS, Wind, check_series, read_series, series_wind
from msg_adapters import topics

STAMP_TOLERANCE_S = 1e-9  # odometry stamps closer than this are the same time


@dataclass(frozen=True)
class TurbineSettings:
    """The turbine node's parameters."""

    turbine: str = setting("iea15_umaine", "packaged turbine name or turbine YAML file")
    platform: str = like(RunConfig, "platform", note="; its hub point is where the wrench is applied")
    hub_height_m: float = setting(0.0, "height of the thrust point above the platform's reference point [m]; "
                                       "0 = the platform's hub point", ge=0.0)
    wind: str = setting("steady", "wind input: steady, step, ramp (from wind_speed_m_s to wind_end_m_s at "
                                  "wind_start_s, ramp over wind_ramp_s), file (wind_file), bag (wind_topic of "
                                  "wind_bag)", choices=(*WIND_KINDS, "bag"))
    wind_speed_m_s: float = setting(DEFAULT_WIND_M_S, "hub-height wind speed (before the step or ramp) [m/s]",
                                    ge=0.0, le=80.0)
    wind_end_m_s: float = setting(DEFAULT_WIND_M_S, "wind speed after the step or ramp [m/s]", ge=0.0, le=80.0)
    wind_start_s: float = setting(0.0, "time of the step or start of the ramp [s]", ge=0.0)
    wind_ramp_s: float = setting(60.0, "duration of the ramp [s]", gt=0.0)
    wind_file: str = setting("", "CSV of time [s] and hub-height wind speed [m/s] (wind file)")
    wind_bag: str = setting("", "bag holding a hub-height wind speed series (wind bag)")
    wind_topic: str = setting(topics.TURBINE["wind_speed"][0],
                              "topic of wind_bag with the wind speed (a turbine quantity topic: Vector3Stamped, x)")
    rotor_start: str = setting("steady", "steady: the turbine starts at its steady operating point in the "
                                           "initial wind; given: at rotor_speed_rad_s and pitch_rad",
                                 choices=("steady", "given"))
    rotor_speed_rad_s: float = setting(0.5, "initial rotor speed (rotor_start given) [rad/s]", ge=0.0)
    pitch_rad: float = setting(0.0, "initial blade pitch (rotor_start given) [rad]", ge=-0.5, le=1.6)
    fixed_platform: bool = setting(False, "ignore the platform's motion (a turbine on a fixed foundation)")
    rosco_logging: int = setting(0, "ROSCO's LoggingLevel: 0 none, 1 its debug channels (rosco.RO.dbg), 2 and its "
                                    "local variables (.dbg2), 3 and the swap array (.dbg3)", ge=0, le=3)
    rosco_debug_dir: str = setting("", "folder where ROSCO's debug files are copied when the node ends "
                                       "(rosco_logging > 0); empty: not kept")
    wait_for_subscribers: int = setting(0, "before answering the first odometry, wait (at most 60 wall seconds) "
                                           "until this many subscribers are connected to each /turbine/ topic (a "
                                           "recorder started alongside, so that its bag misses no sample) and one "
                                           "to the wrench", ge=0)

    def __post_init__(self) -> None:
        if self.wind == "file" and not self.wind_file:
            raise ConfigError("parameter wind_file: wind file needs the path of a CSV of time and speed")
        if self.wind == "bag" and not self.wind_bag:
            raise ConfigError("parameter wind_bag: wind bag needs the path of a bag with a wind speed topic")
        if self.rosco_debug_dir and not self.rosco_logging:
            raise ConfigError("parameter rosco_debug_dir: ROSCO writes debug files only with rosco_logging > 0")

    def make_wind(self) -> Wind:
        if self.wind == "file":
            return series_wind(*read_series(self.wind_file))
        if self.wind == "bag":
            series = Bag(self.wind_bag).scalar(self.wind_topic)
            check_series(series.time_s, series.values[:, 0], f"wind bag {self.wind_bag} {self.wind_topic}")
            return series_wind(series.time_s, series.values[:, 0])
        return Wind(self.wind, self.wind_speed_m_s, self.wind_end_m_s, self.wind_start_s, self.wind_ramp_s)


class TurbineNode(Node):
    def __init__(self, **node_kwargs):
        super().__init__("fowt_turbine", **node_kwargs)
        self.set_parameters([Parameter("use_sim_time", Parameter.Type.BOOL, True)])
        parameters.declare(self, TurbineSettings)
        parameters.refuse_unknown(self)
        s = self.settings = parameters.read(self, TurbineSettings)
        self.turbine = load_turbine(s.turbine)
        self.wind = s.make_wind()
        self.hub_point_m = np.array(load_platform(s.platform).hub_point_m)
        self.thrust_height_m = s.hub_height_m or float(self.hub_point_m[2])
        self.coefficients = RotorCoefficients(read_table(self.turbine.performance_path))
        start = (steady_operating_point(self.turbine, self.coefficients, self.wind.at(0.0))
                 if s.rotor_start == "steady" else (s.rotor_speed_rad_s, s.pitch_rad, 0.0))
        self.rosco = Rosco(self.turbine.discon_path, self.turbine.controller_dt_s, self.turbine.generator_efficiency,
                           s.rosco_logging, pitch_rad=start[1])
        self.model = TurbineModel(self.turbine, self.coefficients, self.rosco, *start)
        self.failed = False
        self._last: HubMotion | None = None  # the hub's motion at the last odometry answered
        qos = QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE)
        self._wrench = self.create_publisher(WrenchStamped, topics.EXTERNAL_WRENCH, qos)
        self._state = {name: self.create_publisher(Vector3Stamped, topic, qos)
                       for name, (topic, _) in topics.TURBINE.items()}
        self.create_subscription(Odometry, topics.MOTION["odom"][0], self._on_odometry, qos)
        self.get_logger().info(
            f"{self.turbine.name}: ROSCO every {self.turbine.controller_dt_s:g} s, wind {s.wind}, thrust at "
            f"{self.thrust_height_m:g} m" + (", platform held fixed" if s.fixed_platform else ""))

    def wait_for_subscribers(self, timeout_s: float = 60.0) -> None:
        """Until each turbine quantity topic has ``wait_for_subscribers`` subscribers and the
        wrench one (the platform node: its first wrench is not lost to discovery); DDS
        discovers them without spinning, so no odometry is answered meanwhile."""
        count = self.settings.wait_for_subscribers
        deadline = time.monotonic() + timeout_s
        while count and (min(p.get_subscription_count() for p in self._state.values()) < count
                         or self._wrench.get_subscription_count() < 1):
            if time.monotonic() > deadline:
                self.get_logger().warning(f"wait_for_subscribers: fewer than {count} subscribers after "
                                          f"{timeout_s:g} s; answering anyway")
                return
            time.sleep(0.05)

    def _on_odometry(self, msg: Odometry) -> None:
        if self.failed:
            return
        t, twist = adapt.body_twist_from_odometry(msg)
        if self._last is not None and t <= self._last.time_s + STAMP_TOLERANCE_S:
            # the odometry of a stamp already answered (sent again while the platform waited): its wrench again,
            # not the turbine's state (the bag would hold it twice at one stamp); an older one is ignored
            if t >= self._last.time_s - STAMP_TOLERANCE_S:
                self._publish_wrench(self._last.time_s)
            return
        motion = hub_motion(t, twist, self._last, self.thrust_height_m, self.settings.fixed_platform)
        model, dt = self.model, self.model.dt_s
        try:
            while model.state.time_s + dt <= t + STAMP_TOLERANCE_S:
                model.step(self.wind.at(model.state.time_s + dt), motion.velocity_m_s,
                           motion.pitch_acceleration_rad_s2,
                           fore_aft_acceleration_m_s2=motion.fore_aft_acceleration_m_s2)
        except ControllerError as exc:
            self.get_logger().error(f"{exc}; the turbine stops answering")
            self.failed = True
            return
        if self._last is None:  # the first odometry: the loads of the initial state
            s = model.state
            s.wind_m_s = self.wind.at(t)
            s.relative_wind_m_s = s.wind_m_s - motion.velocity_m_s
            s.thrust_n, s.aero_torque_nm = aero_loads(self.turbine, self.coefficients, s.relative_wind_m_s,
                                                      s.rotor_speed_rad_s, s.pitch_rad)
        self._last = motion
        self._publish(t)

    def _publish_wrench(self, t: float) -> None:
        thrust, torque = self.model.hub_wrench()
        offset = self.thrust_height_m - float(self.hub_point_m[2])  # thrust point above the platform's hub point
        wrench = np.array([thrust, 0.0, 0.0, torque, offset * thrust, 0.0])
        self._wrench.publish(adapt.wrench_msg(t, wrench, "hub"))

    def _publish(self, t: float) -> None:
        self._publish_wrench(t)
        s = self.model.state
        values = {"rotor_speed": s.rotor_speed_rad_s, "generator_torque": s.generator_torque_nm,
                  "generator_power": self.model.generator_power_w(), "blade_pitch": s.pitch_rad,
                  "wind_speed": s.wind_m_s, "relative_wind_speed": s.relative_wind_m_s}
        for name, value in values.items():
            self._state[name].publish(adapt.quantity_msg(t, value))


def main(args: list[str] | None = None) -> int:
    """``fowt-sim turbine [--ros-args ...]``: until stopped, or 1 after ROSCO failed."""
    logging.basicConfig(level=logging.INFO, format="[%(levelname)s] [%(name)s]: %(message)s")
    log = logging.getLogger("fowt_hydro_sim")
    try:
        init_ros(args)
        node = TurbineNode()
    except Exception as exc:  # bad parameters, turbine file or DISCON.IN: one line, no traceback
        log.error(f"fowt-sim turbine: {exc}".splitlines()[0])
        rclpy.try_shutdown()
        return 2
    try:
        node.wait_for_subscribers()
        while rclpy.ok() and not node.failed:
            rclpy.spin_once(node, timeout_sec=0.1)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        copies = node.rosco.close(node.settings.rosco_debug_dir or None)
        if copies:
            log.info(f"ROSCO's debug files: {', '.join(map(str, copies))}")
        node.destroy_node()
        rclpy.try_shutdown()
    return 1 if node.failed else 0
