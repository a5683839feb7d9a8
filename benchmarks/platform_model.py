"""Benchmark: 3 hours of windmoor12 in LC5.3 (constant Cd), offline, no ROS.

Prints set-up time (wave synthesis and kinematics table), integration time, wall time,
real-time factor and peak memory. Run: python benchmarks/platform_model.py [--duration S]
The numba kernels are compiled (or loaded from cache) by a short warm-up run first.
"""
from __future__ import annotations

import argparse
import resource
import time

from fowt_hydro_sim.config import load_case, load_platform
from fowt_hydro_sim.model import PlatformModel
from fowt_hydro_sim.waves import repeat_period, synthesize


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=10800.0, help="simulated seconds")
    parser.add_argument("--load-case", default="lc5.3")
    parser.add_argument("--dt", type=float, default=0.05)
    args = parser.parse_args()

    platform = load_platform("windmoor12")
    sea = load_case(args.load_case).sea_state
    PlatformModel(platform, synthesize(sea, 600.0), dt_s=args.dt).run(10.0)  # compile / load cache

    start = time.perf_counter()
    model = PlatformModel(platform, synthesize(sea, repeat_period(sea, args.duration)), dt_s=args.dt)
    built = time.perf_counter()
    result = model.run(args.duration, output_interval_s=0.25)
    end = time.perf_counter()
    wall = end - start
    print(f"windmoor12 {args.load_case}, constant Cd, dt {args.dt:g} s, {args.duration:g} s simulated")
    print(f"  strips {len(model.geometry.strips.length_m)}, kinematics points {len(model.geometry.points_m)}, "
          f"wave components {model.waves.frequency_hz.size}, wave table step {model.wave_table_step_s:g} s")
    print(f"  set-up (waves + kinematics table): {built - start:.2f} s")
    print(f"  integration:                       {end - built:.2f} s")
    print(f"  wall time:                         {wall:.2f} s")
    print(f"  real-time factor:                  {args.duration / wall:.0f}x (integration alone "
          f"{args.duration / (end - built):.0f}x)")
    print(f"  peak memory (max RSS):             {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB")
    print(f"  surge std {result.motion[:, 0].std():.3f} m, heave std {result.motion[:, 2].std():.3f} m")


if __name__ == "__main__":
    main()
