"""``fowt-sim simulate`` (one offline run) and ``fowt-sim load-cases`` (the paper's load cases
with both drag models)."""
from __future__ import annotations

import argparse
import sys
from dataclasses import replace
from pathlib import Path

from fowt_hydro_sim.cli import options
from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.config import (
    DEFAULT_PLATFORM,
    HYDRO_OPTION_NAMES,
    RunConfig,
    load_case,
    load_platform,
    load_run_file,
)
from fowt_hydro_sim.studies.psd import TRANSIENT_S

# the paper's study (studies.load_case_study.STUDY_CASES, imported only when it runs: it imports the model)
STUDY_CASES = ("lc5.0", "lc5.1", "lc5.2", "lc5.3", "lc5.4", "lc6.1")

# the turbine's settings a coupled run takes (--turbine rosco; the turbine itself: --turbine-model)
TURBINE_OPTIONS = ("hub_height_m", "wind", "wind_speed_m_s", "wind_end_m_s", "wind_start_s", "wind_ramp_s", "wind_file",
                   "rotor_start", "rotor_speed_rad_s", "pitch_rad", "fixed_platform", "discon_changes")
TURBINE_MODEL = "iea15_umaine"  # the packaged turbine a coupled run takes by default
TURBINE_DEFAULTS_NOTE = "the turbine node's (fowt-sim turbine --help)"
RUN_OPTIONS = ("platform", "drag_model", "duration_s", "dt_s", "wave_table_dt_s", "output_interval_s",
               "initial_state", *HYDRO_OPTION_NAMES, "mooring")


def simulate(args: argparse.Namespace) -> int:
    from fowt_hydro_sim.studies import simulate as study
    if args.config:
        spec = load_run_file(args.config)
        run, sea, case = spec.run, spec.sea_state, spec.load_case
        still_water = sea is None
    else:
        run = RunConfig(**{k: v for k, v in options.values(args, RunConfig, RUN_OPTIONS).items() if v is not None})
        still_water = args.still_water
        sea, case = (None, None) if still_water or args.waves_comp or args.elevation else options.sea_state(args)
    coupled = args.turbine == "rosco" or (args.system and args.turbine is None)
    if args.system:
        run, args.turbine_model = _system(args, run)
    platform = load_platform(run.platform)
    if still_water:
        waves, info = None, {"source": "still water"}
    elif args.waves_comp:
        waves, info = study.comp_file_waves(args.waves_comp)
    elif args.elevation:
        waves, info = study.elevation_record_waves(args.elevation, tuple(args.elevation_point), args.heading_deg,
                                                   platform)
    else:
        waves, info = study.sea_state_waves(sea, run.duration_s, case)
    if coupled:
        return _coupled(args, run, waves, info)
    given = [options.flag(name) for name in TURBINE_OPTIONS if getattr(args, name) is not None]
    if given or args.turbine_model != TURBINE_MODEL:
        raise InputError(f"{(given or ['--turbine-model'])[0]}: a turbine option needs --turbine rosco")
    summary = study.simulate(run, waves, info, Path(args.output), args.transient, args.overwrite)
    sys.stdout.write(study.summary_text(summary, Path(args.output)) + "\n")
    return 0


def _system(args: argparse.Namespace, run: RunConfig) -> tuple[RunConfig, str]:
    """The run and the turbine of ``--system`` (filling the platform, mooring and turbine
    left at their defaults)."""
    from fowt_hydro_sim.turbine.system import system_values
    values = system_values(args.system, {"platform": run.platform, "mooring": run.mooring,
                                         "turbine": args.turbine_model},
                           {"platform": DEFAULT_PLATFORM, "mooring": "", "turbine": TURBINE_MODEL})
    return replace(run, platform=values["platform"], mooring=values["mooring"]), values["turbine"]


def _coupled(args: argparse.Namespace, run: RunConfig, waves, info: dict) -> int:
    """``simulate --turbine rosco``: the turbine and its ROSCO in the loop."""
    from fowt_hydro_sim.studies.coupled_run import coupled_summary_text, simulate_coupled
    from fowt_hydro_sim.turbine.settings import TurbineSettings
    given = {k: v for k, v in options.values(args, TurbineSettings, TURBINE_OPTIONS).items() if v is not None}
    turbine = TurbineSettings(turbine=args.turbine_model, platform=run.platform, **given)
    initial = None if args.config is None and args.initial_state is None else run.initial_state
    summary = simulate_coupled(run, turbine, waves, info, Path(args.output), args.transient, args.overwrite, initial)
    sys.stdout.write(coupled_summary_text(summary, Path(args.output)) + "\n")
    return 0


def load_cases(args: argparse.Namespace) -> int:
    from fowt_hydro_sim.studies.load_case_study import run_study
    out = Path(args.output)
    if out.exists() and any(out.iterdir()) and not args.overwrite:
        raise InputError(f"{out}: exists and is not empty (pass --overwrite to replace its files)")
    cases = tuple(load_case(c).name for c in args.cases)
    rows = run_study(load_platform(args.platform), cases, args.duration, args.transient, args.seed, out)
    sys.stdout.write((out / "band_stds.md").read_text())
    sys.stdout.write(f"wrote {out / 'band_stds.csv'}, {out / 'band_stds.md'} and {len(cases)} PSD plots "
                     f"({len(rows)} rows)\n")
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("simulate", help="run the platform model offline and write its time series",
                       description="Run the platform model offline (no ROS) and write timeseries.csv "
                                   "and summary.json to the output folder.")
    p.add_argument("--config", type=Path, help="run file (YAML: platform, load_case or sea_state, run); "
                                                "replaces the platform, wave and run options")
    waves = p.add_argument_group("waves (default: load case lc5.3)")
    options.add_sea_state(waves)
    waves.add_argument("--waves-comp", type=Path, help="OpenFAST SeaState .Comp file of wave components")
    waves.add_argument("--elevation", type=Path, help="CSV time_s,elevation_m measured at --elevation-point")
    waves.add_argument("--elevation-point", type=float, nargs=2, default=(0.0, 0.0), metavar=("X", "Y"),
                       help="where --elevation was measured, world x y [m] (default 0 0)")
    waves.add_argument("--still-water", action="store_true", help="no waves")
    options.add(p, RunConfig, RUN_OPTIONS, defaults={"initial_state": None},
                notes={"initial_state": "; not given: 0, or with --turbine the static offset under the initial "
                                        "thrust"})
    turbine = p.add_argument_group("turbine (--turbine rosco: the rotor and NREL's ROSCO in the loop, no ROS)")
    turbine.add_argument("--system", help="named system: platform, turbine (with its controller) and mooring "
                                          "that belong together, a packaged name (iea15_volturnus_s) or a system "
                                          "YAML; fills --platform, --mooring and --turbine-model, and implies "
                                          "--turbine rosco")
    turbine.add_argument("--turbine", choices=("none", "rosco"),
                         help="none: the platform alone; rosco: the turbine and its ROSCO controller stepped with "
                              "the platform every controller step (default none, or rosco with --system)")
    turbine.add_argument("--turbine-model", default=TURBINE_MODEL,
                         help="packaged turbine name or turbine YAML (default %(default)s)")
    from fowt_hydro_sim.turbine.settings import TurbineSettings
    options.add(turbine, TurbineSettings, TURBINE_OPTIONS, defaults=dict.fromkeys(TURBINE_OPTIONS),
                notes=dict.fromkeys(TURBINE_OPTIONS, f"; default: {TURBINE_DEFAULTS_NOTE}"))
    p.add_argument("--transient", type=float, help=f"seconds at the start left out of the summary statistics "
                                                     f"(start-up; default {TRANSIENT_S:g}, as analyze drops, or 0 "
                                                     f"for a run not longer than that)")
    p.add_argument("-o", "--output", default="out/simulate", help="output folder (default %(default)s)")
    p.add_argument("--overwrite", action="store_true", help="replace files in a non-empty output folder")
    p.set_defaults(func=simulate)

    p = sub.add_parser("load-cases", help="the paper's load cases with both drag models: band STDs and PSDs",
                       description="Run load cases with the constant and the filtered drag model and write "
                                   "band_stds.csv, band_stds.md and psd_<case>.png to the output folder.")
    options.add(p, RunConfig, ("platform",))
    p.add_argument("--cases", nargs="+", default=list(STUDY_CASES), help="load cases (default: %(default)s)")
    p.add_argument("--duration", type=float, default=12000.0, help="analysed seconds per run (default %(default)s)")
    p.add_argument("--transient", type=float, default=TRANSIENT_S,
                   help="start-up seconds simulated before them (default %(default)s)")
    p.add_argument("--seed", type=int, default=1, help="random phase seed, the same for both models "
                                                         "(default %(default)s)")
    p.add_argument("-o", "--output", default="out/load_cases", help="output folder (default %(default)s)")
    p.add_argument("--overwrite", action="store_true", help="replace files in a non-empty output folder")
    p.set_defaults(func=load_cases)
