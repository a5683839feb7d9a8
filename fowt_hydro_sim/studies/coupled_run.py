"""Offline coupled runs (``fowt-sim simulate --turbine rosco``): the platform model and the
turbine with ROSCO stepped together in one process (``turbine.coupled.run_coupled``),
written as ``fowt-sim simulate`` writes a run (``timeseries.csv`` and ``summary.json``),
with the turbine's channels as more columns and their statistics in the summary."""
from __future__ import annotations

import contextlib
import json
import time
from collections.abc import Iterable
from dataclasses import asdict
from pathlib import Path
from typing import NamedTuple

import numpy as np

from fowt_hydro_sim.physics.config import Platform, RunConfig, load_platform
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import WaveComponents
from fowt_hydro_sim.rosbag.reader import Bag
from fowt_hydro_sim.studies.simulate import (
    MotionRecord,
    checked_output,
    column_names,
    model_for,
    performance_of,
    statistics,
    summary_head,
    summary_text,
    tension_statistics,
)
from fowt_hydro_sim.turbine.coupled import CHANNELS, CoupledPart, run_coupled, static_offset, turbine_on_platform
from fowt_hydro_sim.turbine.settings import TurbineSettings


def bag_series(path: str, topic: str) -> tuple[np.ndarray, np.ndarray]:
    """A turbine quantity topic of a bag (a wind series): its times and values."""
    series = Bag(path).scalar(topic)
    return series.time_s, series.values[:, 0]


class CoupledRecord(NamedTuple):
    """A coupled run's rows: the platform's (``MotionRecord``), its velocities and
    accelerations (n, 6) and the turbine's ``CHANNELS`` (n, len(CHANNELS))."""

    motion: MotionRecord
    velocity: np.ndarray
    acceleration: np.ndarray
    channels: np.ndarray


def write_coupled(path: Path | None, parts: Iterable[CoupledPart]) -> CoupledRecord:
    """Collect a coupled run's parts, writing them to the CSV file ``path`` as they come
    (``simulate``'s columns, then the turbine's ``CHANNELS``; None: not written)."""
    kept: list[tuple[MotionRecord, np.ndarray, np.ndarray, np.ndarray]] = []
    with path.open("w") if path is not None else contextlib.nullcontext() as out:
        for part in parts:
            r, n = part.result, len(part.result.time_s)
            if out is not None and not kept:
                out.write(",".join(column_names(part.tensions.shape[1]) + list(CHANNELS)) + "\n")
            rows = slice(1 if kept else 0, None)  # a later part's first row is the last one written
            if out is not None:
                table = np.column_stack([r.time_s, r.motion, r.velocity, r.acceleration, r.loads.reshape(n, -1),
                                         r.wave_elevation_m, part.tensions.reshape(n, -1), part.turbine])[rows]
                np.savetxt(out, table, delimiter=",", fmt="%.9g")
            kept.append((MotionRecord(r.time_s[rows], r.motion[rows], r.wave_elevation_m[rows], part.tensions[rows]),
                         r.velocity[rows], r.acceleration[rows], part.turbine[rows]))
    record = MotionRecord(*(np.concatenate(column) for column in zip(*(k[0] for k in kept))))
    return CoupledRecord(record, *(np.concatenate([k[i] for k in kept]) for i in (1, 2, 3)))


def channel_statistics(time_s: np.ndarray, channels: np.ndarray, transient_s: float) -> dict:
    """Each turbine channel's mean, STD, minimum and maximum after ``transient_s``."""
    keep = time_s >= time_s[0] + transient_s
    return {name: {"mean": float(x.mean()), "std": float(x.std()), "min": float(x.min()), "max": float(x.max())}
            for name, x in zip(CHANNELS, channels[keep].T)}


class CoupledOutcome(NamedTuple):
    """A coupled run done: its rows, its performance (``simulate.performance_of``), where
    the platform started and the turbine's description for the summary."""

    rows: CoupledRecord
    performance: dict
    model: PlatformModel
    initial_state: tuple[float, ...]
    turbine: dict


def run_coupled_case(platform: Platform, run: RunConfig, turbine: TurbineSettings, waves: WaveComponents | None,
                     initial_state: tuple[float, ...] | None = None, timeseries: Path | None = None) -> CoupledOutcome:
    """``platform`` (the platform of ``run``, possibly edited) with the turbine of ``turbine``
    and its ROSCO in the loop for ``run.duration_s``; its rows written to the CSV file
    ``timeseries`` if given. ``initial_state`` None: the platform starts at its static offset
    under the initial thrust (``turbine.coupled.static_offset``)."""
    start = time.perf_counter()
    model = model_for(platform, run, waves)
    start_rotor = None if turbine.rotor_start == "steady" else (turbine.rotor_speed_rad_s, turbine.pitch_rad, 0.0)
    rotor = turbine_on_platform(turbine.turbine, platform, turbine.make_wind(bag_series), turbine.hub_height_m,
                                start_rotor, turbine.fixed_platform, discon_changes=turbine.discon_changes)
    try:
        if initial_state is None:
            initial_state = tuple(float(v) for v in static_offset(model, rotor))
        model.reset(motion=np.array(initial_state))
        built = time.perf_counter()
        rows = write_coupled(timeseries, run_coupled(model, rotor, run.duration_s, run.output_interval_s))
    finally:
        rotor.close()
    described = {"name": rotor.turbine.name, "controller": "ROSCO", "controller_dt_s": rotor.model.dt_s,
                 "thrust_height_m": rotor.thrust_height_m,
                 "settings": {k: v for k, v in asdict(turbine).items() if k != "platform"}}
    return CoupledOutcome(rows, performance_of(run, start, built, time.perf_counter()), model, initial_state,
                          described)


def simulate_coupled(run: RunConfig, turbine: TurbineSettings, waves: WaveComponents | None, wave_info: dict,
                     output: Path, transient_s: float | None = None, overwrite: bool = False,
                     initial_state: tuple[float, ...] | None = None) -> dict:
    """The platform of ``run`` with the turbine of ``turbine`` and its ROSCO in the loop: run,
    write ``timeseries.csv`` and ``summary.json`` to ``output`` and return the summary (as
    ``studies.simulate.simulate``). ``initial_state`` None: the platform starts at its static
    offset under the initial thrust (``turbine.coupled.static_offset``)."""
    output, transient_s = checked_output(output, run, transient_s, overwrite)
    output.mkdir(parents=True, exist_ok=True)
    done = run_coupled_case(load_platform(run.platform), run, turbine, waves, initial_state,
                            output / "timeseries.csv")
    record = done.rows.motion
    summary = {
        **summary_head(run, done.model, waves, wave_info, done.initial_state),
        "turbine": done.turbine,
        "performance": done.performance,
        "statistics": statistics(record, transient_s),
        "turbine_statistics": channel_statistics(record.time_s, done.rows.channels, transient_s),
        "mooring_tensions": tension_statistics(record, transient_s),
    }
    (output / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    return summary


def coupled_summary_text(summary: dict, output: Path) -> str:
    """The summary as the command prints it: ``simulate``'s, then the turbine's channels."""
    lines = summary_text(summary, output).splitlines()
    t = summary["turbine"]
    table = [f"turbine {t['name']} with ROSCO every {t['controller_dt_s']:g} s, thrust at {t['thrust_height_m']:g} m:",
             f"{'':26s}{'mean':>12s}{'std':>12s}{'min':>12s}{'max':>12s}"]
    for name, s in summary["turbine_statistics"].items():
        table.append(f"{name:26s}{s['mean']:12.5g}{s['std']:12.5g}{s['min']:12.5g}{s['max']:12.5g}")
    return "\n".join(lines[:-1] + table + lines[-1:])


def steady_state(system: str, wind_m_s: float, duration_s: float = 900.0, average_s: float = 400.0) -> dict:
    """The coupled system's steady state in still water and steady wind (``system`` a named
    system, ``turbine.system``): the offline loop run ``duration_s`` from the static offset,
    the platform's motion and the turbine's channels averaged over the last ``average_s``
    (several surge periods: a slow swing left averages out)."""
    from fowt_hydro_sim.physics.model import PlatformModel, RunResult
    from fowt_hydro_sim.turbine.system import load_system
    from fowt_hydro_sim.turbine.wind import Wind

    chosen = load_system(system)
    platform = load_platform(chosen.platform)
    model = PlatformModel(platform, None, dt_s=0.05, mooring_model=chosen.mooring)
    rotor = turbine_on_platform(chosen.turbine, platform, Wind(speed_m_s=wind_m_s))
    try:
        model.reset(motion=static_offset(model, rotor))
        parts = list(run_coupled(model, rotor, duration_s, 0.25))
    finally:
        rotor.close()
    result = RunResult.joined([p.result for p in parts])
    channels = np.concatenate([parts[0].turbine] + [p.turbine[1:] for p in parts[1:]])
    keep = result.time_s >= result.time_s[-1] - average_s
    motion, mean = result.motion[keep], channels[keep].mean(axis=0)
    return {"surge_m": float(motion[:, 0].mean()), "heave_m": float(motion[:, 2].mean()),
            "pitch_rad": float(motion[:, 4].mean()), "surge_std_m": float(motion[:, 0].std()),
            **{name: float(v) for name, v in zip(CHANNELS, mean)}}
