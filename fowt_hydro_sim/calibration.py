"""Drag calibration against measured runs, regression of the fitted Cds over Hs/D, and the
blind prediction (shared/spec/load_cases.md).

Each measured run (a bag with /waves/elevation and /platform/pose) is replayed through
the model with its own elevation record (replay.py),
so model and measurement see the same waves. The Cds named by parameter paths are fitted
to the band STDs by regularised least squares: residuals are the band STD errors per
DOF and band, plus a weak pull of log Cd toward its starting value so that Cds the
metrics cannot tell apart stay put. The Jacobian's runs (one per Cd) go out together to a
Dask cluster, which is what makes the fit take few wall seconds per run.

Parameter paths: ``MEMBERS.ZONE.FIELD[.BAND]`` on the platform YAML, with shell-style
patterns for members, e.g. ``column*.submerged.cd.low_frequency``,
``pontoon*.submerged.cd_horizontal.wave``, ``pontoon*.submerged.cd_vertical``, or
``MEMBERS.end_a_plate.cd``.
"""
from __future__ import annotations

import fnmatch
import json
import logging
import math
import time
from dataclasses import dataclass, replace
from typing import Callable

import numpy as np
import scipy.optimize

from .analysis import AnalysisSettings, RunAnalysis, analyse
from .config import ConfigError
from .replay import MeasuredRun, Variant
from .replay import replay as replay_variant

log = logging.getLogger(__name__)

PRIOR_WEIGHT = 0.02  # residual per unit of log(Cd / start): weak
FD_STEP = 0.05  # forward-difference step in log Cd


# ---------------------------------------------------------------------- parameters
def _targets(document: dict, path: str) -> list[tuple[dict, str, str | None]]:
    """(mapping holding the field, field, band or None) for every member matching ``path``."""
    parts = path.split(".")
    if len(parts) not in (3, 4):
        raise ConfigError(f"parameter {path!r}: expected MEMBERS.ZONE.FIELD[.BAND] or MEMBERS.end_a_plate.cd")
    members = [m for m in document.get("members", []) if fnmatch.fnmatch(m.get("name", ""), parts[0])]
    if not members:
        raise ConfigError(f"parameter {path!r}: no member matches {parts[0]!r}")
    band = parts[3] if len(parts) == 4 else None
    found = []
    for member in members:
        if parts[1] in ("end_a_plate", "end_b_plate"):
            holder = member.get(parts[1])
        else:
            holder = next((z for z in member.get("zones", []) if z.get("name") == parts[1]), None)
        if holder is None or parts[2] not in holder:
            raise ConfigError(f"parameter {path!r}: member {member.get('name')} has no {parts[1]}.{parts[2]}")
        value = holder[parts[2]]
        if band is not None and not (isinstance(value, dict) and band in value):
            raise ConfigError(f"parameter {path!r}: {member.get('name')}.{parts[1]}.{parts[2]} has no band {band!r}")
        found.append((holder, parts[2], band))
    return found


def get_parameter(document: dict, path: str) -> float:
    """A parameter's value (the first matching member's)."""
    holder, field, band = _targets(document, path)[0]
    return float(holder[field][band] if band else holder[field])


def with_parameters(document: dict, values: dict[str, float]) -> dict:
    """A copy of the platform document with the parameters set (on every matching member)."""
    document = json.loads(json.dumps(document))  # a copy in which YAML aliases no longer share mappings
    for path, value in values.items():
        for holder, field, band in _targets(document, path):
            if band is None:
                holder[field] = float(value)
            else:
                holder[field][band] = float(value)
    return document


# ---------------------------------------------------------------------- one replay
def replay(document: dict, run: MeasuredRun, drag_model: str, heading_deg: float = 0.0,
           dt_s: float = 0.05) -> tuple[np.ndarray, np.ndarray]:
    """Time and 6-DOF motion of the model with this platform document, driven by the run's
    elevation record (time 0 = the record's first sample)."""
    return replay_variant(Variant(document, drag_model), replace(run, heading_deg=heading_deg), dt_s)


def errors(model: RunAnalysis, measured: RunAnalysis, settings: AnalysisSettings) -> np.ndarray:
    """Relative band STD errors (model - measured) / measured, per DOF and band."""
    return np.array([model.std[d][b] / measured.std[d][b] - 1.0 for d in settings.dofs for b in settings.bands(d)])


def replay_errors(document: dict, run: MeasuredRun, measured: RunAnalysis, settings: AnalysisSettings,
                   drag_model: str, heading_deg: float) -> np.ndarray:
    """Band STD errors of one replay (a task for the cluster)."""
    time_s, motion = replay(document, run, drag_model, heading_deg)
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


def calibrate(run: MeasuredRun, document: dict, parameters: list[str], settings: AnalysisSettings,
              map_runs: Callable[[list[dict]], list[np.ndarray]] | None = None, drag_model: str = "filtered",
              heading_deg: float = 0.0, bounds: tuple[float, float] = (0.02, 20.0), max_iterations: int = 8,
              ) -> Calibration:
    """Fit ``parameters`` of ``document`` to the run's band STDs. ``map_runs`` evaluates a
    list of platform documents (the default runs them here, one after another)."""
    start_time = time.perf_counter()
    measured = analyse(run.name, run.motion_time_s, run.motion, settings)
    start = {p: get_parameter(document, p) for p in parameters}
    x0 = np.log(np.array([start[p] for p in parameters]))
    if map_runs is None:
        map_runs = lambda docs: [replay_errors(d, run, measured, settings, drag_model, heading_deg) for d in docs]
    cache: dict[bytes, np.ndarray] = {}
    count = [0]

    def documents(xs: list[np.ndarray]) -> list[dict]:
        return [with_parameters(document, dict(zip(parameters, np.exp(x)))) for x in xs]

    def evaluate(xs: list[np.ndarray]) -> list[np.ndarray]:
        todo = [x for x in xs if x.tobytes() not in cache]
        for x, e in zip(todo, map_runs(documents(todo))):
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


# ---------------------------------------------------------------------- regression
def regress(hs_over_d: np.ndarray, values: np.ndarray, degree: int = 2) -> np.ndarray:
    """Polynomial coefficients (highest power first) of a Cd against Hs/D; the degree drops
    to what the number of points allows."""
    degree = min(degree, len(hs_over_d) - 1)
    if degree < 0:
        raise ValueError("regression: no calibrated runs")
    return np.polyfit(hs_over_d, values, degree)


def predict(coefficients: dict[str, np.ndarray], hs_over_d: float, floor: float = 0.02) -> dict[str, float]:
    """Cds for a new sea state from the regressions (never below ``floor``)."""
    return {p: max(floor, float(np.polyval(c, hs_over_d))) for p, c in coefficients.items()}


def error_table(values: dict[str, float]) -> str:
    return ", ".join(f"{k} {v:+.1f} %" for k, v in values.items())


def rms(values: dict[str, float]) -> float:
    return math.sqrt(sum(v * v for v in values.values()) / len(values)) if values else float("nan")
