"""Helpers shared by the adapters: shape validation and message fields."""
from __future__ import annotations

import numpy as np
from geometry_msgs.msg import Vector3
from std_msgs.msg import Header

from msg_adapters.stamps import stamp


def vector(value, size: int, name: str) -> np.ndarray:
    """`value` as a float array of shape (size,), or ValueError naming `name`."""
    out = np.asarray(value, dtype=float)
    if out.shape != (size,):
        raise ValueError(f"{name} must have shape ({size},), got {out.shape}")
    return out


def header(time_s: float, frame_id: str) -> Header:
    """Header with the stamp of `time_s` and `frame_id`."""
    return Header(stamp=stamp(time_s), frame_id=frame_id)


def vector3(values: np.ndarray) -> Vector3:
    """Vector3 of the first three values."""
    return Vector3(x=float(values[0]), y=float(values[1]), z=float(values[2]))


def components(*vectors) -> np.ndarray:
    """Concatenated x, y, z of Vector3 or Point messages."""
    return np.array([c for v in vectors for c in (v.x, v.y, v.z)])
