"""Benchmark: the cost of recording. The node as fast as possible (real_time_factor 0,
all outputs at 20 Hz of simulated time, nobody subscribed), with and without ``record``:
simulated seconds per wall second, the recording's share of the speed, and the bag's size
per simulated hour.

Run with ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST and a ROS_DOMAIN_ID of its own:
    python benchmarks/recording.py [--duration 1800] [--repeats 2]
"""
from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path

from fowt_hydro_sim.rosbag.reader import Bag
from fowt_hydro_sim.testing.ros import node_speed


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=1800.0, help="simulated seconds per run")
    parser.add_argument("--repeats", type=int, default=2, help="runs of each kind (best kept)")
    parser.add_argument("--drag", default="filtered")
    args = parser.parse_args()
    if os.environ.get("ROS_AUTOMATIC_DISCOVERY_RANGE") != "LOCALHOST":
        sys.exit("set ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST (and a ROS_DOMAIN_ID of your own) first")
    with tempfile.TemporaryDirectory() as folder:
        bag = Path(folder) / "run"
        runs = [(node_speed(args.duration, args.drag, None), node_speed(args.duration, args.drag, bag))
                for _ in range(args.repeats)]  # interleaved, so drifts in machine load hit both
        plain, recorded = (max(r[i] for r in runs) for i in (0, 1))
        size = sum(f.stat().st_size for f in bag.iterdir())
        messages = Bag(bag).message_count
    print(f"node, real_time_factor 0, drag {args.drag}, {args.duration:g} s simulated, best of {args.repeats}:")
    print(f"  without recording: {plain:.0f} simulated s per wall s ({', '.join(f'{r[0]:.0f}' for r in runs)})")
    print(f"  recording all topics: {recorded:.0f} simulated s per wall s ({', '.join(f'{r[1]:.0f}' for r in runs)})")
    print(f"  recording costs {100 * (1 - recorded / plain):.1f} % of the speed (target < 25 %)")
    print(f"  bag: {messages} messages, {size / 1e6:.1f} MB, {size / 1e6 * 3600 / args.duration:.1f} MB per "
          f"simulated hour")


if __name__ == "__main__":
    main()
