"""Benchmark: windmoor12 in LC5.3 (3 hours by default), offline, no ROS, with the constant-Cd
and the filtered (frequency-dependent) drag model.

Prints, per drag model: set-up time (waves, kinematics table, filter steady state),
integration time, wall time, real-time factor, and the filtered model's cost per simulated
second relative to the constant model's (target: at most 1.3). Integration times are the
best of ``--repeats`` runs, alternating the models, to be robust to a busy machine.
Then the arithmetic bound: the floating-point operations the filtered step needs per strip
(counted from the kernels, ``FLOPS_PER_STRIP``) x strips x steps per simulated second,
against this core's rate measured with a compiled loop of independent multiply-adds.
Run: python benchmarks/platform_model.py [--duration S] [--repeats N]
The numba kernels are compiled (or loaded from cache) by a short warm-up run first.
"""
from __future__ import annotations

import argparse
import os
import resource
import time

import numpy as np
from numba import njit

from fowt_hydro_sim.physics.config import DRAG_MODELS, load_case, load_platform
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import repeat_period, synthesize


# floating-point operations per strip and transverse direction pair, per right-hand side of
# the filtered model (2 bands, 6 filter states, 10 non-zero A entries, 2 non-zero C entries),
# counted from the kernels (sqrt counted as one)
FLOPS_PER_STRIP_RHS = {
    "relative velocity (morison.relative_velocities)": 62,  # 2 rotations 15, w x r 9, 3, 2 x 2 dots 5
    "filter rates (drag_filters.filter_rates)": 52,  # 2 x (6 B u + 10 A x FMAs)
    "band velocities (drag_filters.band_velocities)": 12,  # 2 x (2 D u + 2 C x FMAs)
    "drag per length (drag_filters.drag_per_length)": 20,  # |v| 4, 2 bands x (|v_b| 4 + 2 x 2)
    "strip wrenches (morison.strip_loads)": 147,  # w x (w x r) 18, 2 x (10 + 9 + 3 wrenches 15) ...
    "strip 6x6 added mass (morison.strip_loads)": 72,  # 36 multiply-adds
    "wetted fraction (morison.wetted_fractions)": 17,
}
FLOPS_ABM_PER_STATE = 18  # predictor and corrector, 9 each, per filter state and step
RHS_PER_STEP = 2  # ABM4 PECE


@njit(fastmath=True, cache=True)
def _multiply_adds(n: int) -> float:
    """16 independent chains of a = a x + y (the compiler may pack them into SIMD lanes)."""
    acc = np.arange(16) * 1e-3 + 1.0
    for _ in range(n):
        for k in range(16):
            acc[k] = acc[k] * 0.999999999 + 1e-9
    return acc.sum()


def core_rate_gflops(n: int = 20_000_000) -> float:
    """This core's multiply-add rate [Gflop/s], best of 3 (2 flops per multiply-add)."""
    _multiply_adds(10)
    best = float("inf")
    for _ in range(3):
        start = time.perf_counter()
        _multiply_adds(n)
        best = min(best, time.perf_counter() - start)
    return 2 * 16 * n / best / 1e9


def arithmetic_bound(n_strips: int, n_states: int, dt_s: float, measured_s_per_s: float) -> str:
    """What the filtered step needs, against the core's rate and the measured time."""
    per_step = RHS_PER_STEP * sum(FLOPS_PER_STRIP_RHS.values()) + FLOPS_ABM_PER_STATE * 2 * n_states
    flops_per_s = per_step * n_strips / dt_s
    rate = core_rate_gflops()
    bound_s_per_s = flops_per_s / (rate * 1e9)
    lines = [f"  arithmetic bound (filtered): {per_step} flops per strip per step x {n_strips} strips x "
             f"{1 / dt_s:g} steps per s = {flops_per_s / 1e6:.2f} Mflop per simulated second",
             f"  core multiply-add rate {rate:.1f} Gflop/s -> bound {1e3 * bound_s_per_s:.3f} ms per simulated "
             f"second ({1 / bound_s_per_s:,.0f}x real time); measured {1e3 * measured_s_per_s:.3f} ms "
             f"({1 / measured_s_per_s:,.0f}x), {bound_s_per_s / measured_s_per_s:.0%} of the bound's speed; "
             f"load average {os.getloadavg()[0]:.1f}"]
    return "\n".join(lines)


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
          f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB")
    filtered = models["filtered"]
    print(arithmetic_bound(filtered.n_strips, filtered.filter_bank.n_states, args.dt,
                           integration["filtered"] / args.duration))


if __name__ == "__main__":
    main()
