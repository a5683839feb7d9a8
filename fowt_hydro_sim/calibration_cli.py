"""``fowt-sim calibrate``: fit drag coefficients to measured runs (on a Dask cluster), or
with ``--regress`` fit them against Hs/D and predict a blind case."""
from __future__ import annotations

import argparse
import json
import logging
import sys
from functools import partial
from pathlib import Path

import numpy as np
import yaml

from .calibration import (Calibration, replay_errors, calibrate, error_table, get_parameter, predict, regress,
                          rms, with_parameters)
from .config import DRAG_MODELS, ConfigError, _read_yaml, load_platform, platform_path
from .replay import MeasuredRun, measured_run

log = logging.getLogger("fowt_hydro_sim")
RESULT_FILE = "calibration.json"


def _settings(args: argparse.Namespace):
    from .analysis import AnalysisSettings
    return AnalysisSettings(transient_s=args.transient, dofs=tuple(args.dofs))


def _column_diameter_m(document: dict) -> float:
    """D of Hs/D: the largest circular member's diameter."""
    diameters = [m["diameter_m"] for m in document["members"] if m.get("section") == "circular"]
    if not diameters:
        raise ConfigError("platform: no circular member to take D (Hs/D) from; give --diameter")
    return float(max(diameters))


def cluster_map(client, run: MeasuredRun, measured, settings, drag_model: str, heading_deg: float, position: int = 0):
    """Replays of platform documents on the cluster: their band STD errors, in order."""
    from .cluster import map_with_progress
    task = partial(replay_errors, settings=settings, drag_model=drag_model, heading_deg=heading_deg)
    return lambda documents: map_with_progress(client, task, documents, f"{run.name}: model runs", position,
                                               run=run, measured=measured)


def calibrate_all(client, runs: list[MeasuredRun], document: dict, parameters: list[str], settings,
                  drag_model: str = "filtered", heading_deg: float = 0.0, max_iterations: int = 8) -> list[Calibration]:
    """Calibrate every run, all at once on the cluster (each run's fit in its own thread,
    so the workers stay busy while one fit waits for a single run)."""
    from concurrent.futures import ThreadPoolExecutor

    from .analysis import analyse

    def one(index_run: tuple[int, MeasuredRun]) -> Calibration:
        index, run = index_run
        measured = analyse(run.name, run.motion_time_s, run.motion, settings)
        return calibrate(run, document, parameters, settings,
                         cluster_map(client, run, measured, settings, drag_model, heading_deg, index),
                         drag_model, heading_deg, max_iterations=max_iterations)

    with ThreadPoolExecutor(max_workers=len(runs)) as pool:
        return list(pool.map(one, enumerate(runs)))


def fit(args: argparse.Namespace) -> int:
    from .cluster import dask_client
    if not args.params:
        raise ConfigError("--params: name the Cds to calibrate, e.g. 'column*.submerged.cd.low_frequency'")
    document = _read_yaml(platform_path(args.platform))
    diameter = args.diameter or _column_diameter_m(document)
    for p in args.params:
        get_parameter(document, p)  # a bad path fails before any run
    settings = _settings(args)
    runs = [measured_run(path) for path in args.measured]
    with dask_client(args.scheduler, args.workers) as client:
        results = calibrate_all(client, runs, document, args.params, settings, args.drag, args.heading,
                                args.max_iterations)
    for run, result in zip(runs, results):
        sys.stdout.write(f"{run.name} (Hs {run.hs_m:.2f} m, Hs/D {run.hs_m / diameter:.3f}): "
                         f"{result.model_runs} model runs, {result.wall_s:.0f} s\n"
                         f"  fitted: {', '.join(f'{k} {v:.3f}' for k, v in result.parameters.items())}\n"
                         f"  errors before: {error_table(result.errors_before)} (RMS {rms(result.errors_before):.1f} %)\n"
                         f"  errors after:  {error_table(result.errors_after)} (RMS {rms(result.errors_after):.1f} %)\n")
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    payload = {"platform": args.platform, "drag_model": args.drag, "diameter_m": diameter,
               "parameters": args.params, "dofs": args.dofs, "transient_s": args.transient,
               "runs": [{**r.as_dict(), "hs_over_d": r.hs_m / diameter} for r in results]}
    (out / RESULT_FILE).write_text(json.dumps(payload, indent=1))
    log.info(f"{out / RESULT_FILE}: {sum(r.model_runs for r in results)} model runs, "
             f"{sum(r.wall_s for r in results):.0f} s")
    return 0


def regression(args: argparse.Namespace) -> int:
    data = json.loads(Path(args.regress).read_text())
    runs = data["runs"]
    x = np.array([r["hs_over_d"] for r in runs])
    coefficients = {p: regress(x, np.array([r["parameters"][p] for r in runs]), args.degree) for p in data["parameters"]}
    lines = [f"Cd against Hs/D over {len(runs)} runs (polynomial, highest power first):"]
    lines += [f"  {p}: {np.array2string(c, precision=4)}" for p, c in coefficients.items()]
    if args.predict is None and args.predict_hs is None:
        sys.stdout.write("\n".join(lines) + "\n")
        return 0
    document = _read_yaml(platform_path(data["platform"]))
    blind = measured_run(args.predict) if args.predict else None
    hs = blind.hs_m if blind else args.predict_hs
    predicted = predict(coefficients, hs / data["diameter_m"])
    lines.append(f"predicted for Hs {hs:.2f} m (Hs/D {hs / data['diameter_m']:.3f}): "
                 + ", ".join(f"{k} {v:.3f}" for k, v in predicted.items()))
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    platform_file = out / "platform_predicted.yaml"
    platform_file.write_text(yaml.safe_dump(with_parameters(document, predicted), sort_keys=False))
    lines.append(f"platform with the predicted Cds: {platform_file}")
    if blind is not None:
        from .analysis import AnalysisSettings, analyse
        settings = AnalysisSettings(transient_s=data["transient_s"], dofs=tuple(data["dofs"]))
        measured = analyse(blind.name, blind.motion_time_s, blind.motion, settings)
        names = [f"{d}.{b}" for d in settings.dofs for b in settings.bands(d)]
        blind_errors = {}
        for label, doc in (("start Cds", document), ("predicted Cds", with_parameters(document, predicted))):
            e = replay_errors(doc, blind, measured, settings, data["drag_model"], args.heading)
            blind_errors[label] = dict(zip(names, (100 * e).tolist()))
            lines.append(f"blind {blind.name}, {label}: {error_table(blind_errors[label])} "
                         f"(RMS {rms(blind_errors[label]):.1f} %)")
        (out / "blind.json").write_text(json.dumps({"run": blind.name, "hs_m": hs, "predicted": predicted,
                                                   "errors": blind_errors}, indent=1))
    sys.stdout.write("\n".join(lines) + "\n")
    return 0


def calibrate_command(args: argparse.Namespace) -> int:
    if args.regress:
        return regression(args)
    if not args.measured:
        raise ConfigError("give --measured BAG... to calibrate, or --regress CALIBRATION.json")
    load_platform(args.platform)  # validates
    return fit(args)


def add_calibrate(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("calibrate", help="fit drag coefficients to measured runs; regress and predict",
                       description="Fit Cds (parameter paths MEMBERS.ZONE.FIELD[.BAND]) to the band STDs of "
                                   "measured bags, each replayed with its own wave elevation, on a Dask cluster; "
                                   "or, with --regress, fit the calibrated Cds against Hs/D and predict a blind "
                                   "case (--predict BAG runs it with the predicted Cds).")
    p.add_argument("--measured", nargs="+", help="measured bags (/waves/elevation and /platform/pose)")
    p.add_argument("--params", nargs="+", help="Cds to fit, e.g. 'column*.submerged.cd.low_frequency'")
    p.add_argument("--platform", default="windmoor12", help="packaged platform name or YAML (the starting Cds)")
    p.add_argument("--drag", default="filtered", choices=DRAG_MODELS, help="drag model")
    p.add_argument("--heading", type=float, default=0.0, help="wave direction of the records [deg]")
    p.add_argument("--dofs", nargs="+", default=["surge", "heave", "pitch"], help="DOFs of the metric")
    p.add_argument("--transient", type=float, default=600.0, help="seconds left out at the start")
    p.add_argument("--diameter", type=float, help="D of Hs/D [m] (default: the largest column)")
    p.add_argument("--max-iterations", type=int, default=8, help="least-squares iterations per run")
    p.add_argument("--scheduler", help="address of an existing Dask scheduler (default: a local cluster)")
    p.add_argument("--workers", type=int, help="local cluster worker processes (default: one per core)")
    p.add_argument("--regress", help="a calibration.json: fit each Cd against Hs/D")
    p.add_argument("--degree", type=int, default=2, help="regression polynomial degree (default: quadratic)")
    p.add_argument("--predict", help="blind measured bag: predict its Cds from Hs/D and run it")
    p.add_argument("--predict-hs", type=float, help="predict the Cds for this Hs [m]")
    p.add_argument("-o", "--output", default="out/calibration", help="output folder")
    p.set_defaults(func=calibrate_command)
