"""The external wrench (a controller, a rotor model): held until the next one is set, in
world axes at the reference point, body axes at the reference point or body axes at the
hub point (``frames.WRENCH_FRAMES``). Also the check of a wrench received from outside."""
from __future__ import annotations

import numpy as np
from numba import njit

from fowt_hydro_sim.frames import WRENCH_FRAMES
from fowt_hydro_sim.physics.config import InputError
from fowt_hydro_sim.physics.rigid_body import cross, matvec

MAX_FORCE_N = 1e9  # 100,000 t: an absurd load on a 14,000 t platform
MAX_MOMENT_NM = 1e11


def check_wrench(wrench: np.ndarray, frame_id: str) -> np.ndarray:
    """The wrench as 6 floats, or InputError: non-finite, absurd, or an unknown frame."""
    wrench = np.asarray(wrench, dtype=float)
    if frame_id not in WRENCH_FRAMES:
        raise InputError(f"external wrench: unknown frame_id {frame_id!r} (use {', '.join(WRENCH_FRAMES)})")
    if not np.all(np.isfinite(wrench)):
        raise InputError(f"external wrench: non-finite value in {wrench.tolist()}")
    if np.abs(wrench[:3]).max() > MAX_FORCE_N or np.abs(wrench[3:]).max() > MAX_MOMENT_NM:
        raise InputError(f"external wrench: absurd value {wrench.tolist()} (limits {MAX_FORCE_N:g} N, "
                         f"{MAX_MOMENT_NM:g} N m)")
    return wrench


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[world wrench (6), body wrench (6), body point of the body wrench (3)]; zero until set."""
    return np.zeros(15), np.zeros((1, 1))


def set_wrench(params: np.ndarray, wrench: np.ndarray, frame: str, hub_point_m) -> None:
    """Write a wrench given in ``frame`` into the component's params, in place."""
    wrench = np.asarray(wrench, dtype=float)
    if wrench.shape != (6,) or not np.all(np.isfinite(wrench)):
        raise ValueError(f"external wrench: need 6 finite numbers, got {wrench!r}")
    if frame not in WRENCH_FRAMES:
        raise ValueError(f"external wrench: unknown frame {frame!r} ({', '.join(WRENCH_FRAMES)})")
    params[0:6] = wrench if frame == "world" else 0.0
    params[6:12] = 0.0 if frame == "world" else wrench
    params[12:15] = hub_point_m if frame == "hub" else 0.0


@njit(cache=True)
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    force_body = matvec(rotation, params[6:9])
    out[0:3] += params[0:3] + force_body
    out[3:6] += params[3:6] + matvec(rotation, params[9:12]) + cross(matvec(rotation, params[12:15]), force_body)
