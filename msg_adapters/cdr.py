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

from fowt_hydro_sim.frames import quaternion_from_euler, to_body_axes
from msg_adapters.sim_time import stamp_parts

ENCAPSULATION = b"\x00\x01\x00\x00"  # CDR, little endian
_ZERO_COVARIANCE = struct.pack("<36d", *([0.0] * 36))
_DOUBLES = {n: struct.Struct(f"<{n}d") for n in (3, 6, 7)}


@lru_cache(maxsize=64)
def _string(text: str, offset: int) -> bytes:
    """A CDR string (uint32 length with the terminating NUL, then the bytes), aligned to 4."""
    data = text.encode() + b"\0"
    return b"\0" * (-offset % 4) + struct.pack("<I", len(data)) + data


def _align8(body: bytes) -> bytes:
    return body + b"\0" * (-len(body) % 8)


def header(time_s: float, frame_id: str) -> bytes:
    """Encapsulation and Header, padded for the float64 fields that follow: shared by every
    stamped message of one time and frame."""
    sec, nanosec = stamp_parts(time_s)
    return ENCAPSULATION + _align8(struct.pack("<iI", sec, nanosec) + _string(frame_id, 8))


def doubles(head: bytes, values) -> bytes:
    """A stamped message of float64 fields: PoseStamped (7: position, quaternion x y z w),
    TwistStamped / AccelStamped / WrenchStamped (6), PointStamped (3)."""
    return head + _DOUBLES[len(values)].pack(*values)


def pose_values(motion) -> list[float]:
    """Position and quaternion (x, y, z, w) of a motion [surge, sway, heave, roll, pitch, yaw]."""
    return _pose_rows(np.asarray(motion, dtype=float)[None, :])[0]


def _pose_rows(motion: np.ndarray) -> list[list[float]]:
    """Position and quaternion of each row of motions (n, 6)."""
    return np.hstack([motion[:, :3], quaternion_from_euler(motion[:, 3], motion[:, 4], motion[:, 5])]).tolist()


def _body_twist_rows(motion: np.ndarray, velocity: np.ndarray) -> list[list[float]]:
    """World-axes velocities (n, 6) in the body axes (as Odometry's twist)."""
    angles = motion[:, 3:]
    return np.hstack([to_body_axes(angles, velocity[:, :3]),
                      to_body_axes(angles, velocity[:, 3:])]).tolist()


def _odometry(stamp: bytes, frame_id: str, child_frame_id: str, pose_row: list, twist_row: list) -> bytes:
    head = stamp + _string(frame_id, 8)
    head += _string(child_frame_id, len(head))
    return (ENCAPSULATION + _align8(head) + _DOUBLES[7].pack(*pose_row) + _ZERO_COVARIANCE
            + _DOUBLES[6].pack(*twist_row) + _ZERO_COVARIANCE)


def clock(time_s: float) -> bytes:
    """rosgraph_msgs/Clock."""
    return ENCAPSULATION + struct.pack("<iI", *stamp_parts(time_s))


def pose(time_s: float, motion, frame_id: str = "world") -> bytes:
    """geometry_msgs/PoseStamped (as ``pose_msg``)."""
    return doubles(header(time_s, frame_id), pose_values(motion))


def six(time_s: float, values, frame_id: str = "world") -> bytes:
    """TwistStamped, AccelStamped or WrenchStamped of six values (as ``twist_msg``,
    ``accel_msg``, ``wrench_msg``: the three share one layout)."""
    return doubles(header(time_s, frame_id), [float(v) for v in values])


def point(time_s: float, x_m: float, y_m: float, z_m: float, frame_id: str = "world") -> bytes:
    """geometry_msgs/PointStamped (as ``elevation_msg``)."""
    return doubles(header(time_s, frame_id), [float(x_m), float(y_m), float(z_m)])


def odometry(time_s: float, motion, velocity, frame_id: str = "world", child_frame_id: str = "platform") -> bytes:
    """nav_msgs/Odometry (as ``odometry_msg``: twist in the platform axes, zero covariances)."""
    motion = np.asarray(motion, dtype=float)[None, :]
    velocity = np.asarray(velocity, dtype=float)[None, :]
    return _odometry(struct.pack("<iI", *stamp_parts(time_s)), frame_id, child_frame_id, _pose_rows(motion)[0],
                     _body_twist_rows(motion, velocity)[0])


def outputs(time_s: np.ndarray, motion: np.ndarray, velocity: np.ndarray, acceleration: np.ndarray,
            loads: np.ndarray, total: np.ndarray, elevation_m: np.ndarray, frame_id: str,
            child_frame_id: str) -> list[list[bytes]]:
    """The node's outputs for each row of a batch, in ``topics.outputs`` order (clock, odom,
    pose, twist, accel, total, each load of ``loads`` (n, k, 6), elevation_used); the
    numerics are vectorised over the batch, leaving one ``struct`` pack per message."""
    poses, twists = _pose_rows(motion), _body_twist_rows(motion, velocity)
    rows = zip(time_s.tolist(), poses, twists, velocity.tolist(), acceleration.tolist(), total.tolist(),
               loads.tolist(), elevation_m.tolist())
    frame = _string(frame_id, 8)
    six, seven, three = _DOUBLES[6].pack, _DOUBLES[7].pack, _DOUBLES[3].pack
    out = []
    for t, pose_row, twist_row, v, a, f, components, eta in rows:
        stamp = struct.pack("<iI", *stamp_parts(t))
        head = ENCAPSULATION + _align8(stamp + frame)
        out.append([ENCAPSULATION + stamp, _odometry(stamp, frame_id, child_frame_id, pose_row, twist_row),
                    head + seven(*pose_row), head + six(*v), head + six(*a), head + six(*f),
                    *(head + six(*c) for c in components), head + three(0.0, 0.0, eta)])
    return out


# ---------------------------------------------------------------------- decoding
# Every contract type ends in float64 fields after its strings; Clock has none.
TRAILING_DOUBLES = {"rosgraph_msgs/msg/Clock": 0, "geometry_msgs/msg/PointStamped": 3,
                    "geometry_msgs/msg/PoseStamped": 7, "geometry_msgs/msg/TwistStamped": 6,
                    "geometry_msgs/msg/AccelStamped": 6, "geometry_msgs/msg/WrenchStamped": 6,
                    "geometry_msgs/msg/Vector3Stamped": 3,
                    "nav_msgs/msg/Odometry": 85}
_STAMP = np.dtype([("sec", "<i4"), ("nanosec", "<u4")])


def frame_id(message: bytes) -> str:
    """The header's frame_id of a stamped message (CDR bytes)."""
    (length,) = struct.unpack_from("<I", message, 12)
    return message[16:16 + length - 1].decode()


def decode_stamped(type_name: str, messages: list[bytes]) -> tuple[np.ndarray, np.ndarray]:
    """Stamps [s] (n,) and trailing float64 fields (n, k) of messages of one contract type,
    vectorised over the messages of each length. ValueError names a type without this
    layout or bytes that are not little-endian CDR of it."""
    if type_name not in TRAILING_DOUBLES:
        raise ValueError(f"type {type_name} is not a stamped contract type ({', '.join(TRAILING_DOUBLES)})")
    k = TRAILING_DOUBLES[type_name]
    time_s, values = np.empty(len(messages)), np.empty((len(messages), k))
    lengths = np.fromiter(map(len, messages), dtype=np.int64, count=len(messages))
    for length in np.unique(lengths):
        rows = np.flatnonzero(lengths == length)
        if length < 12 + 8 * k:
            raise ValueError(f"{type_name}: a message of {length} bytes is too short")
        raw = np.frombuffer(b"".join(messages[i] for i in rows), dtype=np.uint8).reshape(len(rows), length)
        if np.any(raw[:, :2] != np.frombuffer(ENCAPSULATION[:2], dtype=np.uint8)):
            raise ValueError(f"{type_name}: messages are not little-endian CDR")
        stamps = raw[:, 4:12].copy().view(_STAMP)[:, 0]
        time_s[rows] = stamps["sec"] + stamps["nanosec"] * 1e-9
        if k:
            values[rows] = raw[:, length - 8 * k:].copy().view("<f8")
    return time_s, values
