"""Offline runs of the platform model (``fowt-sim simulate``): waves from a sea state, an
OpenFAST ``.Comp`` file, a measured elevation record or none; the run; its statistics; and
its plain columnar output, ``timeseries.csv`` (one column per channel, SI units in the
names, written part by part as the run advances, so that a long run holds only the
motion and the elevation it needs for its statistics) and ``summary.json`` (configuration
and statistics). A free-decay run (still water,
an initial offset) reports the fitted period and damping ratio of each DOF it displaced."""
from __future__ import annotations

import json
import resource
import time
from collections.abc import Callable, Iterable
from dataclasses import asdict
from pathlib import Path
from typing import NamedTuple

import numpy as np

from fowt_hydro_sim import __version__
from fowt_hydro_sim.physics.config import ConfigError, Platform, RunConfig, SeaState, load_platform
from fowt_hydro_sim.physics.loads import NAMES
from fowt_hydro_sim.physics.model import DOF_NAMES, PlatformModel, RunResult
from fowt_hydro_sim.physics.waves.components import (
    WaveComponents,
    from_elevation_record,
    read_comp_file,
    repeat_period,
    synthesize,
)
from fowt_hydro_sim.studies.psd import BANDS_HZ, MIN_SEGMENTS, TRANSIENT_S, band_stds, default_transient

_AXES = ("fx_n", "fy_n", "fz_n", "mx_nm", "my_nm", "mz_nm")
_MOTION_UNITS = ("m", "m", "m", "rad", "rad", "rad")
DECAY_CYCLES = 5  # free decay fitted over its first cycles: drag damping depends on the amplitude


# ---------------------------------------------------------------------- waves
def sea_state_waves(sea: SeaState, duration_s: float, load_case: str | None = None) -> tuple[WaveComponents, dict]:
    """A sea state's synthesised components (repeating every max(duration, 1 h)) and their description."""
    period = repeat_period(sea, duration_s)
    return synthesize(sea, period), {"source": "sea state", **asdict(sea), "repeat_period_s": period,
                                     "load_case": load_case}


def comp_file_waves(path: Path, direct_sum: bool = False) -> tuple[WaveComponents, dict]:
    """A ``.Comp`` file's components (``direct_sum``: those on no common frequency grid too,
    for prescribed motion) and their description."""
    return read_comp_file(path, direct_sum), {"source": "components", "file": str(path)}


def elevation_record_waves(path: Path, point_xy_m: tuple[float, float], heading_deg: float,
                           platform: Platform) -> tuple[WaveComponents, dict]:
    """Components of a measured elevation record (CSV of time_s, elevation_m) at a point."""
    try:
        record = np.loadtxt(path, delimiter=",", comments="#", ndmin=2)
    except (OSError, ValueError) as exc:
        raise ConfigError(f"{path}: cannot be read as two CSV columns time_s, elevation_m ({exc})") from None
    if record.shape[1] != 2:
        raise ConfigError(f"{path}: expected two columns time_s, elevation_m, got {record.shape[1]}")
    env = platform.environment
    waves = from_elevation_record(record[:, 0], record[:, 1], *point_xy_m, heading_deg, env.water_depth_m,
                                  env.gravity_m_s2)
    return waves, {"source": "elevation record", "file": str(path), "point_m": list(point_xy_m)}


# ---------------------------------------------------------------------- the run
class MotionRecord(NamedTuple):
    """What the statistics and the free-decay fit read of a run (``tensions``: each mooring
    line's fairlead and anchor tension, (n, lines, 2) [N])."""

    time_s: np.ndarray
    motion: np.ndarray
    wave_elevation_m: np.ndarray
    tensions: np.ndarray | None = None


def tension_statistics(record: MotionRecord, transient_s: float) -> dict:
    """Per mooring line and end: mean, std, min and max tension [N] after ``transient_s``."""
    if record.tensions is None or not record.tensions.size:
        return {}
    keep = record.time_s >= record.time_s[0] + transient_s
    out = {}
    for i in range(record.tensions.shape[1]):
        for j, end in enumerate(("fairlead", "anchor")):
            x = record.tensions[keep, i, j]
            out[f"line{i + 1}_{end}"] = {"unit": "N", "mean": float(np.nanmean(x)), "std": float(np.nanstd(x)),
                                         "min": float(np.nanmin(x)), "max": float(np.nanmax(x))}
    return out


def statistics(result: RunResult | MotionRecord, transient_s: float) -> dict:
    """Per DOF: mean, std, extremes and the paper's band STDs, leaving out the first
    ``transient_s`` seconds."""
    keep = result.time_s >= result.time_s[0] + transient_s
    if not keep.any():
        raise ConfigError(f"transient {transient_s:g} s leaves nothing of the run to analyse")
    dt = float(result.time_s[1] - result.time_s[0]) if result.time_s.size > 1 else 1.0
    stats: dict = {"analysed_from_s": float(result.time_s[keep][0]), "transient_s": transient_s, "bands_hz": BANDS_HZ}
    for j, name in enumerate(DOF_NAMES):
        x = result.motion[keep, j] * (180 / np.pi if j >= 3 else 1.0)
        stats[name] = {"unit": "deg" if j >= 3 else "m", "mean": float(x.mean()), "std": float(x.std()),
                       "min": float(x.min()), "max": float(x.max()),
                       "band_std": band_stds(x, dt) if x.size >= 8 * MIN_SEGMENTS else None}  # (too short)
    eta = result.wave_elevation_m[keep]
    stats["wave_elevation"] = {"unit": "m", "mean": float(eta.mean()), "std": float(eta.std()),
                               "hs_4std": float(4 * eta.std())}
    return stats


def fit_free_decay(time_s: np.ndarray, x: np.ndarray) -> dict | None:
    """Period and damping ratio of a decay record, fitted over its first ``DECAY_CYCLES``
    cycles (drag damping grows with the amplitude: one ratio holds for an amplitude range):
    least-squares lines through the times of the peaks (the damped period) and through
    the logarithms of their heights above the rest position (the decrement per cycle, hence
    the damping ratio); None if the record holds under two cycles."""
    import scipy.signal  # here: only decay fits need it (0.6 s of every command's start-up)

    rest = float(np.median(x[len(x) // 2:]))
    peaks, _ = scipy.signal.find_peaks(x - rest)
    peaks = peaks[x[peaks] > rest][:DECAY_CYCLES + 1]
    if len(peaks) < 3:
        return None
    cycles = np.arange(len(peaks))
    period_s = float(np.polyfit(cycles, time_s[peaks], 1)[0])
    decrement = -float(np.polyfit(cycles, np.log(x[peaks] - rest), 1)[0])
    zeta = decrement / np.hypot(2 * np.pi, decrement)
    return {"period_s": period_s, "natural_period_s": period_s * float(np.sqrt(1 - zeta**2)),
            "damping_ratio": zeta, "cycles": int(len(peaks) - 1)}


def free_decay(result: RunResult | MotionRecord, initial_state: tuple[float, ...]) -> dict:
    """Fitted decay of each DOF given an initial offset (see ``fit_free_decay``)."""
    fits = {}
    for j, name in enumerate(DOF_NAMES):
        if initial_state[j] != 0 and (fit := fit_free_decay(result.time_s, result.motion[:, j])) is not None:
            fits[name] = fit
    return fits


def checked_output(output: Path | str, run: RunConfig, transient_s: float | None,
                   overwrite: bool) -> tuple[Path, float]:
    """A run's output folder and the transient its statistics leave out (None: the default,
    ``default_transient``); ConfigError for a transient outside the run or a folder that holds
    files without ``overwrite``."""
    output = Path(output)
    if transient_s is None:
        transient_s = default_transient(run.duration_s)
    if not 0 <= transient_s < run.duration_s:
        raise ConfigError(f"--transient: must be in [0, duration {run.duration_s:g} s), got {transient_s:g}")
    if output.exists() and any(output.iterdir()) and not overwrite:
        raise ConfigError(f"{output}: exists and is not empty (pass --overwrite to replace its files)")
    return output, transient_s


def summary_head(run: RunConfig, model: PlatformModel, waves: WaveComponents | None, wave_info: dict,
                 initial_state: tuple[float, ...]) -> dict:
    """The first entries of a run's ``summary.json``: software, platform, drag model, hydro
    options, mooring, waves and run settings."""
    return {
        "software": {"name": "fowt_hydro_sim", "version": __version__},
        "platform": model.platform.name, "drag_model": run.drag_model, "hydro_options": asdict(run.hydro_options),
        "mooring": model.platform.mooring.model,
        "waves": wave_info,
        "run": {"dt_s": run.dt_s, "duration_s": run.duration_s, "output_interval_s": run.output_interval_s or run.dt_s,
                "initial_state": list(initial_state), "wave_table_step_s": model.wave_table_step_s,
                "n_wave_components": 0 if waves is None else int(waves.frequency_hz.size)},
    }


def simulate(run: RunConfig, waves: WaveComponents | None, wave_info: dict, output: Path,
             transient_s: float | None = None, overwrite: bool = False) -> dict:
    """Run the model, write ``timeseries.csv`` and ``summary.json`` to ``output`` and return the
    summary; its statistics leave out the first ``transient_s`` seconds (None: ``TRANSIENT_S``,
    as ``fowt-sim analyze`` does, or nothing of a run not longer than that). ``waves`` None is
    still water."""
    output, transient_s = checked_output(output, run, transient_s, overwrite)
    platform = load_platform(run.platform)
    start = time.perf_counter()
    model = model_for(platform, run, waves)
    built = time.perf_counter()
    result = write_timeseries(output, model.run_parts(run.duration_s, run.output_interval_s),
                              model.mooring_tensions, model.n_mooring_lines)
    performance = performance_of(run, start, built, time.perf_counter())
    summary = {
        **summary_head(run, model, waves, wave_info, run.initial_state),
        "performance": performance,
        "statistics": statistics(result, transient_s),
        "mooring_tensions": tension_statistics(result, transient_s),
    }
    if waves is None and any(run.initial_state):
        summary["free_decay"] = free_decay(result, run.initial_state)
    (output / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    return summary


def model_for(platform: Platform, run: RunConfig, waves: WaveComponents | None) -> PlatformModel:
    """The model of a run of ``platform`` (``run.platform`` is not read) at its initial state."""
    model = PlatformModel(platform, waves, dt_s=run.dt_s, drag_model=run.drag_model,
                          wave_table_dt_s=run.wave_table_dt_s, options=run.hydro_options, mooring_model=run.mooring)
    model.reset(motion=np.array(run.initial_state))
    return model


def performance_of(run: RunConfig, start: float, built: float, end: float) -> dict:
    """A run's performance figures from its start, end of set-up and end (perf_counter)."""
    return {"wall_time_s": end - start, "set_up_s": built - start,
            "real_time_factor": run.duration_s / (end - built),
            "peak_memory_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}


def run_model(platform: Platform, run: RunConfig, waves: WaveComponents | None) -> tuple[RunResult, dict, float]:
    """One run of ``platform`` (``run.platform`` is not read): its result, its performance
    figures and the kinematics table step used [s]."""
    start = time.perf_counter()
    model = model_for(platform, run, waves)
    built = time.perf_counter()
    result = model.run(run.duration_s, output_interval_s=run.output_interval_s)
    return result, performance_of(run, start, built, time.perf_counter()), model.wave_table_step_s


def summary_text(summary: dict, output: Path) -> str:
    """The summary as the command prints it."""
    perf = summary["performance"]
    lines = [f"{summary['platform']}, {summary['waves']['source']}, drag {summary['drag_model']}: "
             f"{summary['run']['duration_s']:g} s simulated in {perf['wall_time_s'] - perf['set_up_s']:.2f} s "
             f"({perf['real_time_factor']:.0f}x real time; set-up {perf['set_up_s']:.1f} s, which includes "
             f"compiling the kernels on a first run)"]
    stats = summary["statistics"]
    lines.append(f"statistics from t = {stats['analysed_from_s']:g} s ({_dropped_text(stats, summary['run'])}); "
                 "band STDs over " + ", ".join(f"{b} {lo:g}-{hi:g} Hz" for b, (lo, hi) in stats["bands_hz"].items()))
    lines.append(f"{'':16s}{'mean':>10s}{'std':>10s}{'min':>10s}{'max':>10s}{'std LF':>10s}{'std WF':>10s}")
    for name in DOF_NAMES:
        s = stats[name]
        bands = "".join(f"{s['band_std'][b]:10.3f}" for b in BANDS_HZ) if s["band_std"] else ""
        lines.append(f"{name + ' [' + s['unit'] + ']':16s}{s['mean']:10.3f}{s['std']:10.3f}{s['min']:10.3f}"
                     f"{s['max']:10.3f}" + bands)
    lines.append(f"wave Hs (4 std) at the reference point: {stats['wave_elevation']['hs_4std']:.2f} m")
    for name, fit in summary.get("free_decay", {}).items():
        lines.append(f"free decay {name}: period {fit['period_s']:.2f} s (undamped {fit['natural_period_s']:.2f} s), "
                     f"damping ratio {100 * fit['damping_ratio']:.2f} % of critical, fitted over "
                     f"{fit['cycles']:.1f} cycles")
    lines.append(f"wrote {output / 'timeseries.csv'} and {output / 'summary.json'}")
    return "\n".join(lines)


def _dropped_text(stats: dict, run: dict) -> str:
    """What the statistics left out at the start of the run, and why."""
    transient = stats["transient_s"]
    if transient > 0:
        return f"the first {transient:g} s dropped as start-up transient, as fowt-sim analyze does; --transient"
    if run["duration_s"] <= TRANSIENT_S:
        return (f"nothing dropped: the run is not longer than the {TRANSIENT_S:g} s default transient; "
                "fowt-sim analyze --transient 0 gives the same")
    return "nothing dropped: --transient 0"


# ---------------------------------------------------------------------- files
def tension_columns(n_lines: int) -> list[str]:
    """The mooring tension columns of ``timeseries.csv``: each line's fairlead and anchor."""
    return [f"line{i + 1}_{end}_tension_n" for i in range(n_lines) for end in ("fairlead", "anchor")]


def column_names(n_lines: int = 0) -> list[str]:
    """The columns of ``timeseries.csv`` of a run with ``n_lines`` mooring lines."""
    names = ["time_s"]
    names += [f"{d}_{u}" for d, u in zip(DOF_NAMES, _MOTION_UNITS)]
    names += [f"{d}_velocity_{u}_s" for d, u in zip(DOF_NAMES, _MOTION_UNITS)]
    names += [f"{d}_acceleration_{u}_s2" for d, u in zip(DOF_NAMES, _MOTION_UNITS)]
    names += [f"{c}_{a}" for c in NAMES for a in _AXES]
    names.append("wave_elevation_m")
    return names + tension_columns(n_lines)


Tensions = Callable[[np.ndarray, np.ndarray], np.ndarray]  # (time, motion) -> (n, lines, 2)


def write_timeseries(folder: Path, parts: Iterable[RunResult], tensions: Tensions | None = None,
                     n_lines: int = 0) -> MotionRecord:
    """Write consecutive parts of a run (``PlatformModel.run_parts``) to ``timeseries.csv`` as
    they come, with the ``n_lines`` mooring lines' tensions (``PlatformModel.mooring_tensions``)
    if given; return the run's motion record."""
    folder.mkdir(parents=True, exist_ok=True)
    kept: list[MotionRecord] = []
    with (folder / "timeseries.csv").open("w") as out:
        out.write(",".join(column_names(n_lines if tensions else 0)) + "\n")
        for part in parts:
            rows = slice(1 if kept else 0, None)  # a later part's first row is the last one written
            n = len(part.time_s)
            lines = tensions(part.time_s, part.motion) if tensions else np.zeros((n, 0, 2))
            table = np.column_stack([part.time_s, part.motion, part.velocity, part.acceleration,
                                     part.loads.reshape(n, -1), part.wave_elevation_m, lines.reshape(n, -1)])[rows]
            np.savetxt(out, table, delimiter=",", fmt="%.9g")
            kept.append(MotionRecord(part.time_s[rows], part.motion[rows], part.wave_elevation_m[rows], lines[rows]))
    return MotionRecord(*(np.concatenate(column) for column in zip(*kept)))


def read_run(folder: Path) -> dict[str, np.ndarray]:
    """The columns of a run's ``timeseries.csv`` by name."""
    path = Path(folder) / "timeseries.csv"
    with path.open() as f:
        names = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return dict(zip(names, data.T))
