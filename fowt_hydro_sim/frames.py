"""Frames and rotations shared by the physics and the message adapters (NumPy only).

Orientation: roll, pitch, yaw as x-y-z Euler angles, R = Rz(yaw) Ry(pitch) Rx(roll), body
axes to world axes (OpenFAST's and HydroDyn's convention). Quaternions are (x, y, z, w)
as in ROS messages. ``rotation_matrix`` is plain NumPy that numba also compiles: the
physics kernel uses the same formula (``physics.rigid_body``).
"""
from __future__ import annotations

import numpy as np

# frame ids an external wrench may be given in: world axes at the reference point, body axes
# at the reference point, body axes at the hub point (the ROS contract's frame ids)
WRENCH_FRAMES = ("world", "platform", "hub")


def rotation_matrix(roll, pitch, yaw) -> np.ndarray:
    """R (3, 3) of scalar angles; for arrays of angles (n,), R has shape (3, 3, n)."""
    cr, sr = np.cos(roll), np.sin(roll)
    cp, sp = np.cos(pitch), np.sin(pitch)
    cy, sy = np.cos(yaw), np.sin(yaw)
    return np.array([
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ])


def to_body_axes(angles: np.ndarray, vectors: np.ndarray) -> np.ndarray:
    """World-axes vectors (n, 3) in the body axes of orientations (n, 3: roll, pitch, yaw)."""
    angles, vectors = np.asarray(angles, dtype=float), np.asarray(vectors, dtype=float)
    rotations = rotation_matrix(angles[:, 0], angles[:, 1], angles[:, 2])  # (3, 3, n)
    return np.einsum("jin,nj->ni", rotations, vectors)


def angular_velocity_from_euler_rates(angles: np.ndarray, rates: np.ndarray) -> np.ndarray:
    """World-axes angular velocity (n, 3) of roll, pitch, yaw rates (n, 3) at the angles (n, 3):
    w = roll' (cp cy, cp sy, -sp) + pitch' (-sy, cy, 0) + yaw' (0, 0, 1)."""
    roll_rate, pitch_rate, yaw_rate = np.moveaxis(np.asarray(rates, dtype=float), -1, 0)
    _, pitch, yaw = np.moveaxis(np.asarray(angles, dtype=float), -1, 0)
    cp, sp, cy, sy = np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    return np.stack([roll_rate * cp * cy - pitch_rate * sy, roll_rate * cp * sy + pitch_rate * cy,
                     -roll_rate * sp + yaw_rate], axis=-1)


def angular_acceleration_from_euler_rates(angles: np.ndarray, rates: np.ndarray,
                                          rate_derivatives: np.ndarray) -> np.ndarray:
    """World-axes angular acceleration (n, 3): the time derivative of
    ``angular_velocity_from_euler_rates`` for angle rates and their derivatives (n, 3)."""
    _, pitch, yaw = np.moveaxis(np.asarray(angles, dtype=float), -1, 0)
    r, p, y = np.moveaxis(np.asarray(rates, dtype=float), -1, 0)
    rr, pp, yy = np.moveaxis(np.asarray(rate_derivatives, dtype=float), -1, 0)
    cp, sp, cy, sy = np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    return np.stack([rr * cp * cy - r * (sp * cy * p + cp * sy * y) - pp * sy - p * cy * y,
                     rr * cp * sy + r * (cp * cy * y - sp * sy * p) + pp * cy - p * sy * y,
                     -rr * sp - r * cp * p + yy], axis=-1)


def quaternion_from_euler(roll, pitch, yaw) -> np.ndarray:
    """Unit quaternion (x, y, z, w), w >= 0, of R = Rz(yaw) Ry(pitch) Rx(roll); the angles
    may be arrays (of one shape), giving quaternions in the last axis."""
    cr, sr = np.cos(0.5 * np.asarray(roll)), np.sin(0.5 * np.asarray(roll))
    cp, sp = np.cos(0.5 * np.asarray(pitch)), np.sin(0.5 * np.asarray(pitch))
    cy, sy = np.cos(0.5 * np.asarray(yaw)), np.sin(0.5 * np.asarray(yaw))
    q = np.stack([
        sr * cp * cy - cr * sp * sy,
        cr * sp * cy + sr * cp * sy,
        cr * cp * sy - sr * sp * cy,
        cr * cp * cy + sr * sp * sy,
    ], axis=-1)
    return np.where(q[..., 3:] < 0.0, -q, q)


def euler_from_quaternion(q) -> np.ndarray:
    """Roll, pitch, yaw of quaternions (x, y, z, w) in the last axis, normalised first;
    pitch in [-pi/2, pi/2]."""
    q = np.asarray(q, dtype=float)
    if q.ndim == 0 or q.shape[-1] != 4:
        raise ValueError(f"quaternion must have shape (4,) or (n, 4), got {q.shape}")
    if not np.all(np.isfinite(q)):
        raise ValueError(f"quaternion has non-finite components: {q}")
    norm = np.linalg.norm(q, axis=-1, keepdims=True)
    if np.any(norm == 0.0):
        raise ValueError("quaternion is zero and has no orientation")
    x, y, z, w = np.moveaxis(q / norm, -1, 0)
    r20 = 2.0 * (x * z - w * y)
    r21 = 2.0 * (y * z + w * x)
    r22 = 1.0 - 2.0 * (x * x + y * y)
    r10 = 2.0 * (x * y + w * z)
    r00 = 1.0 - 2.0 * (y * y + z * z)
    return np.stack([np.arctan2(r21, r22), np.arctan2(-r20, np.hypot(r21, r22)), np.arctan2(r10, r00)], axis=-1)
