"""``fowt-sim calibrate``: fit drag coefficients to measured runs (on a Dask cluster), or
with ``--regress`` fit them against Hs/D and predict a blind case."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from fowt_hydro_sim.cli import options
from fowt_hydro_sim.physics.config import ConfigError, RunConfig, load_platform
from fowt_hydro_sim.studies.psd import TRANSIENT_S


def calibrate_command(args: argparse.Namespace) -> int:
    # the studies import scipy and the model: here, not at the top (fowt-sim calibrate --help)
    from fowt_hydro_sim.studies.analysis import AnalysisSettings
    from fowt_hydro_sim.studies.calibration import fit_runs, regression_report
    from fowt_hydro_sim.studies.replay import measured_run

    run = options.values(args, RunConfig, ("platform", "drag_model", "dt_s"))
    if args.regress:
        blind = measured_run(args.predict) if args.predict else None
        lines = regression_report(Path(args.regress), Path(args.output), args.degree, blind, args.predict_hs,
                                  args.heading)
    else:
        if not args.measured:
            raise ConfigError("give --measured BAG... to calibrate, or --regress CALIBRATION.json")
        if not args.params:
            raise ConfigError("--params: name the Cds to calibrate, e.g. 'column*.submerged.cd.low_frequency'")
        platform = load_platform(run["platform"])
        settings = AnalysisSettings(transient_s=args.transient, dofs=tuple(args.dofs))
        runs = [measured_run(path) for path in args.measured]
        lines = fit_runs(runs, platform, run["platform"], args.params, settings, Path(args.output), run["drag_model"],
                         args.heading, args.diameter, args.max_iterations, run["dt_s"], args.scheduler, args.workers)
    sys.stdout.write("\n".join(lines) + "\n")
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("calibrate", help="fit drag coefficients to measured runs; regress and predict",
                       description="Fit Cds (parameter paths MEMBERS.ZONE.FIELD[.BAND]) to the band STDs of "
                                   "measured bags, each replayed with its own wave elevation, on a Dask cluster; "
                                   "or, with --regress, fit the calibrated Cds against Hs/D and predict a blind "
                                   "case (--predict BAG runs it with the predicted Cds).")
    p.add_argument("--measured", nargs="+", help="measured bags (/waves/elevation and /platform/pose)")
    p.add_argument("--params", nargs="+", help="Cds to fit, e.g. 'column*.submerged.cd.low_frequency'")
    options.add(p, RunConfig, ("platform", "drag_model", "dt_s"), defaults={"drag_model": "filtered"},
                notes={"platform": " (the starting Cds)", "dt_s": " of the replays"})
    p.add_argument("--heading", type=float, default=0.0, help="wave direction of the records [deg] (default 0)")
    p.add_argument("--dofs", nargs="+", default=["surge", "heave", "pitch"],
                   help="DOFs of the metric (default: %(default)s)")
    p.add_argument("--transient", type=float, default=TRANSIENT_S,
                   help="seconds left out at the start (default %(default)s)")
    p.add_argument("--diameter", type=float, help="D of Hs/D [m] (default: the largest column)")
    p.add_argument("--max-iterations", type=int, default=8,
                   help="least-squares iterations per run (default %(default)s)")
    p.add_argument("--scheduler", help="address of an existing Dask scheduler (default: a local cluster)")
    p.add_argument("--workers", type=int, help="local cluster worker processes (default: one per core)")
    p.add_argument("--regress", help="a calibration.json: fit each Cd against Hs/D")
    p.add_argument("--degree", type=int, default=2, help="regression polynomial degree (default %(default)s)")
    p.add_argument("--predict", help="blind measured bag: predict its Cds from Hs/D and run it")
    p.add_argument("--predict-hs", type=float, help="predict the Cds for this Hs [m]")
    p.add_argument("-o", "--output", default="out/calibration", help="output folder (default %(default)s)")
    p.set_defaults(func=calibrate_command)
