"""Real nodes over DDS for the tests and benchmarks: the simulator and controller as child
processes (``fowt-sim node|controller``), and a listener node in the calling process that
records what they publish (rclpy is imported only by the listener). Loopback only: ``start`` refuses to run unless
ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST (test/conftest.py and .ci/run set it)."""
from __future__ import annotations

import os
import re
import subprocess
import sys
import threading
import time
from pathlib import Path

from fowt_hydro_sim.testing import REPO


def command_line(command: str, **parameters) -> list[str]:
    """``fowt-sim <command> --ros-args -p k:=v ...`` as arguments."""
    args = [sys.executable, "-m", "fowt_hydro_sim.cli", command, "--ros-args"]
    for name, value in parameters.items():
        text = str(value).lower() if isinstance(value, bool) else str(value)
        args += ["-p", f"{name}:={text}"]
    return args


def start(command: str, *, prefix: tuple[str, ...] = (), **parameters) -> subprocess.Popen:
    """``fowt-sim <command> --ros-args -p k:=v ...`` in a child process (stderr: its log),
    after ``prefix`` (e.g. ``("chrt", "-f", "50")``)."""
    if os.environ.get("ROS_AUTOMATIC_DISCOVERY_RANGE") != "LOCALHOST":
        raise RuntimeError("set ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST (and a ROS_DOMAIN_ID of your own) first")
    return subprocess.Popen([*prefix, *command_line(command, **parameters)], cwd=REPO, stdin=subprocess.DEVNULL,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def finish(process: subprocess.Popen, timeout_s: float = 60.0) -> str:
    """Wait for the process (terminate it if still running) and return its output."""
    try:
        output, _ = process.communicate(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        process.terminate()
        try:
            output, _ = process.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()
            output, _ = process.communicate()
    return output


class Listener:
    """A node recording messages per topic, spun in a background thread; also publishes."""

    def __init__(self, topics: dict[str, type]):
        import rclpy
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.qos import QoSProfile, ReliabilityPolicy

        reliable = QoSProfile(depth=10000, reliability=ReliabilityPolicy.RELIABLE)
        self._reliable = reliable
        self.context = rclpy.Context()
        rclpy.init(context=self.context)
        self.node = rclpy.create_node(f"fowt_test_listener_{os.getpid()}", context=self.context)
        self.messages: dict[str, list] = {topic: [] for topic in topics}
        self.arrival: dict[str, list] = {topic: [] for topic in topics}
        for topic, kind in topics.items():
            self.node.create_subscription(kind, topic, self._recorder(topic), reliable)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self._thread = threading.Thread(target=self._spin, daemon=True)
        self._running = True
        self._thread.start()

    def _recorder(self, topic: str):
        def record(msg) -> None:
            self.arrival[topic].append(time.monotonic())
            self.messages[topic].append(msg)
        return record

    def _spin(self) -> None:
        while self._running and self.context.ok():
            self.executor.spin_once(timeout_sec=0.05)

    def publisher(self, kind: type, topic: str):
        return self.node.create_publisher(kind, topic, self._reliable)

    def wait_for(self, condition, timeout_s: float) -> bool:
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            if condition():
                return True
            time.sleep(0.05)
        return condition()

    def close(self) -> None:
        self._running = False
        self._thread.join(timeout=5)
        self.executor.shutdown()
        self.node.destroy_node()
        self.context.try_shutdown()


def node_speed(duration_s: float, drag: str, record: Path | None = None) -> float:
    """Simulated seconds per wall second of one node run."""
    sim, wall, _ = node_run(duration_s, drag, record)
    return sim / wall


def node_run(duration_s: float, drag: str, record: Path | None = None) -> tuple[float, float, float]:
    """Simulated seconds, wall seconds and CPU seconds of the stepping of one node run as
    fast as possible."""
    params = {"real_time_factor": 0.0, "duration_s": duration_s, "drag_model": drag}
    if record is not None:
        params.update(record=str(record), record_overwrite=True)
    output = finish(start("node", **params), 3600.0)
    done = re.search(r"([\d.]+) s simulated in ([\d.]+) s of wall time \(([\d.]+) s of CPU\)", output)
    if not done:
        raise RuntimeError(f"the node did not report its speed:\n{output}")
    sim, wall, cpu = map(float, done.groups())
    return sim, wall, cpu
