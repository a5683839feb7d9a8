"""Simulation time (float seconds) to and from builtin_interfaces/Time and rosgraph_msgs/Clock."""
from __future__ import annotations

import math

from builtin_interfaces.msg import Time
from rosgraph_msgs.msg import Clock

NS_PER_S = 10**9


def stamp_parts(time_s: float) -> tuple[int, int]:
    """(sec, nanosec) of a simulation time in seconds, rounded to the nearest nanosecond."""
    if not math.isfinite(time_s):
        raise ValueError(f"time must be finite, got {time_s}")
    if time_s < 0.0:
        raise ValueError(f"time must be non-negative for a ROS stamp, got {time_s} s")
    whole = math.floor(time_s)
    ns = whole * NS_PER_S + round((time_s - whole) * 1e9)  # split: t * 1e9 loses ns above ~1e7 s
    return ns // NS_PER_S, ns % NS_PER_S


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
