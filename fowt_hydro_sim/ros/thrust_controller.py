"""``fowt-sim controller``: an example controller closing the loop with the simulator node.

It reads the platform's odometry and answers each message with a tower-top thrust along the
hub's x axis, stamped with the odometry's time (so a lockstep simulator can step):

    thrust = mean_thrust_n - pitch_damping_n_s_rad * pitch_rate

a constant rotor thrust with a platform-pitch damping term (a pitch rate forward lowers the
thrust). It runs on simulation time (``use_sim_time`` is set).
"""
from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np
import rclpy
from geometry_msgs.msg import WrenchStamped
from nav_msgs.msg import Odometry
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.qos import QoSProfile, ReliabilityPolicy

import msg_adapters as adapt
from fowt_hydro_sim.frames import WRENCH_FRAMES
from fowt_hydro_sim.ros import parameters
from fowt_hydro_sim.ros.startup import init_ros
from fowt_hydro_sim.settings import setting


@dataclass(frozen=True)
class ControllerSettings:
    """The controller's parameters."""

    mean_thrust_n: float = setting(1.5e6, "constant rotor thrust [N]")
    pitch_damping_n_s_rad: float = setting(0.0, "thrust change per platform pitch rate [N s/rad]")
    frame_id: str = setting("hub", "wrench frame", choices=WRENCH_FRAMES)


class ThrustController(Node):
    def __init__(self, **node_kwargs):
        super().__init__("fowt_thrust_controller", **node_kwargs)
        self.set_parameters([Parameter("use_sim_time", Parameter.Type.BOOL, True)])
        parameters.declare(self, ControllerSettings)
        parameters.refuse_unknown(self)
        s = parameters.read(self, ControllerSettings)
        self.mean_thrust_n, self.damping, self.frame_id = s.mean_thrust_n, s.pitch_damping_n_s_rad, s.frame_id
        qos = QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE)
        self._publisher = self.create_publisher(WrenchStamped, "/platform/external_wrench", qos)
        self.create_subscription(Odometry, "/platform/odom", self._on_odometry, qos)

    def thrust_n(self, pitch_rate_rad_s: float) -> float:
        return self.mean_thrust_n - self.damping * pitch_rate_rad_s

    def _on_odometry(self, msg: Odometry) -> None:
        t, _, _ = adapt.state_from_odometry(msg)
        pitch_rate = msg.twist.twist.angular.y  # body axes: the rate about the platform's y axis
        wrench = np.array([self.thrust_n(pitch_rate), 0.0, 0.0, 0.0, 0.0, 0.0])
        self._publisher.publish(adapt.wrench_msg(t, wrench, self.frame_id))


def main(args: list[str] | None = None) -> int:
    """``fowt-sim controller [--ros-args ...]``."""
    logging.basicConfig(level=logging.INFO)
    init_ros(args)
    try:
        node = ThrustController()
    except ValueError as exc:
        logging.getLogger("fowt_hydro_sim").error(f"fowt-sim controller: {exc}")
        rclpy.try_shutdown()
        return 2
    try:
        while rclpy.ok():  # a timeout: the stop signal (KeyboardInterrupt) is taken between waits
            rclpy.spin_once(node, timeout_sec=0.1)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
    return 0
