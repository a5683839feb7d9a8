"""Benchmark: the closed loop (platform node + turbine node with NREL's ROSCO) over DDS on
loopback, lockstep, publishing at 20 Hz of simulated time.

1. As fast as possible (real_time_factor 0): simulated seconds per wall second of
   platform + turbine + ROSCO, without and with the bag recorder (``fowt-sim closed-loop``).
2. Real time (real_time_factor 1) for --paced-duration simulated seconds: the jitter of the
   wrench's arrival at a listener (the interval between wrenches against the 50 ms period,
   and the arrival's offset from the wall-clock schedule of its stamp, about its median).

Run with ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST and a ROS_DOMAIN_ID of its own:
    python benchmarks/closed_loop.py [--duration 600] [--paced-duration 60]
"""
from __future__ import annotations

import argparse
import os
import re
import sys
import tempfile
from pathlib import Path

import numpy as np
from geometry_msgs.msg import WrenchStamped

import msg_adapters as adapt
from fowt_hydro_sim.ros import closed_loop
from fowt_hydro_sim.testing.ros import Listener, finish, start

WIND = {"wind": "steady", "wind_speed_m_s": 13.0}


def loop_speed(node: dict, listener: Listener | None = None) -> tuple[float, str]:
    platform = start("node", lockstep=True, **node)
    turbine = start("turbine", **WIND)
    try:
        output = finish(platform, 3600.0)
    finally:
        finish(turbine, 10.0)
    done = re.search(r"([\d.]+) s simulated in ([\d.]+) s of wall time", output)
    if not done:
        raise RuntimeError(f"the node did not report its speed:\n{output}")
    sim, wall = map(float, done.groups())
    return sim / wall, output


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=600.0, help="simulated seconds, accelerated run")
    parser.add_argument("--paced-duration", type=float, default=60.0, help="simulated seconds at real time")
    args = parser.parse_args()
    if os.environ.get("ROS_AUTOMATIC_DISCOVERY_RANGE") != "LOCALHOST":
        sys.exit("set ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST (and a ROS_DOMAIN_ID of your own) first")
    offset = list(closed_loop.static_offset({}, WIND))
    common = {"load_case": "lc5.2", "initial_state": offset}

    speed, _ = loop_speed({**common, "duration_s": args.duration, "real_time_factor": 0.0})
    print(f"closed loop, lc5.2 waves, 13 m/s wind, 20 Hz lockstep, {args.duration:g} s simulated:")
    print(f"  as fast as possible, platform + turbine + ROSCO: {speed:.1f} simulated s per wall s")
    with tempfile.TemporaryDirectory() as folder:
        result = closed_loop.run(Path(folder) / "bag", {**common, "duration_s": args.duration,
                                                        "real_time_factor": 0.0}, WIND)
    print(f"  with the recorder (fowt-sim closed-loop): {result.speed:.1f} simulated s per wall s")

    listener = Listener({"/platform/external_wrench": WrenchStamped})
    _, output = loop_speed({**common, "duration_s": args.paced_duration, "real_time_factor": 1.0})
    listener.close()
    stamps = np.array([adapt.wrench_from_msg(m)[0] for m in listener.messages["/platform/external_wrench"]])
    arrival = np.array(listener.arrival["/platform/external_wrench"])
    keep = np.concatenate([[True], np.diff(stamps) > 0])  # a wrench answered again is not a new one
    stamps, arrival = stamps[keep], arrival[keep]
    interval_ms = np.abs(np.diff(arrival) - np.diff(stamps)) * 1e3
    offset_ms = (arrival - stamps) * 1e3
    offset_ms = np.abs(offset_ms - np.median(offset_ms))
    late = re.search(r"pacing lateness p50 ([\d.]+) ms, p99 ([\d.]+) ms", output)
    print(f"real time, {args.paced_duration:g} s, {len(stamps)} wrenches received:")
    print(f"  interval jitter |dt_arrival - dt_stamp|: p50 {np.percentile(interval_ms, 50):.2f} ms, "
          f"p99 {np.percentile(interval_ms, 99):.2f} ms, max {interval_ms.max():.2f} ms")
    print(f"  arrival offset from the schedule, about its median: p50 {np.percentile(offset_ms, 50):.2f} ms, "
          f"p99 {np.percentile(offset_ms, 99):.2f} ms")
    if late:
        print(f"  the platform node's own pacing lateness: p50 {late.group(1)} ms, p99 {late.group(2)} ms")


if __name__ == "__main__":
    main()
