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
from fowt_hydro_sim.physics.config import load_platform
from fowt_hydro_sim.ros import parameters
from fowt_hydro_sim.ros.startup import ignore_stop_signals, init_ros
from fowt_hydro_sim.rosbag.reader import Bag
from fowt_hydro_sim.turbine import settings
from fowt_hydro_sim.turbine.coupled import STAMP_TOLERANCE_S, turbine_on_platform
from fowt_hydro_sim.turbine.discon import ControllerError
from fowt_hydro_sim.turbine.system import with_system
from fowt_hydro_sim.turbine.wind import Wind
from msg_adapters import topics


def bag_series(path: str, topic: str) -> tuple[np.ndarray, np.ndarray]:
    """A turbine quantity topic of a bag: its times and values."""
    series = Bag(path).scalar(topic)
    return series.time_s, series.values[:, 0]


@dataclass(frozen=True)
class TurbineSettings(settings.TurbineSettings):
    """The turbine node's parameters (``turbine.settings``), its wind read from a bag too."""

    def make_wind(self, bag_series: settings.BagSeries | None = bag_series) -> Wind:
        return super().make_wind(bag_series)


class TurbineNode(Node):
    def __init__(self, **node_kwargs):
        super().__init__("fowt_turbine", **node_kwargs)
        self.set_parameters([Parameter("use_sim_time", Parameter.Type.BOOL, True)])
        parameters.declare(self, TurbineSettings)
        parameters.refuse_unknown(self)
        s = self.settings = with_system(parameters.read(self, TurbineSettings))
        start = None if s.rotor_start == "steady" else (s.rotor_speed_rad_s, s.pitch_rad, 0.0)
        self.rotor = turbine_on_platform(s.turbine, load_platform(s.platform), s.make_wind(), s.hub_height_m, start,
                                         s.fixed_platform, s.rosco_logging, discon_changes=s.discon_changes)
        self.turbine, self.model, self.wind = self.rotor.turbine, self.rotor.model, self.rotor.wind
        self.failed = False
        qos = QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE)
        self._wrench = self.create_publisher(WrenchStamped, topics.EXTERNAL_WRENCH, qos)
        self._state = {name: self.create_publisher(Vector3Stamped, topic, qos)
                       for name, (topic, _) in topics.TURBINE.items()}
        self.create_subscription(Odometry, topics.MOTION["odom"][0], self._on_odometry, qos)
        self.get_logger().info(
            f"{self.turbine.name}: ROSCO every {self.turbine.controller_dt_s:g} s, wind {s.wind}, thrust at "
            f"{self.rotor.thrust_height_m:g} m" + (", platform held fixed" if s.fixed_platform else ""))

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
        last = self.rotor.last_time_s
        if last is not None and t <= last + STAMP_TOLERANCE_S:
            # the odometry of a stamp already answered (sent again while the platform waited): its wrench again,
            # not the turbine's state (the bag would hold it twice at one stamp); an older one is ignored
            if t >= last - STAMP_TOLERANCE_S:
                self._publish_wrench(last)
            return
        try:
            self.rotor.answer(t, twist)
        except ControllerError as exc:
            self.get_logger().error(f"{exc}; the turbine stops answering")
            self.failed = True
            return
        self._publish(t)

    def _publish_wrench(self, t: float) -> None:
        self._wrench.publish(adapt.wrench_msg(t, self.rotor.hub_wrench(), "hub"))

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
        ignore_stop_signals()
        copies = node.rotor.close(node.settings.rosco_debug_dir or None)
        if copies:
            log.info(f"ROSCO's debug files: {', '.join(map(str, copies))}")
        node.destroy_node()
        rclpy.try_shutdown()
    return 1 if node.failed else 0
