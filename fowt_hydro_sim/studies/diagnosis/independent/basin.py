"""The independent benchmark's "basin": runs of the Cummins/BEM simulator in a load case's
sea, with the scenario's baseline differences, its injected effect (in a form the diagnosis
catalogue does not use), a pre-roll and 1 % sensor noise; each run cached on disk, keyed by
everything that makes it."""
from __future__ import annotations

import hashlib
import json
from functools import lru_cache
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.config import Platform, load_case
from fowt_hydro_sim.studies.diagnosis.independent import bem, cummins, drift, drift_study
from fowt_hydro_sim.studies.diagnosis.independent.catenary import ChainLines, surge_curve
from fowt_hydro_sim.studies.replay import PREROLL_S, MeasuredRun

VERSION = 1  # bump when the simulator's results change: the cache keys change with it
DT_S = 0.05
SENSOR_NOISE = 0.01  # white noise STD, share of each signal's STD

# The basin's own slow drift: the hull's BEM surge mean-drift coefficient D(w) (rad/s, N/m^2,
# the freely floating hull's, drift.py) by Newman's approximation, the same table as the
# model's default ``slow_drift: newman``: a null run then differs from the model only by the
# two simulators' structure and the scenario's baseline differences.
BASELINE_DRIFT: cummins.Table = drift_study.drift_coefficients(drift.load_table())
# the injected drift: a steeper frequency-dependent table on top of the baseline's
INJECTED_DRIFT: cummins.Table = ((0.3, 1.0e4), (0.5, 6.0e4), (0.8, 1.5e5), (1.2, 2.5e5), (3.2, 3.0e5))
# the baseline differences' spread: Cd scale, Ca scale (uniform +-), strip lengths drawn from
BASELINE_SPREAD = {"cd": 0.10, "ca": 0.05}
STRIP_LENGTHS_M = (None, 0.5, 2.0)


def baseline(seed: int, drift: cummins.Table = BASELINE_DRIFT) -> cummins.Baseline:
    """The scenario's baseline differences (the same in each of its runs): Cd and Ca scales
    and the strip length drawn from the seed."""
    rng = np.random.default_rng(seed)
    return cummins.Baseline(cd_scale=1.0 + rng.uniform(-1, 1) * BASELINE_SPREAD["cd"],
                            added_mass_scale=1.0 + rng.uniform(-1, 1) * BASELINE_SPREAD["ca"],
                            strip_length_m=STRIP_LENGTHS_M[int(rng.integers(len(STRIP_LENGTHS_M)))],
                            drift_coefficient_n_m2=tuple(drift))


def effects(form: str | None, values: dict[str, float], platform: Platform) -> cummins.Effects:
    """The injected effect: ``frequency_dependent_drift`` (INJECTED_DRIFT times ``scale``),
    ``mixed_damping`` (surge and pitch, linear and quadratic), ``catenary_mooring`` (the
    chain lines' surge curve, catenary.py) or ``rotor_1p`` (a harmonic pitch moment)."""
    if form is None:
        return cummins.Effects()
    if form == "frequency_dependent_drift":
        return cummins.Effects(drift_coefficient_n_m2=tuple((w, values["scale"] * d) for w, d in INJECTED_DRIFT))
    if form == "mixed_damping":
        linear = (values["surge_linear_n_s_m"], 0.0, 0.0, 0.0, values["pitch_linear_n_m_s"], 0.0)
        quadratic = (values["surge_quadratic_n_s2_m2"], 0.0, 0.0, 0.0, values["pitch_quadratic_n_m_s2"], 0.0)
        return cummins.Effects(linear_damping=linear, quadratic_damping=quadratic)
    if form == "catenary_mooring":
        lines = ChainLines(values["anchor_distance_m"], values["length_m"], values["weight_n_m"])
        return cummins.Effects(mooring_curve_n=surge_curve(platform, lines))
    if form == "rotor_1p":
        return cummins.Effects(harmonic_load=((4, values["amplitude_n_m"], values["frequency_hz"]),))
    raise ValueError(f"unknown injected form {form!r}")


@lru_cache(maxsize=1)
def _database() -> bem.HydroDatabase:
    return bem.load_database()


def run_key(form: str | None, values: dict[str, float], seed: int, case: str, duration_s: float,
            with_effect: bool, drift: cummins.Table, platform: Platform) -> str:
    """The cache key: everything that makes the run."""
    text = json.dumps([VERSION, form, values, seed, case, duration_s, with_effect, drift, repr(platform)],
                      sort_keys=True, default=str)
    return hashlib.blake2b(text.encode(), digest_size=12).hexdigest()


def basin_run(name: str, form: str | None, values: dict[str, float], seed: int, case: str, platform: Platform,
              duration_s: float, with_effect: bool = True, drift: cummins.Table = BASELINE_DRIFT,
              cache: Path | None = None) -> MeasuredRun:
    """A "measured" run of the independent simulator in ``case``'s sea (JONSWAP with the
    case's Hs, Tp and gamma, repeating over the record, seeded from ``seed`` and the case),
    started PREROLL_S before the record, with 1 % noise on motion and elevation."""
    key = run_key(form, values, seed, case, duration_s, with_effect, drift, platform)
    path = cache / f"{key}.npz" if cache else None
    if path is not None and path.exists():
        stored = np.load(path)
        return MeasuredRun(name, stored["elevation_time_s"], stored["elevation_m"], (0.0, 0.0),
                           stored["motion_time_s"], stored["motion"])
    sea = load_case(case).sea_state
    case_seed = seed + int(hashlib.blake2b(case.encode(), digest_size=2).hexdigest(), 16)
    waves = cummins.jonswap_waves(sea.hs_m, sea.tp_s, sea.gamma, duration_s, case_seed, sea.heading_deg)
    injected = effects(form, values, platform) if with_effect else cummins.Effects()
    run = cummins.measured_run(platform, _database(), waves, duration_s, name, DT_S, baseline(seed, drift), injected,
                               preroll_s=PREROLL_S)
    rng = np.random.default_rng(case_seed)
    motion = run.motion + rng.normal(0.0, 1.0, run.motion.shape) * SENSOR_NOISE * run.motion.std(axis=0)
    eta = run.elevation_m + rng.normal(0.0, SENSOR_NOISE * run.elevation_m.std(), run.elevation_m.size)
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        np.savez_compressed(path, elevation_time_s=run.elevation_time_s, elevation_m=eta,
                            motion_time_s=run.motion_time_s, motion=motion)
    return MeasuredRun(name, run.elevation_time_s, eta, (0.0, 0.0), run.motion_time_s, motion)
