"""Benchmark: windmoor12 in LC5.3 (3 hours by default), offline, no ROS, with the constant-Cd
and the filtered (frequency-dependent) drag model.

Prints, per drag model: set-up time (waves, kinematics table, filter steady state),
integration time, wall time, real-time factor, and the filtered model's cost per simulated
second relative to the constant model's (target: at most 1.3). Integration times are the
best of ``--repeats`` runs, alternating the models, to be robust to a busy machine.
Run: python benchmarks/platform_model.py [--duration S] [--repeats N]
The numba kernels are compiled (or loaded from cache) by a short warm-up run first.
"""
from __future__ import annotations

import argparse
import resource
import time

from fowt_hydro_sim.physics.config import DRAG_MODELS, load_case, load_platform
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import repeat_period, synthesize


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=10800.0, help="simulated seconds")
    parser.add_argument("--load-case", default="lc5.3")
    parser.add_argument("--dt", type=float, default=0.05)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()

    platform = load_platform("windmoor12")
    sea = load_case(args.load_case).sea_state
    for drag in DRAG_MODELS:  # compile / load the kernels' cache
        PlatformModel(platform, synthesize(sea, 600.0), dt_s=args.dt, drag_model=drag).run(10.0)

    start = time.perf_counter()
    waves = synthesize(sea, repeat_period(sea, args.duration))
    synthesis_s = time.perf_counter() - start
    models, set_up = {}, {}
    for drag in DRAG_MODELS:
        begin = time.perf_counter()
        models[drag] = PlatformModel(platform, waves, dt_s=args.dt, drag_model=drag)
        set_up[drag] = time.perf_counter() - begin
    integration = {drag: float("inf") for drag in DRAG_MODELS}
    results = {}
    for _ in range(args.repeats):
        for drag, model in models.items():
            model.reset()
            begin = time.perf_counter()
            results[drag] = model.run(args.duration, output_interval_s=0.25)
            integration[drag] = min(integration[drag], time.perf_counter() - begin)
    model = models["constant"]
    print(f"windmoor12 {args.load_case}, dt {args.dt:g} s, {args.duration:g} s simulated, "
          f"best of {args.repeats} runs")
    print(f"  strips {model.n_strips}, kinematics points {len(model.geometry.points_m)}, "
          f"wave components {waves.frequency_hz.size}, wave table step {model.wave_table_step_s:g} s, "
          f"filter states {models['filtered'].filter_bank.n_states} per strip and direction")
    print(f"  {'drag model':12s}{'set-up s':>10s}{'integration s':>15s}{'wall s':>9s}{'real-time x':>13s}"
          f"{'surge std m':>13s}")
    for drag in DRAG_MODELS:
        wall = set_up[drag] + integration[drag]
        print(f"  {drag:12s}{set_up[drag]:10.2f}{integration[drag]:15.2f}{wall:9.2f}"
              f"{args.duration / integration[drag]:13.0f}{results[drag].motion[:, 0].std():13.3f}")
    print(f"  filtered / constant time per simulated second: "
          f"{integration['filtered'] / integration['constant']:.2f} (target <= 1.30)")
    print(f"  wave synthesis {synthesis_s:.2f} s (shared); peak memory (max RSS) "
          f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB (both models' tables)")


if __name__ == "__main__":
    main()
