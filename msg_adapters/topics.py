"""The topic contract (docs/ros_interface.md): names and message types, as data.

The load topics follow the model's load components: ``/platform/loads/NAME`` for each
published component (the registry is ``fowt_hydro_sim.physics.loads``; callers pass its
names in, so that this package needs no physics) plus ``/platform/loads/total``.
"""
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
LOADS_PREFIX = "/platform/loads/"
TOTAL = "total"  # /platform/loads/total: the sum of the components the registry marks as summed
INPUTS = {ELEVATION: POINT_STAMPED, EXTERNAL_WRENCH: WRENCH_STAMPED}
MOTION = {  # the node's outputs before the loads, by short name: (topic, type)
    "clock": ("/clock", CLOCK),
    "odom": ("/platform/odom", ODOMETRY),
    "pose": (POSE, POSE_STAMPED),
    "twist": ("/platform/twist", TWIST_STAMPED),
    "accel": ("/platform/accel", ACCEL_STAMPED),
}
ELEVATION_USED = ("/waves/elevation_used", POINT_STAMPED)
VECTOR3_STAMPED = "geometry_msgs/msg/Vector3Stamped"
TURBINE = {  # the turbine node's state, by short name: (topic, type); the value in vector.x, SI units
    "rotor_speed": ("/turbine/rotor_speed", VECTOR3_STAMPED),  # rad/s
    "generator_torque": ("/turbine/generator_torque", VECTOR3_STAMPED),  # N m
    "generator_power": ("/turbine/generator_power", VECTOR3_STAMPED),  # W
    "blade_pitch": ("/turbine/blade_pitch", VECTOR3_STAMPED),  # rad
    "wind_speed": ("/turbine/wind_speed", VECTOR3_STAMPED),  # free wind at the hub, m/s
    "relative_wind_speed": ("/turbine/relative_wind_speed", VECTOR3_STAMPED),  # wind minus hub fore-aft velocity, m/s
}
MOORING_PREFIX = "/platform/mooring/"  # /platform/mooring/lineN/tension, N from 1: the lines' tensions


def tension_topic(line: int) -> str:
    """The topic of mooring line ``line``'s tensions (counting from 1): Vector3Stamped,
    ``vector.x`` the fairlead tension, ``vector.y`` the anchor tension [N]."""
    return f"{MOORING_PREFIX}line{line}/tension"


def load_topic(name: str) -> str:
    return LOADS_PREFIX + name


def outputs(load_names: tuple[str, ...]) -> dict[str, tuple[str, str]]:
    """The node's outputs by short name, (topic, type), in publishing order: motion, the
    total, one topic per load component named, the elevation used."""
    return {**MOTION, TOTAL: (load_topic(TOTAL), WRENCH_STAMPED),
            **{name: (load_topic(name), WRENCH_STAMPED) for name in load_names},
            "elevation_used": ELEVATION_USED}


def type_of(topic: str) -> str | None:
    """The contract's type of a topic (any ``/platform/loads/NAME`` is a wrench), or None."""
    if topic.startswith(LOADS_PREFIX):
        return WRENCH_STAMPED
    if topic.startswith(MOORING_PREFIX) and topic.endswith("/tension"):
        return VECTOR3_STAMPED
    known = {**INPUTS, **dict(MOTION.values()), ELEVATION_USED[0]: ELEVATION_USED[1]}
    return known.get(topic)


def type_name(message_class: type) -> str:
    """'nav_msgs/msg/Odometry' of a generated rclpy message class."""
    return f"{message_class.__module__.split('.')[0]}/msg/{message_class.__name__}"


MEANINGS = {  # what each topic of the contract carries (the load topics': the load registry's summaries)
    ELEVATION: "one sample of the wave elevation: `header.stamp` = when it was measured, `point.x`, `point.y` = "
               "where (world frame, must be `wave_point_xy`), `point.z` = elevation [m]; used with "
               "`wave_source:=topic`",
    EXTERNAL_WRENCH: "a load on the platform (rotor thrust from a controller, an aerodynamic model...); "
                     "`header.frame_id` says where it acts: `hub` (platform axes, at the hub point), `platform` "
                     "(platform axes, at the reference point) or `world` (world axes, at the reference point); "
                     "it stays applied until the next message",
    "/clock": "simulation time",
    "/platform/odom": "pose in `world`; twist in `platform` axes (the ROS convention for odometry)",
    POSE: "position and orientation of the reference point in `world`",
    "/platform/twist": "linear and angular velocity, `world` axes",
    "/platform/accel": "linear and angular acceleration, `world` axes",
    ELEVATION_USED[0]: "the elevation the model used at the reference point, whatever the wave source",
    "/turbine/rotor_speed": "rotor speed [rad/s] in `vector.x`",
    "/turbine/generator_torque": "generator torque [N m] in `vector.x`",
    "/turbine/generator_power": "generator power [W] in `vector.x`",
    "/turbine/blade_pitch": "blade pitch [rad] in `vector.x`",
    "/turbine/wind_speed": "free wind speed at the hub [m/s] in `vector.x`",
    "/turbine/relative_wind_speed": "wind speed minus the hub's fore-aft velocity [m/s] in `vector.x`",
}
