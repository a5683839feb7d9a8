"""The independent benchmark's "basin": runs of the Cummins/BEM simulator in a load case's
sea, with the scenario's baseline differences (random ones drawn from its seed, and terms the
model has too set as scenario values: the drift's strength, the drag's Cd factor), its
injected effect (in a form the diagnosis catalogue does not use), a pre-roll and 1 % sensor
noise; and the campaign's free decays (``DECAYS``, calm water, rotor parked); each run cached
on disk, keyed by everything that makes it."""
from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Callable
from dataclasses import asdict, dataclass, replace
from functools import lru_cache
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.config import Platform, load_case
from fowt_hydro_sim.physics.model import DOF_NAMES
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
# the basin's baseline drift over the model's (its ``drift_coefficients_n_m2`` by Newman's
# approximation): the mean surge offset it gives in regular waves of 1.5 m at 7, 8, 10 and 12 s
# (drift on minus off, 800-2400 s) is the model's times 1.0000, 1.0000, 1.0003 and 1.0008 (the
# same table, rounded to 5 digits in the platform file); docs/diagnosis.md
MODEL_DRIFT_RATIO = 1.0
# the injected drift: a steeper frequency-dependent table on top of the baseline's
INJECTED_DRIFT: cummins.Table = ((0.3, 1.0e4), (0.5, 6.0e4), (0.8, 1.5e5), (1.2, 2.5e5), (3.2, 3.0e5))
# the baseline differences' spread: Cd scale, Ca scale (uniform +-), strip lengths drawn from
BASELINE_SPREAD = {"cd": 0.10, "ca": 0.05}
STRIP_LENGTHS_M = (None, 0.5, 2.0)
# the campaign's free decays: DOF, initial offset [m, rad], record [s] (about ten surge and
# pitch cycles). Surge and pitch: the DOFs whose slow motion the diagnosis reads, where the
# damping and the slow drift must be told apart. (The two simulators' heave periods differ by
# about 15 %, 16.6 s against 14.4 s: a BEM hull's heave added mass against strips', a
# structural difference no term of the model reads.)
DECAYS = (("surge", 10.0, 1000.0), ("pitch", math.radians(4.0), 300.0))


@dataclass(frozen=True)
class BaselineTerms:
    """Baseline terms the model has too, set by a scenario: the basin's drift table times
    ``drift_scale``, its Cds times ``cd_factor`` on top of the drawn U(0.9, 1.1);
    ``spread`` False: no random difference (Cd and Ca scales 1, the platform's strips)."""

    drift_scale: float = 1.0
    cd_factor: float = 1.0
    spread: bool = True

    @classmethod
    def from_values(cls, values: dict | None) -> BaselineTerms:
        """From a scenario's ``baseline`` mapping; ValueError naming an unknown key or a bad value."""
        values = dict(values or {})
        unknown = set(values) - set(cls.__dataclass_fields__)
        if unknown:
            raise ValueError(f"unknown baseline term {', '.join(sorted(unknown))} (known: "
                             f"{', '.join(cls.__dataclass_fields__)})")
        if "spread" in values and not isinstance(values["spread"], bool):
            raise ValueError(f"baseline spread must be true or false, got {values['spread']!r}")
        for name in ("drift_scale", "cd_factor"):
            value = values.get(name, 1.0)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not value > 0:
                raise ValueError(f"baseline {name} must be a number above 0, got {value!r}")
        return cls(**{k: (v if k == "spread" else float(v)) for k, v in values.items()})

    def changed(self) -> dict:
        """The terms that differ from the default (the cache key's share of them)."""
        default = asdict(BaselineTerms())
        return {k: v for k, v in asdict(self).items() if v != default[k]}


def baseline(seed: int, drift: cummins.Table = BASELINE_DRIFT, terms: BaselineTerms = BaselineTerms()
             ) -> cummins.Baseline:
    """The scenario's baseline differences (the same in each of its runs): Cd and Ca scales
    and the strip length drawn from the seed (none if ``terms.spread`` is False), the Cds
    times ``terms.cd_factor`` and the drift table times ``terms.drift_scale``."""
    rng = np.random.default_rng(seed)
    cd, ca = 1.0 + rng.uniform(-1, 1) * BASELINE_SPREAD["cd"], 1.0 + rng.uniform(-1, 1) * BASELINE_SPREAD["ca"]
    strip = STRIP_LENGTHS_M[int(rng.integers(len(STRIP_LENGTHS_M)))]
    if not terms.spread:
        cd, ca, strip = 1.0, 1.0, None
    return cummins.Baseline(cd_scale=cd * terms.cd_factor, added_mass_scale=ca, strip_length_m=strip,
                            drift_coefficient_n_m2=tuple((w, terms.drift_scale * d) for w, d in drift))


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
            with_effect: bool, drift: cummins.Table, platform: Platform, terms: BaselineTerms = BaselineTerms()
            ) -> str:
    """The cache key: everything that makes the run (the baseline terms where they differ
    from the default, so the runs cached before they existed keep their keys)."""
    made = [VERSION, form, values, seed, case, duration_s, with_effect, drift, repr(platform)]
    text = json.dumps(made + ([terms.changed()] if terms.changed() else []), sort_keys=True, default=str)
    return hashlib.blake2b(text.encode(), digest_size=12).hexdigest()


def basin_run(name: str, form: str | None, values: dict[str, float], seed: int, case: str, platform: Platform,
              duration_s: float, with_effect: bool = True, drift: cummins.Table = BASELINE_DRIFT,
              cache: Path | None = None, terms: BaselineTerms = BaselineTerms()) -> MeasuredRun:
    """A "measured" run of the independent simulator in ``case``'s sea (JONSWAP with the
    case's Hs, Tp and gamma, repeating over the record, seeded from ``seed`` and the case),
    started PREROLL_S before the record, with 1 % noise on motion and elevation, and the
    scenario's baseline ``terms``."""
    case_seed = seed + int(hashlib.blake2b(case.encode(), digest_size=2).hexdigest(), 16)

    def make() -> dict[str, np.ndarray]:
        sea = load_case(case).sea_state
        waves = cummins.jonswap_waves(sea.hs_m, sea.tp_s, sea.gamma, duration_s, case_seed, sea.heading_deg)
        injected = effects(form, values, platform) if with_effect else cummins.Effects()
        run = cummins.measured_run(platform, _database(), waves, duration_s, name, DT_S,
                                   baseline(seed, drift, terms), injected, preroll_s=PREROLL_S)
        rng = np.random.default_rng(case_seed)
        motion = run.motion + rng.normal(0.0, 1.0, run.motion.shape) * SENSOR_NOISE * run.motion.std(axis=0)
        eta = run.elevation_m + rng.normal(0.0, SENSOR_NOISE * run.elevation_m.std(), run.elevation_m.size)
        return {"elevation_time_s": run.elevation_time_s, "elevation_m": eta,
                "motion_time_s": run.motion_time_s, "motion": motion}

    stored = _cached(cache, run_key(form, values, seed, case, duration_s, with_effect, drift, platform, terms), make)
    return MeasuredRun(name, stored["elevation_time_s"], stored["elevation_m"], (0.0, 0.0), stored["motion_time_s"],
                       stored["motion"])


def decay_run(name: str, dof: str, offset: float, form: str | None, values: dict[str, float], seed: int,
              platform: Platform, duration_s: float, cache: Path | None = None,
              terms: BaselineTerms = BaselineTerms()) -> MeasuredRun:
    """A "measured" free decay of the independent simulator: released at rest from ``offset``
    in ``dof`` in calm water, with the scenario's baseline ``terms`` and injected effect (but
    no harmonic load: the rotor is parked), 1 % sensor noise on the motion; the elevation is
    the calm water's, zero."""
    def make() -> dict[str, np.ndarray]:
        initial = np.zeros(6)
        initial[DOF_NAMES.index(dof)] = offset
        injected = replace(effects(form, values, platform), harmonic_load=())
        trajectory = cummins.integrate(platform, _database(), None, duration_s, DT_S,
                                       baseline(seed, BASELINE_DRIFT, terms), injected, initial=initial)
        time_s = np.arange(0.0, duration_s + 1e-9, cummins.MOTION_STEP_S)
        motion = np.stack([np.interp(time_s, trajectory.time_s, trajectory.position[:, i]) for i in range(6)], axis=1)
        rng = np.random.default_rng(seed + DOF_NAMES.index(dof))
        motion = motion + rng.normal(0.0, 1.0, motion.shape) * SENSOR_NOISE * motion.std(axis=0)
        return {"motion_time_s": time_s, "motion": motion}

    key = run_key(form, values, seed, f"decay {dof} {offset!r}", duration_s, True, BASELINE_DRIFT, platform, terms)
    stored = _cached(cache, key, make)
    time_s = stored["motion_time_s"]
    return MeasuredRun(name, time_s, np.zeros(time_s.size), (0.0, 0.0), time_s, stored["motion"], decay_dof=dof)


def _cached(cache: Path | None, key: str, make: Callable[[], dict[str, np.ndarray]]) -> dict[str, np.ndarray]:
    """The arrays stored under ``key`` in ``cache``, or ``make()``'s, stored there (no cache:
    made every time)."""
    path = cache / f"{key}.npz" if cache else None
    if path is not None and path.exists():
        with np.load(path) as stored:
            return dict(stored)
    arrays = make()
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        np.savez_compressed(path, **arrays)
    return arrays
