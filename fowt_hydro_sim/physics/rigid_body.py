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

rotation_matrix = njit(cache=True)(frames.rotation_matrix)


@njit(cache=True)
def euler_rates(roll: float, pitch: float, yaw: float, omega: np.ndarray) -> np.ndarray:
    """Roll, pitch, yaw rates for a world-axes angular velocity."""
    cy, sy = np.cos(yaw), np.sin(yaw)
    cp, sp = np.cos(pitch), np.sin(pitch)
    pitch_rate = -sy * omega[0] + cy * omega[1]
    roll_rate = (cy * omega[0] + sy * omega[1]) / cp
    yaw_rate = omega[2] + sp * roll_rate
    return np.array([roll_rate, pitch_rate, yaw_rate])


@njit(cache=True, inline="always")
def cross3(a: tuple, b: tuple) -> tuple[float, float, float]:
    """a x b of two 3-tuples (no array made)."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


@njit(cache=True)
def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


@njit(cache=True)
def matvec(matrix: np.ndarray, x: np.ndarray) -> np.ndarray:
    """matrix @ x written out: numba's ``@`` calls BLAS, whose call costs more than a 3x3 or
    6x6 product (the step made about 25 of them per right-hand side)."""
    out = np.empty(matrix.shape[0])
    for i in range(matrix.shape[0]):
        acc = 0.0
        for j in range(x.size):
            acc += matrix[i, j] * x[j]
        out[i] = acc
    return out


@njit(cache=True)
def rotate_inertia(rotation: np.ndarray, inertia: np.ndarray) -> np.ndarray:
    """R I R^T, written out (3x3 products are cheaper by hand than through BLAS)."""
    tmp = np.zeros((3, 3))
    out = np.zeros((3, 3))
    for i in range(3):
        for j in range(3):
            for k in range(3):
                tmp[i, j] += rotation[i, k] * inertia[k, j]
    for i in range(3):
        for j in range(3):
            for k in range(3):
                out[i, j] += tmp[i, k] * rotation[j, k]
    return out


@njit(cache=True)
def mass_matrix_and_bias(mass: float, cog_body: np.ndarray, inertia_cog_body: np.ndarray,
                         rotation: np.ndarray, omega: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """6x6 mass matrix about the reference point (world axes) and the velocity terms
    [m w x (w x r_g); w x (I_G w) + m r_g x (w x (w x r_g))] that move to the right-hand side."""
    g = (rotation[0, 0] * cog_body[0] + rotation[0, 1] * cog_body[1] + rotation[0, 2] * cog_body[2],
         rotation[1, 0] * cog_body[0] + rotation[1, 1] * cog_body[1] + rotation[1, 2] * cog_body[2],
         rotation[2, 0] * cog_body[0] + rotation[2, 1] * cog_body[1] + rotation[2, 2] * cog_body[2])
    inertia_g = rotate_inertia(rotation, inertia_cog_body)
    s = ((0.0, -g[2], g[1]), (g[2], 0.0, -g[0]), (-g[1], g[0], 0.0))  # skew(r_g)
    out = np.zeros((6, 6))
    for i in range(3):
        out[i, i] = mass
        for j in range(3):
            out[i, 3 + j] = -mass * s[i][j]
            out[3 + i, j] = mass * s[i][j]
            out[3 + i, 3 + j] = inertia_g[i, j] - mass * (s[i][0] * s[0][j] + s[i][1] * s[1][j] + s[i][2] * s[2][j])
    w = (omega[0], omega[1], omega[2])
    centripetal = cross3(w, cross3(w, g))
    i_omega = (inertia_g[0, 0] * w[0] + inertia_g[0, 1] * w[1] + inertia_g[0, 2] * w[2],
               inertia_g[1, 0] * w[0] + inertia_g[1, 1] * w[1] + inertia_g[1, 2] * w[2],
               inertia_g[2, 0] * w[0] + inertia_g[2, 1] * w[1] + inertia_g[2, 2] * w[2])
    gyroscopic, offset = cross3(w, i_omega), cross3(g, centripetal)
    bias = np.empty(6)
    for i in range(3):
        bias[i] = mass * centripetal[i]
        bias[3 + i] = gyroscopic[i] + mass * offset[i]
    return out, bias


@njit(cache=True)
def solve_spd(matrix: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Solve a small symmetric positive-definite system by Cholesky (no LAPACK call)."""
    n = rhs.size
    low = np.zeros((n, n))
    for i in range(n):
        for j in range(i + 1):
            acc = matrix[i, j]
            for k in range(j):
                acc -= low[i, k] * low[j, k]
            low[i, j] = np.sqrt(acc) if i == j else acc / low[j, j]
    x = rhs.copy()
    for i in range(n):
        for k in range(i):
            x[i] -= low[i, k] * x[k]
        x[i] /= low[i, i]
    for i in range(n - 1, -1, -1):
        for k in range(i + 1, n):
            x[i] -= low[k, i] * x[k]
        x[i] /= low[i, i]
    return x

