"""Measured runs and their replay: the model, or a variant of it, driven by a run's own
measured wave elevation record, so that model and measurement see the same waves.

A ``Variant`` is everything that may differ from the plain model when replaying: the
platform, the drag model, loads beyond Morison's (``physics.loads.extension``) and a time
shift of the elevation record. Calibration varies the platform's Cds; the gap diagnosis's
effects (``studies.diagnosis.effects``) vary any of them.
"""
from __future__ import annotations

import hashlib
from collections import OrderedDict
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import scipy.fft

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.config import HydroOptions, Platform
from fowt_hydro_sim.physics.loads.extension import Extension
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.strips import discretise
from fowt_hydro_sim.physics.waves.components import WaveComponents, from_elevation_record
from fowt_hydro_sim.physics.waves.kinematics import KinematicsTable, table_step

OUTPUT_INTERVAL_S = 0.25  # motion samples of a replayed run
PREROLL_S = 600.0  # model time before the record: with the 300 s transient, three decay times of the surge resonance
WAVE_F_MAX_HZ = 0.5  # elevation components kept
TABLE_BUDGET_BYTES = 3.2e9  # kinematics tables kept for further replays (seven 3-hour records: 0.41 GB each)
_tables: OrderedDict[bytes, KinematicsTable] = OrderedDict()


@dataclass(frozen=True)
class MeasuredRun:
    """What a measured bag holds: the elevation record and the platform's 6-DOF motion
    (optionally the acceleration and mooring loads, which the replay does not need).
    ``decay_dof``: a free decay in calm water of that DOF (its elevation is the calm
    water's, or zero where the bag has none)."""

    name: str
    elevation_time_s: np.ndarray
    elevation_m: np.ndarray
    point_xy_m: tuple[float, float]
    motion_time_s: np.ndarray
    motion: np.ndarray
    heading_deg: float = 0.0  # the waves' direction of travel (long-crested)
    decay_dof: str | None = None

    @property
    def hs_m(self) -> float:
        """Significant wave height of the record, 4 x its elevation STD."""
        return 4.0 * float(np.std(self.elevation_m))

    @property
    def elevation_step_s(self) -> float:
        return float(self.elevation_time_s[1] - self.elevation_time_s[0])


def measured_run(path: str | Path, heading_deg: float = 0.0, decay_dof: str | None = None) -> MeasuredRun:
    """Read a measured run from a bag (contract: /waves/elevation and /platform/pose); the
    elevation is resampled onto a uniform grid at its median step. A free decay
    (``decay_dof``) needs no elevation: without one it is calm water, zero on the motion's clock.
    A bag imported as a free decay (its import's ``free_decay``) is read only as one, in its DOF."""
    from fowt_hydro_sim.rosbag.reader import Bag
    from msg_adapters import topics as contract
    bag = Bag(path)
    imported_decay = ((bag.config or {}).get("measured") or {}).get("free_decay")
    if imported_decay is not None and decay_dof != imported_decay:
        raise InputError(f"{path}: a free decay in {imported_decay} (its import's free_decay), "
                         + (f"given as one in {decay_dof}" if decay_dof else
                            f"not a wave run: give it as a free decay (diagnose --decay {imported_decay}={path})"))
    motion = bag.motion()
    calm = contract.ELEVATION not in bag.topics or not bag.topics[contract.ELEVATION].message_count
    if decay_dof is not None and calm:
        return MeasuredRun(Path(path).name, motion.time_s, np.zeros(motion.time_s.size), (0.0, 0.0), motion.time_s,
                           motion.values, heading_deg, decay_dof)
    elevation = bag.elevation()
    step = float(np.median(np.diff(elevation.time_s)))
    grid = np.arange(elevation.time_s[0], elevation.time_s[-1] + 0.5 * step, step)
    eta = np.interp(grid, elevation.time_s, elevation.values[:, 2])
    return MeasuredRun(Path(path).name, grid, eta, (float(elevation.values[0, 0]), float(elevation.values[0, 1])),
                       motion.time_s, motion.values, heading_deg, decay_dof)


@dataclass(frozen=True)
class Variant:
    """A model to replay runs with. ``elevation_shift_s`` is added to the record's stamps
    (a probe whose clock runs late by d is corrected by -d). ``options``: the moving body's
    hydrodynamics (config.HydroOptions; None: the model's default)."""

    platform: Platform
    drag_model: str = "constant"
    extension: Extension = field(default_factory=Extension)
    elevation_shift_s: float = 0.0
    options: HydroOptions | None = None


def replay(variant: Variant, run: MeasuredRun, dt_s: float = 0.05, duration_s: float | None = None,
           preroll_s: float = PREROLL_S) -> tuple[np.ndarray, np.ndarray]:
    """Time and 6-DOF motion of the variant driven by the run's elevation record, on the
    record's clock (time 0 = the record's first sample, shifted), until the run's last
    motion sample (or for ``duration_s``).

    The model starts ``preroll_s`` before the record, in the record's periodic extension
    (the decomposition makes the sea periodic), so that it is past its start-up transient
    when the record begins: a model starting from rest inside the compared window would
    show a decaying low-frequency response that the measurement does not have."""
    platform = variant.platform
    env = platform.environment
    waves = from_elevation_record(run.elevation_time_s - run.elevation_time_s[0], run.elevation_m,
                                  *run.point_xy_m, run.heading_deg, env.water_depth_m, env.gravity_m_s2,
                                  f_max_hz=WAVE_F_MAX_HZ).delayed(preroll_s)
    table = kinematics_table(platform, waves)
    model = PlatformModel(platform, waves, dt_s=dt_s, drag_model=variant.drag_model, wave_table_dt_s=table.step_s,
                          extension=variant.extension.delayed(preroll_s), kinematics=table, options=variant.options)
    start = run.elevation_time_s[0] + variant.elevation_shift_s
    duration = duration_s if duration_s is not None else float(run.motion_time_s[-1] - start)
    result = model.run(preroll_s + duration, output_interval_s=OUTPUT_INTERVAL_S)
    keep = result.time_s >= preroll_s - 1e-9
    return result.time_s[keep] - preroll_s + start, result.motion[keep]


def fast_table_step(waves: WaveComponents) -> float:
    """A kinematics table step at most ``table_step``'s that divides the repeat period into a
    number of samples the FFT handles fast (a record's own length often has a large prime
    factor: a 3-hour record's table then took 10 s instead of 2.5 s)."""
    step = table_step(waves)
    return waves.period_s / scipy.fft.next_fast_len(int(round(waves.period_s / step)), real=True)


def kinematics_table(platform: Platform, waves: WaveComponents) -> KinematicsTable:
    """The waves' kinematics at the platform's points, kept for the next replays of the same
    run (a fit replays each run many times with other coefficients, same points): the
    latest used within ``TABLE_BUDGET_BYTES``, so that a diagnosis cycling over its runs
    does not rebuild each table on every replay (a count limit below the runs would)."""
    env = platform.environment
    points = discretise(platform).points_m
    step = fast_table_step(waves)
    digest = hashlib.blake2b(digest_size=16)
    for array in (waves.frequency_hz, waves.amplitude_m, waves.phase_rad, waves.direction_rad, points,
                  np.array([step, env.water_depth_m, env.gravity_m_s2, env.water_density_kg_m3])):
        digest.update(np.ascontiguousarray(array, dtype=float).tobytes())
    key = digest.digest()
    if key in _tables:
        _tables.move_to_end(key)
        return _tables[key]
    table = KinematicsTable.build(waves, points, step, env.water_depth_m, env.gravity_m_s2, env.water_density_kg_m3)
    _tables[key] = table
    while len(_tables) > 1 and sum(t.values.nbytes for t in _tables.values()) > TABLE_BUDGET_BYTES:
        _tables.popitem(last=False)
    return table
