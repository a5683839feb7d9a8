"""``fowt-sim measured import``: basin test files (CSV/TSV, HDF5, MATLAB .mat) as measured
bags, Froude-scaled to full scale, with their checks reported."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

from fowt_hydro_sim.physics.config import ConfigError


def import_command(args: argparse.Namespace) -> int:
    from fowt_hydro_sim.io.basin import load_column_map
    from fowt_hydro_sim.studies.basin_import import import_files
    if not args.max_gap > 0:
        raise ConfigError(f"--max-gap: must be > 0 s, got {args.max_gap:g}")
    mapping = load_column_map(args.map)
    for path, run in import_files(args.files, mapping, args.output, args.max_gap, args.overwrite):
        sys.stdout.write(f"wrote {path}: {run.time_s.size} samples, {run.time_s[-1] - run.time_s[0]:.1f} s full "
                         f"scale, {len(run.probes)} probe(s), {len(run.notes)} problem(s) handled\n")
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    from fowt_hydro_sim.io.basin import MAX_GAP_S
    p = sub.add_parser("measured", help="measured runs: import basin files as bags")
    commands = p.add_subparsers(dest="measured_command", required=True, metavar="COMMAND")
    imp = commands.add_parser("import", help="write measured bags from basin files (CSV/TSV, HDF5, .mat)",
                              description="Read basin test files with a column map (channel -> quantity, unit, "
                                          "sign, offset; probe positions; motion point; scale), check each run's "
                                          "clock and channels (gaps, dropouts, samples out of order, probe clock "
                                          "offsets: one line each, interpolated when short, refused when long), "
                                          "Froude-scale it to full scale and write one bag per run, which "
                                          "calibrate and diagnose read.")
    imp.add_argument("files", nargs="+", type=Path, help="basin files: .csv, .tsv/.txt, .h5/.hdf5, .mat")
    imp.add_argument("--map", required=True, type=Path, help="the column map (YAML)")
    imp.add_argument("-o", "--output", required=True, type=Path, help="folder of the bags (one per run)")
    imp.add_argument("--max-gap", type=float, default=MAX_GAP_S,
                     help="longest clock gap or dropout interpolated, full-scale seconds; longer ones refuse the "
                          "run (default %(default)s)")
    imp.add_argument("--overwrite", action="store_true", help="replace existing bags")
    imp.set_defaults(func=import_command)
