"""``fowt-sim analyze``: PSDs, band STDs and errors against a reference, of recorded runs."""
from __future__ import annotations

import argparse
import logging
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from fowt_hydro_sim.studies.psd import TRANSIENT_S

if TYPE_CHECKING:  # the studies import scipy and the model: imported when the command runs
    from fowt_hydro_sim.studies.analysis import AnalysisSettings

log = logging.getLogger("fowt_hydro_sim")


def _band_option(text: str) -> tuple[str | None, str, tuple[float, float]]:
    """[DOF.]NAME=LOW:HIGH"""
    try:
        name, limits = text.split("=")
        low, high = (float(v) for v in limits.split(":"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"band {text!r}: expected [DOF.]NAME=LOW:HIGH in Hz") from None
    dof, _, band = name.rpartition(".")
    return dof or None, band, (low, high)


def analysis_settings(args: argparse.Namespace) -> AnalysisSettings:
    """The analysis settings of the command's options; ConfigError names a bad option."""
    from fowt_hydro_sim.physics.config import ConfigError
    from fowt_hydro_sim.physics.model import DOF_NAMES
    from fowt_hydro_sim.studies.analysis import AnalysisSettings
    from fowt_hydro_sim.studies.psd import BANDS_HZ

    unknown = [d for d in args.dofs if d not in DOF_NAMES]
    if unknown:
        raise ConfigError(f"--dofs: unknown {', '.join(unknown)} (use {', '.join(DOF_NAMES)})")
    default = {name: limits for dof, name, limits in args.band or [] if dof is None} or dict(BANDS_HZ)
    bands = {dof: dict(default) for dof in args.dofs}
    for dof, name, limits in args.band or []:
        if dof is not None:
            if dof not in bands:
                raise ConfigError(f"--band {dof}.{name}: {dof} is not analysed (--dofs {' '.join(args.dofs)})")
            bands[dof][name] = limits
    for dof, named in bands.items():
        for name, (low, high) in named.items():
            if not 0 <= low < high:
                raise ConfigError(f"--band {dof}.{name}: need 0 <= low < high, got {low:g}:{high:g}")
    if not 0 < args.confidence < 1 or args.threshold <= 0 or args.transient < 0 or args.segment <= 0:
        raise ConfigError("--confidence in (0, 1), --threshold > 0, --transient >= 0, --segment > 0")
    return AnalysisSettings(transient_s=args.transient, segment_s=args.segment, window=args.window,
                            overlap=args.overlap, dofs=tuple(args.dofs), bands_hz=bands,
                            threshold=args.threshold / 100.0, confidence=args.confidence)


def analyze(args: argparse.Namespace) -> int:
    from fowt_hydro_sim.studies.analysis import analyze_bags
    output = Path(args.output) if args.output else Path(args.runs[0]).with_name(Path(args.runs[0]).name + "_report")
    text, files = analyze_bags(args.runs, args.ref or [], analysis_settings(args), output)
    sys.stdout.write(text + "\n")
    log.info(f"{output}: {', '.join(f.name for f in files)}")
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("analyze", help="PSDs, band STDs and errors against a reference, of recorded runs",
                       description="Analyse runs, bags (their /platform/pose) or fowt-sim simulate output "
                                   "folders (timeseries.csv): Welch PSD per DOF, band STDs with "
                                   "confidence intervals, and against --ref the STD error per DOF and band, "
                                   "pass/fail and pass rate. Writes table.txt, band_stds.csv, errors.csv, "
                                   "analysis.json and PNG figures.")
    p.add_argument("runs", nargs="+", help="run bags or simulate output folders")
    p.add_argument("--ref", nargs="+", help="reference (measured) bags or folders: one for all runs, or one per run")
    p.add_argument("-o", "--output", help="report folder (default: RUN_report beside the first run)")
    p.add_argument("--transient", type=float, default=TRANSIENT_S,
                   help="seconds discarded at each run's start, as simulate drops (default %(default)s)")
    p.add_argument("--segment", type=float, default=2048.0, help="Welch segment [s] (default %(default)s)")
    p.add_argument("--window", default="hann", help="Welch window, a scipy.signal window name (default %(default)s)")
    p.add_argument("--overlap", type=float, default=0.5, help="Welch segment overlap fraction (default %(default)s)")
    p.add_argument("--dofs", nargs="+", default=["surge", "heave", "pitch"],
                   help="DOFs analysed (default: %(default)s)")
    p.add_argument("--band", type=_band_option, action="append",
                   help="band [DOF.]NAME=LOW:HIGH in Hz, repeatable (default low_frequency=0.005:0.05, "
                        "wave=0.05:0.25; with a DOF, overrides that DOF's band)")
    p.add_argument("--threshold", type=float, default=15.0,
                   help="pass if |STD error| <= this [%%] (default %(default)s)")
    p.add_argument("--confidence", type=float, default=0.9,
                   help="confidence level of the intervals (default %(default)s)")
    p.set_defaults(func=analyze)
