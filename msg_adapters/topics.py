"""The topic contract (shared/spec/ros_interface.md): names and message types, as data."""
from __future__ import annotations

CLOCK = "rosgraph_msgs/msg/Clock"
ODOMETRY = "nav_msgs/msg/Odometry"
POINT_STAMPED = "geometry_msgs/msg/PointStamped"
POSE_STAMPED = "geometry_msgs/msg/PoseStamped"
TWIST_STAMPED = "geometry_msgs/msg/TwistStamped"
ACCEL_STAMPED = "geometry_msgs/msg/AccelStamped"
WRENCH_STAMPED = "geometry_msgs/msg/WrenchStamped"

ELEVATION = "/waves/elevation"
EXTERNAL_WRENCH = "/platform/external_wrench"
POSE = "/platform/pose"
INPUTS = {ELEVATION: POINT_STAMPED, EXTERNAL_WRENCH: WRENCH_STAMPED}
TOTAL_OF = ("drag", "inertia", "hydrostatic", "mooring", "external")  # summed into /platform/loads/total
LOADS = ("drag", "inertia", "added_mass", "hydrostatic", "mooring", "gravity", "external")  # one topic each
# the node's outputs by short name: (topic, type)
OUTPUTS = {
    "clock": ("/clock", CLOCK),
    "odom": ("/platform/odom", ODOMETRY),
    "pose": (POSE, POSE_STAMPED),
    "twist": ("/platform/twist", TWIST_STAMPED),
    "accel": ("/platform/accel", ACCEL_STAMPED),
    "total": ("/platform/loads/total", WRENCH_STAMPED),
    **{name: (f"/platform/loads/{name}", WRENCH_STAMPED) for name in LOADS},
    "elevation_used": ("/waves/elevation_used", POINT_STAMPED),
}
TYPES = {**INPUTS, **dict(OUTPUTS.values())}  # every contract topic's type


def type_name(message_class: type) -> str:
    """'nav_msgs/msg/Odometry' of a generated rclpy message class."""
    return f"{message_class.__module__.split('.')[0]}/msg/{message_class.__name__}"
