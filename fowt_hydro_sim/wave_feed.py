"""Wave elevation samples at one point feeding a model's streamed kinematics: the checks
and resampling (``inputs.ElevationResampler``), the causal filter bank
(``wave_stream.ElevationStream``) and the model's wave ring, in one place shared by the
node (topic and bag sources) and offline runs (``run_with_elevation``)."""
from __future__ import annotations

import math
from collections import deque
from typing import Iterable

import numpy as np

from .inputs import ElevationResampler
from .model import PlatformModel, RunResult
from .wave_stream import ElevationStream

RING_MARGIN_S = 60.0  # the ring holds the kernel's span and this much more


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

    @property
    def pending(self) -> bool:
        """Resampled samples wait to be streamed."""
        return bool(self._grid)

    def accept(self, time_s: float, x_m: float, y_m: float, elevation_m: float, frame_id: str) -> int:
        """Check and queue one sample (InputError if refused); returns the grid samples it made."""
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
