"""Benchmark: the ROS 2 node (fowt-sim node) as a user runs it, over DDS on loopback.

1. Accelerated: real_time_factor 0, every output topic at 20 Hz of simulated time:
   simulated seconds per wall second, with nobody subscribed (the node's own throughput,
   best of 3) and with a Python listener subscribed to every topic on the same cores.
2. Real time: real_time_factor 1 for --paced-duration s: the node's own pacing lateness
   (wall time behind the schedule at each publish), p50 and p99.

Run with ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST and a ROS_DOMAIN_ID of its own:
    python benchmarks/node.py [--duration 600] [--paced-duration 30]
"""
from __future__ import annotations

import argparse
import os
import re
import sys
import time

from fowt_hydro_sim.ros.node import MESSAGE_CLASSES, OUTPUTS
from fowt_hydro_sim.testing.ros import Listener, finish, node_speed, start

TOPICS = {topic: MESSAGE_CLASSES[kind] for topic, kind in OUTPUTS.values()}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=600.0, help="simulated seconds, accelerated run")
    parser.add_argument("--paced-duration", type=float, default=30.0, help="wall seconds at real time")
    parser.add_argument("--drag", default="filtered")
    args = parser.parse_args()
    if os.environ.get("ROS_AUTOMATIC_DISCOVERY_RANGE") != "LOCALHOST":
        sys.exit("set ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST (and a ROS_DOMAIN_ID of your own) first")

    alone = [node_speed(args.duration, args.drag, None) for _ in range(3)]
    print(f"accelerated, {len(TOPICS)} topics at 20 Hz simulated, drag {args.drag}, {args.duration:g} s:")
    print(f"  nobody subscribed: {max(alone):.0f} simulated s per wall s (best of 3: "
          f"{', '.join(f'{a:.0f}' for a in alone)}; target >= 500)")

    listener = Listener(TOPICS)
    node = start("node", real_time_factor=0.0, duration_s=args.duration, drag_model=args.drag)
    listener.wait_for(lambda: node.poll() is not None, 3600.0)
    output = finish(node, 10)
    time.sleep(0.5)
    listener.close()
    done = re.search(r"([\d.]+) s simulated in ([\d.]+) s of wall time", output)
    received = {topic: len(msgs) for topic, msgs in listener.messages.items()}
    if not done or "duration" not in output:
        print(output)
    if done:
        sim, wall = map(float, done.groups())
        print(f"  a Python listener subscribed to all: {sim / wall:.0f} simulated s per wall s ({sim:g} s in "
              f"{wall:.2f} s)")
    print(f"  messages received per topic: min {min(received.values())}, max {max(received.values())} "
          f"(expected {int(args.duration * 20) + 1})")

    node = start("node", real_time_factor=1.0, drag_model=args.drag)
    time.sleep(args.paced_duration)
    node.terminate()
    output = finish(node, 10)
    paced = re.search(r"p50 ([\d.]+) ms, p99 ([\d.]+) ms over (\d+) steps", output)
    print(f"real time, {args.paced_duration:g} s:")
    if paced:
        p50, p99, n = paced.groups()
        print(f"  pacing lateness p50 {p50} ms, p99 {p99} ms over {n} steps (target p99 < 2 ms)")
    else:
        print(output)


if __name__ == "__main__":
    main()
