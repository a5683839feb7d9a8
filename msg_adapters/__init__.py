"""Conversions between the model's arrays (see fowt_hydro_sim.rigid_body) and ROS 2 messages."""
from msg_adapters.motion import (accel_msg, acceleration_from_accel, motion_from_pose, odometry_msg,
                                 pose_msg, state_from_odometry, twist_msg, velocity_from_twist)
from msg_adapters.stamps import clock_msg, seconds, stamp
from msg_adapters.waves import elevation_from_msg, elevation_msg
from msg_adapters.wrench import wrench_from_msg, wrench_msg

__all__ = [
    "accel_msg", "acceleration_from_accel", "clock_msg", "elevation_from_msg", "elevation_msg",
    "motion_from_pose", "odometry_msg", "pose_msg", "seconds", "stamp", "state_from_odometry",
    "twist_msg", "velocity_from_twist", "wrench_from_msg", "wrench_msg",
]
