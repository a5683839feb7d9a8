"""Simulation time (float seconds) to and from builtin_interfaces/Time and rosgraph_msgs/Clock."""
from __future__ import annotations

from builtin_interfaces.msg import Time
from rosgraph_msgs.msg import Clock

from msg_adapters.sim_time import stamp_parts


def stamp(time_s: float) -> Time:
    """Time message for a simulation time in seconds, rounded to the nearest nanosecond."""
    sec, nanosec = stamp_parts(time_s)
    return Time(sec=sec, nanosec=nanosec)


def seconds(msg: Time) -> float:
    """Simulation time in seconds of a Time message."""
    return msg.sec + msg.nanosec / 1e9


def clock_msg(time_s: float) -> Clock:
    """Clock message for a simulation time in seconds."""
    return Clock(clock=stamp(time_s))
