"""The external wrench (a controller, a rotor model): held until the next one is set, in
world axes at the reference point, body axes at the reference point or body axes at the
hub point (``frames.WRENCH_FRAMES``). Also the check of a wrench received from outside."""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from fowt_hydro_sim.frames import WRENCH_FRAMES
from fowt_hydro_sim.physics.config import SampleError
from fowt_hydro_sim.physics.jit import step_loop
from fowt_hydro_sim.physics.rigid_body import cross3

MAX_FORCE_N = 1e9  # 100,000 t: an absurd load on a 14,000 t platform
MAX_MOMENT_NM = 1e11


def check_wrench(wrench: np.ndarray, frame_id: str) -> np.ndarray:
    """The wrench as 6 floats, or SampleError: non-finite, absurd, or an unknown frame."""
    wrench = np.asarray(wrench, dtype=float)
    if frame_id not in WRENCH_FRAMES:
        raise SampleError(f"external wrench: unknown frame_id {frame_id!r} (use {', '.join(WRENCH_FRAMES)})")
    if not np.all(np.isfinite(wrench)):
        raise SampleError(f"external wrench: non-finite value in {wrench.tolist()}")
    if np.abs(wrench[:3]).max() > MAX_FORCE_N or np.abs(wrench[3:]).max() > MAX_MOMENT_NM:
        raise SampleError(f"external wrench: absurd value {wrench.tolist()} (limits {MAX_FORCE_N:g} N, "
                         f"{MAX_MOMENT_NM:g} N m)")
    return wrench


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[world wrench (6), body wrench (6), body point of the body wrench (3)]; zero until set."""
    return np.zeros(15), np.zeros((1, 1))


def set_wrench(params: np.ndarray, wrench: np.ndarray, frame: str, hub_point_m) -> None:
    """Write a wrench given in ``frame`` into the component's params, in place."""
    values = [float(v) for v in np.ravel(wrench)]  # (plain floats: a coupled loop's exchange in microseconds)
    if len(values) != 6 or not all(math.isfinite(v) for v in values):
        raise ValueError(f"external wrench: need 6 finite numbers, got {wrench!r}")
    if frame not in WRENCH_FRAMES:
        raise ValueError(f"external wrench: unknown frame {frame!r} ({', '.join(WRENCH_FRAMES)})")
    params[:] = (values + [0.0] * 9 if frame == "world" else
                 [0.0] * 6 + values + (list(hub_point_m) if frame == "hub" else [0.0] * 3))


@step_loop
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    """The world wrench plus the body wrench turned to world axes, its force acting at the
    body point (written out: no temporaries in the step loop)."""
    force, moment, point = _turned(rotation, params, 6), _turned(rotation, params, 9), _turned(rotation, params, 12)
    lever = cross3(point, force)
    for i in range(3):
        out[i] += params[i] + force[i]
        out[3 + i] += params[3 + i] + moment[i] + lever[i]


@njit(cache=True, inline="always")
def _turned(rotation: np.ndarray, params: np.ndarray, k: int) -> tuple[float, float, float]:
    """R params[k:k + 3]: a body-axes vector in world axes."""
    return (rotation[0, 0] * params[k] + rotation[0, 1] * params[k + 1] + rotation[0, 2] * params[k + 2],
            rotation[1, 0] * params[k] + rotation[1, 1] * params[k + 1] + rotation[1, 2] * params[k + 2],
            rotation[2, 0] * params[k] + rotation[2, 1] * params[k + 1] + rotation[2, 2] * params[k + 2])

