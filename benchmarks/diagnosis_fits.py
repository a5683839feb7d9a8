"""A benchmark scenario's candidate fits, cell by cell: why a first fit ends where it does.

From the independent basin's runs of one scenario of a split set (made once, kept in
``OUTPUT/runs``), the diagnosis's first round on its tuning runs (wave runs and free decays)
in the fit window: the plain model's residuals (gap / tolerance) in every cell flagged on
the whole records, per run; then each effect at the values given (``--at``) and each effect's
first fit (``--fit``, ``method.fit_effect`` as the diagnosis runs it; ``--cells``: fitted to
those cells only, as a second round is to the cells not set aside; ``--decays-only``: on the
free decays alone), with the least-squares cost and the window closure. Every variant is
judged in the plain model's cells, as in the diagnosis. One process, no cluster; not timed.

    python benchmarks/diagnosis_fits.py held-out-6 'baseline_drag#s1' \\
        --at model_drag:cd_scale=0.68 --fit model_drag linear_damping model_slow_drift -o out/fits
"""
from __future__ import annotations

import argparse
from dataclasses import replace
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.config import load_platform
from fowt_hydro_sim.studies.diagnosis import benchmark, method
from fowt_hydro_sim.studies.diagnosis.effects import CATALOGUE
from fowt_hydro_sim.studies.diagnosis.gap import Gap, GapSettings
from fowt_hydro_sim.studies.diagnosis.runner import in_process


def point(text: str) -> tuple[str, dict[str, float]]:
    """``EFFECT:NAME=VALUE[,NAME=VALUE...]`` -> (effect, values)."""
    effect, _, assignments = text.partition(":")
    return effect, {name: float(value) for name, value in (a.split("=") for a in assignments.split(","))}


def table(label: str, gaps: list[Gap], plain: list[Gap], window_plain: list[Gap], cells: list[np.ndarray],
          names: list[tuple[str, str]]) -> None:
    """One variant's cost, window closure and residuals in the flagged cells (a column per run)."""
    cost = float(np.sum(method.residuals(gaps) ** 2))
    print(f"{label}: cost {cost:.2f}, window closure {method.window_closure(plain, window_plain, gaps):+.3f}")
    for i in cells:
        print(f"    {' '.join(names[i]):34s}" + " ".join(f"{g.residual[i]:+8.2f}" for g in gaps))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("set", choices=benchmark.SPLIT_SETS)
    parser.add_argument("scenario")
    parser.add_argument("--at", nargs="*", type=point, default=[], metavar="EFFECT:NAME=VALUE,...")
    parser.add_argument("--fit", nargs="*", default=[], choices=sorted(CATALOGUE), metavar="EFFECT")
    parser.add_argument("--cells", nargs="*", default=None, metavar="DOF:METRIC",
                        help="fit to these cells only (default every cell; the others charge a fit for moving them)")
    parser.add_argument("--decays-only", action="store_true",
                        help="fit on the free decays alone (the table still shows every run at the fitted values)")
    parser.add_argument("--duration", type=float, default=3600.0, help="seconds per basin run")
    parser.add_argument("-o", "--output", type=Path, default=Path("out/diagnosis_fits"))
    args = parser.parse_args()

    (scenario,) = benchmark.split_scenarios(args.set, names=[args.scenario])
    platform = load_platform("windmoor12")
    made = {(case, effect): benchmark.scenario_run((s, case, effect), platform, args.duration, "independent",
                                                   args.output / "runs")
            for s, case, effect in benchmark.truth_jobs([scenario], decays=True)}
    decays = benchmark.analysable([made[case, True] for case in benchmark.decay_cases(True)])
    tuning = [made[case, True] for case in scenario.tuning_cases] + decays
    settings = replace(GapSettings(), decays=bool(decays))
    evaluate = in_process(tuning, platform, settings, CATALOGUE, 0.1, benchmark.MODEL_OPTIONS["independent"])
    runs = range(len(tuning))
    window_s = method.fit_window(tuning, method.FIT_WINDOW_S)
    span = (window_s,) if window_s else ()
    plain = [g for g, _ in evaluate([(None, {}, i, False) for i in runs])]
    window_plain = [g for g, _ in evaluate([(None, {}, i, False, *span) for i in runs])]
    evaluate = method.judged_as_plain(evaluate, plain, window_s, window_plain)
    cells, names = np.flatnonzero(np.any([g.flagged for g in plain], axis=0)), settings.cells()
    print(f"{args.set} {scenario.name}, runs: {', '.join(r.name for r in tuning)}; the first {window_s:g} s")
    table("plain model", window_plain, plain, window_plain, cells, names)
    for effect, values in args.at:
        gaps = [g for g, _ in evaluate([(effect, values, i, False, *span) for i in runs])]
        table(f"{effect} at {values}", gaps, plain, window_plain, cells, names)
    mask = None if args.cells is None else np.array([f"{dof}:{metric}" in args.cells for dof, metric in names])
    fitted_runs = [i for i in runs if tuning[i].decay_dof is not None] if args.decays_only else list(runs)
    for effect in args.fit:
        values, gaps, count = method.fit_effect(CATALOGUE[effect], evaluate, fitted_runs, 4, effect, mask, window_s,
                                                [window_plain[i] for i in fitted_runs])
        if args.decays_only:
            gaps = [g for g, _ in evaluate([(effect, values, i, False, *span) for i in runs])]
        fitted = ", ".join(f"{k} {v:.4g}" for k, v in values.items())
        table(f"{effect} fitted ({fitted}; {count} model runs)", gaps, plain, window_plain, cells, names)


if __name__ == "__main__":
    main()
