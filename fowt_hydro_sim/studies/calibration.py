"""Drag calibration against measured runs, regression of the fitted Cds over Hs/D, and the
blind prediction (docs/load_cases.md).

Each measured run (a bag with /waves/elevation and /platform/pose) is replayed through
the model with its own elevation record (``studies.replay``), so model and measurement see
the same waves. The Cds named by parameter paths (``physics.platform_edits``, e.g.
``column*.submerged.cd.low_frequency``) are fitted to the band STDs by regularised least
squares: residuals are the band STD errors per DOF and band, plus a weak pull of log Cd
toward its starting value so that Cds the metrics cannot tell apart stay put. The
Jacobian's runs (one per Cd) go out together to a Dask cluster, which is what makes the
fit take few wall seconds per run.
"""
from __future__ import annotations

import json
import logging
import math
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, replace
from functools import partial
from pathlib import Path

import numpy as np
import scipy.optimize
import yaml

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.config import Platform, RunConfig, platform_document
from fowt_hydro_sim.physics.platform_edits import coefficient, widest_circular_diameter_m, with_coefficients
from fowt_hydro_sim.studies.analysis import AnalysisSettings, RunAnalysis, analyse
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant
from fowt_hydro_sim.studies.replay import replay as replay_variant

log = logging.getLogger(__name__)

PRIOR_WEIGHT = 0.02  # residual per unit of log(Cd / start): weak
FD_STEP = 0.05  # forward-difference step in log Cd
RESULT_FILE = "calibration.json"
DT_S = RunConfig.dt_s  # the replays' step: the run configuration's default


# ---------------------------------------------------------------------- one replay
def replay(platform: Platform, run: MeasuredRun, drag_model: str, heading_deg: float = 0.0,
           dt_s: float = DT_S) -> tuple[np.ndarray, np.ndarray]:
    """Time and 6-DOF motion of the model with this platform, driven by the run's elevation
    record (time 0 = the record's first sample)."""
    return replay_variant(Variant(platform, drag_model), replace(run, heading_deg=heading_deg), dt_s)


def errors(model: RunAnalysis, measured: RunAnalysis, settings: AnalysisSettings) -> np.ndarray:
    """Relative band STD errors (model - measured) / measured, per DOF and band."""
    return np.array([model.std[d][b] / measured.std[d][b] - 1.0 for d in settings.dofs for b in settings.bands(d)])


def replay_errors(platform: Platform, run: MeasuredRun, measured: RunAnalysis, settings: AnalysisSettings,
                  drag_model: str, heading_deg: float, dt_s: float = DT_S) -> np.ndarray:
    """Band STD errors of one replay (a task for the cluster)."""
    time_s, motion = replay(platform, run, drag_model, heading_deg, dt_s)
    return errors(analyse("model", time_s, motion, settings), measured, settings)


# ---------------------------------------------------------------------- fitting
@dataclass
class Calibration:
    """The outcome of calibrating one measured run."""

    run: str
    hs_m: float
    parameters: dict[str, float]  # fitted
    start: dict[str, float]
    errors_before: dict[str, float]  # "dof.band": percent
    errors_after: dict[str, float]
    model_runs: int
    wall_s: float

    def as_dict(self) -> dict:
        return dict(self.__dict__)


def calibrate(run: MeasuredRun, platform: Platform, parameters: list[str], settings: AnalysisSettings,
              map_runs: Callable[[list[Platform]], list[np.ndarray]] | None = None, drag_model: str = "filtered",
              heading_deg: float = 0.0, bounds: tuple[float, float] = (0.02, 20.0), max_iterations: int = 8,
              dt_s: float = DT_S) -> Calibration:
    """Fit ``parameters`` of ``platform`` to the run's band STDs. ``map_runs`` evaluates a
    list of platforms (the default runs them here, one after another)."""
    start_time = time.perf_counter()
    measured = analyse(run.name, run.motion_time_s, run.motion, settings)
    start = {p: coefficient(platform, p) for p in parameters}
    x0 = np.log(np.array([start[p] for p in parameters]))
    if map_runs is None:
        map_runs = lambda platforms: [replay_errors(p, run, measured, settings, drag_model, heading_deg, dt_s)
                                      for p in platforms]
    cache: dict[bytes, np.ndarray] = {}
    count = [0]

    def platforms(xs: list[np.ndarray]) -> list[Platform]:
        return [with_coefficients(platform, dict(zip(parameters, np.exp(x)))) for x in xs]

    def evaluate(xs: list[np.ndarray]) -> list[np.ndarray]:
        todo = [x for x in xs if x.tobytes() not in cache]
        for x, e in zip(todo, map_runs(platforms(todo))):
            cache[x.tobytes()] = e
        count[0] += len(todo)
        return [cache[x.tobytes()] for x in xs]

    def residual(x: np.ndarray) -> np.ndarray:
        return np.concatenate([evaluate([x])[0], PRIOR_WEIGHT * (x - x0)])

    def jacobian(x: np.ndarray) -> np.ndarray:
        steps = [x + FD_STEP * np.eye(len(x))[i] for i in range(len(x))]
        base, *shifted = evaluate([x, *steps])
        columns = [(e - base) / FD_STEP for e in shifted]
        return np.vstack([np.column_stack(columns), PRIOR_WEIGHT * np.eye(len(x))])

    before = evaluate([x0])[0]
    fit = scipy.optimize.least_squares(residual, x0, jac=jacobian, bounds=np.log(bounds), method="trf",
                                       max_nfev=max_iterations, x_scale=1.0, xtol=1e-3, ftol=1e-4)
    after = evaluate([fit.x])[0]
    names = [f"{d}.{b}" for d in settings.dofs for b in settings.bands(d)]
    return Calibration(run.name, run.hs_m, dict(zip(parameters, np.exp(fit.x).tolist())), start,
                       dict(zip(names, (100 * before).tolist())), dict(zip(names, (100 * after).tolist())),
                       count[0], time.perf_counter() - start_time)


def cluster_map(client, run: MeasuredRun, measured: RunAnalysis, settings: AnalysisSettings, drag_model: str,
                heading_deg: float, dt_s: float = DT_S, position: int = 0):
    """``map_runs`` on the cluster: the replays of platforms, their band STD errors in order."""
    from fowt_hydro_sim.studies.cluster import map_with_progress
    task = partial(replay_errors, settings=settings, drag_model=drag_model, heading_deg=heading_deg, dt_s=dt_s)
    return lambda platforms: map_with_progress(client, task, platforms, f"{run.name}: model runs", position,
                                               run=run, measured=measured)


def calibrate_all(client, runs: list[MeasuredRun], platform: Platform, parameters: list[str],
                  settings: AnalysisSettings, drag_model: str = "filtered", heading_deg: float = 0.0,
                  max_iterations: int = 8, dt_s: float = DT_S) -> list[Calibration]:
    """Calibrate every run, all at once on the cluster (each run's fit in its own thread,
    so the workers stay busy while one fit waits for a single run)."""
    def one(index_run: tuple[int, MeasuredRun]) -> Calibration:
        index, run = index_run
        measured = analyse(run.name, run.motion_time_s, run.motion, settings)
        return calibrate(run, platform, parameters, settings,
                         cluster_map(client, run, measured, settings, drag_model, heading_deg, dt_s, index),
                         drag_model, heading_deg, max_iterations=max_iterations, dt_s=dt_s)

    with ThreadPoolExecutor(max_workers=len(runs)) as pool:
        return list(pool.map(one, enumerate(runs)))


def fit_runs(runs: list[MeasuredRun], platform: Platform, platform_name: str, parameters: list[str],
             settings: AnalysisSettings, output: Path, drag_model: str = "filtered", heading_deg: float = 0.0,
             diameter_m: float | None = None, max_iterations: int = 8, dt_s: float = DT_S,
             scheduler: str | None = None, workers: int | None = None) -> list[str]:
    """``fowt-sim calibrate``: fit every run on a Dask cluster, write ``calibration.json``;
    returns the report's lines."""
    from fowt_hydro_sim.studies.cluster import dask_client
    diameter = diameter_m or widest_circular_diameter_m(platform)
    for p in parameters:
        coefficient(platform, p)  # a bad path fails before any run
    with dask_client(scheduler, workers) as client:
        results = calibrate_all(client, runs, platform, parameters, settings, drag_model, heading_deg,
                                max_iterations, dt_s)
    lines = []
    for run, result in zip(runs, results):
        lines += [f"{run.name} (Hs {run.hs_m:.2f} m, Hs/D {run.hs_m / diameter:.3f}): "
                  f"{result.model_runs} model runs, {result.wall_s:.0f} s",
                  f"  fitted: {', '.join(f'{k} {v:.3f}' for k, v in result.parameters.items())}",
                  f"  errors before: {error_table(result.errors_before)} (RMS {rms(result.errors_before):.1f} %)",
                  f"  errors after:  {error_table(result.errors_after)} (RMS {rms(result.errors_after):.1f} %)"]
    output.mkdir(parents=True, exist_ok=True)
    payload = {"platform": platform_name, "platform_document": platform_document(platform), "drag_model": drag_model,
               "diameter_m": diameter, "parameters": parameters, "dofs": list(settings.dofs),
               "transient_s": settings.transient_s, "dt_s": dt_s,
               "runs": [{**r.as_dict(), "hs_over_d": r.hs_m / diameter} for r in results]}
    (output / RESULT_FILE).write_text(json.dumps(payload, indent=1))
    log.info(f"{output / RESULT_FILE}: {sum(r.model_runs for r in results)} model runs, "
             f"{sum(r.wall_s for r in results):.0f} s")
    return lines


# ---------------------------------------------------------------------- regression
def regress(hs_over_d: np.ndarray, values: np.ndarray, degree: int = 2) -> np.ndarray:
    """Polynomial coefficients (highest power first) of a Cd against Hs/D; the degree drops
    to what the number of points allows."""
    degree = min(degree, len(hs_over_d) - 1)
    if degree < 0:
        raise InputError("regression: no calibrated runs")
    return np.polyfit(hs_over_d, values, degree)


def predict(coefficients: dict[str, np.ndarray], hs_over_d: float, floor: float = 0.02) -> dict[str, float]:
    """Cds for a new sea state from the regressions (never below ``floor``)."""
    return {p: max(floor, float(np.polyval(c, hs_over_d))) for p, c in coefficients.items()}


def regression_report(calibration_file: Path, output: Path, degree: int = 2, blind: MeasuredRun | None = None,
                      predict_hs_m: float | None = None, heading_deg: float = 0.0) -> list[str]:
    """``fowt-sim calibrate --regress``: each Cd of a calibration against Hs/D; with a blind run
    (or an Hs), the predicted Cds, ``platform_predicted.yaml`` and the blind run with the
    start and the predicted Cds (``blind.json``). Returns the report's lines."""
    from fowt_hydro_sim.physics.config import platform_from_dict
    data = json.loads(Path(calibration_file).read_text())
    runs = data["runs"]
    x = np.array([r["hs_over_d"] for r in runs])
    coefficients = {p: regress(x, np.array([r["parameters"][p] for r in runs]), degree) for p in data["parameters"]}
    lines = [f"Cd against Hs/D over {len(runs)} runs (polynomial, highest power first):"]
    lines += [f"  {p}: {np.array2string(c, precision=4)}" for p, c in coefficients.items()]
    if blind is None and predict_hs_m is None:
        return lines
    platform = platform_from_dict(data["platform_document"], str(calibration_file))
    hs = blind.hs_m if blind else predict_hs_m
    predicted = predict(coefficients, hs / data["diameter_m"])
    lines.append(f"predicted for Hs {hs:.2f} m (Hs/D {hs / data['diameter_m']:.3f}): "
                 + ", ".join(f"{k} {v:.3f}" for k, v in predicted.items()))
    output.mkdir(parents=True, exist_ok=True)
    platform_file = output / "platform_predicted.yaml"
    predicted_platform = with_coefficients(platform, predicted)
    platform_file.write_text(yaml.safe_dump(platform_document(predicted_platform), sort_keys=False))
    lines.append(f"platform with the predicted Cds: {platform_file}")
    if blind is not None:
        settings = AnalysisSettings(transient_s=data["transient_s"], dofs=tuple(data["dofs"]))
        measured = analyse(blind.name, blind.motion_time_s, blind.motion, settings)
        names = [f"{d}.{b}" for d in settings.dofs for b in settings.bands(d)]
        blind_errors = {}
        for label, candidate in (("start Cds", platform), ("predicted Cds", predicted_platform)):
            e = replay_errors(candidate, blind, measured, settings, data["drag_model"], heading_deg, data["dt_s"])
            blind_errors[label] = dict(zip(names, (100 * e).tolist()))
            lines.append(f"blind {blind.name}, {label}: {error_table(blind_errors[label])} "
                         f"(RMS {rms(blind_errors[label]):.1f} %)")
        (output / "blind.json").write_text(json.dumps({"run": blind.name, "hs_m": hs, "predicted": predicted,
                                                      "errors": blind_errors}, indent=1))
    return lines


def error_table(values: dict[str, float]) -> str:
    return ", ".join(f"{k} {v:+.1f} %" for k, v in values.items())


def rms(values: dict[str, float]) -> float:
    return math.sqrt(sum(v * v for v in values.values()) / len(values)) if values else float("nan")
