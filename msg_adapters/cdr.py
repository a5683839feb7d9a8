"""The node's output messages serialised straight to CDR bytes (XCDR1, little endian, as
rclpy's ``serialize_message``), for ``Publisher.publish(bytes)`` and for bag writers.

Building an rclpy message in Python and converting it costs about 40 us; packing the same
bytes with ``struct`` costs a few, and a batch's messages built as arrays (``output_blocks``:
each topic's messages are a template with the stamps and values written in as columns)
about 0.2 us each. The layouts are those of the message definitions: a
Header (int32 sec, uint32 nanosec, string frame_id) then float64 fields aligned to 8 bytes
from the end of the 4-byte encapsulation header. ``test_msg_adapters`` checks every
function byte for byte against ``serialize_message`` of the message-building adapters.
"""
from __future__ import annotations

import struct
from functools import lru_cache

import numpy as np

from fowt_hydro_sim.frames import quaternion_from_euler, to_body_axes
from msg_adapters.sim_time import NS_PER_S, nanoseconds_array, stamp_parts

ENCAPSULATION = b"\x00\x01\x00\x00"  # CDR, little endian
_ZERO_COVARIANCE = struct.pack("<36d", *([0.0] * 36))
_DOUBLES = {n: struct.Struct(f"<{n}d") for n in (3, 6, 7)}
_STAMP = np.dtype([("sec", "<i4"), ("nanosec", "<u4")])


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
    return _poses(np.asarray(motion, dtype=float)[None, :])[0].tolist()


def _poses(motion: np.ndarray) -> np.ndarray:
    """Position and quaternion (n, 7) of each row of motions (n, 6)."""
    return np.hstack([motion[:, :3], quaternion_from_euler(motion[:, 3], motion[:, 4], motion[:, 5])])


def _body_twists(motion: np.ndarray, velocity: np.ndarray) -> np.ndarray:
    """World-axes velocities (n, 6) in the body axes (as Odometry's twist)."""
    angles = motion[:, 3:]
    return np.hstack([to_body_axes(angles, velocity[:, :3]), to_body_axes(angles, velocity[:, 3:])])


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
    return _odometry(struct.pack("<iI", *stamp_parts(time_s)), frame_id, child_frame_id,
                     _poses(motion)[0].tolist(), _body_twists(motion, velocity)[0].tolist())


def stamps(time_s: np.ndarray) -> np.ndarray:
    """The stamp bytes of each time (n, 8): int32 sec and uint32 nanosec, little endian,
    rounded to the nearest ns (as ``stamp_parts``)."""
    sec, nanosec = np.divmod(nanoseconds_array(time_s), NS_PER_S)
    out = np.empty(len(sec), dtype=_STAMP)
    out["sec"], out["nanosec"] = sec, nanosec
    return out.view(np.uint8).reshape(-1, 8)


def block(template: bytes, stamp_bytes: np.ndarray, fields: list[tuple[int, np.ndarray]]) -> np.ndarray:
    """A message per row (n, len(template)) uint8: the template (a message of its type and
    frame ids), with the stamp at byte 4 and each (offset, values (n, k)) as float64 fields."""
    out = np.empty((len(stamp_bytes), len(template)), dtype=np.uint8)
    out[:] = np.frombuffer(template, dtype=np.uint8)
    out[:, 4:12] = stamp_bytes
    for offset, values in fields:
        values = np.ascontiguousarray(values, dtype="<f8")
        out[:, offset:offset + 8 * values.shape[1]] = values.view(np.uint8).reshape(len(values), -1)
    return out


def messages(rows: np.ndarray) -> list[bytes]:
    """The messages of a block (n, length) as bytes, one per row."""
    data, length = rows.tobytes(), rows.shape[1]
    return [data[i:i + length] for i in range(0, len(data), length)]


@lru_cache(maxsize=16)
def _templates(frame_id: str, child_frame_id: str) -> tuple[bytes, ...]:
    """Clock, Odometry, PoseStamped, six-value and PointStamped messages at t = 0, all zero."""
    zeros = np.zeros(6)
    return (clock(0.0), odometry(0.0, zeros, zeros, frame_id, child_frame_id), pose(0.0, zeros, frame_id),
            six(0.0, zeros, frame_id), point(0.0, 0.0, 0.0, 0.0, frame_id))


def output_blocks(time_s: np.ndarray, motion: np.ndarray, velocity: np.ndarray, acceleration: np.ndarray,
                  loads: np.ndarray, total: np.ndarray, elevation_m: np.ndarray, frame_id: str,
                  child_frame_id: str) -> list[np.ndarray]:
    """The node's outputs for a batch of rows, one block (n, length) per topic in
    ``topics.outputs`` order (clock, odom, pose, twist, accel, total, each load of ``loads``
    (n, k, 6), elevation_used): every message built by array operations over the batch."""
    clock_t, odometry_t, pose_t, six_t, point_t = _templates(frame_id, child_frame_id)
    motion = np.asarray(motion, dtype=float)
    stamp_bytes, poses, twists = stamps(time_s), _poses(motion), _body_twists(motion, velocity)
    odometry_pose = len(odometry_t) - 8 * (7 + 36 + 6 + 36)
    elevation = np.zeros((len(stamp_bytes), 3))
    elevation[:, 2] = elevation_m
    wrench = len(six_t) - 48
    return [block(clock_t, stamp_bytes, []),
            block(odometry_t, stamp_bytes, [(odometry_pose, poses), (odometry_pose + 8 * (7 + 36), twists)]),
            block(pose_t, stamp_bytes, [(len(pose_t) - 56, poses)]),
            block(six_t, stamp_bytes, [(wrench, velocity)]), block(six_t, stamp_bytes, [(wrench, acceleration)]),
            block(six_t, stamp_bytes, [(wrench, total)]),
            *(block(six_t, stamp_bytes, [(wrench, loads[:, k])]) for k in range(loads.shape[1])),
            block(point_t, stamp_bytes, [(len(point_t) - 24, elevation)])]


def tension_blocks(time_s: np.ndarray, tensions: np.ndarray, frame_id: str) -> list[np.ndarray]:
    """The mooring lines' tension messages, one block per line (``topics.tension_topic``):
    Vector3Stamped, x the fairlead and y the anchor tension of ``tensions`` (n, lines, 2) [N]
    (Vector3Stamped and PointStamped share one layout: header and three float64)."""
    point_t = _templates(frame_id, "")[4]
    values = np.zeros((len(time_s), 3))
    stamp_bytes, out = stamps(time_s), []
    for line in range(tensions.shape[1]):
        values[:, 0:2] = tensions[:, line]
        out.append(block(point_t, stamp_bytes, [(len(point_t) - 24, values)]))
    return out


def outputs(time_s: np.ndarray, motion: np.ndarray, velocity: np.ndarray, acceleration: np.ndarray,
            loads: np.ndarray, total: np.ndarray, elevation_m: np.ndarray, frame_id: str,
            child_frame_id: str) -> list[list[bytes]]:
    """``output_blocks`` as bytes: each row's messages in ``topics.outputs`` order."""
    blocks = output_blocks(time_s, motion, velocity, acceleration, loads, total, elevation_m, frame_id,
                           child_frame_id)
    return [list(row) for row in zip(*map(messages, blocks))]


# ---------------------------------------------------------------------- decoding
# Every contract type ends in float64 fields after its strings; Clock has none.
TRAILING_DOUBLES = {"rosgraph_msgs/msg/Clock": 0, "geometry_msgs/msg/PointStamped": 3,
                    "geometry_msgs/msg/PoseStamped": 7, "geometry_msgs/msg/TwistStamped": 6,
                    "geometry_msgs/msg/AccelStamped": 6, "geometry_msgs/msg/WrenchStamped": 6,
                    "geometry_msgs/msg/Vector3Stamped": 3,
                    "nav_msgs/msg/Odometry": 85}


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
