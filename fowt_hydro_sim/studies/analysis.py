"""Offline analysis of recorded runs (the metric of docs/load_cases.md): Welch PSD
of each DOF, band STDs with chi-square confidence intervals, and against a reference run
(measured, or another simulation) the STD error per DOF and band, pass/fail at a
threshold and the pass rate, as in the paper's tables.

Confidence: a band variance from a record of T seconds has about ``band_dof`` degrees of
freedom, so its STD lies in a chi-square interval, and the ratio of two runs' band
variances in an F interval; each Welch PSD bin has ``welch_dof`` degrees of freedom, and
the PSD figure shades its chi-square band. An error whose interval excludes zero is "significant": a
real gap rather than sampling noise.

A run is a bag (recorded by the node, or measured) or the folder ``fowt-sim simulate``
writes (timeseries.csv, summary.json). Its figures say its sea state, drag model and
record length, mark Tp and the platform's natural frequencies, and say when the spectral
resolution is too coarse for the low-frequency band.
"""
from __future__ import annotations

import csv
import dataclasses
import json
import math
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np
import scipy.stats
import yaml

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.model import DOF_NAMES
from fowt_hydro_sim.studies.figures import pyplot
from fowt_hydro_sim.studies.psd import (
    BANDS_HZ,
    SEGMENT_S,
    TRANSIENT_S,
    band_dof,
    band_std,
    psd,
    psd_interval,
    welch_dof,
)

ANGULAR = {"roll", "pitch", "yaw"}  # analysed in degrees
MIN_BINS_BELOW_RESONANCE = 10  # a resonance at f is resolved with at least this many PSD bins below f


@dataclass(frozen=True)
class RunContext:
    """What the figures say about a run: sea state, drag model, the platform's natural
    frequencies by DOF (each mode named after the DOF holding most of its kinetic energy)."""

    hs_m: float | None = None
    tp_s: float | None = None
    gamma: float | None = None
    drag_model: str | None = None
    natural_hz: dict[str, float] = field(default_factory=dict)

    def text(self) -> str:
        sea = (f"Hs {self.hs_m:g} m, Tp {self.tp_s:g} s, gamma {self.gamma:g}" if self.hs_m else
               "still water" if self.hs_m == 0 else "")
        return ", ".join(filter(None, (sea, f"drag {self.drag_model}" if self.drag_model else "")))


def natural_frequencies_hz(platform) -> dict[str, float]:
    """Undamped natural frequencies of the linearised platform, one per mode, named after
    the DOF with the largest share of the mode's kinetic energy (|v_i|^2 M_ii). MoorDyn's
    lines are linearised as their quasi-static catenaries (the moorpy model of the same file:
    MoorDyn's static lines within 0.3 %, docs/validation.md)."""
    from fowt_hydro_sim.physics.model import PlatformModel
    if platform.mooring.model == "moordyn":
        platform = dataclasses.replace(platform, mooring=platform.mooring.chosen("moorpy"))
    model = PlatformModel(platform, None)
    mass = model.mass_matrix()
    eigenvalues, vectors = np.linalg.eig(np.linalg.solve(mass, model.restoring_matrix()))
    found: dict[str, float] = {}
    for value, vector in sorted(zip(eigenvalues.real, vectors.T), key=lambda pair: pair[0]):
        if value > 0:
            dof = DOF_NAMES[int(np.argmax(np.abs(vector) ** 2 * np.diag(mass)))]
            found.setdefault(dof, math.sqrt(value) / (2 * math.pi))
    return found


def resolution_note(frequency_hz: np.ndarray, natural_hz: dict[str, float]) -> str:
    """'' if each natural frequency has enough PSD bins below it; else which are not resolved."""
    df = float(frequency_hz[1] - frequency_hz[0])
    coarse = [f"{dof} {f:.4f} Hz" for dof, f in natural_hz.items() if f < MIN_BINS_BELOW_RESONANCE * df]
    return (f"resonance NOT RESOLVED ({', '.join(coarse)}; df {df:.4f} Hz): run longer or use longer segments"
            if coarse else "")


def unit(dof: str) -> str:
    return "deg" if dof in ANGULAR else "m"


@dataclass(frozen=True)
class AnalysisSettings:
    """How runs are analysed and compared (the CLI's options)."""

    transient_s: float = TRANSIENT_S  # discarded at the start of each run (as fowt-sim simulate does)
    segment_s: float = SEGMENT_S  # Welch segment
    window: str = "hann"
    overlap: float = 0.5
    dofs: tuple[str, ...] = ("surge", "heave", "pitch")
    bands_hz: dict[str, dict[str, tuple[float, float]]] = field(default_factory=dict)  # per DOF; default BANDS_HZ
    threshold: float = 0.15  # |STD error| within this passes
    confidence: float = 0.90

    def bands(self, dof: str) -> dict[str, tuple[float, float]]:
        return self.bands_hz.get(dof, BANDS_HZ)


@dataclass
class RunAnalysis:
    """One run's spectra and band statistics, per DOF and band."""

    name: str
    analysed_s: float
    frequency_hz: np.ndarray
    psd: dict[str, np.ndarray]
    std: dict[str, dict[str, float]]
    dof_nu: dict[str, dict[str, float]]  # equivalent degrees of freedom of each band variance
    std_interval: dict[str, dict[str, tuple[float, float]]]
    context: RunContext = field(default_factory=RunContext)
    psd_nu: float = float("nan")  # equivalent degrees of freedom of each PSD bin (psd.welch_dof)


def uniform(time_s: np.ndarray, values: np.ndarray) -> tuple[float, np.ndarray]:
    """(step, values) on a uniform grid at the median step (linear interpolation)."""
    step = float(np.median(np.diff(time_s)))
    if step <= 0:
        raise InputError("analysis: stamps do not increase")
    grid = np.arange(time_s[0], time_s[-1] + 0.5 * step, step)
    return step, np.column_stack([np.interp(grid, time_s, column) for column in values.T])


def analyse(name: str, time_s: np.ndarray, motion: np.ndarray, settings: AnalysisSettings,
            context: RunContext = RunContext()) -> RunAnalysis:
    """Spectra and band STDs of a run's 6-DOF motion (surge ... yaw, angles in rad)."""
    keep = time_s >= time_s[0] + settings.transient_s
    if keep.sum() < 64:
        raise InputError(f"run {name}: {time_s[-1] - time_s[0]:.0f} s recorded, nothing left after the "
                         f"{settings.transient_s:g} s transient (--transient)")
    step, values = uniform(time_s[keep], motion[keep])
    analysed_s = step * len(values)
    spectra, stds, nus, intervals = {}, {}, {}, {}
    alpha = 1.0 - settings.confidence
    for dof in settings.dofs:
        column = values[:, DOF_NAMES.index(dof)] * (180.0 / math.pi if dof in ANGULAR else 1.0)
        frequency, spectra[dof] = psd(column, step, settings.segment_s, settings.window, settings.overlap)
        stds[dof], nus[dof], intervals[dof] = {}, {}, {}
        for band, limits in settings.bands(dof).items():
            std = band_std(frequency, spectra[dof], limits)
            nu = band_dof(frequency, spectra[dof], limits, analysed_s)
            stds[dof][band], nus[dof][band] = std, nu
            intervals[dof][band] = (std * math.sqrt(nu / scipy.stats.chi2.ppf(1 - alpha / 2, nu)),
                                    std * math.sqrt(nu / scipy.stats.chi2.ppf(alpha / 2, nu))) if nu > 0 else \
                (float("nan"), float("nan"))
    nu = welch_dof(len(values), step, settings.segment_s, settings.window, settings.overlap)
    return RunAnalysis(name, analysed_s, frequency, spectra, stds, nus, intervals, context, nu)


def compare(run: RunAnalysis, reference: RunAnalysis, settings: AnalysisSettings) -> list[dict]:
    """One row per DOF and band: both STDs, the error (run - ref) / ref in percent with its
    confidence interval (F distribution of the variance ratio), pass and significance."""
    rows, alpha = [], 1.0 - settings.confidence
    for dof in settings.dofs:
        for band in settings.bands(dof):
            s, r = run.std[dof][band], reference.std[dof][band]
            nu_s, nu_r = run.dof_nu[dof][band], reference.dof_nu[dof][band]
            error = 100.0 * (s / r - 1.0) if r > 0 else float("nan")
            ratio = (s / r) ** 2 if r > 0 else float("nan")
            low = ratio / scipy.stats.f.ppf(1 - alpha / 2, nu_s, nu_r)
            high = ratio / scipy.stats.f.ppf(alpha / 2, nu_s, nu_r)
            interval = (100.0 * (math.sqrt(low) - 1.0), 100.0 * (math.sqrt(high) - 1.0))
            rows.append({"run": run.name, "reference": reference.name, "dof": dof, "unit": unit(dof), "band": band,
                         "std_run": s, "std_reference": r, "error_percent": error,
                         "error_low_percent": interval[0], "error_high_percent": interval[1],
                         "passes": bool(abs(error) <= 100.0 * settings.threshold),
                         "significant": bool(interval[0] > 0 or interval[1] < 0)})
    return rows


def pass_rate(rows: list[dict]) -> float:
    return sum(r["passes"] for r in rows) / len(rows) if rows else float("nan")


def stats_rows(analyses: list[RunAnalysis]) -> list[dict]:
    """Band STDs with their confidence intervals, one row per run, DOF and band."""
    return [{"run": a.name, "dof": dof, "unit": unit(dof), "band": band, "std": a.std[dof][band],
             "std_low": a.std_interval[dof][band][0], "std_high": a.std_interval[dof][band][1],
             "dof_equivalent": a.dof_nu[dof][band], "analysed_s": a.analysed_s}
            for a in analyses for dof in a.std for band in a.std[dof]]


def table_text(analyses: list[RunAnalysis], comparisons: list[dict], settings: AnalysisSettings) -> str:
    """The terminal table: band STDs (and errors against the reference, the paper's Table 4
    layout: one line per run, DOF and band) and the pass rate per run and overall."""
    conf = f"{100 * settings.confidence:g} %"
    if not comparisons:
        lines = [f"{'run':<18}{'DOF':<8}{'band':<15}{'STD':>10}   {conf} interval"]
        lines += [f"{r['run']:<18}{r['dof']:<8}{r['band']:<15}{r['std']:>10.4g}   [{r['std_low']:.4g}, "
                  f"{r['std_high']:.4g}] {r['unit']}" for r in stats_rows(analyses)]
        return "\n".join(lines)
    lines = [f"{'run':<18}{'DOF':<8}{'band':<15}{'STD':>10}{'reference':>11}{'error':>9}   {conf} interval   pass"]
    for r in comparisons:
        flag = "yes" if r["passes"] else "NO"
        star = " *" if r["significant"] else ""
        lines.append(f"{r['run']:<18}{r['dof']:<8}{r['band']:<15}{r['std_run']:>10.4g}{r['std_reference']:>11.4g}"
                     f"{r['error_percent']:>+8.1f}%   [{r['error_low_percent']:+.1f}, {r['error_high_percent']:+.1f}] %"
                     f"   {flag}{star}")
    for run in dict.fromkeys(r["run"] for r in comparisons):
        mine = [r for r in comparisons if r["run"] == run]
        lines.append(f"{run}: {sum(r['passes'] for r in mine)}/{len(mine)} within "
                     f"+-{100 * settings.threshold:g} %")
    lines.append(f"pass rate: {100 * pass_rate(comparisons):.0f} % of {len(comparisons)} band metrics "
                 f"(* = significant at {conf})")
    return "\n".join(lines)


def write_report(analyses: list[RunAnalysis], comparisons: list[dict], settings: AnalysisSettings,
                 folder: Path, references: list[RunAnalysis] = ()) -> list[Path]:
    """CSV and JSON tables and PNG figures in ``folder``; returns the files written."""
    folder.mkdir(parents=True, exist_ok=True)
    written = [_csv(folder / "band_stds.csv", stats_rows([*analyses, *references]))]
    if comparisons:
        written.append(_csv(folder / "errors.csv", comparisons))
    summary = {"settings": {**asdict(settings), "bands_hz": {d: settings.bands(d) for d in settings.dofs}},
               "band_stds": stats_rows([*analyses, *references]), "errors": comparisons,
               "pass_rate": pass_rate(comparisons) if comparisons else None}
    (folder / "analysis.json").write_text(json.dumps(summary, indent=1))
    written.append(folder / "analysis.json")
    (folder / "table.txt").write_text(table_text(analyses, comparisons, settings) + "\n")
    written.append(folder / "table.txt")
    pairs = _pairs(analyses, references)
    for run, reference in pairs:
        written.append(plot_psd(run, reference, settings, folder / f"psd_{_slug(run.name)}.png"))
        figure = folder / f"band_stds_{_slug(run.name)}.png"
        if reference is not None:
            written.append(plot_band_errors([r for r in comparisons if r["run"] == run.name], settings, figure))
        else:
            written.append(plot_band_stds(run, settings, figure))
    return [path for path in written if path is not None]  # figures: None without matplotlib


def load_run(path: str | Path) -> tuple[np.ndarray, np.ndarray, RunContext]:
    """Stamps, 6-DOF motion (angles in rad) and context of a bag, or of a ``fowt-sim
    simulate`` output folder (timeseries.csv and summary.json)."""
    from fowt_hydro_sim.physics.config import load_platform, platform_from_dict
    from fowt_hydro_sim.rosbag.reader import Bag
    from fowt_hydro_sim.rosbag.writer import METADATA_FILE
    path = Path(path)
    if (path / "timeseries.csv").is_file() and not (path / METADATA_FILE).exists():
        from fowt_hydro_sim.studies.simulate import read_run
        columns = read_run(path)
        summary = json.loads((path / "summary.json").read_text()) if (path / "summary.json").is_file() else {}
        waves = summary.get("waves", {})
        try:
            natural = natural_frequencies_hz(load_platform(summary.get("platform", "windmoor12")))
        except ValueError:  # a platform file no longer where it was: no natural frequencies marked
            natural = {}
        context = RunContext(waves.get("hs_m"), waves.get("tp_s"), waves.get("gamma"), summary.get("drag_model"),
                             natural)
        motion = np.column_stack([columns[c] for c in ("surge_m", "sway_m", "heave_m", "roll_rad", "pitch_rad",
                                                       "yaw_rad")])
        return columns["time_s"], motion, context
    bag = Bag(path)
    motion = bag.motion()
    config = bag.config or {}
    sea = config.get("sea_state") or {}
    platform_yaml = config.get("platform_yaml")
    natural = natural_frequencies_hz(platform_from_dict(yaml.safe_load(platform_yaml), path.name)) \
        if platform_yaml else {}
    context = RunContext(sea.get("hs_m"), sea.get("tp_s"), sea.get("gamma"),
                         (config.get("parameters") or {}).get("drag_model"), natural)
    return motion.time_s, motion.values, context


def analyze_bags(runs: list[str | Path], references: list[str | Path], settings: AnalysisSettings,
                 output: Path) -> tuple[str, list[Path]]:
    """``fowt-sim analyze``: every run (bag or simulate folder) analysed, against one
    reference for all or one per run; the table's text and the report's files."""
    if references and len(references) not in (1, len(runs)):
        raise InputError(f"--ref: give one reference, or one per run ({len(runs)}), got {len(references)}")

    def load(path: str | Path) -> RunAnalysis:
        time_s, motion, context = load_run(path)
        return analyse(Path(path).name, time_s, motion, settings, context)

    analysed = [load(p) for p in runs]
    reference_runs = [load(p) for p in references]
    pairs = list(zip(analysed, reference_runs * len(analysed) if len(reference_runs) == 1 else reference_runs))
    comparisons = [row for run, ref in pairs for row in compare(run, ref, settings)]
    text = (f"each run analysed after its first {settings.transient_s:g} s (start-up transient dropped, as "
            f"fowt-sim simulate does; --transient)\n" + table_text(analysed, comparisons, settings))
    files = write_report(analysed, comparisons, settings, Path(output), reference_runs)
    loop_text, loop_files = closed_loop_report(runs, settings, Path(output))
    turbine_text, turbine_files = turbine_report(runs, settings, Path(output))
    tension_text, tension_files = tension_report(runs, settings, Path(output))
    return (text + loop_text + turbine_text + tension_text, files + loop_files + turbine_files + tension_files)


# the turbine side analysed: (timeseries.csv column or bag topic short name, quantity, unit, scale to that unit)
TURBINE_QUANTITIES = (("rotor_speed_rad_s", "rotor_speed", "rpm", 60 / (2 * math.pi)),
                      ("blade_pitch_rad", "blade_pitch", "deg", 180 / math.pi),
                      ("generator_torque_nm", "generator_torque", "MN m", 1e-6),
                      ("generator_power_w", "generator_power", "MW", 1e-6),
                      ("thrust_n", "thrust", "MN", 1e-6))
TOWER_BASE = ("tower_base_moment", "MN m", 1e-6)


def turbine_series(path: str | Path) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """A coupled run's turbine channels [SI] by quantity (``TURBINE_QUANTITIES``) and its
    tower-base fore-aft bending moment [N m] (``studies.turbine_loads``): from a simulate
    folder of a coupled run all of them (the moment when its platform has an ElastoDyn
    deck); from a bag the turbine topics it holds (no thrust there: no moment); none for a
    run without a turbine."""
    from fowt_hydro_sim.physics.config import load_platform
    from fowt_hydro_sim.rosbag.reader import Bag
    from fowt_hydro_sim.rosbag.writer import METADATA_FILE
    from fowt_hydro_sim.studies.turbine_loads import above_tower_base, tower_base_moment
    from msg_adapters import topics
    path = Path(path)
    if (path / METADATA_FILE).exists():
        bag = Bag(path)
        out, time_s = {}, None
        for _, quantity, _, _ in TURBINE_QUANTITIES:
            if quantity in topics.TURBINE and topics.TURBINE[quantity][0] in bag.topics:
                series = bag.scalar(topics.TURBINE[quantity][0])
                if time_s is None:  # the first topic's stamps; the others at them (a topic may miss a sample)
                    time_s = series.time_s
                out[quantity] = np.interp(time_s, series.time_s, series.values[:, 0])
        return (np.zeros(0) if time_s is None else time_s), out
    from fowt_hydro_sim.studies.simulate import read_run
    columns = read_run(path)
    if "thrust_n" not in columns:
        return columns["time_s"], {}
    out = {quantity: columns[column] for column, quantity, _, _ in TURBINE_QUANTITIES}
    summary = json.loads((path / "summary.json").read_text()) if (path / "summary.json").is_file() else {}
    try:
        platform = load_platform(summary["platform"])
    except (KeyError, ValueError):  # no summary, or a platform file no longer where it was
        return columns["time_s"], out
    above = above_tower_base(platform)
    if above is not None and "turbine" in summary:
        dofs = list(zip(DOF_NAMES, ("m", "m", "m", "rad", "rad", "rad")))
        motion, velocity, acceleration = (np.column_stack([columns[pattern.format(d=d, u=u)] for d, u in dofs])
                                          for pattern in ("{d}_{u}", "{d}_velocity_{u}_s", "{d}_acceleration_{u}_s2"))
        out[TOWER_BASE[0]] = tower_base_moment(motion, velocity, acceleration, columns["thrust_n"], above,
                                               (platform.hub_point_m[0], summary["turbine"]["thrust_height_m"]),
                                               platform.environment.gravity_m_s2)
    return columns["time_s"], out


def turbine_report(runs: list[str | Path], settings: AnalysisSettings, folder: Path) -> tuple[str, list[Path]]:
    """For the runs with a turbine: each quantity's (rotor speed, blade pitch, generator
    torque and power, thrust, tower-base fore-aft moment) mean, STD, maximum and DEL
    (rainflow, S-N slope m = 10 of the steel tower, 1 Hz equivalent over the analysed time)
    after the transient, in ``turbine.csv``, and their PSDs (``turbine_psd_RUN.png``)."""
    from fowt_hydro_sim.studies.turbine_loads import channel_row
    units = {quantity: (unit, scale) for _, quantity, unit, scale in TURBINE_QUANTITIES}
    units[TOWER_BASE[0]] = TOWER_BASE[1:]
    folder.mkdir(parents=True, exist_ok=True)
    rows, files = [], []
    for path in runs:
        time_s, series = turbine_series(path)
        keep = time_s >= time_s[0] + settings.transient_s if time_s.size else time_s.astype(bool)
        if not series or keep.sum() < 2:
            continue
        name = Path(path).name
        duration = float(time_s[keep][-1] - time_s[keep][0])
        scaled = {quantity: values[keep] * units[quantity][1] for quantity, values in series.items()}
        rows += [{"run": name, **channel_row(quantity, values, duration), "unit": units[quantity][0]}
                 for quantity, values in scaled.items()]
        files.append(plot_turbine_psd(name, time_s[keep], scaled, units, settings,
                                      folder / f"turbine_psd_{_slug(name)}.png"))
    if not rows:
        return "", []
    files = [path for path in files if path is not None]  # figures: None without matplotlib or too short
    files.append(_csv(folder / "turbine.csv", rows))
    lines = ["", f"turbine (after {settings.transient_s:g} s; DEL: rainflow, S-N slope m = {rows[0]['sn_slope']:g}, "
                 f"1 Hz equivalent cycles):"]
    lines += [f"  {r['run']:<16} {r['quantity']:<18} mean {r['mean']:10.4g} std {r['std']:9.3g} max {r['max']:10.4g} "
              f"DEL {r['del']:9.3g} {r['unit']}" for r in rows]
    return "\n".join(lines), files


def plot_turbine_psd(name: str, time_s: np.ndarray, series: dict[str, np.ndarray],
                     units: dict[str, tuple[str, float]], settings: AnalysisSettings, path: Path) -> Path | None:
    """Each turbine quantity's PSD, one panel each (None without matplotlib or too short)."""
    plt = pyplot()
    if plt is None or time_s.size < 64:
        return None
    dt, _ = uniform(time_s, np.zeros((time_s.size, 1)))
    fig, axes = plt.subplots(len(series), 1, figsize=(7.5, 2.0 * len(series)), sharex=True, squeeze=False)
    for ax, (quantity, values) in zip(axes[:, 0], series.items()):
        _, grid = uniform(time_s, values[:, None])
        frequency, density = psd(grid[:, 0] - grid[:, 0].mean(), dt, settings.segment_s)
        if np.any(density[1:] > 0):  # (a channel held constant, e.g. the power above rated, has no spectrum)
            ax.semilogy(frequency[1:], density[1:], lw=0.9)
        ax.set_ylabel(f"{quantity}\n[{units[quantity][0]}$^2$/Hz]", fontsize=8)
        ax.grid(alpha=0.3, which="both")
    axes[0, 0].set_xlim(0, 0.5)
    axes[0, 0].set_title(f"turbine PSDs: {name}, after {settings.transient_s:g} s", fontsize=9)
    axes[-1, 0].set_xlabel("frequency [Hz]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def run_tensions(path: str | Path) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """A run's mooring tensions: time [s] and each series (``line1_fairlead``, ``line1_anchor``
    ...) [N], from a simulate folder's tension columns or a bag's /platform/mooring topics;
    no series for a run without them."""
    from fowt_hydro_sim.rosbag.reader import Bag
    from fowt_hydro_sim.rosbag.writer import METADATA_FILE
    from msg_adapters import topics
    path = Path(path)
    if not (path / METADATA_FILE).exists():
        from fowt_hydro_sim.studies.simulate import read_run
        columns = read_run(path)
        return columns["time_s"], {name[:-len("_tension_n")]: values for name, values in columns.items()
                                   if name.endswith("_tension_n")}
    bag = Bag(path)
    out, time_s = {}, np.zeros(0)
    line = 1
    while topics.tension_topic(line) in bag.topics:
        series = bag.series(topics.tension_topic(line))
        time_s = series.time_s
        out[f"line{line}_fairlead"], out[f"line{line}_anchor"] = series.values[:, 0], series.values[:, 1]
        line += 1
    return time_s, out


def tension_report(runs: list[str | Path], settings: AnalysisSettings, folder: Path) -> tuple[str, list[Path]]:
    """For the runs with mooring tensions: each line's fairlead and anchor tension mean, STD,
    maximum and damage-equivalent load (studies.tensions: rainflow, S-N slope m = 3, 1 Hz
    equivalent) after the transient, in ``tensions.csv``, and the fairlead tensions' PSDs."""
    from fowt_hydro_sim.studies.tensions import tension_rows
    rows, files = [], []
    for path in runs:
        time_s, series = run_tensions(path)
        if not series:
            continue
        name = Path(path).name
        rows += tension_rows(name, time_s, series, settings.transient_s)
        files.append(plot_tension_psd(name, time_s, series, settings, folder / f"tension_psd_{_slug(name)}.png"))
    if not rows:
        return "", []
    files = [path for path in files if path is not None]  # figures: None without matplotlib
    files.append(_csv(folder / "tensions.csv", rows))
    lines = ["", f"mooring tensions (after {settings.transient_s:g} s; DEL: rainflow, S-N slope m = "
                 f"{rows[0]['sn_slope']:g}, 1 Hz equivalent cycles):"]
    lines += [f"  {r['run']:<16} {r['tension']:<16} mean {r['mean_n'] / 1e3:9.1f} kN  std {r['std_n'] / 1e3:8.1f} kN  "
              f"max {r['max_n'] / 1e3:9.1f} kN  DEL {r['del_n'] / 1e3:8.1f} kN" for r in rows]
    return "\n".join(lines), files


def plot_tension_psd(name: str, time_s: np.ndarray, series: dict[str, np.ndarray], settings: AnalysisSettings,
                     path: Path) -> Path | None:
    """The fairlead tensions' PSDs after the transient (None without matplotlib or too short)."""
    plt = pyplot()
    keep = time_s >= time_s[0] + settings.transient_s
    if plt is None or keep.sum() < 64:
        return None
    dt, _ = uniform(time_s[keep], np.zeros((int(keep.sum()), 1)))
    fig, ax = plt.subplots(figsize=(8.0, 4.0))
    for channel, values in series.items():
        if channel.endswith("_fairlead") and np.all(np.isfinite(values[keep])):
            frequency, density = psd(values[keep] / 1e3, dt, settings.segment_s)
            ax.semilogy(frequency, density, lw=0.9, label=channel)
    ax.set_xlim(0, 0.5)
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("fairlead tension PSD [kN$^2$/Hz]")
    ax.set_title(f"mooring tensions: {name}")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def closed_loop_report(runs: list[str | Path], settings: AnalysisSettings, folder: Path) -> tuple[str, list[Path]]:
    """For the runs with a turbine (a closed loop): time-series plots of rotor speed, pitch,
    power, platform pitch and surge, and their statistics after the transient."""
    from fowt_hydro_sim.rosbag.reader import Bag
    from fowt_hydro_sim.rosbag.writer import METADATA_FILE
    from fowt_hydro_sim.studies import turbine_plots
    rows, files = [], []
    for path in runs:
        if not (Path(path) / METADATA_FILE).exists():  # a simulate folder: no turbine
            continue
        bag = Bag(path)
        if not turbine_plots.has_turbine(bag):
            continue
        name = Path(path).name
        series = turbine_plots.closed_loop_series(bag)
        rows += turbine_plots.stats_rows(name, series, settings.transient_s)
        files.append(turbine_plots.plot_closed_loop(name, series, folder / f"closed_loop_{_slug(name)}.png"))
    if not rows:
        return "", []
    files = [path for path in files if path is not None]  # figures: None without matplotlib
    files.append(_csv(folder / "closed_loop.csv", rows))
    lines = ["", f"closed loop (after {settings.transient_s:g} s):"]
    lines += [f"  {r['run']:<16} {r['quantity']:<16} mean {r['mean']:10.4g} std {r['std']:9.3g} "
              f"min {r['min']:10.4g} max {r['max']:10.4g} {r['unit']}" for r in rows]
    return "\n".join(lines), files


def _pairs(analyses, references):
    if not references:
        return [(a, None) for a in analyses]
    if len(references) == 1:
        return [(a, references[0]) for a in analyses]
    return list(zip(analyses, references))


def _slug(name: str) -> str:
    return "".join(c if c.isalnum() or c in "-_." else "_" for c in name)


def _csv(path: Path, rows: list[dict]) -> Path:
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    return path


def psd_labels(run: RunAnalysis, reference: RunAnalysis | None, dofs: tuple[str, ...],
               confidence: float = 0.9) -> dict[str, object]:
    """The PSD figure's title lines, legend names (with the run's chi-square confidence band
    at ``confidence``) and marked frequencies (label: Hz) of the DOFs shown."""
    context = dataclasses.replace(run.context, natural_hz={d: f for d, f in run.context.natural_hz.items()
                                                           if d in dofs})
    title = [f"PSD: {run.name}" + (f" vs reference {reference.name}" if reference else ""),
             ", ".join(filter(None, (context.text(), f"{run.analysed_s:.0f} s analysed, "
                                     f"df {run.frequency_hz[1] - run.frequency_hz[0]:.4f} Hz")))]
    note = resolution_note(run.frequency_hz, context.natural_hz)
    marks = {f"{dof} {1 / f:.0f} s": f for dof, f in context.natural_hz.items()}
    if context.tp_s:
        marks[f"Tp {context.tp_s:g} s"] = 1.0 / context.tp_s
    return {"title": title + ([note] if note else []), "run": f"run: {run.name}",
            "reference": f"reference: {reference.name}" if reference else None, "marks": marks,
            "band": f"run's {100 * confidence:g} % confidence band (chi-square, {run.psd_nu:.1f} dof)"}


def plot_psd(run: RunAnalysis, reference: RunAnalysis | None, settings: AnalysisSettings, path: Path) -> Path | None:
    """PSD of each DOF, the run against the reference, log axes, bands shaded, Tp and the
    natural frequencies marked; the title says the sea state, drag model and record length."""
    labels = psd_labels(run, reference, settings.dofs, settings.confidence)
    plt = pyplot()
    if plt is None:
        return None
    fig, axes = plt.subplots(len(settings.dofs), 1, figsize=(7.5, 2.8 * len(settings.dofs)), sharex=True,
                             squeeze=False)
    for ax, dof in zip(axes[:, 0], settings.dofs):
        for (band, (low, high)), colour in zip(settings.bands(dof).items(), ("tab:orange", "tab:blue", "tab:green")):
            ax.axvspan(low, high, color=colour, alpha=0.08, label=f"{band} band")
        if math.isfinite(run.psd_nu):
            low, high = psd_interval(run.psd[dof][1:], run.psd_nu, settings.confidence)
            ax.fill_between(run.frequency_hz[1:], low, high, color="tab:blue", alpha=0.2, lw=0, label=labels["band"])
        for analysis, style, name in ((reference, "k-", labels["reference"]), (run, "-", labels["run"])):
            if analysis is not None:
                f, s = analysis.frequency_hz, analysis.psd[dof]
                ax.loglog(f[1:], s[1:], style, lw=1.0, label=name)
        for text, frequency in labels["marks"].items():
            ax.axvline(frequency, color="0.4", ls=":", lw=0.8)
            if dof == settings.dofs[-1]:
                ax.annotate(text, (frequency, 0.02), xycoords=("data", "axes fraction"), rotation=90, fontsize=7,
                            va="bottom", ha="right", color="0.3")
        ax.set_ylabel(f"{dof} [{unit(dof)}$^2$/Hz]")
        ax.grid(alpha=0.3, which="both")
        ax.set_xlim(0.002, 0.5)
        top = max(a.psd[dof].max() for a in (run, reference) if a is not None)
        ax.set_ylim(top * 1e-6, top * 3)
    axes[0, 0].legend(fontsize=8, loc="lower left")
    axes[0, 0].set_title("\n".join(labels["title"]), fontsize=9, color="tab:red" if len(labels["title"]) > 2 else "k")
    axes[-1, 0].set_xlabel("frequency [Hz]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_band_stds(run: RunAnalysis, settings: AnalysisSettings, path: Path) -> Path | None:
    """The run's band STDs as bars, one panel per DOF, with their chi-square confidence
    intervals (the figure without a reference)."""
    plt = pyplot()
    if plt is None:
        return None
    fig, axes = plt.subplots(1, len(settings.dofs), figsize=(3.0 * len(settings.dofs) + 1.0, 3.8), squeeze=False)
    for ax, dof in zip(axes[0], settings.dofs):
        bands = list(settings.bands(dof))
        std = np.array([run.std[dof][b] for b in bands])
        low = np.array([run.std_interval[dof][b][0] for b in bands])
        high = np.array([run.std_interval[dof][b][1] for b in bands])
        x = np.arange(len(bands))
        ax.bar(x, std, 0.6, color="tab:blue", yerr=[std - low, high - std], capsize=4, ecolor="0.3")
        for i, value in enumerate(std):
            ax.annotate(f"{value:.3g}", (i, value), ha="right", va="bottom", fontsize=8, xytext=(-6, 2),
                        textcoords="offset points")
        ax.set_xticks(x, bands, fontsize=8)
        ax.set_ylabel(f"{dof} band STD [{unit(dof)}]")
        ax.grid(alpha=0.3, axis="y")
    fig.suptitle(f"band STDs: {run.name}, {run.analysed_s:.0f} s analysed; {100 * settings.confidence:g} % "
                 f"confidence intervals (chi-square)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_band_errors(rows: list[dict], settings: AnalysisSettings, path: Path) -> Path | None:
    """Band STDs of run and reference as bars, the error and its interval annotated."""
    plt = pyplot()
    if plt is None:
        return None
    fig, ax = plt.subplots(figsize=(max(6.0, 1.1 * len(rows)), 3.8))
    x = np.arange(len(rows))
    ratio_ref = np.ones(len(rows))
    ratio_run = np.array([r["std_run"] / r["std_reference"] if r["std_reference"] > 0 else np.nan for r in rows])
    ax.bar(x - 0.2, ratio_ref, 0.4, color="0.6", label=f"reference: {rows[0]['reference']}")
    low = 1 + np.array([r["error_low_percent"] for r in rows]) / 100
    high = 1 + np.array([r["error_high_percent"] for r in rows]) / 100
    ax.bar(x + 0.2, ratio_run, 0.4, color=["tab:green" if r["passes"] else "tab:red" for r in rows],
           label=f"run: {rows[0]['run']}", yerr=[ratio_run - low, high - ratio_run], capsize=3, ecolor="0.3")
    for i, r in enumerate(rows):
        ax.annotate(f"{r['error_percent']:+.0f} %" + ("*" if r["significant"] else ""), (i + 0.2, ratio_run[i]),
                    ha="center", va="bottom", fontsize=8)
    ax.axhspan(1 - settings.threshold, 1 + settings.threshold, color="tab:green", alpha=0.08)
    ax.set_xticks(x, [f"{r['dof']}\n{r['band']}" for r in rows], fontsize=8)
    ax.set_ylabel("band STD / reference")
    ax.set_title(f"band STDs, +-{100 * settings.threshold:g} % shaded; {100 * settings.confidence:g} % "
                 f"intervals, * significant")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
