"""The node's output messages serialised straight to CDR bytes (XCDR1, little endian, as
rclpy's ``serialize_message``), for ``Publisher.publish(bytes)`` and for bag writers.

Building an rclpy message in Python and converting it costs about 40 us; packing the same
bytes with ``struct`` costs a few. The layouts are those of the message definitions: a
Header (int32 sec, uint32 nanosec, string frame_id) then float64 fields aligned to 8 bytes
from the end of the 4-byte encapsulation header. ``test_msg_adapters`` checks every
function byte for byte against ``serialize_message`` of the message-building adapters.
"""
from __future__ import annotations

import struct
from functools import lru_cache

import numpy as np

from fowt_hydro_sim.rigid_body import quaternion_from_euler, rotation_matrix
from msg_adapters.stamps import stamp_parts

ENCAPSULATION = b"\x00\x01\x00\x00"  # CDR, little endian
_ZERO_COVARIANCE = struct.pack("<36d", *([0.0] * 36))


@lru_cache(maxsize=64)
def _string(text: str, offset: int) -> bytes:
    """A CDR string (uint32 length with the terminating NUL, then the bytes), aligned to 4."""
    data = text.encode() + b"\0"
    return b"\0" * (-offset % 4) + struct.pack("<I", len(data)) + data


def _align8(body: bytes) -> bytes:
    return body + b"\0" * (-len(body) % 8)


def _header(time_s: float, frame_id: str) -> bytes:
    sec, nanosec = stamp_parts(time_s)
    return struct.pack("<iI", sec, nanosec) + _string(frame_id, 8)


def _stamped(time_s: float, frame_id: str, values) -> bytes:
    """A Header followed by float64 fields (PoseStamped, TwistStamped, WrenchStamped ...)."""
    return ENCAPSULATION + _align8(_header(time_s, frame_id)) + struct.pack(f"<{len(values)}d", *values)


def _pose_values(motion: np.ndarray) -> list[float]:
    x, y, z, roll, pitch, yaw = map(float, motion)
    return [x, y, z, *quaternion_from_euler(roll, pitch, yaw).tolist()]


def clock(time_s: float) -> bytes:
    """rosgraph_msgs/Clock."""
    return ENCAPSULATION + struct.pack("<iI", *stamp_parts(time_s))


def pose(time_s: float, motion: np.ndarray, frame_id: str = "world") -> bytes:
    """geometry_msgs/PoseStamped (as ``pose_msg``)."""
    return _stamped(time_s, frame_id, _pose_values(motion))


def six(time_s: float, values: np.ndarray, frame_id: str = "world") -> bytes:
    """TwistStamped, AccelStamped or WrenchStamped of six values (as ``twist_msg``,
    ``accel_msg``, ``wrench_msg``: the three share one layout)."""
    return _stamped(time_s, frame_id, [float(v) for v in values])


def point(time_s: float, x_m: float, y_m: float, z_m: float, frame_id: str = "world") -> bytes:
    """geometry_msgs/PointStamped (as ``elevation_msg``)."""
    return _stamped(time_s, frame_id, [float(x_m), float(y_m), float(z_m)])


def odometry(time_s: float, motion: np.ndarray, velocity: np.ndarray, frame_id: str = "world",
             child_frame_id: str = "platform") -> bytes:
    """nav_msgs/Odometry (as ``odometry_msg``: twist in the platform axes, zero covariances)."""
    head = _header(time_s, frame_id)
    head += _string(child_frame_id, len(head))
    to_body = rotation_matrix(*map(float, motion[3:6])).T
    twist = np.concatenate([to_body @ velocity[:3], to_body @ velocity[3:]])
    return (ENCAPSULATION + _align8(head) + struct.pack("<7d", *_pose_values(motion)) + _ZERO_COVARIANCE
            + struct.pack("<6d", *map(float, twist)) + _ZERO_COVARIANCE)
