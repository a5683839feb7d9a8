"""Rigid-body kinematics and inertia about the platform reference point, compiled for the
kernel.

Orientation as in ``fowt_hydro_sim.frames`` (R = Rz(yaw) Ry(pitch) Rx(roll), body axes to
world axes). Velocities are in world axes: v of the reference point, w the angular
velocity.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from fowt_hydro_sim import frames
from fowt_hydro_sim.physics.jit import copy_into, step_loop

rotation_matrix = njit(cache=True)(frames.rotation_matrix)


@step_loop
def rotation_into(roll: float, pitch: float, yaw: float, out: np.ndarray) -> None:
    """``rotation_matrix`` into ``out`` (3, 3)."""
    cr, sr = np.cos(roll), np.sin(roll)
    cp, sp = np.cos(pitch), np.sin(pitch)
    cy, sy = np.cos(yaw), np.sin(yaw)
    out[0, 0], out[0, 1], out[0, 2] = cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr
    out[1, 0], out[1, 1], out[1, 2] = sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr
    out[2, 0], out[2, 1], out[2, 2] = -sp, cp * sr, cp * cr


@step_loop
def euler_rates(roll: float, pitch: float, yaw: float, omega: np.ndarray, out: np.ndarray) -> None:
    """Roll, pitch, yaw rates for a world-axes angular velocity, into ``out`` (3,)."""
    cy, sy = np.cos(yaw), np.sin(yaw)
    cp, sp = np.cos(pitch), np.sin(pitch)
    roll_rate = (cy * omega[0] + sy * omega[1]) / cp
    out[0] = roll_rate
    out[1] = -sy * omega[0] + cy * omega[1]
    out[2] = omega[2] + sp * roll_rate


@njit(cache=True, inline="always")
def to_body(rotation: np.ndarray, x: float, y: float, z: float) -> tuple[float, float, float]:
    """R^T [x, y, z]: world axes to body axes (or to any frame's axes)."""
    return (rotation[0, 0] * x + rotation[1, 0] * y + rotation[2, 0] * z,
            rotation[0, 1] * x + rotation[1, 1] * y + rotation[2, 1] * z,
            rotation[0, 2] * x + rotation[1, 2] * y + rotation[2, 2] * z)


@njit(cache=True, inline="always")
def cross3(a: tuple, b: tuple) -> tuple[float, float, float]:
    """a x b of two 3-tuples (no array made)."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@njit(cache=True, inline="always")
def rotate_inertia(rotation: np.ndarray, inertia: np.ndarray, out: np.ndarray) -> None:
    """out = R I R^T (3x3), written out (3x3 products are cheaper by hand than through BLAS);
    ``out`` may not be ``inertia``."""
    for i in range(3):
        ri = (rotation[i, 0] * inertia[0, 0] + rotation[i, 1] * inertia[1, 0] + rotation[i, 2] * inertia[2, 0],
              rotation[i, 0] * inertia[0, 1] + rotation[i, 1] * inertia[1, 1] + rotation[i, 2] * inertia[2, 1],
              rotation[i, 0] * inertia[0, 2] + rotation[i, 1] * inertia[1, 2] + rotation[i, 2] * inertia[2, 2])
        for j in range(3):
            out[i, j] = ri[0] * rotation[j, 0] + ri[1] * rotation[j, 1] + ri[2] * rotation[j, 2]


@step_loop
def mass_matrix_and_bias(mass: float, cog_body: np.ndarray, inertia_cog_body: np.ndarray,
                         rotation: np.ndarray, omega: np.ndarray, out: np.ndarray, bias: np.ndarray) -> None:
    """Into ``out`` (6, 6): the mass matrix about the reference point (world axes); into
    ``bias`` (6,): the velocity terms [m w x (w x r_g); w x (I_G w) + m r_g x (w x (w x r_g))]
    that move to the right-hand side."""
    g = (rotation[0, 0] * cog_body[0] + rotation[0, 1] * cog_body[1] + rotation[0, 2] * cog_body[2],
         rotation[1, 0] * cog_body[0] + rotation[1, 1] * cog_body[1] + rotation[1, 2] * cog_body[2],
         rotation[2, 0] * cog_body[0] + rotation[2, 1] * cog_body[1] + rotation[2, 2] * cog_body[2])
    inertia_g = out[3:6, 3:6]  # R I_G R^T first, then the parallel-axis term added in place
    rotate_inertia(rotation, inertia_cog_body, inertia_g)
    s = ((0.0, -g[2], g[1]), (g[2], 0.0, -g[0]), (-g[1], g[0], 0.0))  # skew(r_g)
    w = (omega[0], omega[1], omega[2])
    i_omega = (inertia_g[0, 0] * w[0] + inertia_g[0, 1] * w[1] + inertia_g[0, 2] * w[2],
               inertia_g[1, 0] * w[0] + inertia_g[1, 1] * w[1] + inertia_g[1, 2] * w[2],
               inertia_g[2, 0] * w[0] + inertia_g[2, 1] * w[1] + inertia_g[2, 2] * w[2])
    for i in range(3):
        for j in range(3):
            out[i, j] = mass if i == j else 0.0
            out[i, 3 + j] = -mass * s[i][j]
            out[3 + i, j] = mass * s[i][j]
            out[3 + i, 3 + j] -= mass * (s[i][0] * s[0][j] + s[i][1] * s[1][j] + s[i][2] * s[2][j])
    centripetal = cross3(w, cross3(w, g))
    gyroscopic, offset = cross3(w, i_omega), cross3(g, centripetal)
    for i in range(3):
        bias[i] = mass * centripetal[i]
        bias[3 + i] = gyroscopic[i] + mass * offset[i]


@step_loop
def solve_spd(matrix: np.ndarray, rhs: np.ndarray, low: np.ndarray, x: np.ndarray) -> None:
    """Solve a small symmetric positive-definite system by Cholesky into ``x`` (no LAPACK
    call); ``low`` (n, n) is scratch for the factor."""
    n = rhs.size
    for i in range(n):
        for j in range(i + 1):
            acc = matrix[i, j]
            for k in range(j):
                acc -= low[i, k] * low[j, k]
            low[i, j] = np.sqrt(acc) if i == j else acc / low[j, j]
    copy_into(rhs, x)
    for i in range(n):
        for k in range(i):
            x[i] -= low[i, k] * x[k]
        x[i] /= low[i, i]
    for i in range(n - 1, -1, -1):
        for k in range(i + 1, n):
            x[i] -= low[k, i] * x[k]
        x[i] /= low[i, i]

