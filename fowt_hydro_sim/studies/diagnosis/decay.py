"""Free decays as diagnosis runs: the platform released from an offset in calm water, its
oscillation in that DOF measured half-cycle by half-cycle, and the model's against the
measured one as two gap cells (``gap.DECAY_METRICS``):

- ``decay_period``: the half-periods' error, sum (tau_model - tau_measured) / sum tau_measured;
- ``decay_damping``: the damping ratio's error, from the log decrement of successive
  peak-to-trough heights H_k, zeta_k = ln(H_k / H_{k+1}) / pi, as
  sum (zeta_model - zeta_measured) / sum zeta_measured.

Heights and half-periods do not depend on where the equilibrium lies, so the two records
need not share it. The samples of each half-cycle give a Student-t interval, as a wave run's
blocks do. Half-cycles are counted while the measured height stays above ``END_SHARE`` of
the first (the noise and the last small cycles say little), at most ``MAX_HALF_CYCLES``.

Wave runs tell a slow-drift force and a drag (or any damping) apart only by the mean offset:
the low-frequency STD fixes drift^2 / damping. A decay moves with the damping and not with
the drift: the diagnosis then reads the two apart.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.model import DOF_NAMES, PlatformModel
from fowt_hydro_sim.studies.diagnosis.gap import Gap, GapSettings, mean_interval
from fowt_hydro_sim.studies.replay import OUTPUT_INTERVAL_S, MeasuredRun, Variant

END_SHARE = 0.2  # half-cycles counted while the measured peak-to-trough height exceeds this share of the first
MAX_HALF_CYCLES = 16
MIN_HALF_CYCLES = 4  # three damping samples at least
HYSTERESIS_SHARE = 0.05  # a crossing counts once the signal is this share of the largest deviation beyond the centre
RELEASE_SHARE = 0.95  # the release's half-cycle: the first to come this close to the largest deviation


def release_index(x: np.ndarray) -> tuple[int, float]:
    """A decay record's release, the largest deviation from the record's mean in the first
    half-cycle that comes within RELEASE_SHARE of the record's largest (the end of a hold,
    or the record's start), and the hysteresis band of its crossings."""
    deviation = x - x.mean()
    largest = float(np.max(np.abs(deviation)))
    first = int(np.argmax(np.abs(deviation) >= RELEASE_SHARE * largest))
    band = HYSTERESIS_SHARE * largest
    sign = 1.0 if deviation[first] > 0 else -1.0
    crossed = np.flatnonzero(sign * deviation[first:] < -band)
    end = first + (int(crossed[0]) if crossed.size else deviation.size - first)
    return first + int(np.argmax(sign * deviation[first:end])), band


def extrema(time_s: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The alternating extrema of a decay record from its release (``release_index``): one
    per complete half-cycle, each refined by a parabola through its neighbours; times and
    values."""
    x = np.asarray(x, dtype=float)
    deviation = x - x.mean()
    start, band = release_index(x)
    sign = 1.0 if deviation[start] > 0 else -1.0
    indices, best = [], start
    for i in range(start, x.size):
        if sign * deviation[i] > sign * deviation[best]:
            best = i
        if sign * deviation[i] < -band:  # crossed to the other side: the half-cycle's extremum is known
            indices.append(best)
            sign, best = -sign, i
    times, values = [], []
    for i in indices:
        t, v = float(time_s[i]), float(x[i])
        if 0 < i < x.size - 1 and i != start:  # (the release may follow a hold: no parabola there)
            y0, y1, y2 = x[i - 1:i + 2]
            curvature = y0 - 2.0 * y1 + y2
            if curvature != 0.0:
                shift = float(np.clip(0.5 * (y0 - y2) / curvature, -0.5, 0.5))
                t += shift * float(time_s[i + 1] - time_s[i])
                v = y1 - 0.25 * (y0 - y2) * shift
        times.append(t)
        values.append(v)
    return np.array(times), np.array(values)


def half_cycles(time_s: np.ndarray, x: np.ndarray, count: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Half-periods tau_k and damping ratios zeta_k of a decay's first ``count`` half-cycles
    (default: while the peak-to-trough height exceeds END_SHARE of the first, at most
    MAX_HALF_CYCLES): ``count`` heights give ``count - 1`` damping ratios, and as many
    half-periods, counted from the first extremum after the release (a record that holds the
    platform before releasing it does not lengthen the first)."""
    t, v = extrema(time_s, x)
    heights = np.abs(np.diff(v))
    if count is None:
        above = heights >= END_SHARE * heights[0] if heights.size else heights.astype(bool)
        count = min(int(np.argmin(above)) if not above.all() else above.size, MAX_HALF_CYCLES)
    count = min(count, heights.size)
    tau = np.diff(t[1:])[:count - 1] if count > 1 else np.zeros(0)
    zeta = np.log(heights[:count - 1] / heights[1:count]) / math.pi if count > 1 else np.zeros(0)
    return tau, zeta


def release(time_s: np.ndarray, motion: np.ndarray, dof: str) -> tuple[float, np.ndarray]:
    """The time of a decay's release (``release_index``) and the 6-DOF pose there (the mean
    of the three samples about it)."""
    i = int(np.clip(release_index(np.asarray(motion[:, DOF_NAMES.index(dof)], dtype=float))[0], 1, len(time_s) - 2))
    return float(time_s[i]), motion[i - 1:i + 2].mean(axis=0)


def check_decay(name: str, time_s: np.ndarray, motion: np.ndarray, dof: str) -> None:
    """InputError naming a decay run that cannot be analysed: too few half-cycles above END_SHARE."""
    if dof not in DOF_NAMES:
        raise InputError(f"decay {name}: unknown DOF {dof!r} (known: {', '.join(DOF_NAMES)})")
    tau, _ = half_cycles(time_s, motion[:, DOF_NAMES.index(dof)])
    if tau.size + 1 < MIN_HALF_CYCLES:
        raise InputError(f"decay {name}: {tau.size + 1} half-cycles of {dof} above {END_SHARE:.0%} of the first "
                         f"height; the diagnosis needs {MIN_HALF_CYCLES}")


def decay_gap(name: str, measured: tuple[np.ndarray, np.ndarray], model: tuple[np.ndarray, np.ndarray], dof: str,
              settings: GapSettings) -> Gap:
    """The decay cells of a model's decay (time, motion (n, 6)) against a measured one in
    ``dof``; every other cell not judged."""
    j = DOF_NAMES.index(dof)
    tau_m, zeta_m = half_cycles(measured[0], measured[1][:, j])
    tau_s, zeta_s = half_cycles(model[0], model[1][:, j], tau_m.size + 1)
    n = min(tau_m.size, tau_s.size)
    rows = {}
    for metric, m, s in (("decay_period", tau_m[:n], tau_s[:n]), ("decay_damping", zeta_m[:n], zeta_s[:n])):
        scale = float(np.mean(m)) if m.size else 0.0
        if m.size >= 2 and scale > 0:
            centre, half = mean_interval((s - m) / scale, settings.confidence)
            rows[metric] = (centre, centre - half, centre + half)
        else:  # no cycles to compare (an overdamped model): as far off as a decay can be, not significant
            rows[metric] = (-1.0 if metric == "decay_period" else 1.0, -math.inf, math.inf)
    cells = settings.cells()
    covers = settings.covered(dof)
    value, low, high = (np.array([rows[metric][k] if c else 0.0 for (_, metric), c in zip(cells, covers)])
                        for k in range(3))
    tolerance = np.array([settings.tolerance(metric) if c else np.inf for (_, metric), c in zip(cells, covers)])
    return Gap(name, value, low, high, tolerance, covers, dof)


def replay_decay(variant: Variant, run: MeasuredRun, dt_s: float = 0.05) -> tuple[np.ndarray, np.ndarray]:
    """A decay run replayed: the variant released at rest from the run's pose at its release
    (``release``), in calm water and without the variant's load series (waves' loads, a
    rotor's: a decay is made with the rotor parked), until the run's last motion sample;
    time on the run's clock and 6-DOF motion."""
    start_s, pose = release(run.motion_time_s, run.motion, run.decay_dof)
    extension = replace(variant.extension, force_n=np.zeros((4, 6)))
    model = PlatformModel(variant.platform, None, dt_s=dt_s, drag_model=variant.drag_model, extension=extension,
                          options=variant.options)
    model.reset(motion=pose)
    result = model.run(float(run.motion_time_s[-1]) - start_s, output_interval_s=OUTPUT_INTERVAL_S)
    return result.time_s + start_s, result.motion
