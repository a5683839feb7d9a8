"""Wave elevation samples at one point feeding a model's streamed kinematics: the checks
and resampling (``ElevationResampler``), the causal filter bank (``waves.stream``) and the
model's wave ring, in one place shared by the node (topic and bag sources) and offline
runs (``run_with_elevation``). Each refused sample is an ``SampleError`` naming the
problem; the caller logs it and keeps going."""
from __future__ import annotations

import math
from collections import deque
from collections.abc import Iterable

import numpy as np

from fowt_hydro_sim.physics.config import SampleError
from fowt_hydro_sim.physics.model import PlatformModel, RunResult
from fowt_hydro_sim.physics.waves.stream import ElevationStream

RING_MARGIN_S = 60.0  # the ring holds the kernel's span and this much more
MAX_AHEAD_S = 3600.0  # elevation samples further ahead of the simulation are refused
MAX_ELEVATION_M = 50.0  # beyond any sea (crests of the largest recorded waves are ~20 m): refused


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
        """Grid samples (time, elevation) made available by this sample, or SampleError."""
        if not math.isfinite(elevation_m) or not math.isfinite(time_s):
            raise SampleError(f"wave elevation: non-finite sample {elevation_m} m at t = {time_s} s")
        if abs(elevation_m) > MAX_ELEVATION_M:
            raise SampleError(f"wave elevation: {elevation_m:g} m at t = {time_s:.3f} s is beyond "
                             f"+-{MAX_ELEVATION_M:g} m, not a sea surface")
        if frame_id != self.frame_id:
            raise SampleError(f"wave elevation: frame_id {frame_id!r}, expected {self.frame_id!r}")
        if math.hypot(x_m - self.x_m, y_m - self.y_m) > self.tolerance_m:
            raise SampleError(f"wave elevation: measured at ({x_m:g}, {y_m:g}) m, expected ({self.x_m:g}, "
                             f"{self.y_m:g}) m (the wave_point_xy parameter)")
        if self.last is not None and time_s <= self.last[0]:
            kind = "duplicated" if time_s == self.last[0] else "out of order"
            raise SampleError(f"wave elevation: {kind} sample at t = {time_s:.3f} s (last {self.last[0]:.3f} s)")
        if time_s > now_s + MAX_AHEAD_S:
            raise SampleError(f"wave elevation: sample at t = {time_s:.3f} s is more than {MAX_AHEAD_S:g} s "
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


class WaveFeed:
    """Elevation samples in, streamed kinematics written into ``model`` (which it switches
    to streamed waves); the kinematics lag the samples by ``delay_s``."""

    def __init__(self, model: PlatformModel, point_xy_m: tuple[float, float], frame_id: str,
                 sample_dt_s: float, preview_s: float, heading_deg: float):
        env = model.platform.environment
        self.model = model
        self.stream = ElevationStream(model.geometry.points_m, point_xy_m, heading_deg, env.water_depth_m,
                                      env.gravity_m_s2, env.water_density_kg_m3, sample_dt_s, preview_s,
                                      elevation_points_xy_m=np.zeros((1, 2)))
        span_s = self.stream.n_taps * sample_dt_s + RING_MARGIN_S
        model.use_streamed_waves(sample_dt_s, int(math.ceil(span_s / sample_dt_s)))
        self.resampler = ElevationResampler(*point_xy_m, frame_id, sample_dt_s)
        self._grid: deque[tuple[float, float]] = deque(maxlen=1_000_000)  # resampled, not yet streamed
        self.until_s = -math.inf  # kinematics are written up to this time

    @property
    def delay_s(self) -> float:
        return self.stream.delay_s

    def accept(self, time_s: float, x_m: float, y_m: float, elevation_m: float, frame_id: str) -> int:
        """Check and queue one sample (SampleError if refused); returns the grid samples it made."""
        samples = self.resampler.accept(time_s, x_m, y_m, elevation_m, frame_id, self.model.time_s)
        self._grid.extend(samples)
        return len(samples)

    def fill_still_water(self) -> None:
        """One still-water grid sample (the source has gone quiet)."""
        self._grid.extend(self.resampler.fill_still_water(self.resampler.next_index * self.resampler.sample_dt_s))

    def feed(self, until_s: float) -> bool:
        """Stream queued samples until the kinematics reach ``until_s`` (no further: the
        table is a ring); True once they have."""
        while self._grid and self.until_s < until_s:
            t, eta = self._grid.popleft()
            kinematics = self.stream.push(eta)
            if kinematics is not None:
                self.until_s = t - self.stream.delay_s
                self.model.write_waves(self.until_s, kinematics, float(self.stream.elevation_m[0]))
        return self.until_s >= until_s

    def needed_until(self, duration_s: float) -> float:
        """How far the kinematics must reach to step ``duration_s`` from the model's time."""
        return self.model.time_s + duration_s + 3 * self.resampler.sample_dt_s


def run_with_elevation(model: PlatformModel, samples: Iterable[tuple[float, float, float, float, str]],
                       point_xy_m: tuple[float, float], frame_id: str, sample_dt_s: float, preview_s: float,
                       heading_deg: float, duration_s: float, output_interval_s: float,
                       chunk_s: float = 1.0) -> RunResult:
    """Offline run driven by elevation samples (time, x, y, elevation, frame), exactly as
    the node streams them: ``chunk_s`` at a time, while the samples last."""
    feed = WaveFeed(model, point_xy_m, frame_id, sample_dt_s, preview_s, heading_deg)
    samples = iter(samples)
    results = []
    while model.time_s < duration_s - 1e-9:
        step_s = min(chunk_s, duration_s - model.time_s)
        while not feed.feed(feed.needed_until(step_s)):
            sample = next(samples, None)
            if sample is None:
                return RunResult.joined(results)
            feed.accept(*sample)
        results.append(model.run(step_s, output_interval_s=output_interval_s))
    return RunResult.joined(results)
