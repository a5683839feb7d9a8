"""Benchmark: the offline coupled loop (platform model + IEA 15 MW rotor + NREL's ROSCO in
one process, no ROS; ``turbine.coupled.run_coupled``) on VolturnUS-S, exchanging every
controller step (0.05 s), with its linear mooring (a 6x6 matrix) and MoorPy's
catenaries; and its agreement with the ROS closed loop (platform node in lockstep + turbine
node over DDS on loopback) for the same inputs.

1. Speed: simulated seconds per wall second (and per CPU second of the process: the
   machine may be shared; the load average is printed) of --duration seconds in LC5.2
   waves at 13 m/s, after a short warm-up run (the kernels compiled and loaded).
2. Agreement (--agreement-duration seconds, still water, 11 m/s, a start off the static
   offset): the largest difference of the platform's motion and of the rotor speed and
   blade pitch between the two paths.

Run with ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST and a ROS_DOMAIN_ID of its own:
    python benchmarks/coupled_loop.py [--duration 600] [--agreement-duration 60] [--repeat 3]
"""
from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.config import load_case, load_platform
from fowt_hydro_sim.physics.model import PlatformModel, RunResult
from fowt_hydro_sim.physics.waves.components import repeat_period, synthesize
from fowt_hydro_sim.turbine.coupled import CHANNELS, run_coupled, static_offset, turbine_on_platform
from fowt_hydro_sim.turbine.wind import Wind

PLATFORM = "volturnus_s"


def speed(mooring: str, duration_s: float) -> tuple[float, float]:
    """Simulated seconds per wall second and per CPU second of one coupled run in LC5.2."""
    platform = load_platform(PLATFORM)
    sea = load_case("lc5.2").sea_state
    model = PlatformModel(platform, synthesize(sea, repeat_period(sea, duration_s)), dt_s=0.05,
                          mooring_model=mooring)
    rotor = turbine_on_platform("iea15_umaine", platform, Wind(speed_m_s=13.0))
    model.reset(motion=static_offset(model, rotor))
    for _ in run_coupled(model, rotor, 5.0):  # warm-up: the kernels loaded, the first wave block made
        pass
    wall, cpu = time.perf_counter(), time.process_time()
    for _ in run_coupled(model, rotor, duration_s, 0.25):
        pass
    wall, cpu = time.perf_counter() - wall, time.process_time() - cpu
    rotor.close()
    return duration_s / wall, duration_s / cpu


def agreement(duration_s: float) -> dict[str, float]:
    """The largest differences between the offline and the ROS closed loop."""
    from fowt_hydro_sim.ros import closed_loop
    from fowt_hydro_sim.rosbag.reader import Bag
    from msg_adapters import topics

    platform = load_platform(PLATFORM)
    model = PlatformModel(platform, None, dt_s=0.05)
    rotor = turbine_on_platform("iea15_umaine", platform, Wind(speed_m_s=11.0))
    initial = static_offset(model, rotor) + np.array([2.0, 0.0, 0.0, 0.0, 0.02, 0.0])
    model.reset(motion=initial)
    start = time.perf_counter()
    parts = list(run_coupled(model, rotor, duration_s))
    offline_wall = time.perf_counter() - start
    rotor.close()
    ours = RunResult.joined([p.result for p in parts])
    channels = np.concatenate([parts[0].turbine] + [p.turbine[1:] for p in parts[1:]])
    with tempfile.TemporaryDirectory() as folder:
        result = closed_loop.run(Path(folder) / "loop",
                                 {"platform": PLATFORM, "duration_s": duration_s, "real_time_factor": 0.0,
                                  "drag_model": "constant", "wave_source": "none",
                                  "initial_state": [float(v) for v in initial]},
                                 {"wind": "steady", "wind_speed_m_s": 11.0}, timeout_s=3600.0)
        if any(result.returncodes.values()):
            raise SystemExit(f"the ROS closed loop failed: {result.returncodes}")
        bag = Bag(Path(folder) / "loop")
        motion = bag.motion().values
        out = {"surge_m": float(np.abs(motion[:, 0] - ours.motion[:, 0]).max()),
               "pitch_rad": float(np.abs(motion[:, 4] - ours.motion[:, 4]).max()),
               "ros_speed": result.speed, "offline_speed": duration_s / offline_wall}
        for name, topic in (("rotor_speed_rad_s", "rotor_speed"), ("blade_pitch_rad", "blade_pitch")):
            theirs = bag.scalar(topics.TURBINE[topic][0]).values[:, 0]
            out[name] = float(np.abs(theirs - channels[:, CHANNELS.index(name)]).max())
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=600.0, help="simulated seconds per speed run")
    parser.add_argument("--agreement-duration", type=float, default=60.0,
                        help="simulated seconds of the comparison with the ROS closed loop (0: none)")
    parser.add_argument("--repeat", type=int, default=3, help="speed runs per mooring (the best is reported too)")
    args = parser.parse_args()
    print(f"load average before: {' '.join(f'{v:.2f}' for v in os.getloadavg())} on {os.cpu_count()} CPUs")
    for mooring in ("linear", "moorpy"):
        runs = [speed(mooring, args.duration) for _ in range(args.repeat)]
        walls, cpus = zip(*runs)
        print(f"{PLATFORM} + IEA-15 + ROSCO, {mooring} mooring, LC5.2 waves, 13 m/s, {args.duration:g} s: "
              f"{np.median(walls):.0f}x real time per wall second (median of {len(runs)}; best {max(walls):.0f}x), "
              f"{np.median(cpus):.0f}x per CPU second")
    print(f"load average after: {' '.join(f'{v:.2f}' for v in os.getloadavg())}")
    if args.agreement_duration > 0:
        a = agreement(args.agreement_duration)
        print(f"offline vs ROS closed loop, {args.agreement_duration:g} s (still water, 11 m/s): largest difference "
              f"surge {a['surge_m']:.2e} m, pitch {a['pitch_rad']:.2e} rad, rotor speed "
              f"{a['rotor_speed_rad_s']:.2e} rad/s, blade pitch {a['blade_pitch_rad']:.2e} rad; speed offline "
              f"{a['offline_speed']:.0f}x, over ROS {a['ros_speed']:.1f}x real time")


if __name__ == "__main__":
    main()
