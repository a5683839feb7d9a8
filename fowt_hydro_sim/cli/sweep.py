"""``fowt-sim sweep``: load cases x seeds x drag models x platform variants (x wind speeds x
controller variants with a named system's turbine in the loop) on a Dask cluster, one table of statistics and band
STDs, means over seeds with confidence intervals."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from fowt_hydro_sim.cli import options
from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.config import DEFAULT_PLATFORM, DRAG_MODELS, RunConfig
from fowt_hydro_sim.turbine.wind import DEFAULT_WIND_M_S

if TYPE_CHECKING:  # the study imports scipy and the model: imported when the command runs
    from fowt_hydro_sim.studies.sweep import Variant

RUN_OPTIONS = ("duration_s", "dt_s", "wave_table_dt_s", "output_interval_s")


def _variants(platforms: list[str], cd_scales: list[float]) -> tuple[Variant, ...]:
    """Every platform with every Cd scale, named ``PLATFORM`` (scale 1) or ``PLATFORM_cdSCALE``."""
    from fowt_hydro_sim.studies.sweep import Variant
    return tuple(Variant(Path(p).stem + ("" if s == 1.0 else f"_cd{s:g}"), p, cd_scale=s)
                 for p in platforms for s in cd_scales)


def sweep(args: argparse.Namespace) -> int:
    from fowt_hydro_sim.studies import sweep as study
    if args.config:
        table = study.load_sweep_file(args.config)
    else:
        run = RunConfig(**{k: v for k, v in options.values(args, RunConfig, RUN_OPTIONS).items() if v is not None})
        if args.seed_count and len(args.seeds) != 1:
            raise InputError(f"--seed-count: give one count with --seeds, got {len(args.seeds)} numbers")
        seeds = tuple(range(1, args.seeds[0] + 1)) if args.seed_count else tuple(args.seeds)
        if args.wind_speeds and not args.system:
            raise InputError("--wind-speeds: wind speeds need a turbine: give --system")
        if args.discon_changes and not args.system:
            raise InputError("--discon-changes: controller changes need a turbine: give --system")
        if args.system and args.platforms != [DEFAULT_PLATFORM]:
            raise InputError("--platforms: a system brings its platform; vary it with --cd-scales")
        variants = (study.system_variants(args.system, args.cd_scales) if args.system
                    else _variants(args.platforms, args.cd_scales))
        winds = tuple(args.wind_speeds or (DEFAULT_WIND_M_S,)) if args.system else ()
        controllers = tuple(args.discon_changes or ("",))
        table = study.Sweep(tuple(args.load_cases), seeds, tuple(args.drag_models), variants, run, args.transient,
                            args.system or "", winds, controllers)
    outcome = study.run_sweep(table, Path(args.output), args.scheduler, args.workers, args.bags, args.confidence,
                              args.overwrite)
    sys.stdout.write(study.summary_text(outcome) + "\n")
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("sweep", help="load cases x seeds x drag models x platform variants on a Dask cluster",
                       description="Run a table of runs (load cases x seeds x drag models x platform variants; "
                                   "with --system x wind speeds x controller variants, the turbine and ROSCO in "
                                   "the loop) on "
                                   "a Dask cluster; runs.csv gets one row of statistics and band STDs per run as "
                                   "it finishes, summary.csv the means over seeds with confidence intervals "
                                   "(Student-t; log-normal for STDs, never below zero; Parquet copies when "
                                   "pyarrow is installed). Rerunning into the same folder skips the runs already "
                                   "finished there.")
    p.add_argument("--config", type=Path, help="sweep file (YAML: load_cases, seeds, drag_models, variants, run, "
                                                "transient_s); replaces the table and run options")
    table = p.add_argument_group("the table (without --config)")
    table.add_argument("--load-cases", nargs="+", default=["lc5.3"], metavar="CASE",
                       help="load cases (default %(default)s)")
    table.add_argument("--seeds", nargs="+", type=int, default=[1], metavar="SEED",
                       help="random phase seeds (default %(default)s)")
    table.add_argument("--seed-count", action="store_true", help="--seeds N means seeds 1 .. N")
    table.add_argument("--drag-models", nargs="+", choices=DRAG_MODELS, default=["constant"], metavar="MODEL",
                       help=f"drag models, of {', '.join(DRAG_MODELS)} (default %(default)s)")
    table.add_argument("--platforms", nargs="+", default=[DEFAULT_PLATFORM], metavar="PLATFORM",
                       help="packaged platform names or platform YAML files (default %(default)s)")
    table.add_argument("--system", help="named system (packaged name, e.g. iea15_volturnus_s, or system YAML): "
                                        "the turbine and its ROSCO in the loop, each run a simulate --system run; "
                                        "its platform replaces --platforms")
    table.add_argument("--wind-speeds", nargs="+", type=float, metavar="M_S",
                       help=f"steady hub-height wind speeds of a --system sweep [m/s] (default {DEFAULT_WIND_M_S:g})")
    table.add_argument("--discon-changes", nargs="+", metavar="CHANGES",
                       help="controller variants of a --system sweep, each 'NAME=VALUE; NAME=VALUE' of ROSCO's "
                            "DISCON.IN entries ('' for the file as it is), e.g. '' 'Fl_Kp=-5' 'Fl_Kp=0' "
                            "(default: the file as it is)")
    table.add_argument("--cd-scales", nargs="+", type=float, default=[1.0], metavar="SCALE",
                       help="every drag coefficient times each scale: one variant per platform and scale "
                            "(default %(default)s)")
    options.add(table, RunConfig, RUN_OPTIONS)
    table.add_argument("--transient", type=float, default=0.0,
                       help="seconds at the start left out of the statistics (default %(default)s)")
    p.add_argument("--confidence", type=float, default=0.95, help="confidence level of the intervals over seeds "
                                                                   "(default %(default)s)")
    p.add_argument("--bags", action="store_true", help="also record each run's outputs to a bag under OUTPUT/bags")
    p.add_argument("--scheduler", help="address of an existing Dask scheduler (default: a local cluster)")
    p.add_argument("--workers", type=int, help="local cluster worker processes (default: one per core)")
    p.add_argument("-o", "--output", default="out/sweep", help="output folder; a rerun resumes there "
                                                                "(default %(default)s)")
    p.add_argument("--overwrite", action="store_true", help="drop the tables already in the output folder")
    p.set_defaults(func=sweep)
