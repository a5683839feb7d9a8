"""``fowt-sim record -o DIR``: record topics of the ROS graph to a rosbag2 bag (MCAP).

Topics: every topic seen on the graph (looked for again every 0.5 s, so topics appearing
later are recorded too; ``/rosout`` and ``/parameter_events`` left out), or only
``--topics``. A topic is subscribed once it has a publisher (its QoS is needed):
messages are taken as CDR bytes (raw subscription, no deserialisation), reliable with a
queue of 10000, or best effort if a publisher offers only best effort; transient local if
every publisher is. The publishers' offered QoS is stored in the bag.

Log time = simulation time: the latest ``/clock`` received (or the topic ``/clock`` is
remapped to with ``--ros-args -r /clock:=...``). Before any ``/clock`` arrives
the wall clock (``time.time_ns()``) is used, with one warning (and another if ``/clock``
appears later, since the log times then jump).

The bag is always closed (complete, readable by any rosbag2/MCAP reader): on Ctrl-C,
SIGTERM or after ``--duration`` wall seconds, after taking what is already queued.
"""
from __future__ import annotations

import argparse
import datetime
import logging
import signal
import struct
import sys
import threading
import time
from pathlib import Path

from fowt_hydro_sim.ros.player import message_class, split_ros_args
from fowt_hydro_sim.rosbag.writer import BagError, BagWriter, RecordingStopped, qos_profiles

log = logging.getLogger("fowt_hydro_sim.recorder")

IGNORED = ("/rosout", "/parameter_events")  # left out unless asked for with --topics
CLOCK_TOPIC = "/clock"
DEPTH = 10000
DISCOVERY_PERIOD_S = 0.5
DRAIN_S = 1.0  # at the end: wall seconds at most to take messages already queued


def clock_ns(data: bytes) -> int | None:
    """The time of a rosgraph_msgs/Clock in CDR, in ns; None if the bytes are not one."""
    if len(data) < 12 or data[1] not in (0, 1):
        return None
    sec, nanosec = struct.unpack_from("<iI" if data[1] == 1 else ">iI", data, 4)
    return sec * 1_000_000_000 + nanosec


class Recorder:
    """A node subscribing to the selected topics and writing what arrives to the bag."""

    def __init__(self, writer: BagWriter, topics: list[str] | None):
        import rclpy
        from rclpy.qos import QoSProfile, ReliabilityPolicy
        from rosgraph_msgs.msg import Clock

        self.writer = writer
        self.failure: str | None = None  # why the recording stopped early (disk full)
        self.wanted = list(topics) if topics else None
        self.node = rclpy.create_node("fowt_sim_record")
        self.channels: dict[str, int] = {}  # recorded topic: channel id
        self.reliability: dict[str, str] = {}
        self._subscriptions = {}
        self._warned: set[str] = set()  # topics (or keys) warned about once
        self.clock_ns: int | None = None
        self._wall_messages = 0  # written with wall-clock log times
        # /clock only for the log time (best effort matches any publisher); replaced by the
        # recording subscription if /clock is recorded
        self._clock_subscription = self.node.create_subscription(
            Clock, CLOCK_TOPIC, self._on_clock, QoSProfile(depth=100, reliability=ReliabilityPolicy.BEST_EFFORT),
            raw=True)
        self.clock_topic = self._clock_subscription.topic_name  # /clock, or where --ros-args -r remapped it
        self.discover()
        self.node.create_timer(DISCOVERY_PERIOD_S, self.discover)

    # ------------------------------------------------------------------ time
    def _on_clock(self, data: bytes) -> None:
        t = clock_ns(data)
        if t is None:
            return
        if self.clock_ns is None and self._wall_messages:
            log.warning(f"/clock received: log times are simulation time from now on (the first "
                        f"{self._wall_messages} message(s) have wall-clock log times)")
        self.clock_ns = t

    def _log_time(self) -> int:
        if self.clock_ns is not None:
            return self.clock_ns
        if not self._wall_messages:
            log.warning("no /clock received yet: log times are wall-clock time until one is")
        self._wall_messages += 1
        return time.time_ns()

    # ------------------------------------------------------------------ topics
    def _warn_once(self, key: str, text: str) -> None:
        if key not in self._warned:
            self._warned.add(key)
            log.warning(text)

    def discover(self) -> None:
        """Subscribe to the selected topics that have a publisher and are not recorded yet."""
        from rclpy.qos import DurabilityPolicy, ReliabilityPolicy

        for name, types in self.node.get_topic_names_and_types():
            if (name in IGNORED) if self.wanted is None else (name not in self.wanted):
                continue
            publishers = self.node.get_publishers_info_by_topic(name)
            if name in self.channels:
                if self.reliability[name] == "reliable" and any(
                        p.qos_profile.reliability == ReliabilityPolicy.BEST_EFFORT for p in publishers):
                    self._warn_once(f"{name} best effort", f"{name}: a best-effort publisher appeared; its messages "
                                                           f"are not recorded (subscribed reliable)")
                continue
            if not publishers or name in self._warned:
                continue  # only subscribers so far: wait for a publisher and its QoS
            if len(types) != 1:
                self._warn_once(name, f"{name}: not recorded, it has several types ({', '.join(types)})")
                continue
            try:
                kind = message_class(types[0])
            except ValueError as exc:
                self._warn_once(name, f"{name}: not recorded: {exc}")
                continue
            offered = []
            for p in publishers:
                q = p.qos_profile
                offered += qos_profiles("best_effort" if q.reliability == ReliabilityPolicy.BEST_EFFORT else "reliable",
                                        "transient_local" if q.durability == DurabilityPolicy.TRANSIENT_LOCAL
                                        else "volatile", q.depth)
            reliability = "best_effort" if any(q["reliability"] == "best_effort" for q in offered) else "reliable"
            durability = "transient_local" if all(q["durability"] == "transient_local" for q in offered) else "volatile"
            try:
                channel = self.writer.add_topic(name, types[0], offered)
            except (BagError, LookupError) as exc:  # LookupError: no message definition for the schema
                self._warn_once(name, f"{name}: not recorded: {exc}")
                continue
            self._subscribe(name, kind, channel, reliability, durability)

    def _subscribe(self, name: str, kind: type, channel: int, reliability: str, durability: str) -> None:
        from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

        def write(channel_id: int, log_time_ns: int, data: bytes) -> None:
            try:
                self.writer.write(channel_id, log_time_ns, data)
            except RecordingStopped as exc:  # disk full: the bag is closed, readable; recording ends
                log.error(f"fowt-sim record: {exc}")
                self.failure = str(exc)

        if name == self.clock_topic:
            def on_message(data: bytes) -> None:
                self._on_clock(data)
                write(channel, self._log_time(), data)
        else:
            def on_message(data: bytes) -> None:
                write(channel, self._log_time(), data)
        qos = QoSProfile(depth=DEPTH, reliability=ReliabilityPolicy.BEST_EFFORT if reliability == "best_effort"
                         else ReliabilityPolicy.RELIABLE,
                         durability=DurabilityPolicy.TRANSIENT_LOCAL if durability == "transient_local"
                         else DurabilityPolicy.VOLATILE)
        self._subscriptions[name] = self.node.create_subscription(kind, name, on_message, qos, raw=True)
        if name == self.clock_topic and self._clock_subscription is not None:
            self.node.destroy_subscription(self._clock_subscription)
            self._clock_subscription = None
        self.channels[name], self.reliability[name] = channel, reliability
        type_name = f"{kind.__module__.split('.')[0]}/msg/{kind.__name__}"
        log.info(f"recording {name} ({type_name}, {reliability.replace('_', ' ')}"
                 + (", transient local" if durability == "transient_local" else "") + ")")

    def counts(self) -> dict[str, int]:
        return {name: self.writer.counts.get(channel, 0) for name, channel in self.channels.items()}


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="fowt-sim record", description="Record topics of the ROS graph to a rosbag2 bag (MCAP). Log time = the "
                                            "latest /clock (wall clock until one arrives). ROS arguments go after "
                                            "--ros-args.")
    p.add_argument("-o", "--output", required=True, metavar="DIR", help="bag directory to create")
    p.add_argument("--topics", nargs="+", metavar="T", help="record only these topics (default: every topic seen, "
                                                            "except /rosout and /parameter_events)")
    p.add_argument("--overwrite", action="store_true", help="replace an existing bag at DIR")
    p.add_argument("--duration", type=float, metavar="S", help="stop after S wall seconds (default: when stopped)")
    p.add_argument("--config", metavar="FILE", help="YAML mapping stored in the bag as its run configuration, beside "
                                                    "the recorder's own entry (fowt-sim info shows it; default: none)")
    return p


def read_config(path: str) -> dict:
    """The run configuration in the YAML file ``path`` (a mapping); ValueError says why not."""
    import yaml

    try:
        config = yaml.safe_load(Path(path).read_text())
    except OSError as exc:
        raise ValueError(f"--config {path}: cannot be read ({exc.strerror or exc})") from None
    except yaml.YAMLError as exc:
        raise ValueError(f"--config {path}: not YAML ({str(exc).splitlines()[0]})") from None
    if not isinstance(config, dict):
        raise ValueError(f"--config {path}: not a YAML mapping")
    return config


def main(argv: list[str] | None = None) -> int:
    """``fowt-sim record -o DIR [options] [--ros-args ...]``; exit 0 when stopped (Ctrl-C,
    SIGTERM, --duration), 1 when the bag could not be written further (disk full: closed,
    readable), 2 for bad input (one line on stderr)."""
    logging.basicConfig(level=logging.INFO, format="[%(levelname)s] [%(name)s]: %(message)s")
    own, ros_args = split_ros_args(sys.argv[1:] if argv is None else list(argv))
    try:
        args = parser().parse_args(own)
    except SystemExit as exc:  # usage or --help, printed by argparse
        return int(exc.code or 0)
    if args.duration is not None and not 0 < args.duration < float("inf"):
        log.error(f"fowt-sim record: --duration must be a positive number of seconds, got {args.duration:g}")
        return 2
    topics = [t if t.startswith("/") else "/" + t for t in dict.fromkeys(args.topics)] if args.topics else None
    try:
        run = read_config(args.config) if args.config else {}
    except ValueError as exc:
        log.error(f"fowt-sim record: {exc}")
        return 2

    import rclpy
    from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor

    from fowt_hydro_sim.ros.startup import init_ros

    stop = threading.Event()
    try:
        init_ros(["fowt-sim", *ros_args])
    except Exception as exc:  # bad ROS arguments
        log.error(f"fowt-sim record: ROS arguments: {type(exc).__name__}: {exc}".splitlines()[0])
        rclpy.try_shutdown()
        return 2

    def on_signal(signum, frame) -> None:  # a flag, not an exception in the middle of a write
        if stop.is_set():
            raise KeyboardInterrupt  # second signal: stop now (the bag is still closed)
        stop.set()

    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)
    config = {**run, "recorder": {"topics": topics or "all",
                           "started_wall": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")}}
    hint = " (--overwrite replaces a bag)" if not args.overwrite and Path(args.output).exists() else ""
    try:
        writer = BagWriter(args.output, config=config, overwrite=args.overwrite)
    except (BagError, OSError) as exc:
        log.error(f"fowt-sim record: {exc}".splitlines()[0] + hint)
        rclpy.try_shutdown()
        return 2
    recorder = executor = None
    start = time.monotonic()
    try:
        recorder = Recorder(writer, topics)
        executor = SingleThreadedExecutor()
        executor.add_node(recorder.node)
        log.info(f"recording {', '.join(topics) if topics else 'all topics'} to {writer.path}"
                 + (f" for {args.duration:g} s" if args.duration else " until stopped"))
        deadline = start + args.duration if args.duration else float("inf")
        while not stop.is_set() and rclpy.ok() and time.monotonic() < deadline and recorder.failure is None:
            executor.spin_once(timeout_sec=0.1)
        drain_end = time.monotonic() + DRAIN_S
        while rclpy.ok() and time.monotonic() < drain_end:  # what is already queued
            before = writer.message_count
            executor.spin_once(timeout_sec=0.05)
            if writer.message_count == before:
                break
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        try:
            writer.close()
        finally:
            if recorder is not None:
                counts = recorder.counts()
                if topics:
                    for name in topics:
                        if name not in counts:
                            log.warning(f"{name}: never recorded (no publisher seen)")
                log.info(f"recorded {writer.message_count} messages in {time.monotonic() - start:.1f} s"
                         + (": " + ", ".join(f"{name} {n}" for name, n in sorted(counts.items())) if counts else ""))
                if executor is not None:
                    executor.shutdown(timeout_sec=1.0)
                recorder.node.destroy_node()
            rclpy.try_shutdown()
    return 1 if recorder is not None and recorder.failure else 0
