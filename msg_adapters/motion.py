"""Platform motion, velocity and acceleration to and from geometry_msgs and nav_msgs.

Motion is [surge, sway, heave, roll, pitch, yaw] of the reference point in `world`;
velocities and accelerations are [v, w] in world axes, except Odometry's twist, which
is in the platform (child frame) axes as ROS specifies.
"""
from __future__ import annotations

import numpy as np
from geometry_msgs.msg import AccelStamped, Point, Pose, PoseStamped, Quaternion, TwistStamped
from nav_msgs.msg import Odometry

from fowt_hydro_sim.frames import euler_from_quaternion, quaternion_from_euler, rotation_matrix, to_body_axes
from msg_adapters._common import components, header, vector, vector3
from msg_adapters.stamps import seconds


def _pose(motion: np.ndarray) -> Pose:
    """Pose of a validated motion vector."""
    x, y, z, w = quaternion_from_euler(motion[3], motion[4], motion[5])
    return Pose(position=Point(x=float(motion[0]), y=float(motion[1]), z=float(motion[2])),
                orientation=Quaternion(x=float(x), y=float(y), z=float(z), w=float(w)))


def _motion(pose: Pose) -> np.ndarray:
    """Motion vector of a Pose."""
    o = pose.orientation
    return np.concatenate([components(pose.position), euler_from_quaternion([o.x, o.y, o.z, o.w])])


def pose_msg(time_s: float, motion, frame_id: str = "world") -> PoseStamped:
    """PoseStamped of the platform reference point."""
    return PoseStamped(header=header(time_s, frame_id), pose=_pose(vector(motion, 6, "motion")))


def motion_from_pose(msg: PoseStamped) -> tuple[float, np.ndarray]:
    """(time, motion) of a PoseStamped."""
    return seconds(msg.header.stamp), _motion(msg.pose)


def twist_msg(time_s: float, velocity, frame_id: str = "world") -> TwistStamped:
    """TwistStamped of a velocity [v, w], axes as given."""
    velocity = vector(velocity, 6, "velocity")
    msg = TwistStamped(header=header(time_s, frame_id))
    msg.twist.linear, msg.twist.angular = vector3(velocity[:3]), vector3(velocity[3:])
    return msg


def velocity_from_twist(msg: TwistStamped) -> tuple[float, np.ndarray]:
    """(time, velocity) of a TwistStamped."""
    return seconds(msg.header.stamp), components(msg.twist.linear, msg.twist.angular)


def accel_msg(time_s: float, acceleration, frame_id: str = "world") -> AccelStamped:
    """AccelStamped of an acceleration [a, alpha], axes as given."""
    acceleration = vector(acceleration, 6, "acceleration")
    msg = AccelStamped(header=header(time_s, frame_id))
    msg.accel.linear, msg.accel.angular = vector3(acceleration[:3]), vector3(acceleration[3:])
    return msg


def acceleration_from_accel(msg: AccelStamped) -> tuple[float, np.ndarray]:
    """(time, acceleration) of an AccelStamped."""
    return seconds(msg.header.stamp), components(msg.accel.linear, msg.accel.angular)


def odometry_msg(time_s: float, motion, velocity, frame_id: str = "world",
                 child_frame_id: str = "platform") -> Odometry:
    """Odometry: pose in `frame_id`, twist in the platform axes (R^T v, R^T w); zero covariances."""
    motion = vector(motion, 6, "motion")
    velocity = vector(velocity, 6, "velocity")
    body = to_body_axes(np.tile(motion[3:], (2, 1)), velocity.reshape(2, 3))  # the batch's formula (cdr)
    msg = Odometry(header=header(time_s, frame_id), child_frame_id=child_frame_id)
    msg.pose.pose = _pose(motion)
    msg.twist.twist.linear = vector3(body[0])
    msg.twist.twist.angular = vector3(body[1])
    return msg


def state_from_odometry(msg: Odometry) -> tuple[float, np.ndarray, np.ndarray]:
    """(time, motion, velocity in world axes) of an Odometry."""
    motion = _motion(msg.pose.pose)
    to_world = rotation_matrix(motion[3], motion[4], motion[5])
    body = components(msg.twist.twist.linear, msg.twist.twist.angular)
    return seconds(msg.header.stamp), motion, np.concatenate([to_world @ body[:3], to_world @ body[3:]])


def body_twist_from_odometry(msg: Odometry) -> tuple[float, np.ndarray]:
    """(time, [v, omega] in the platform's body axes) of an Odometry (its twist's own axes)."""
    return seconds(msg.header.stamp), components(msg.twist.twist.linear, msg.twist.twist.angular)
