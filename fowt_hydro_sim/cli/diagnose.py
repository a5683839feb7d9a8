"""``fowt-sim diagnose``: the sim-to-real gap of measured runs, its cause and how far it
shrinks; ``fowt-sim diagnose-benchmark``: the diagnosis checked on runs whose effect is
withheld from the model."""
from __future__ import annotations

import argparse
import sys
from dataclasses import replace
from pathlib import Path

from fowt_hydro_sim.cli import options
from fowt_hydro_sim.physics.config import ConfigError, RunConfig, SeaState, load_platform
from fowt_hydro_sim.studies.diagnosis.benchmark import INDEPENDENT_INJECTIONS, SPLIT_FILE, SPLIT_SETS
from fowt_hydro_sim.studies.diagnosis.effects import CATALOGUE, Effect
from fowt_hydro_sim.studies.diagnosis.method import FIT_WINDOW_S
from fowt_hydro_sim.studies.diagnosis.runner import REPLAY_DT_S

# the generated scenario list's options and their defaults (not with --set)
GENERATED = {"strengths": 2, "nulls": 10, "out_of_catalogue": 2}


def _effects(names: list[str] | None) -> dict[str, Effect]:
    if not names:
        return dict(CATALOGUE)
    unknown = [n for n in names if n not in CATALOGUE]
    if unknown:
        raise ConfigError(f"--effects: unknown {', '.join(unknown)} (catalogue: {', '.join(CATALOGUE)})")
    return {n: CATALOGUE[n] for n in names}


def _common(args: argparse.Namespace):
    from fowt_hydro_sim.studies.diagnosis.gap import GapSettings
    if args.transient < 0:
        raise ConfigError(f"--transient: must be >= 0 s, got {args.transient:g}")
    run = options.values(args, RunConfig, ("platform", "dt_s"))
    return (load_platform(run["platform"]), GapSettings(transient_s=args.transient, dofs=tuple(args.dofs)),
            _effects(args.effects), run["dt_s"])


def _decays(given: list[str] | None, dofs: list[str]) -> list[tuple[str, str]]:
    """--decay's DOF=BAG pairs; ConfigError naming a malformed one or a DOF not diagnosed."""
    out = []
    for item in given or []:
        dof, sep, path = item.partition("=")
        if not sep or not path:
            raise ConfigError(f"--decay: need DOF=BAG (e.g. surge=bags/surge_decay), got {item!r}")
        if dof not in dofs:
            raise ConfigError(f"--decay {item}: {dof!r} is not a DOF of the gap (--dofs: {', '.join(dofs)})")
        out.append((dof, path))
    return out


def diagnose_command(args: argparse.Namespace) -> int:
    from fowt_hydro_sim.studies.diagnosis.runner import diagnose_bags
    platform, settings, effects, dt_s = _common(args)
    decays = _decays(args.decay, args.dofs)
    lines = diagnose_bags(args.measured, args.blind or [], platform, replace(settings, decays=bool(decays)), effects,
                          args.output, args.heading, args.max_evaluations, dt_s, args.scheduler, args.workers,
                          args.fit_window, decays)
    sys.stdout.write("\n".join(lines) + "\n")
    return 0


def benchmark_command(args: argparse.Namespace) -> int:
    from fowt_hydro_sim.studies.diagnosis.benchmark import benchmark
    platform, settings, effects, dt_s = _common(args)
    given = [f"--{name.replace('_', '-')}" for name, default in GENERATED.items() if getattr(args, name) != default]
    if args.scenario_set and given:
        raise ConfigError(f"{', '.join(given)}: the scenarios of a --set are fixed in its file (--inject and "
                          "--scenarios choose among them)")
    if args.no_decays and args.source != "independent":
        raise ConfigError("--no-decays: only the independent source has free decays (--source independent)")
    settings = replace(settings, decays=args.source == "independent" and not args.no_decays)
    lines = benchmark(platform, settings, effects, Path(args.output), args.inject, args.strengths, args.nulls,
                      args.out_of_catalogue, args.duration, args.max_evaluations, dt_s,
                      args.scheduler, args.workers,
                      args.source, options.values(args, SeaState, ("seed",))["seed"], args.scenario_set,
                      args.scenarios)
    sys.stdout.write("\n".join(lines) + "\n")
    return 0


def _add_common(p: argparse.ArgumentParser) -> None:
    options.add(p, RunConfig, ("platform", "dt_s"), defaults={"dt_s": REPLAY_DT_S},
                notes={"platform": " (the model diagnosed)", "dt_s": " of the replays"})
    p.add_argument("--effects", nargs="+", help=f"candidate effects (default: all: {', '.join(CATALOGUE)})")
    p.add_argument("--dofs", nargs="+", default=["surge", "heave", "pitch"],
                   help="DOFs of the gap (default: %(default)s)")
    p.add_argument("--transient", type=float, default=300.0,
                   help="seconds left out at the start of each run (default %(default)s)")
    p.add_argument("--max-evaluations", type=int, default=4,
                   help="least-squares evaluations per candidate (default %(default)s)")
    p.add_argument("--scheduler", help="address of an existing Dask scheduler (default: a local cluster)")
    p.add_argument("--workers", type=int, help="local cluster worker processes (default: one per core)")


def add_parsers(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("diagnose", help="where the sim-to-real gap lies, which effect causes it, how far it shrinks",
                       description="Replay measured bags with their own wave elevation, measure the gap per DOF and "
                                   "metric with confidence intervals, fit each candidate effect of the catalogue to "
                                   "the tuning runs on a Dask cluster, name the one that explains the gap (or say "
                                   "'unexplained') and check it on blind runs without refitting.")
    p.add_argument("--measured", nargs="+", required=True, help="tuning bags (/waves/elevation, /platform/pose)")
    p.add_argument("--blind", nargs="+", help="blind bags: the chosen effect is checked on them, not refitted")
    p.add_argument("--decay", nargs="+", metavar="DOF=BAG",
                   help="free-decay bags (/platform/pose; calm water), each with the DOF it decays in, e.g. "
                        "surge=bags/surge_decay: their periods and damping join the tuning runs' gap")
    p.add_argument("--heading", type=float, default=0.0, help="wave direction of the records [deg] (default 0)")
    _add_common(p)
    p.add_argument("--fit-window", type=float, default=FIT_WINDOW_S,
                   help="tuning records longer than this [s] are fitted on their first part, then replayed whole; "
                        "0: fit on whole records (default %(default)s)")
    p.add_argument("-o", "--output", default="out/diagnosis", help="report folder (default %(default)s)")
    p.set_defaults(func=diagnose_command)
    b = sub.add_parser("diagnose-benchmark", help="score the diagnosis on runs whose effect is withheld",
                       description="Make 'measured' runs with one effect switched on (each at two strengths, five "
                                   "sea states, 1 % sensor noise, small property errors), plus null and "
                                   "out-of-catalogue scenarios; diagnose each with the plain model (the default hydro "
                                   "options) and score: top-1 accuracy, false alarms, unexplained, blind closure. "
                                   "--source twin: the runs are the model's own, the effect in its catalogue form; "
                                   "independent: the Cummins/BEM simulator's, effects in other forms (runs cached "
                                   "in OUTPUT/runs).")
    b.add_argument("--source", choices=("twin", "independent"), default="twin",
                   help="simulator of the 'measured' runs (default %(default)s)")
    b.add_argument("--inject", nargs="+", help="effects to inject (default: all; twin: catalogue effects; "
                                               f"independent: {', '.join(INDEPENDENT_INJECTIONS)})")
    b.add_argument("--strengths", type=int, default=GENERATED["strengths"], choices=(0, 1, 2),
                   help="strengths per injected effect; not with --set (default %(default)s)")
    b.add_argument("--nulls", type=int, default=GENERATED["nulls"],
                   help="null scenarios, noise and property errors only; not with --set (default %(default)s)")
    b.add_argument("--out-of-catalogue", type=int, default=GENERATED["out_of_catalogue"], choices=(0, 1, 2),
                   help="out-of-catalogue scenarios, a rotor 1P pitch moment and wind thrust (independent: the "
                        "1P moment only); not with --set (default %(default)s)")
    b.add_argument("--set", dest="scenario_set", choices=SPLIT_SETS,
                   help="with --source independent: the scenarios of a set fixed in "
                        f"{SPLIT_FILE.name} (development, or a held-out set; their seeds and load cases) "
                        "instead of the generated list; --inject keeps the injected forms named (default: the "
                        "generated list)")
    b.add_argument("--scenarios", nargs="+", help="with --set: only these scenarios of the set (default: all)")
    b.add_argument("--no-decays", action="store_true",
                   help="independent source: leave out the basin's free decays in surge and pitch (default: "
                        "each scenario has them as tuning runs)")
    b.add_argument("--duration", type=float, default=10800.0,
                   help="seconds per measured run (default %(default)s, 3 hours)")
    options.add(b, SeaState, ("seed",), defaults={"seed": None},
                notes={"seed": " of the first scenario's runs; scenario i's from seed + 17 i (default 1000 twin, "
                               "2000 independent)"})
    _add_common(b)
    b.add_argument("-o", "--output", default="out/diagnosis_benchmark", help="output folder (default %(default)s)")
    b.set_defaults(func=benchmark_command)
