"""``fowt-sim``: the command-line entry point (subcommands; ``simulate`` runs the model offline).

Errors in the user's input end the command with one line naming the problem (exit 2),
never a traceback.
"""
from __future__ import annotations

import argparse
import logging
import resource
import sys
import time
from dataclasses import asdict
from pathlib import Path

import numpy as np
import yaml

from . import __version__
from .calibration_cli import add_calibrate
from .diagnosis_cli import add_diagnose
from .config import DRAG_MODELS, ConfigError, SeaState, load_case, load_platform, load_run_file
from .load_case_study import STUDY_CASES, run_study
from .model import DOF_NAMES, PlatformModel, RunResult
from .output import write_run
from .spectral import BANDS_HZ, MIN_SEGMENTS, band_stds
from .waves import WaveComponents, from_elevation_record, read_comp_file, repeat_period, synthesize

log = logging.getLogger("fowt_hydro_sim")


def _sea_state(args: argparse.Namespace) -> SeaState:
    if args.hs is not None or args.tp is not None:
        if args.hs is None or args.tp is None:
            raise ConfigError("--hs and --tp go together")
        return SeaState(args.hs, args.tp, args.gamma or 1.0, heading_deg=args.heading, seed=args.seed)
    case = load_case(args.load_case).sea_state
    return SeaState(case.hs_m, case.tp_s, case.gamma, heading_deg=args.heading, seed=args.seed)


def _waves(args: argparse.Namespace, platform) -> tuple[WaveComponents | None, dict]:
    env = platform.environment
    if args.still_water:
        return None, {"source": "still water"}
    if args.waves_comp:
        return read_comp_file(args.waves_comp), {"source": "components", "file": str(args.waves_comp)}
    if args.elevation:
        try:
            record = np.loadtxt(args.elevation, delimiter=",", comments="#", ndmin=2)
        except (OSError, ValueError) as exc:
            raise ConfigError(f"{args.elevation}: cannot be read as two CSV columns time_s, elevation_m ({exc})") from None
        if record.shape[1] != 2:
            raise ConfigError(f"{args.elevation}: expected two columns time_s, elevation_m, got {record.shape[1]}")
        x, y = args.elevation_point
        waves = from_elevation_record(record[:, 0], record[:, 1], x, y, args.heading, env.water_depth_m,
                                      env.gravity_m_s2)
        return waves, {"source": "elevation record", "file": str(args.elevation), "point_m": [x, y]}
    sea = _sea_state(args)
    period = repeat_period(sea, args.duration)
    return synthesize(sea, period), {"source": "sea state", **asdict(sea), "repeat_period_s": period,
                                     "load_case": None if args.hs is not None else args.load_case}


def _apply_run_file(args: argparse.Namespace) -> None:
    """Take platform, waves and run settings from ``--config``."""
    spec = load_run_file(args.config)
    args.platform, args.drag = spec.platform, spec.run.drag_model
    args.duration, args.dt = spec.run.duration_s, spec.run.dt_s
    args.output_interval = spec.run.output_interval_s or spec.run.dt_s
    args.wave_table_dt = spec.run.wave_table_dt_s
    args.initial = list(spec.run.initial_state)
    args.still_water = spec.sea_state is None
    if spec.sea_state is not None:
        sea = spec.sea_state
        args.load_case, args.seed, args.heading = spec.load_case, sea.seed, sea.heading_deg
        args.hs, args.tp, args.gamma = (None, None, None) if spec.load_case else (sea.hs_m, sea.tp_s, sea.gamma)


def simulate(args: argparse.Namespace) -> int:
    if args.config:
        _apply_run_file(args)
    out = Path(args.output)
    if out.exists() and any(out.iterdir()) and not args.overwrite:
        raise ConfigError(f"{out}: exists and is not empty (pass --overwrite to replace its files)")
    platform = load_platform(args.platform)
    waves, wave_info = _waves(args, platform)
    start = time.perf_counter()
    model = PlatformModel(platform, waves, dt_s=args.dt, drag_model=args.drag,
                           wave_table_dt_s=args.wave_table_dt)
    built = time.perf_counter()
    if args.initial:
        model.reset(motion=np.array(args.initial))
    result = model.run(args.duration, output_interval_s=args.output_interval)
    end = time.perf_counter()
    wall = end - start
    summary = {
        "software": {"name": "fowt_hydro_sim", "version": __version__},
        "platform": platform.name, "drag_model": args.drag, "waves": wave_info,
        "run": {"dt_s": args.dt, "duration_s": args.duration, "output_interval_s": args.output_interval,
                "initial_state": args.initial or [0.0] * 6, "wave_table_step_s": model.wave_table_step_s,
                "n_wave_components": 0 if waves is None else int(waves.frequency_hz.size)},
        "performance": {"wall_time_s": wall, "set_up_s": built - start,
                        "real_time_factor": args.duration / (end - built),
                        "peak_memory_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024},
        "statistics": _statistics(result, args.transient),
    }
    write_run(out, result, summary)
    _print_summary(summary, out)
    return 0


def _statistics(result: RunResult, transient_s: float) -> dict:
    """Per DOF: mean, std, extremes and the paper's band STDs, leaving out the first
    ``transient_s`` seconds."""
    keep = result.time_s >= result.time_s[0] + transient_s
    if not keep.any():
        raise ConfigError(f"--transient {transient_s:g} s leaves nothing of the run to analyse")
    dt = float(result.time_s[1] - result.time_s[0]) if result.time_s.size > 1 else 1.0
    stats: dict = {"analysed_from_s": float(result.time_s[keep][0]), "bands_hz": BANDS_HZ}
    for j, name in enumerate(DOF_NAMES):
        x = result.motion[keep, j] * (180 / np.pi if j >= 3 else 1.0)
        stats[name] = {"unit": "deg" if j >= 3 else "m", "mean": float(x.mean()), "std": float(x.std()),
                       "min": float(x.min()), "max": float(x.max()),
                       "band_std": band_stds(x, dt) if x.size >= 8 * MIN_SEGMENTS else None}  # (too short)
    eta = result.wave_elevation_m[keep]
    stats["wave_elevation"] = {"unit": "m", "mean": float(eta.mean()), "std": float(eta.std()),
                               "hs_4std": float(4 * eta.std())}
    return stats


def _print_summary(summary: dict, out: Path) -> None:
    perf = summary["performance"]
    print(f"{summary['platform']}, {summary['waves']['source']}, drag {summary['drag_model']}: "
          f"{summary['run']['duration_s']:g} s simulated in {perf['wall_time_s'] - perf['set_up_s']:.2f} s "
          f"({perf['real_time_factor']:.0f}x real time; set-up {perf['set_up_s']:.1f} s, which includes "
          f"compiling the kernels on a first run)")
    stats = summary["statistics"]
    print(f"statistics from t = {stats['analysed_from_s']:g} s; band STDs over "
          + ", ".join(f"{b} {lo:g}-{hi:g} Hz" for b, (lo, hi) in stats["bands_hz"].items()))
    print(f"{'':16s}{'mean':>10s}{'std':>10s}{'min':>10s}{'max':>10s}{'std LF':>10s}{'std WF':>10s}")
    for name in DOF_NAMES:
        s = stats[name]
        bands = "".join(f"{s['band_std'][b]:10.3f}" for b in BANDS_HZ) if s["band_std"] else ""
        print(f"{name + ' [' + s['unit'] + ']':16s}{s['mean']:10.3f}{s['std']:10.3f}{s['min']:10.3f}{s['max']:10.3f}"
              + bands)
    print(f"wave Hs (4 std) at the reference point: {summary['statistics']['wave_elevation']['hs_4std']:.2f} m")
    print(f"wrote {out / 'timeseries.csv'} and {out / 'summary.json'}")


def _add_simulate(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("simulate", help="run the platform model offline and write its time series",
                       description="Run the platform model offline (no ROS) and write timeseries.csv "
                                   "and summary.json to the output folder.")
    p.add_argument("--config", type=Path, help="run file (YAML: platform, load_case or sea_state, run); "
                                                "replaces the platform, wave and run options")
    p.add_argument("--platform", default="windmoor12", help="packaged platform name or YAML file")
    waves = p.add_argument_group("waves (default: load case lc5.3)")
    waves.add_argument("--load-case", default="lc5.3", help="a load case of the paper (lc5.0 .. lc6.5)")
    waves.add_argument("--hs", type=float, help="significant wave height [m] (with --tp)")
    waves.add_argument("--tp", type=float, help="peak period [s]")
    waves.add_argument("--gamma", type=float, help="JONSWAP peak enhancement (default 1)")
    waves.add_argument("--heading", type=float, default=0.0, help="wave direction [deg], 0 = toward +x")
    waves.add_argument("--seed", type=int, default=1, help="random phase seed")
    waves.add_argument("--waves-comp", type=Path, help="OpenFAST SeaState .Comp file of wave components")
    waves.add_argument("--elevation", type=Path, help="CSV time_s,elevation_m measured at --elevation-point")
    waves.add_argument("--elevation-point", type=float, nargs=2, default=(0.0, 0.0), metavar=("X", "Y"))
    waves.add_argument("--still-water", action="store_true", help="no waves")
    p.add_argument("--drag", default="constant", choices=DRAG_MODELS,
                   help="drag model: constant Cd (the paper's case 1) or filtered, one Cd per frequency "
                        "band (case 2; bands in the platform YAML)")
    p.add_argument("--duration", type=float, default=600.0, help="simulated time [s]")
    p.add_argument("--dt", type=float, default=0.05, help="time step [s]")
    p.add_argument("--wave-table-dt", type=float, help="kinematics table step [s] (default: chosen "
                                                         "for 1e-3 interpolation error); must divide the repeat period")
    p.add_argument("--output-interval", type=float, default=0.25, help="output sample interval [s]")
    p.add_argument("--transient", type=float, default=0.0, help="seconds at the start left out of the "
                                                                  "summary statistics (start-up)")
    p.add_argument("--initial", type=float, nargs=6, metavar="Q", help="initial offset: 3 m, 3 rad")
    p.add_argument("-o", "--output", default="out/simulate", help="output folder")
    p.add_argument("--overwrite", action="store_true", help="replace files in a non-empty output folder")
    p.set_defaults(func=simulate)


def load_cases(args: argparse.Namespace) -> int:
    out = Path(args.output)
    if out.exists() and any(out.iterdir()) and not args.overwrite:
        raise ConfigError(f"{out}: exists and is not empty (pass --overwrite to replace its files)")
    cases = tuple(load_case(c).name for c in args.cases)
    rows = run_study(load_platform(args.platform), cases, args.duration, args.transient, args.seed, out)
    print((out / "band_stds.md").read_text(), end="")
    print(f"wrote {out / 'band_stds.csv'}, {out / 'band_stds.md'} and {len(cases)} PSD plots ({len(rows)} rows)")
    return 0


def _add_load_cases(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("load-cases", help="the paper's load cases with both drag models: band STDs and PSDs",
                       description="Run load cases with the constant and the filtered drag model and write "
                                   "band_stds.csv, band_stds.md and psd_<case>.png to the output folder.")
    p.add_argument("--platform", default="windmoor12", help="packaged platform name or YAML file")
    p.add_argument("--cases", nargs="+", default=list(STUDY_CASES), help="load cases (default: %(default)s)")
    p.add_argument("--duration", type=float, default=12000.0, help="analysed seconds per run")
    p.add_argument("--transient", type=float, default=600.0, help="start-up seconds simulated before them")
    p.add_argument("--seed", type=int, default=1, help="random phase seed (the same for both models)")
    p.add_argument("-o", "--output", default="out/load_cases", help="output folder")
    p.add_argument("--overwrite", action="store_true", help="replace files in a non-empty output folder")
    p.set_defaults(func=load_cases)


def waves(args: argparse.Namespace) -> int:
    from .rosbag.wave_bags import write_wave_bag
    environment = load_platform(args.platform).environment
    n = write_wave_bag(args.output, _sea_state(args), args.duration, environment, args.sample_dt,
                       tuple(args.point), overwrite=args.overwrite,
                       load_case=None if args.hs is not None else args.load_case)
    log.info(f"{args.output}: {n} elevation samples, {args.duration:g} s")
    return 0


def _add_waves(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("waves", help="write a bag of /waves/elevation for a sea state or load case",
                       description="Synthesise the sea state's elevation at one point and write it as a bag of "
                                   "/waves/elevation (geometry_msgs/PointStamped), log time = sample time.")
    p.add_argument("--load-case", default="lc5.3", help="load case giving the sea state (default: %(default)s)")
    p.add_argument("--hs", type=float, help="significant wave height [m] (with --tp, instead of a load case)")
    p.add_argument("--tp", type=float, help="peak period [s]")
    p.add_argument("--gamma", type=float, help="JONSWAP peak enhancement (default 1 with --hs/--tp)")
    p.add_argument("--heading", type=float, default=0.0, help="wave direction [deg]")
    p.add_argument("--seed", type=int, default=1, help="random phase seed")
    p.add_argument("--duration", type=float, default=10800.0, help="seconds of record")
    p.add_argument("--sample-dt", type=float, default=0.1, help="sample step [s]")
    p.add_argument("--point", type=float, nargs=2, default=(0.0, 0.0), metavar=("X", "Y"),
                   help="where the elevation is measured (world frame) [m]")
    p.add_argument("--platform", default="windmoor12", help="platform whose water depth and gravity apply")
    p.add_argument("-o", "--output", required=True, help="bag directory to write")
    p.add_argument("--overwrite", action="store_true", help="replace an existing bag")
    p.set_defaults(func=waves)


def recover(args: argparse.Namespace) -> int:
    from .rosbag.recover import recover as rebuild
    log.info(f"{args.bag}: {rebuild(args.bag)} messages recovered")
    return 0


def info(args: argparse.Namespace) -> int:
    from .rosbag.reader import Bag
    from .run_config import write_params_file
    bag = Bag(args.bag)
    lines = [f"bag {bag.path}: {bag.message_count} messages"]
    lines += [f"  {topic}  {t.type}  {t.message_count}" for topic, t in sorted(bag.topics.items())]
    if bag.config:
        lines += ["configuration:", *("  " + line for line in yaml.safe_dump(
            {k: v for k, v in bag.config.items() if k != "platform_yaml"}, sort_keys=False).splitlines())]
    sys.stdout.write("\n".join(lines) + "\n")
    if args.params_file:
        log.info(f"{write_params_file(bag.config or {}, args.params_file)}: rerun with fowt-sim node --ros-args "
                 f"--params-file {args.params_file}")
    return 0


def _add_bag_tools(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("recover", help="rebuild a bag whose recording was killed",
                       description="Rewrite a bag left incomplete (killed recording) from its complete chunks; "
                                   "the damaged file is kept as *.mcap.damaged.")
    p.add_argument("bag", help="bag directory")
    p.set_defaults(func=recover)
    p = sub.add_parser("info", help="a bag's topics, counts and run configuration",
                       description="Print a bag's topics and run configuration; --params-file writes the node "
                                   "parameter file that reruns a recorded run.")
    p.add_argument("bag", help="bag directory")
    p.add_argument("--params-file", help="write the node parameters reproducing the run to this file")
    p.set_defaults(func=info)


def _band_option(text: str) -> tuple[str | None, str, tuple[float, float]]:
    """[DOF.]NAME=LOW:HIGH"""
    try:
        name, limits = text.split("=")
        low, high = (float(v) for v in limits.split(":"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"band {text!r}: expected [DOF.]NAME=LOW:HIGH in Hz") from None
    dof, _, band = name.rpartition(".")
    return dof or None, band, (low, high)


def analysis_settings(args: argparse.Namespace):
    from .analysis import AnalysisSettings
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
    from .analysis import analyse, compare, table_text, write_report
    from .rosbag.reader import Bag
    settings = analysis_settings(args)
    if args.ref and len(args.ref) not in (1, len(args.runs)):
        raise ConfigError(f"--ref: give one reference, or one per run ({len(args.runs)}), got {len(args.ref)}")

    def load(path: str):
        motion = Bag(path).motion()
        return analyse(Path(path).name, motion.time_s, motion.values, settings)

    runs = [load(p) for p in args.runs]
    references = [load(p) for p in args.ref or []]
    pairs = list(zip(runs, references * len(runs) if len(references) == 1 else references))
    comparisons = [row for run, ref in pairs for row in compare(run, ref, settings)]
    sys.stdout.write(table_text(runs, comparisons, settings) + "\n")
    files = write_report(runs, comparisons, settings, Path(args.output), references)
    log.info(f"{args.output}: {', '.join(f.name for f in files)}")
    return 0


def _add_analyze(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("analyze", help="PSDs, band STDs and errors against a reference, of recorded runs",
                       description="Analyse bags (their /platform/pose): Welch PSD per DOF, band STDs with "
                                   "confidence intervals, and against --ref the STD error per DOF and band, "
                                   "pass/fail and pass rate. Writes table.txt, band_stds.csv, errors.csv, "
                                   "analysis.json and PNG figures.")
    p.add_argument("runs", nargs="+", help="run bags")
    p.add_argument("--ref", nargs="+", help="reference (measured) bags: one for all runs, or one per run")
    p.add_argument("-o", "--output", required=True, help="report folder")
    p.add_argument("--transient", type=float, default=600.0, help="seconds discarded at each run's start")
    p.add_argument("--segment", type=float, default=2048.0, help="Welch segment [s] (default %(default)s)")
    p.add_argument("--window", default="hann", help="Welch window (a scipy.signal window name)")
    p.add_argument("--overlap", type=float, default=0.5, help="Welch segment overlap fraction")
    p.add_argument("--dofs", nargs="+", default=["surge", "heave", "pitch"], help="DOFs analysed")
    p.add_argument("--band", type=_band_option, action="append",
                   help="band [DOF.]NAME=LOW:HIGH in Hz, repeatable (default low_frequency=0.005:0.05, "
                        "wave=0.05:0.25; with a DOF, overrides that DOF's band)")
    p.add_argument("--threshold", type=float, default=15.0, help="pass if |STD error| <= this [%%]")
    p.add_argument("--confidence", type=float, default=0.9, help="confidence level of the intervals")
    p.set_defaults(func=analyze)


def _ros_command(name: str, argv: list[str]) -> int:
    """``fowt-sim node|controller [--ros-args ...]``: the ROS 2 nodes (their arguments are ROS's)."""
    if any(a in ("-h", "--help") for a in argv[:1]):
        print(f"usage: fowt-sim {name} [--ros-args -p name:=value ... --params-file file.yaml]")
        return 0
    if name == "node":
        from .node import main as run
    else:
        from .controller import main as run
    return run(["fowt-sim", *argv])


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] in (["node"], ["controller"]):
        return _ros_command(argv[0], argv[1:])
    if argv[:1] == ["play"]:
        from .player import main as play
        return play(argv[1:])
    if argv[:1] == ["record"]:
        from .recorder import main as record
        return record(argv[1:])
    parser = argparse.ArgumentParser(prog="fowt-sim", description="Floating offshore wind platform simulator "
                                     "(also: fowt-sim node | controller [--ros-args ...], the ROS 2 nodes; "
                                     "fowt-sim play | record, bag replay and recording)")
    parser.add_argument("-v", "--verbose", action="store_true", help="debug logging")
    sub = parser.add_subparsers(dest="command", required=True)
    _add_simulate(sub)
    _add_load_cases(sub)
    _add_waves(sub)
    _add_bag_tools(sub)
    _add_analyze(sub)
    add_calibrate(sub)
    add_diagnose(sub)
    args = parser.parse_args(argv)
    logging.basicConfig(level=logging.DEBUG if args.verbose else logging.INFO, format="%(levelname)s %(name)s: %(message)s")
    try:
        return args.func(args)
    except (ConfigError, ValueError) as exc:
        print(f"fowt-sim {args.command}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
