"""Conversions between the model's arrays (see fowt_hydro_sim.frames) and ROS 2 messages.

The message-building adapters need the ROS message packages and are imported on first
use; ``cdr`` (bytes to and from arrays) and ``topics`` (the contract) need no ROS, so the
offline tools run without it.
"""
from importlib import import_module

_MODULE_OF = {
    "accel_msg": "motion", "acceleration_from_accel": "motion", "motion_from_pose": "motion",
    "body_twist_from_odometry": "motion", "odometry_msg": "motion", "quantity_msg": "turbine", "pose_msg": "motion",
    "state_from_odometry": "motion", "twist_msg": "motion",
    "velocity_from_twist": "motion", "clock_msg": "stamps", "seconds": "stamps", "stamp": "stamps",
    "elevation_from_msg": "waves", "elevation_msg": "waves", "wrench_from_msg": "wrench", "wrench_msg": "wrench",
}
__all__ = sorted(_MODULE_OF)


def __getattr__(name: str):
    if name not in _MODULE_OF:
        raise AttributeError(f"module 'msg_adapters' has no attribute {name!r}")
    return getattr(import_module(f"msg_adapters.{_MODULE_OF[name]}"), name)
