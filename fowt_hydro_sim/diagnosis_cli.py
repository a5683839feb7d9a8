"""``fowt-sim diagnose``: the sim-to-real gap of measured runs, its cause and how far it
shrinks; ``fowt-sim diagnose-benchmark``: the diagnosis checked on runs whose effect is
withheld from the model."""
from __future__ import annotations

import argparse
import json
import logging
import sys
from pathlib import Path

from .config import ConfigError, _read_yaml, load_platform, platform_path
from .effects import CATALOGUE, Effect

log = logging.getLogger("fowt_hydro_sim")


def _effects(names: list[str] | None) -> dict[str, Effect]:
    if not names:
        return dict(CATALOGUE)
    unknown = [n for n in names if n not in CATALOGUE]
    if unknown:
        raise ConfigError(f"--effects: unknown {', '.join(unknown)} (catalogue: {', '.join(CATALOGUE)})")
    return {n: CATALOGUE[n] for n in names}


def _settings(args: argparse.Namespace):
    from .gap import GapSettings
    if args.transient < 0:
        raise ConfigError(f"--transient: must be >= 0 s, got {args.transient:g}")
    return GapSettings(transient_s=args.transient, dofs=tuple(args.dofs))


def _summary_lines(diagnosis) -> list[str]:
    lines = [f"gap: {len(diagnosis.flagged_cells(diagnosis.tuning_before))} flagged cells on the tuning runs"]
    lines += [f"  {run}: {dof} {metric}" for run, dof, metric in diagnosis.flagged_cells(diagnosis.tuning_before)]
    if diagnosis.candidates:
        lines.append(f"{'candidate':<26}{'score':>9}{'closure':>9}  parameters")
        lines += [f"{c.effect:<26}{c.score:>9.1f}{100 * c.closure:>8.0f}%  "
                  + ", ".join(f"{k} {v:.4g}" for k, v in c.values.items()) for c in diagnosis.candidates]
    lines.append(f"verdict: {diagnosis.verdict}" + (f": {diagnosis.chosen}" if diagnosis.chosen else "")
                 + f" ({diagnosis.reason})")
    if diagnosis.blind_after:
        lines.append(f"blind runs (not refitted): {100 * diagnosis.blind_closure:.0f} % of the gap closed")
    return lines


def diagnose_command(args: argparse.Namespace) -> int:
    from .cluster import dask_client
    from .diagnosis import check_runs, cluster_evaluate, diagnose
    from .diagnosis_report import write_report
    from .replay import measured_run
    load_platform(args.platform)  # validates
    document = _read_yaml(platform_path(args.platform))
    effects, settings = _effects(args.effects), _settings(args)
    tuning = [measured_run(p, args.heading) for p in args.measured]
    blind = [measured_run(p, args.heading) for p in args.blind or []]
    check_runs(tuning + blind, settings)  # before any cluster starts
    with dask_client(args.scheduler, args.workers) as client:
        evaluate = cluster_evaluate(client, tuning + blind, document, settings, effects)
        diagnosis = diagnose(tuning, blind, evaluate, settings, effects, args.max_evaluations)
    report = write_report(diagnosis, args.output)
    sys.stdout.write("\n".join(_summary_lines(diagnosis)) + f"\nreport: {report}\n")
    return 0


def benchmark_command(args: argparse.Namespace) -> int:
    from .cluster import dask_client
    from .diagnosis_benchmark import INJECTIONS, run_benchmark, scenarios, summary
    unknown = [n for n in args.inject or [] if n not in INJECTIONS]
    if unknown:
        raise ConfigError(f"--inject: unknown {', '.join(unknown)} (catalogue: {', '.join(INJECTIONS)})")
    if args.duration < args.transient + 600:
        raise ConfigError(f"--duration: need at least the transient plus 600 s, got {args.duration:g} s")
    document = _read_yaml(platform_path(args.platform))
    chosen = scenarios(args.inject, args.strengths, args.nulls, args.out_of_catalogue)
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    lines = []

    def report(score) -> None:
        line = (f"{score.scenario:<30} {score.verdict:<19} named {str(score.named):<26} "
                f"{'right' if score.correct else 'WRONG'}  detected {score.detected}  "
                f"blind closure {'-' if score.blind_closure is None else f'{100 * score.blind_closure:.0f} %'}  "
                f"{score.wall_s:.0f} s")
        lines.append(line)
        log.info(line)

    with dask_client(args.scheduler, args.workers) as client:
        scores = run_benchmark(client, chosen, document, _settings(args), _effects(args.effects),
                               args.duration, args.max_evaluations, report)
    figures = summary(scores)
    (out / "benchmark.json").write_text(json.dumps({"summary": figures, "scenarios": [s.__dict__ for s in scores]},
                                                   indent=1) + "\n")
    sys.stdout.write("\n".join(lines) + "\n" + json.dumps(figures, indent=1) + "\n")
    return 0


def _common(p: argparse.ArgumentParser) -> None:
    p.add_argument("--platform", default="windmoor12", help="packaged platform name or YAML (the model diagnosed)")
    p.add_argument("--effects", nargs="+", help=f"candidate effects (default: all: {', '.join(CATALOGUE)})")
    p.add_argument("--dofs", nargs="+", default=["surge", "heave", "pitch"], help="DOFs of the gap")
    p.add_argument("--transient", type=float, default=300.0, help="seconds left out at the start of each run")
    p.add_argument("--max-evaluations", type=int, default=4, help="least-squares evaluations per candidate")
    p.add_argument("--scheduler", help="address of an existing Dask scheduler (default: a local cluster)")
    p.add_argument("--workers", type=int, help="local cluster worker processes (default: one per core)")


def add_diagnose(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("diagnose", help="where the sim-to-real gap lies, which effect causes it, how far it shrinks",
                       description="Replay measured bags with their own wave elevation, measure the gap per DOF and "
                                   "metric with confidence intervals, fit each candidate effect of the catalogue to "
                                   "the tuning runs on a Dask cluster, name the one that explains the gap (or say "
                                   "'unexplained') and check it on blind runs without refitting.")
    p.add_argument("--measured", nargs="+", required=True, help="tuning bags (/waves/elevation, /platform/pose)")
    p.add_argument("--blind", nargs="+", help="blind bags: the chosen effect is checked on them, not refitted")
    p.add_argument("--heading", type=float, default=0.0, help="wave direction of the records [deg]")
    _common(p)
    p.add_argument("-o", "--output", default="out/diagnosis", help="report folder")
    p.set_defaults(func=diagnose_command)
    b = sub.add_parser("diagnose-benchmark", help="score the diagnosis on runs whose effect is withheld",
                       description="Make 'measured' runs with one effect switched on (each at two strengths, five "
                                   "sea states, 1 % sensor noise, small property errors), plus null and "
                                   "out-of-catalogue scenarios; diagnose each with the plain model and score: top-1 "
                                   "accuracy, false alarms, unexplained, blind closure.")
    b.add_argument("--inject", nargs="+", help="effects to inject (default: every catalogue effect)")
    b.add_argument("--strengths", type=int, default=2, choices=(0, 1, 2), help="strengths per injected effect")
    b.add_argument("--nulls", type=int, default=10, help="null scenarios (noise and property errors only)")
    b.add_argument("--out-of-catalogue", type=int, default=2, choices=(0, 1, 2),
                   help="out-of-catalogue scenarios (a rotor 1P pitch moment, wind thrust)")
    b.add_argument("--duration", type=float, default=1800.0, help="seconds per measured run")
    _common(b)
    b.add_argument("-o", "--output", default="out/diagnosis_benchmark", help="output folder")
    b.set_defaults(func=benchmark_command)
