"""Benchmark: the ROS 2 node (fowt-sim node) as a user runs it, over DDS on loopback.

1. As fast as possible: real_time_factor 0, every output topic at 20 Hz of simulated time,
   nobody subscribed, without and with recording (interleaved, best of --repeats):
   simulated seconds per wall second, and the stepping's CPU seconds (which depend less on
   what else runs); then with a Python listener subscribed to every topic.
2. Real time: real_time_factor 1 for --paced-duration wall seconds, recording on; a
   subscriber in another process takes /platform/pose: the interval between arrivals
   (ideal 50 ms) p50 / p99 / max, the arrival offset from the stamps' schedule about its
   median, the longest interval and the stamp it ended at, and the node's own pacing
   lateness and its wait for wave blocks (a paced run longer than --wave-block-s crosses
   block boundaries: 600 s by default). Also with node and subscriber under
   ``nice -n -15`` and ``chrt -f 50`` (real-time scheduling) where the user may.

The load average is printed beside each figure: on a shared machine the figures follow it.

Run with ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST and a ROS_DOMAIN_ID of its own:
    python benchmarks/node.py [--duration 600] [--repeats 3] [--paced-duration 30] [--wave-block-s 600]
"""
from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.model import WAVE_BLOCK_S
from fowt_hydro_sim.ros.node import MESSAGE_CLASSES, OUTPUTS
from fowt_hydro_sim.testing.ros import Listener, finish, node_run, start

TOPICS = {topic: MESSAGE_CLASSES[kind] for topic, kind in OUTPUTS.values()}
PRIORITIES = (("nice", "-n", "-15"), ("chrt", "-f", "50"))  # a higher share; real-time scheduling


def load() -> str:
    return "load " + " ".join(Path("/proc/loadavg").read_text().split()[:3])


def subscribe(seconds: float, out: str) -> None:
    """Child process: take /platform/pose (raw, reliable) for ``seconds`` after the first
    one; save the arrival times (monotonic) and stamps."""
    import gc

    import rclpy
    from geometry_msgs.msg import PoseStamped
    from rclpy.executors import SingleThreadedExecutor
    from rclpy.qos import QoSProfile, ReliabilityPolicy

    from msg_adapters.cdr import decode_stamped

    rclpy.init()
    node = rclpy.create_node(f"fowt_bench_pose_{os.getpid()}")
    arrivals, messages = [], []

    def on_pose(data: bytes) -> None:
        arrivals.append(time.monotonic())
        messages.append(data)

    node.create_subscription(PoseStamped, "/platform/pose", on_pose,
                             QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE), raw=True)
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    gc.freeze()
    deadline = None
    while deadline is None or time.monotonic() < deadline:
        executor.spin_once(timeout_sec=0.1)
        if deadline is None and arrivals:
            deadline = arrivals[0] + seconds
    stamps, _ = decode_stamped("geometry_msgs/msg/PoseStamped", messages)
    np.savez(out, arrival_s=np.array(arrivals), stamp_s=stamps)
    node.destroy_node()
    rclpy.try_shutdown()


def accelerated(duration_s: float, drag: str, repeats: int) -> None:
    print(f"as fast as possible, {len(TOPICS)} topics at 20 Hz simulated, drag {drag}, {duration_s:g} s:")
    with tempfile.TemporaryDirectory() as folder:
        for _ in range(repeats):  # interleaved, so drifts in machine load hit both
            for record in (None, Path(folder) / "run"):
                before = load()
                sim, wall, cpu = node_run(duration_s, drag, record)
                print(f"  {'recording   ' if record else 'no recording'}: {sim / wall:5.0f}x real time "
                      f"({wall:.2f} s wall, {cpu:.2f} s CPU: {sim / cpu:.0f} simulated s per CPU s); {before}")

    before = load()
    listener = Listener(TOPICS)
    node = start("node", real_time_factor=0.0, duration_s=duration_s, drag_model=drag, wait_for_subscribers=1)
    listener.wait_for(lambda: node.poll() is not None, 3600.0)
    output = finish(node, 10)
    time.sleep(0.5)
    listener.close()
    done = re.search(r"([\d.]+) s simulated in ([\d.]+) s of wall time", output)
    received = {topic: len(msgs) for topic, msgs in listener.messages.items()}
    if done:
        sim, wall = map(float, done.groups())
        print(f"  a Python listener subscribed to all: {sim / wall:.0f}x real time; messages received per "
              f"topic: min {min(received.values())}, max {max(received.values())} of "
              f"{int(duration_s * 20) + 1}; {before}")
    else:
        print(output)


def paced(seconds: float, drag: str, prefix: tuple[str, ...], wave_block_s: float) -> None:
    """Real time, recording, with a pose subscriber in another process."""
    with tempfile.TemporaryDirectory() as folder:
        before = load()
        out = Path(folder) / "pose.npz"
        subscriber = subprocess.Popen([*prefix, sys.executable, __file__, "--subscribe", str(seconds), str(out)])
        node = start("node", prefix=prefix, real_time_factor=1.0, drag_model=drag, record=str(Path(folder) / "run"),
                     wait_for_subscribers=1, wave_block_s=wave_block_s)
        try:
            subscriber.wait(timeout=seconds + 120)
        finally:
            node.terminate()
            output = finish(node, 20)
        after = load()
        if not out.exists():
            print(output)
            return
        data = np.load(out)
    arrival, stamp = data["arrival_s"], data["stamp_s"]
    interval_ms = np.diff(arrival) * 1e3
    offset_ms = (arrival - arrival[0] - (stamp - stamp[0])) * 1e3
    offset_ms -= np.median(offset_ms)
    jitter = np.abs(interval_ms - 50.0)
    gaps = int(np.sum(np.abs(np.diff(stamp) - 0.05) > 1e-6))
    late = re.search(r"p50 ([\d.]+) ms, p99 ([\d.]+) ms over (\d+) steps", output)
    blocks = re.search(r"([\d.]+) s waiting for wave blocks", output)
    longest = int(np.argmax(interval_ms))
    label = " ".join(prefix) or "normal scheduling"
    print(f"  {label}: pose interval p50 {np.percentile(interval_ms, 50):.2f} / p99 "
          f"{np.percentile(interval_ms, 99):.2f} / max {interval_ms.max():.2f} ms (ideal 50; the longest ending at "
          f"t = {stamp[longest + 1]:.2f} s); |interval - 50| p99 "
          f"{np.percentile(jitter, 99):.2f} ms; arrival offset about its median p99 "
          f"{np.percentile(np.abs(offset_ms), 99):.2f} ms, max {np.abs(offset_ms).max():.2f} ms; {len(stamp)} poses, "
          f"{gaps} stamp gaps" + (f"; node pacing lateness p50 {late[1]}, p99 {late[2]} ms" if late else "")
          + (f"; {blocks[1]} s waiting for wave blocks (blocks of {wave_block_s:g} s)" if blocks else "")
          + f"; {before} -> {after}")


def main() -> None:
    if len(sys.argv) == 4 and sys.argv[1] == "--subscribe":
        subscribe(float(sys.argv[2]), sys.argv[3])
        return
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=600.0, help="simulated seconds, accelerated runs")
    parser.add_argument("--repeats", type=int, default=3, help="accelerated runs of each kind")
    parser.add_argument("--paced-duration", type=float, default=30.0, help="wall seconds at real time")
    parser.add_argument("--drag", default="filtered")
    parser.add_argument("--only", choices=("accelerated", "paced"), help="run one part")
    parser.add_argument("--wave-block-s", type=float, default=WAVE_BLOCK_S,
                        help="the paced node's wave block (a boundary every this many seconds)")
    args = parser.parse_args()
    if os.environ.get("ROS_AUTOMATIC_DISCOVERY_RANGE") != "LOCALHOST":
        sys.exit("set ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST (and a ROS_DOMAIN_ID of your own) first")
    if args.only != "paced":
        accelerated(args.duration, args.drag, args.repeats)
    if args.only != "accelerated":
        print(f"real time, recording, {args.paced_duration:g} s, a pose subscriber in another process:")
        paced(args.paced_duration, args.drag, (), args.wave_block_s)
        for prefix in PRIORITIES:
            if subprocess.run([*prefix, "true"], capture_output=True).returncode == 0:
                paced(args.paced_duration, args.drag, prefix, args.wave_block_s)
            else:
                print(f"  ({' '.join(prefix)} not permitted here: not measured)")


if __name__ == "__main__":
    main()
