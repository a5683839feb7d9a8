"""Benchmark and check of the calibration without basin data.

"Measured" runs are made with the model itself: windmoor12 with the six surge Cds (column
submerged and splash zones, pontoons horizontal; low-frequency and wave bands) set per
load case along a known law in Hs/D, driven by each case's synthesised waves, with 1 %
sensor noise on the motion. The Cds are then hidden: calibrated from the platform file's
values on LC5.0-5.4 (on a local Dask cluster), regressed on Hs/D (quadratic), predicted
for LC6.1, and LC6.1 is run blind with the predicted Cds.

Prints: wall time and model runs of the calibration, recovered against true Cds, the band
STD errors before and after on LC5.x and blind on LC6.1.

    python benchmarks/calibration.py [--duration 10800] [--workers 2]
"""
from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.config import Platform, SeaState, load_case, load_platform
from fowt_hydro_sim.physics.platform_edits import coefficient, with_coefficients
from fowt_hydro_sim.physics.waves.components import synthesize
from fowt_hydro_sim.rosbag.measured import write_measured_bag
from fowt_hydro_sim.studies.analysis import AnalysisSettings, analyse
from fowt_hydro_sim.studies.calibration import calibrate_all, errors, predict, regress, replay, rms
from fowt_hydro_sim.studies.cluster import dask_client
from fowt_hydro_sim.studies.replay import MeasuredRun, measured_run

SURGE_CDS = [f"column*.{zone}.cd.{band}" for zone in ("submerged", "splash") for band in ("low_frequency", "wave")] \
    + [f"pontoon*.submerged.cd_horizontal.{band}" for band in ("low_frequency", "wave")]
TUNING, BLIND = ("lc5.0", "lc5.1", "lc5.2", "lc5.3", "lc5.4"), "lc6.1"
D_M = 15.0


def true_cds(start: dict[str, float], hs_over_d: float) -> dict[str, float]:
    """The hidden law: low-frequency Cds grow with Hs/D, wave Cds fall, both linear."""
    return {p: v * ((0.7 + 0.9 * hs_over_d) if "low_frequency" in p else (1.25 - 0.5 * hs_over_d))
            for p, v in start.items()}


def make_measured(folder: Path, platform: Platform, case: str, duration_s: float, noise: float, seed: int) -> Path:
    spec = load_case(case).sea_state
    sea = SeaState(spec.hs_m, spec.tp_s, spec.gamma, seed=seed)
    t = np.arange(0.0, duration_s + 1e-9, 0.1)
    eta = synthesize(sea, duration_s).elevation_series(0.0, 0.0, 0.1, 150.0, 9.80665)
    eta = np.resize(eta, t.size)
    truth = with_coefficients(platform, true_cds({p: coefficient(platform, p) for p in SURGE_CDS}, spec.hs_m / D_M))
    time_s, motion = replay(truth, MeasuredRun(case, t, eta, (0.0, 0.0), t, np.zeros((t.size, 6))), "filtered")
    rng = np.random.default_rng(seed)
    motion = motion + noise * motion.std(axis=0) * rng.normal(size=motion.shape)
    return write_measured_bag(folder / case, t, eta, (0.0, 0.0), time_s, motion)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=10800.0, help="seconds per run")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--noise", type=float, default=0.01, help="sensor noise, fraction of each DOF's STD")
    parser.add_argument("--scheduler", help="an existing Dask scheduler")
    args = parser.parse_args()
    platform = load_platform("windmoor12")
    start = {p: coefficient(platform, p) for p in SURGE_CDS}
    settings = AnalysisSettings(transient_s=600.0, dofs=("surge", "heave", "pitch"))
    with tempfile.TemporaryDirectory() as folder:
        made = time.perf_counter()
        bags = {case: make_measured(Path(folder), platform, case, args.duration, args.noise, seed)
                for seed, case in enumerate((*TUNING, BLIND), start=1)}
        print(f"measured runs made: {len(bags)} x {args.duration:g} s in {time.perf_counter() - made:.0f} s")
        began = time.perf_counter()
        with dask_client(args.scheduler, args.workers) as client:
            calibrated = calibrate_all(client, [measured_run(bags[case]) for case in TUNING], platform, SURGE_CDS,
                                       settings)
        results = dict(zip(TUNING, calibrated))
        wall = time.perf_counter() - began
        print(f"calibration of {len(SURGE_CDS)} surge Cds on {', '.join(TUNING)} ({args.duration:g} s runs, "
              f"{args.workers} local workers): {wall:.0f} s wall, {sum(r.model_runs for r in results.values())} "
              f"model runs")
        for case, r in results.items():
            truth = true_cds(start, load_case(case).sea_state.hs_m / D_M)
            worst = max(abs(r.parameters[p] / truth[p] - 1) for p in SURGE_CDS)
            print(f"  {case}: RMS band error {rms(r.errors_before):.1f} % -> {rms(r.errors_after):.1f} %, "
                  f"Cds within {100 * worst:.0f} % of the truth "
                  f"({', '.join(f'{r.parameters[p]:.2f}/{truth[p]:.2f}' for p in SURGE_CDS)})")
        x = np.array([load_case(c).sea_state.hs_m / D_M for c in TUNING])
        coefficients = {p: regress(x, np.array([results[c].parameters[p] for c in TUNING])) for p in SURGE_CDS}
        blind_hs_d = load_case(BLIND).sea_state.hs_m / D_M
        predicted, truth = predict(coefficients, blind_hs_d), true_cds(start, blind_hs_d)
        print(f"{BLIND} (Hs/D {blind_hs_d:.3f}) predicted / true Cds: "
              + ", ".join(f"{predicted[p]:.2f}/{truth[p]:.2f}" for p in SURGE_CDS))
        run = measured_run(bags[BLIND])
        measured = analyse(BLIND, run.motion_time_s, run.motion, settings)
        names = [f"{d}.{b}" for d in settings.dofs for b in settings.bands(d)]
        for label, candidate in (("start Cds", platform), ("predicted Cds", with_coefficients(platform, predicted))):
            time_s, motion = replay(candidate, run, "filtered")
            e = 100 * errors(analyse("model", time_s, motion, settings), measured, settings)
            print(f"  blind {BLIND}, {label}: " + ", ".join(f"{n} {v:+.1f} %" for n, v in zip(names, e))
                  + f" (RMS {np.sqrt(np.mean(e ** 2)):.1f} %, {np.mean(np.abs(e) <= 15):.0%} within 15 %)")


if __name__ == "__main__":
    main()
