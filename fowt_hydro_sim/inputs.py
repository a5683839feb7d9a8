"""Checks of the node's inputs, without ROS: wave elevation samples (resampled onto the
stream's uniform grid) and external wrenches. Each refusal is a message naming the problem;
the caller logs it and keeps the last good input."""
from __future__ import annotations

import math

import numpy as np

from .model import WRENCH_FRAMES

MAX_FORCE_N = 1e9  # 100,000 t: an absurd load on a 14,000 t platform
MAX_MOMENT_NM = 1e11
MAX_AHEAD_S = 3600.0  # elevation samples further ahead of the simulation are refused


class InputError(ValueError):
    """An input message the node refuses (the message says why)."""


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


class ElevationResampler:
    """Checks elevation samples from one measurement point and turns them into a uniform
    series every ``sample_dt_s`` (linear interpolation between accepted samples)."""

    def __init__(self, x_m: float, y_m: float, frame_id: str, sample_dt_s: float, tolerance_m: float = 1.0):
        self.x_m, self.y_m, self.frame_id = x_m, y_m, frame_id
        self.sample_dt_s, self.tolerance_m = sample_dt_s, tolerance_m
        self.last: tuple[float, float] | None = None  # last accepted (time, elevation)
        self.next_index = 0  # the next grid sample: index * sample_dt_s
        self.gap_s = 0.0  # time since the previous accepted sample

    def accept(self, time_s: float, x_m: float, y_m: float, elevation_m: float, frame_id: str,
               now_s: float) -> list[tuple[float, float]]:
        """Grid samples (time, elevation) made available by this sample, or InputError."""
        if not math.isfinite(elevation_m) or not math.isfinite(time_s):
            raise InputError(f"wave elevation: non-finite sample {elevation_m} m at t = {time_s} s")
        if frame_id != self.frame_id:
            raise InputError(f"wave elevation: frame_id {frame_id!r}, expected {self.frame_id!r}")
        if math.hypot(x_m - self.x_m, y_m - self.y_m) > self.tolerance_m:
            raise InputError(f"wave elevation: measured at ({x_m:g}, {y_m:g}) m, expected ({self.x_m:g}, "
                             f"{self.y_m:g}) m (the wave_point_xy parameter)")
        if self.last is not None and time_s <= self.last[0]:
            kind = "duplicated" if time_s == self.last[0] else "out of order"
            raise InputError(f"wave elevation: {kind} sample at t = {time_s:.3f} s (last {self.last[0]:.3f} s)")
        if time_s > now_s + MAX_AHEAD_S:
            raise InputError(f"wave elevation: sample at t = {time_s:.3f} s is more than {MAX_AHEAD_S:g} s "
                             f"ahead of the simulation ({now_s:.3f} s)")
        self.gap_s = 0.0 if self.last is None else time_s - self.last[0]
        out = []
        if self.last is None:
            self.next_index = max(self.next_index, math.ceil(time_s / self.sample_dt_s - 1e-9))
        else:
            t0, e0 = self.last
            while self.next_index * self.sample_dt_s <= time_s + 1e-9:
                t = self.next_index * self.sample_dt_s
                out.append((t, e0 + (elevation_m - e0) * (t - t0) / (time_s - t0)))
                self.next_index += 1
        if self.last is None and abs(self.next_index * self.sample_dt_s - time_s) < 1e-9:
            out.append((time_s, elevation_m))
            self.next_index += 1
        self.last = (time_s, elevation_m)
        return out

    def fill_still_water(self, until_s: float) -> list[tuple[float, float]]:
        """Zero-elevation grid samples up to ``until_s`` (the topic has stopped)."""
        out = []
        while self.next_index * self.sample_dt_s <= until_s + 1e-9:
            out.append((self.next_index * self.sample_dt_s, 0.0))
            self.next_index += 1
        if out:
            self.last = (out[-1][0], 0.0)
        return out
