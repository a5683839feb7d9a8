"""Load-case sweeps (``fowt-sim sweep``): a table of runs, load cases x seeds x drag models x
platform variants, run on a Dask cluster; each run's statistics and band STDs become one row
of ``runs.csv``, written as the run finishes, and ``summary.csv`` gives per load case (drag
model and variant) the mean of every statistic over the seeds with its confidence interval
(Student-t; log-normal for STDs, which stays positive). A rerun into the same folder skips
the runs already in ``runs.csv`` (resuming an interrupted sweep, or extending one with more
seeds or cases); Parquet copies of both tables are written too when pyarrow can be imported.

A run is exactly ``fowt-sim simulate`` with the same settings (``studies.simulate.run_model``
and ``statistics``); a platform variant is a platform (packaged name or YAML file) with
typed edits of ``physics.platform_edits`` (drag, added-mass and mooring-stiffness scales,
coefficients by path).

With a named system (``turbine.system``: platform, turbine with its ROSCO, mooring) the sweep
is one of the coupled turbine: load cases x wind speeds x seeds x drag models x variants of
the system's platform, each run exactly ``fowt-sim simulate --system SYSTEM --wind-speed W``
(``studies.coupled_run.run_coupled_case``), its row with the turbine's statistics
(``TURBINE_METRICS``) beside the platform's.
"""
from __future__ import annotations

import csv
import io
import json
import logging
import math
import os
import re
import time
from collections.abc import Iterable
from dataclasses import asdict, dataclass, field, replace
from itertools import product
from pathlib import Path
from typing import Any

import numpy as np
import yaml

from fowt_hydro_sim.physics.config import (
    DEFAULT_PLATFORM,
    DRAG_MODELS,
    ConfigError,
    Platform,
    RunConfig,
    SeaState,
    load_case,
    load_platform,
    run_from_dict,
)
from fowt_hydro_sim.physics.model import DOF_NAMES, RunResult
from fowt_hydro_sim.physics.platform_edits import (
    scaled_added_mass,
    scaled_drag,
    scaled_mooring_stiffness,
    with_coefficients,
)
from fowt_hydro_sim.studies.psd import BANDS_HZ
from fowt_hydro_sim.studies.simulate import model_for, performance_of, sea_state_waves, statistics
from fowt_hydro_sim.studies.turbine_loads import TOWER_METRICS, tower_base_metrics
from fowt_hydro_sim.turbine.wind import DEFAULT_WIND_M_S

log = logging.getLogger(__name__)

RUNS_FILE = "runs.csv"
SUMMARY_FILE = "summary.csv"
SETTINGS_FILE = "sweep.json"
KEY = ("load_case", "seed", "drag_model", "variant")
GROUP = ("load_case", "drag_model", "variant")
WIND = "wind_speed_m_s"  # a coupled sweep's key columns more: the wind speed and the controller's changes
CONTROLLER = "discon_changes"
COUPLED_KEY = ("load_case", WIND, CONTROLLER, "seed", "drag_model", "variant")
COUPLED_GROUP = ("load_case", WIND, CONTROLLER, "drag_model", "variant")
_STATS = ("mean", "std", "min", "max")
_SCALES = ("cd_scale", "added_mass_scale", "mooring_stiffness_scale")


# ---------------------------------------------------------------------- the table of runs
@dataclass(frozen=True)
class Variant:
    """A platform variant: a platform (packaged name or YAML file) and typed edits."""

    name: str
    platform: str = DEFAULT_PLATFORM
    cd_scale: float = 1.0
    added_mass_scale: float = 1.0
    mooring_stiffness_scale: float = 1.0
    coefficients: tuple[tuple[str, float], ...] = ()  # (path, value): platform_edits.with_coefficients

    def build(self) -> Platform:
        """The edited platform; ConfigError names the variant."""
        try:
            platform = load_platform(self.platform)
            if self.coefficients:
                platform = with_coefficients(platform, dict(self.coefficients))
            for scale, edit in zip(_SCALES, (scaled_drag, scaled_added_mass, scaled_mooring_stiffness)):
                if getattr(self, scale) != 1.0:
                    platform = edit(platform, getattr(self, scale))
        except ConfigError as exc:
            raise ConfigError(f"variant {self.name!r}: {exc}") from None
        return platform

    def document(self) -> dict:
        return {**asdict(self), "coefficients": dict(self.coefficients)}


@dataclass(frozen=True)
class Sweep:
    """Load cases x seeds x drag models x variants, every run with the same run settings
    (``run.platform`` and ``run.drag_model`` are not read) and statistics after ``transient_s``."""

    load_cases: tuple[str, ...]
    seeds: tuple[int, ...]
    drag_models: tuple[str, ...] = ("constant",)
    variants: tuple[Variant, ...] = (Variant(DEFAULT_PLATFORM),)
    run: RunConfig = field(default_factory=RunConfig)
    transient_s: float = 0.0
    system: str = ""  # a named system: the coupled turbine in the loop (variants of its platform)
    wind_speeds_m_s: tuple[float, ...] = ()  # the coupled sweep's hub-height wind speeds (steady wind)
    discon_changes: tuple[str, ...] = ("",)  # the coupled sweep's controller variants: DISCON.IN changes ("": none)

    def __post_init__(self) -> None:
        check_sweep(self)

    @property
    def coupled(self) -> bool:
        """Whether the turbine and its controller are in the loop (a named system)."""
        return bool(self.system)

    @property
    def key(self) -> tuple[str, ...]:
        """The columns naming a run."""
        return COUPLED_KEY if self.coupled else KEY

    def runs(self) -> list[dict]:
        """Every run's key (load_case, [wind_speed_m_s, discon_changes,] seed, drag_model,
        variant), in table order."""
        names = [v.name for v in self.variants]
        if self.coupled:
            return [dict(zip(COUPLED_KEY, k)) for k in product(self.load_cases, self.wind_speeds_m_s,
                                                                self.discon_changes, self.seeds, self.drag_models,
                                                                names)]
        return [dict(zip(KEY, k)) for k in product(self.load_cases, self.seeds, self.drag_models, names)]

    def run_settings(self) -> RunConfig:
        """The run settings of every run: a system's mooring model when the run names none."""
        if self.coupled and not self.run.mooring:
            from fowt_hydro_sim.turbine.system import load_system
            return replace(self.run, mooring=load_system(self.system).mooring)
        return self.run

    def settings_document(self) -> dict:
        """What a resumed sweep must share with the rows on disk."""
        run = {k: v for k, v in asdict(self.run_settings()).items() if k not in ("platform", "drag_model")}
        document = {"run": {**run, "initial_state": list(self.run.initial_state)}, "transient_s": self.transient_s,
                    "variants": {v.name: v.document() for v in self.variants}}
        return {**document, "system": self.system} if self.coupled else document


def system_variants(system: str, cd_scales: Iterable[float] = (1.0,)) -> tuple[Variant, ...]:
    """The named system's platform with every Cd scale, named ``SYSTEM`` (scale 1) or
    ``SYSTEM_cdSCALE``; ConfigError for an unknown system."""
    from fowt_hydro_sim.turbine.system import load_system
    chosen = load_system(system)
    return tuple(Variant(chosen.name + ("" if s == 1.0 else f"_cd{s:g}"), chosen.platform, cd_scale=s)
                 for s in cd_scales)


def check_sweep(sweep: Sweep) -> None:
    """ConfigError naming the first bad entry of a sweep."""
    for name, values in (("load_cases", sweep.load_cases), ("seeds", sweep.seeds),
                         ("drag_models", sweep.drag_models), ("variants", sweep.variants)):
        if not values:
            raise ConfigError(f"sweep: {name} is empty")
        if len(set(values)) != len(values):
            raise ConfigError(f"sweep: {name} has duplicates")
    for case in sweep.load_cases:
        load_case(case)
    if any(not isinstance(s, int) or isinstance(s, bool) or s < 0 for s in sweep.seeds):
        raise ConfigError(f"sweep: seeds must be non-negative integers, got {list(sweep.seeds)}")
    for drag in sweep.drag_models:
        if drag not in DRAG_MODELS:
            raise ConfigError(f"sweep: drag model {drag!r}: must be one of {', '.join(DRAG_MODELS)}")
    names = [v.name for v in sweep.variants]
    if len(set(names)) != len(names):
        raise ConfigError(f"sweep: variant names must differ, got {names}")
    for v in sweep.variants:
        if not v.name or "/" in v.name:
            raise ConfigError(f"sweep: variant name {v.name!r}: must be a non-empty name without '/'")
        for scale in _SCALES:
            if not (math.isfinite(getattr(v, scale)) and getattr(v, scale) > 0):
                raise ConfigError(f"sweep: variant {v.name!r}: {scale} must be a positive number")
    if not (math.isfinite(sweep.transient_s) and 0 <= sweep.transient_s < sweep.run.duration_s):
        raise ConfigError(f"sweep: transient_s must be in [0, duration_s), got {sweep.transient_s:g}")
    if sweep.wind_speeds_m_s and not sweep.system:
        raise ConfigError("sweep: wind speeds need a turbine: give a named system (--system)")
    if sweep.discon_changes != ("",) and not sweep.system:
        raise ConfigError("sweep: controller changes need a turbine: give a named system (--system)")
    if not sweep.discon_changes or len(set(sweep.discon_changes)) != len(sweep.discon_changes):
        raise ConfigError(f"sweep: discon_changes must be distinct, got {list(sweep.discon_changes)}")
    if sweep.system:
        from fowt_hydro_sim.turbine.system import load_system
        chosen = load_system(sweep.system)
        if not sweep.wind_speeds_m_s:
            raise ConfigError("sweep: a system's sweep needs wind speeds")
        if len(set(sweep.wind_speeds_m_s)) != len(sweep.wind_speeds_m_s):
            raise ConfigError("sweep: wind_speeds has duplicates")
        if any(not (isinstance(w, float) and math.isfinite(w) and 0 < w <= 80) for w in sweep.wind_speeds_m_s):
            raise ConfigError(f"sweep: wind speeds must be numbers in (0, 80] m/s, got {list(sweep.wind_speeds_m_s)}")
        other = [v.name for v in sweep.variants if v.platform != chosen.platform]
        if other:
            raise ConfigError(f"sweep: variant {other[0]!r}: with system {chosen.name!r} a variant edits its "
                              f"platform {chosen.platform!r}")
        from fowt_hydro_sim.turbine.description import load_turbine
        for changes in sweep.discon_changes:  # a name its DISCON.IN has not: refused before any run
            load_turbine(chosen.turbine, discon_changes=changes)


def _variant(data: Any, where: str) -> Variant:
    if not isinstance(data, dict) or "name" not in data:
        raise ConfigError(f"{where}: expected a mapping with a name")
    unknown = set(data) - {"name", "platform", "coefficients", *_SCALES}
    if unknown:
        raise ConfigError(f"{where}: unknown field(s) {', '.join(sorted(unknown))}")
    coefficients = data.get("coefficients") or {}
    if not isinstance(coefficients, dict):
        raise ConfigError(f"{where}.coefficients: expected a mapping of coefficient path to value")
    try:
        scales = {s: float(data[s]) for s in _SCALES if s in data}
        values = tuple((str(k), float(v)) for k, v in coefficients.items())
    except (TypeError, ValueError) as exc:
        raise ConfigError(f"{where}: scales and coefficients must be numbers ({exc})") from None
    return Variant(str(data["name"]), str(data.get("platform", DEFAULT_PLATFORM)), coefficients=values, **scales)


def sweep_from_dict(data: Any, source: str = "sweep") -> Sweep:
    """A sweep from a mapping (a sweep YAML file)::

        load_cases: [lc5.2, lc5.3]
        seeds: [1, 2, 3]                 # or a count: 3 (seeds 1..3)
        drag_models: [constant, filtered]
        variants:                        # default: the packaged platform as it is
          - {name: base}
          - {name: cd_plus_20, cd_scale: 1.2}
          - {name: stiff, platform: my_platform.yaml, mooring_stiffness_scale: 1.5,
             coefficients: {column*.submerged.cd.constant: 0.9}}
        run: {duration_s: 3600, dt_s: 0.05, output_interval_s: 0.25}
        transient_s: 600

    or, the coupled turbine (variants: of the system's platform, by default as it is)::

        system: iea15_volturnus_s
        wind_speeds: [8, 12, 18]
        discon_changes: ["", "Fl_Kp=-5.0", "Fl_Kp=0"]   # controller variants (DISCON.IN entries)
        load_cases: [lc5.3]
        seeds: 3
    """
    if not isinstance(data, dict):
        raise ConfigError(f"{source}: expected a mapping")
    unknown = set(data) - {"load_cases", "seeds", "drag_models", "variants", "run", "transient_s", "system",
                           "wind_speeds", "discon_changes"}
    if unknown:
        raise ConfigError(f"{source}: unknown field(s) {', '.join(sorted(unknown))}")

    def names(key: str, default: Any = None) -> tuple:
        value = data.get(key, default)
        if value is None:
            raise ConfigError(f"{source}: {key}: missing")
        return tuple(value) if isinstance(value, list) else (value,)

    seeds = data.get("seeds", 1)
    seeds = tuple(range(1, seeds + 1)) if isinstance(seeds, int) and not isinstance(seeds, bool) else names("seeds")
    system = str(data.get("system") or "")
    if system and "variants" in data:
        system_platform = system_variants(system)[0].platform
        variants = tuple(_variant({"platform": system_platform, **v} if isinstance(v, dict) else v,
                                  f"{source}: variants[{i}]") for i, v in enumerate(names("variants")))
    elif system:
        variants = system_variants(system)
    else:
        variants = tuple(_variant(v, f"{source}: variants[{i}]")
                         for i, v in enumerate(names("variants", [{"name": "base"}])))
    try:
        transient_s = float(data.get("transient_s", 0.0))
        winds = tuple(float(w) for w in names("wind_speeds", [])) if "wind_speeds" in data else (
            (DEFAULT_WIND_M_S,) if system else ())
    except (TypeError, ValueError):
        raise ConfigError(f"{source}: transient_s and wind_speeds: must be numbers") from None
    controllers = tuple("" if c is None else str(c) for c in names("discon_changes", [""]))
    return Sweep(tuple(str(c) for c in names("load_cases")), seeds,
                 tuple(str(d) for d in names("drag_models", ["constant"])),
                 variants, run_from_dict(data.get("run") or {}, f"{source}: run"), transient_s, system, winds,
                 controllers)


def load_sweep_file(path: str | Path) -> Sweep:
    """A sweep from its YAML file; ConfigError naming the problem."""
    path = Path(path)
    try:
        data = yaml.safe_load(path.read_text())
    except (OSError, yaml.YAMLError) as exc:
        raise ConfigError(f"{path}: cannot be read as YAML ({str(exc).splitlines()[0]})") from None
    return sweep_from_dict(data, path.name)


# ---------------------------------------------------------------------- one run (a cluster task)
def metric_names(coupled: bool = False) -> list[str]:
    """The statistics columns of a row, units in the names (``coupled``: and the turbine's)."""
    out = []
    for j, name in enumerate(DOF_NAMES):
        unit = "deg" if j >= 3 else "m"
        out += [f"{name}_{s}_{unit}" for s in _STATS] + [f"{name}_std_{b}_{unit}" for b in BANDS_HZ]
    out += ["wave_hs_4std_m", *TENSION_METRICS]
    if coupled:
        out += [f"{short}_{s}_{unit}" for _, short, unit in TURBINE_METRICS for s in _STATS]
        out += list(TOWER_METRICS)
    return out


# a coupled row's turbine columns: (channel of turbine.coupled.CHANNELS, name, unit), each its mean, STD, min, max
TURBINE_METRICS = (("rotor_speed_rad_s", "rotor_speed", "rad_s"), ("blade_pitch_rad", "blade_pitch", "rad"),
                   ("generator_torque_nm", "generator_torque", "nm"), ("generator_power_w", "generator_power", "w"),
                   ("thrust_n", "thrust", "n"))


# the mooring's fairlead tensions in a row: each statistic of the line where it is largest
TENSION_METRICS = ("fairlead_tension_mean_n", "fairlead_tension_std_n", "fairlead_tension_max_n",
                   "fairlead_tension_del_n")


def tension_metrics(time_s: np.ndarray, tensions: np.ndarray, transient_s: float) -> dict[str, float]:
    """The row's tension columns from each line's fairlead tension (n, lines, 2) after the
    transient: mean, STD, maximum and DEL (``studies.tensions``, S-N slope 3), each the
    largest over the lines; NaN without lines."""
    from fowt_hydro_sim.studies.tensions import tension_rows
    rows = tension_rows("", time_s, {f"line{i + 1}": tensions[:, i, 0] for i in range(tensions.shape[1])},
                        transient_s)
    keys = ("mean_n", "std_n", "max_n", "del_n")
    return {name: max((r[key] for r in rows), default=float("nan")) for name, key in zip(TENSION_METRICS, keys)}


def columns(coupled: bool = False) -> list[str]:
    """A runs table's columns (``coupled``: a system's sweep)."""
    return [*(COUPLED_KEY if coupled else KEY), "hs_m", "tp_s", "gamma", *metric_names(coupled), "wall_time_s",
            "real_time_factor"]


def row_of(key: dict, sea: SeaState, stats: dict, performance: dict, tensions: dict[str, float]) -> dict:
    """A table row: the run's key, its sea state, its statistics (``simulate.statistics``) and
    its fairlead tensions' (``tension_metrics``)."""
    row: dict = {**key, "hs_m": sea.hs_m, "tp_s": sea.tp_s, "gamma": sea.gamma}
    for j, name in enumerate(DOF_NAMES):
        s, unit = stats[name], "deg" if j >= 3 else "m"
        row.update({f"{name}_{k}_{unit}": s[k] for k in _STATS})
        row.update({f"{name}_std_{b}_{unit}": (s["band_std"] or {}).get(b, float("nan")) for b in BANDS_HZ})
    row["wave_hs_4std_m"] = stats["wave_elevation"]["hs_4std"]
    row.update(tensions)
    return {**row, "wall_time_s": performance["wall_time_s"], "real_time_factor": performance["real_time_factor"]}


def sea_of(key: dict) -> SeaState:
    spec = load_case(key["load_case"]).sea_state
    return replace(spec, seed=int(key["seed"]))


def run_name(key: dict) -> str:
    """A run's folder name: ``lc5.3_seed1_constant_base`` (a coupled run's: ``lc5.3_wind12_seed1_...``,
    with controller changes ``lc5.3_wind12_Fl_Kp=-5_seed1_...``)."""
    wind = f"_wind{key[WIND]:g}" if WIND in key else ""
    if key.get(CONTROLLER):
        wind += "_" + re.sub(r"[^A-Za-z0-9.=+-]+", "_", key[CONTROLLER]).strip("_")
    return f"{key['load_case']}{wind}_seed{key['seed']}_{key['drag_model']}_{key['variant']}"


def run_coupled_one(key: dict, platform: Platform, run: RunConfig, transient_s: float, system: str,
                    bag_folder: str | None) -> dict:
    """One run of a system's sweep (what ``fowt-sim simulate --system SYSTEM --wind-speed W``
    does with these settings), as a row; with ``bag_folder``, its time series also go to a
    folder there named after the run, as ``simulate`` writes them (``timeseries.csv``, and a
    ``summary.json`` of its settings: ``fowt-sim analyze`` reads it)."""
    from fowt_hydro_sim.studies.coupled_run import channel_statistics, run_coupled_case
    from fowt_hydro_sim.turbine.settings import TurbineSettings
    from fowt_hydro_sim.turbine.system import load_system
    sea = sea_of(key)
    waves, info = sea_state_waves(sea, run.duration_s, key["load_case"])
    settings = replace(run, drag_model=key["drag_model"])
    turbine = TurbineSettings(turbine=load_system(system).turbine, wind_speed_m_s=float(key[WIND]),
                              discon_changes=key[CONTROLLER])
    folder = Path(bag_folder) / run_name(key) if bag_folder is not None else None
    if folder is not None:
        folder.mkdir(parents=True, exist_ok=True)
    done = run_coupled_case(platform, settings, turbine, waves, timeseries=folder and folder / "timeseries.csv")
    record = done.rows.motion
    if folder is not None:
        (folder / "summary.json").write_text(json.dumps(
            {"sweep_run": key, "system": system, "platform": platform.name, "drag_model": settings.drag_model,
             "waves": info, "run": asdict(settings), "turbine": done.turbine}, indent=2, default=list) + "\n")
    row = row_of(key, sea, statistics(record, transient_s), done.performance,
                 tension_metrics(record.time_s, record.tensions, transient_s))
    turbine_stats = channel_statistics(record.time_s, done.rows.channels, transient_s)
    for channel, short, unit in TURBINE_METRICS:
        row.update({f"{short}_{s}_{unit}": turbine_stats[channel][s] for s in _STATS})
    row.update(tower_base_metrics(record.time_s, done.rows, platform, done.turbine["thrust_height_m"], transient_s))
    return row


def run_one(key: dict, platform: Platform, run: RunConfig, transient_s: float, bag_folder: str | None) -> dict:
    """One run of the sweep (what ``fowt-sim simulate`` does with these settings), as a row;
    with ``bag_folder``, its outputs also go to a bag there named after the run."""
    sea = sea_of(key)
    waves, info = sea_state_waves(sea, run.duration_s, key["load_case"])
    settings = replace(run, drag_model=key["drag_model"])
    start = time.perf_counter()
    model = model_for(platform, settings, waves)
    built = time.perf_counter()
    result = model.run(settings.duration_s, output_interval_s=settings.output_interval_s)
    performance = performance_of(settings, start, built, time.perf_counter())
    line_tensions = model.mooring_tensions(result.time_s, result.motion)
    if bag_folder is not None:
        write_bag(Path(bag_folder) / run_name(key), result, {"sweep_run": key, "waves": info,
                                                             "run": asdict(settings), "platform": platform.name},
                  line_tensions)
    tensions = tension_metrics(result.time_s, line_tensions, transient_s)
    return row_of(key, sea, statistics(result, transient_s), performance, tensions)


def write_bag(path: Path, result: RunResult, config: dict, tensions: np.ndarray | None = None) -> None:
    """The run's outputs on the node's contract topics (as ``fowt-sim node`` records them),
    with each mooring line's tensions (n, lines, 2: fairlead, anchor [N]) on its
    ``/platform/mooring/lineN/tension`` topic when the platform has lines."""
    from fowt_hydro_sim.physics.loads import PUBLISHED, ROW, SUMMED
    from fowt_hydro_sim.rosbag.writer import BagWriter, qos_profiles
    from msg_adapters import cdr, topics
    from msg_adapters.sim_time import nanoseconds

    config = json.loads(json.dumps(config, default=list))  # plain YAML types
    total = result.loads[:, [ROW[c] for c in SUMMED]].sum(axis=1)
    samples = cdr.outputs(result.time_s, result.motion, result.velocity, result.acceleration,
                          result.loads[:, [ROW[c] for c in PUBLISHED]], total, result.wave_elevation_m,
                          "world", "platform")
    outputs = list(topics.outputs(PUBLISHED).values())
    if tensions is not None and tensions.shape[1]:
        outputs += [(topics.tension_topic(i + 1), topics.VECTOR3_STAMPED) for i in range(tensions.shape[1])]
        lines = zip(*map(cdr.messages, cdr.tension_blocks(result.time_s, tensions, "world")))
        samples = [[*row, *line] for row, line in zip(samples, lines)]
    with BagWriter(path, config=config, overwrite=True) as bag:
        channels = [bag.add_topic(topic, kind, qos_profiles()) for topic, kind in outputs]
        bag.write_rows((nanoseconds(t), zip(channels, messages))
                       for t, messages in zip(result.time_s.tolist(), samples))


# ---------------------------------------------------------------------- the table on disk
def _line(row: dict) -> str:
    buffer = io.StringIO()
    csv.writer(buffer, lineterminator="\n").writerow([row[c] for c in columns(WIND in row)])
    return buffer.getvalue()


def _value(column: str, text: str) -> Any:
    if column in ("load_case", "drag_model", "variant", CONTROLLER):
        return text
    return int(text) if column == "seed" else float(text)


def read_rows(path: Path, coupled: bool = False) -> list[dict]:
    """The finished rows of a runs table (``coupled``: a system's sweep's; a last line cut
    short by an interruption is left out, and cut off the file so that appending goes on
    cleanly)."""
    if not path.exists():
        return []
    text = path.read_text()
    if not text.endswith("\n"):
        text = text[: text.rfind("\n") + 1]
        path.write_text(text)
    lines = text.splitlines()
    if not lines:
        return []
    if lines[0].split(",") != columns(coupled):
        raise ConfigError(f"{path}: its columns are not this version's sweep table's (use another output folder)")
    return [{c: _value(c, v) for c, v in zip(columns(coupled), values)} for values in csv.reader(lines[1:])]


def append_row(path: Path, row: dict) -> None:
    """Append one row in one write, flushed to disk (a kill leaves at most a cut last line)."""
    new = not path.exists() or path.stat().st_size == 0
    with open(path, "a") as f:
        f.write((",".join(columns(WIND in row)) + "\n" if new else "") + _line(row))
        f.flush()
        os.fsync(f.fileno())


def prepare_output(folder: Path, sweep: Sweep, overwrite: bool) -> list[dict]:
    """Make the folder ready and return the rows already finished there; ConfigError if they
    were made with other run settings or variants of the same name."""
    folder.mkdir(parents=True, exist_ok=True)
    settings_path = folder / SETTINGS_FILE
    if overwrite:
        for name in (RUNS_FILE, SUMMARY_FILE, SETTINGS_FILE, "runs.parquet", "summary.parquet"):
            (folder / name).unlink(missing_ok=True)
    document = sweep.settings_document()
    if settings_path.exists():
        old = json.loads(settings_path.read_text())
        if old.get("system", "") != document.get("system", ""):
            raise ConfigError(f"{folder}: holds a sweep of system {old.get('system') or '(none: the platform alone)'}"
                              f"; pass --overwrite to start again or use another folder")
        if old["run"] != document["run"] or old["transient_s"] != document["transient_s"]:
            raise ConfigError(f"{folder}: holds a sweep with other run settings ({old['run']}, transient "
                              f"{old['transient_s']:g} s); pass --overwrite to start again or use another folder")
        for name, variant in document["variants"].items():
            if name in old["variants"] and old["variants"][name] != variant:
                raise ConfigError(f"{folder}: variant {name!r} was defined otherwise there; rename it")
        document["variants"] = {**old["variants"], **document["variants"]}
    elif (folder / RUNS_FILE).exists():
        raise ConfigError(f"{folder}: has {RUNS_FILE} without {SETTINGS_FILE}; pass --overwrite")
    settings_path.write_text(json.dumps(document, indent=2) + "\n")
    return read_rows(folder / RUNS_FILE, sweep.coupled)


# ---------------------------------------------------------------------- means over seeds
STUDENT_T = "student_t"  # interval of the mean of any statistic
LOGNORMAL = "lognormal_cox"  # interval of the mean of a positive one (an STD, Hs)


def is_positive(metric: str) -> bool:
    """Whether a statistic of ``metric_names`` can only be positive (an STD or Hs = 4 STD)."""
    return "_std_" in metric or metric.endswith("_4std_m")


def confidence_interval(values: np.ndarray, level: float, positive: bool = False) -> tuple[float, float, float, float]:
    """Mean, sample standard deviation and the confidence interval (low, high) at ``level``
    of the mean of ``values`` over seeds (NaN interval for fewer than two values).

    Any statistic: the Student-t interval, mean +- t s / sqrt(n). A ``positive`` one (an
    STD): the log-normal interval of the mean by Cox's method with Student's t (Olsson,
    J. Stat. Educ. 13(1), 2005): with y = ln(values), mean ybar and variance s^2,
    exp(ybar + s^2/2 +- t sqrt(s^2/n + s^4/(2(n-1)))). It never goes below zero; with two
    seeds it is wide (t has one degree of freedom) but positive. Values of exactly zero (a
    DOF the waves do not excite) have no logarithm: then the Student-t interval, its lower
    end clipped at zero."""
    import scipy.stats  # here: 2 s of start-up for the commands that build no summary

    values = np.asarray(values, dtype=float)
    n = values.size
    mean = float(values.mean())
    if n < 2:
        return mean, float("nan"), float("nan"), float("nan")
    std = float(values.std(ddof=1))
    t = float(scipy.stats.t.ppf(0.5 + level / 2, n - 1))
    if positive and np.all(values > 0):
        logs = np.log(values)
        variance = float(logs.var(ddof=1))
        centre = float(logs.mean()) + variance / 2
        half = t * math.sqrt(variance / n + variance**2 / (2 * (n - 1)))
        return mean, std, math.exp(centre - half), math.exp(centre + half)
    half = t * std / math.sqrt(n)
    return mean, std, max(mean - half, 0.0) if positive else mean - half, mean + half


def summarise(rows: list[dict], level: float = 0.95) -> list[dict]:
    """Per load case, drag model and variant (and wind speed in a system's sweep; in the
    rows' order), every statistic's mean over the seeds with its confidence interval
    (``confidence_interval``: log-normal for STDs, Student-t for the others, named in the
    row's ``interval``): one row per statistic."""
    coupled = bool(rows) and WIND in rows[0]
    by = COUPLED_GROUP if coupled else GROUP
    groups: dict[tuple, list[dict]] = {}
    for row in rows:
        groups.setdefault(tuple(row[g] for g in by), []).append(row)
    out = []
    for group, members in groups.items():
        for metric in metric_names(coupled):
            positive = is_positive(metric)
            mean, std, low, high = confidence_interval(np.array([r[metric] for r in members]), level, positive)
            out.append({**dict(zip(by, group)), "statistic": metric, "n_seeds": len(members), "mean": mean,
                        "std_over_seeds": std, "ci_low": low, "ci_high": high, "confidence": level,
                        "interval": LOGNORMAL if positive else STUDENT_T})
    return out


def write_summary(folder: Path, rows: list[dict], level: float) -> list[Path]:
    """``summary.csv`` (and Parquet copies of both tables when pyarrow can be imported)."""
    summary = summarise(rows, level)
    with open(folder / SUMMARY_FILE, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(summary[0]), lineterminator="\n")
        writer.writeheader()
        writer.writerows(summary)
    written = [folder / RUNS_FILE, folder / SUMMARY_FILE]
    try:
        import pyarrow
        import pyarrow.parquet
    except ImportError:
        log.info("pyarrow cannot be imported: CSV tables only")
        return written
    for name, table in (("runs.parquet", rows), ("summary.parquet", summary)):
        pyarrow.parquet.write_table(pyarrow.Table.from_pylist(table), folder / name)
        written.append(folder / name)
    return written


# ---------------------------------------------------------------------- the sweep
def order(rows: Iterable[dict], sweep: Sweep) -> list[dict]:
    """The rows of this sweep in table order."""
    by_key = {tuple(r[k] for k in sweep.key): r for r in rows}
    return [by_key[k] for k in (tuple(run[c] for c in sweep.key) for run in sweep.runs()) if k in by_key]


def run_sweep(sweep: Sweep, folder: str | Path, scheduler: str | None = None, workers: int | None = None,
              bags: bool = False, level: float = 0.95, overwrite: bool = False) -> dict:
    """Run the sweep's unfinished runs on a Dask cluster, appending each row to ``runs.csv``
    as it finishes, then write ``summary.csv``; returns counts, wall time and files."""
    from fowt_hydro_sim.studies.cluster import dask_client, results_as_completed
    if not 0 < level < 1:
        raise ConfigError(f"confidence level must be in (0, 1), got {level:g}")
    folder = Path(folder)
    platforms = {v.name: v.build() for v in sweep.variants}  # bad variants fail before any cluster starts
    done = prepare_output(folder, sweep, overwrite)
    finished = {tuple(r[k] for k in sweep.key) for r in done}
    todo = [key for key in sweep.runs() if tuple(key[k] for k in sweep.key) not in finished]
    log.info("%d runs, %d already finished in %s", len(sweep.runs()), len(sweep.runs()) - len(todo), folder)
    start = time.perf_counter()
    if todo:
        bag_folder = str(folder / "bags") if bags else None
        tasks = [(key, platforms[key["variant"]]) for key in todo]
        if sweep.coupled:  # ROSCO's banner written at once, inside the window where it is logged, not at the
            # worker's exit on the command's output (gfortran buffers a standard output that is no terminal)
            os.environ.setdefault("GFORTRAN_UNBUFFERED_PRECONNECTED", "y")
        with dask_client(scheduler, workers) as client:
            for row in results_as_completed(client, _task, tasks, "sweep", done=len(sweep.runs()) - len(todo),
                                            run=sweep.run_settings(), transient_s=sweep.transient_s,
                                            system=sweep.system, bag_folder=bag_folder):
                append_row(folder / RUNS_FILE, row)
    rows = order(read_rows(folder / RUNS_FILE, sweep.coupled), sweep)
    files = write_summary(folder, rows, level)
    return {"runs": len(rows), "new": len(todo), "wall_s": time.perf_counter() - start,
            "files": [str(f) for f in files], "summary": summarise(rows, level)}


def _task(task: tuple[dict, Platform], run: RunConfig, transient_s: float, system: str,
          bag_folder: str | None) -> dict:
    key, platform = task
    if system:
        return run_coupled_one(key, platform, run, transient_s, system, bag_folder)
    return run_one(key, platform, run, transient_s, bag_folder)


SHOWN = ("surge_std_low_frequency_m", "heave_std_wave_m", "pitch_std_wave_deg")
SHOWN_COUPLED = ("surge_mean_m", "pitch_std_wave_deg", "rotor_speed_std_rad_s", "generator_power_mean_w",
                 "tower_base_moment_del_nm")


def summary_text(outcome: dict, statistics_shown: tuple[str, ...] | None = None) -> str:
    """A few statistics' means and intervals per load case (and wind speed), as the command
    prints them."""
    coupled = bool(outcome["summary"]) and WIND in outcome["summary"][0]
    statistics_shown = statistics_shown or (SHOWN_COUPLED if coupled else SHOWN)
    shown = [r for r in outcome["summary"] if r["statistic"] in statistics_shown]
    level = shown[0]["confidence"] if shown else 0.95
    lines = [f"{outcome['runs']} runs ({outcome['new']} new) in {outcome['wall_s']:.1f} s; mean over seeds "
             f"[{100 * level:g} % confidence interval: Student-t, log-normal for STDs]"]
    width = max([14, *(len(r["variant"]) + 2 for r in shown)])
    for r in shown:
        interval = f"[{r['ci_low']:.4g}, {r['ci_high']:.4g}]" if r["n_seeds"] > 1 else "(one seed)"
        wind = f"{r[WIND]:5g} m/s  " + (f"{r[CONTROLLER]}  " if r[CONTROLLER] else "") if coupled else ""
        lines.append(f"{r['load_case']:8s}{wind}{r['drag_model']:10s}{r['variant']:{width}s}{r['statistic']:28s}"
                     f"{r['mean']:10.4g} {interval}  n={r['n_seeds']}")
    lines.append("wrote " + ", ".join(outcome["files"]))
    return "\n".join(lines)
