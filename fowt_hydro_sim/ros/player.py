"""``fowt-sim play BAG``: publish a bag's messages on the ROS graph, in log-time order, at
the recorded pace scaled by ``--rate``.

Messages go out as their recorded CDR bytes (``Publisher.publish(bytes)``: no
deserialisation). The wall time between two messages is their log-time difference over
the rate; ``--rate 0`` publishes as fast as possible. The schedule is kept against the
start of playback, so delays do not add up.

``--clock`` also publishes ``rosgraph_msgs/Clock`` on ``/clock``: once per distinct log
time, just before the first message of that time (log time = simulation time in the bags
this package writes), so a node using simulation time sees the clock reach a message's
time before the message. A ``/clock`` recorded in the bag is then not played (the
generated clock replaces it).

``--loop`` plays the bag again when it ends; pass k (from 0) has its log times offset by
k times the bag's span (last minus first log time of the played topics), so the schedule
and the generated clock keep going forward. The messages themselves (and their header
stamps) are published unchanged.

Publishers: reliable, volatile, keep-all, unless the bag's metadata.yaml offers a
different reliability or durability for the topic (that of its first offered profile).

Flow control on reliable topics: no message is given up while its subscribers keep taking
them. As fast as possible (``--rate 0``) the player publishes ``WINDOW`` messages of a topic,
then waits until every subscriber has acknowledged them, so a slower subscriber (a node
stepping as fast as possible takes its samples as it needs them) slows the playback down,
however long it takes. Paced, a message the middleware refuses (its queue for a subscriber far
behind is full) is published again once the subscribers have acknowledged the queue. At the
end the player waits until everything is acknowledged. It gives up only on a subscriber that
leaves a wait unacknowledged for ``STALL_S`` wall seconds (stuck): said in one line, exit code
1, as for a message refused twice (lost to a subscriber).
"""
from __future__ import annotations

import argparse
import importlib
import logging
import struct
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import yaml
from mcap.exceptions import McapError
from zstandard import ZstdError

from fowt_hydro_sim.rosbag.writer import METADATA_FILE, BagError
from msg_adapters.cdr import ENCAPSULATION

log = logging.getLogger("fowt_hydro_sim.player")

DEPTH = 1000
CLOCK_TOPIC = "/clock"
# reliable topics: messages published before waiting for their acknowledgement (an acknowledgement
# may wait for the writer's next heartbeat, 3 s with Fast DDS's defaults: the window sets the
# pace of a replay as fast as possible then, about 170 messages/s at least)
WINDOW = 500
STALL_S = 60.0  # wall seconds a window may stay unacknowledged (a subscriber taking < 8 messages/s): stuck
ACK_SLICE_S = 0.5  # waiting for acknowledgements in slices of this many wall seconds (Ctrl-C is taken between)
CLOCK_ACK_TIMEOUT_S = 5.0  # at the end: wall seconds at most for the generated /clock (keep-last) to be acknowledged
_RELIABILITY = {"reliable": "reliable", "best_effort": "best_effort", 1: "reliable", 2: "best_effort"}
_DURABILITY = {"volatile": "volatile", "transient_local": "transient_local", 1: "transient_local", 2: "volatile"}


class PlaybackStalled(RuntimeError):
    """A subscriber acknowledged nothing for STALL_S wall seconds: the playback was given up."""


@dataclass(frozen=True)
class Topic:
    name: str
    type_name: str
    message_class: type
    reliability: str = "reliable"
    durability: str = "volatile"


def message_class(type_name: str) -> type:
    """The generated message class of 'package/msg/Name'; ValueError names the problem."""
    parts = type_name.split("/")
    if len(parts) != 3 or parts[1] != "msg" or not all(parts):
        raise ValueError(f"message type {type_name!r}: expected package/msg/Name")
    package, _, name = parts
    try:
        module = importlib.import_module(f"{package}.msg")
    except ImportError:
        raise ValueError(f"message type {type_name}: unknown (Python package {package} is not installed)") from None
    kind = getattr(module, name, None)
    if not isinstance(kind, type):
        raise ValueError(f"message type {type_name}: unknown ({package}.msg has no {name})")
    return kind


def split_ros_args(argv: list[str]) -> tuple[list[str], list[str]]:
    """(own arguments, ROS arguments from ``--ros-args`` on, that token included)."""
    if "--ros-args" in argv:
        i = argv.index("--ros-args")
        return argv[:i], argv[i:]
    return list(argv), []


def _offered_qos(path: Path) -> dict[str, tuple[str, str]]:
    """{topic: (reliability, durability)} from the first offered QoS profile of each topic in
    metadata.yaml (a list, rosbag2 version 9, or a YAML string, older versions); topics
    without a readable profile are left out."""
    try:
        info = yaml.safe_load((path / METADATA_FILE).read_text())["rosbag2_bagfile_information"]
        entries = info.get("topics_with_message_count") or []
    except (OSError, yaml.YAMLError, KeyError, TypeError, AttributeError):
        return {}
    found = {}
    for entry in entries:
        try:
            meta = entry["topic_metadata"]
            profiles = meta.get("offered_qos_profiles") or []
            if isinstance(profiles, str):
                profiles = yaml.safe_load(profiles) or []
            first = profiles[0]
            reliability = _RELIABILITY.get(first.get("reliability"), "reliable")
            durability = _DURABILITY.get(first.get("durability"), "volatile")
            found[meta["name"]] = (reliability, durability)
        except (KeyError, TypeError, IndexError, AttributeError, yaml.YAMLError):
            continue
    return found


def open_bag(path: str, topics: list[str] | None, clock: bool):
    """The bag and the topics to play; BagError or ValueError name what is wrong."""
    from fowt_hydro_sim.rosbag.reader import Bag  # numpy, mcap: not needed for --help

    bag = Bag(path)
    if topics:
        topics = [t if t.startswith("/") else "/" + t for t in topics]
        unknown = [t for t in topics if t not in bag.topics]
        if unknown:
            raise BagError(f"bag {bag.path}: no topic {', '.join(unknown)} "
                           f"(topics: {', '.join(sorted(bag.topics)) or 'none'})")
        names = list(dict.fromkeys(topics))
    else:
        names = sorted(bag.topics)
    if clock and CLOCK_TOPIC in names:
        names.remove(CLOCK_TOPIC)
        log.info(f"--clock: the recorded {CLOCK_TOPIC} is not played, the generated clock replaces it")
    if sum(bag.topics[n].message_count for n in names) == 0:
        raise BagError(f"bag {bag.path}: no messages to play on {', '.join(names) or 'the selected topics'}")
    qos = _offered_qos(bag.path)
    selected = []
    for name in names:
        type_name = bag.topics[name].type
        try:
            kind = message_class(type_name)
        except ValueError as exc:
            raise ValueError(f"bag {bag.path}: topic {name}: {exc}") from None
        selected.append(Topic(name, type_name, kind, *qos.get(name, ("reliable", "volatile"))))
    return bag, selected


def clock_bytes(time_ns: int) -> bytes:
    """rosgraph_msgs/Clock as CDR from integer nanoseconds (no float rounding)."""
    sec, nanosec = divmod(time_ns, 1_000_000_000)
    return ENCAPSULATION + struct.pack("<iI", sec, nanosec)


class Player:
    """Publishers for the selected topics (and /clock) on a node; ``play`` runs the schedule."""

    def __init__(self, bag, topics: list[Topic], rate: float, clock: bool, loop: bool, stall_s: float = STALL_S):
        import rclpy
        from rclpy.impl.implementation_singleton import rclpy_implementation
        from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

        self._error = rclpy_implementation.RCLError
        self.bag, self.topics, self.rate, self.clock, self.loop = bag, topics, rate, clock, loop
        self.stall_s = stall_s
        self.node = rclpy.create_node("fowt_sim_play")
        self.publishers = {}
        self._unacked: dict[str, int] = {}  # reliable topics: messages published since the last acknowledgement
        for t in topics:
            best_effort = t.reliability == "best_effort"
            # reliable: keep all, so a fast replay waits for its subscribers instead of overwriting
            qos = QoSProfile(history=HistoryPolicy.KEEP_LAST if best_effort else HistoryPolicy.KEEP_ALL, depth=DEPTH,
                             reliability=ReliabilityPolicy.BEST_EFFORT if best_effort else ReliabilityPolicy.RELIABLE,
                             durability=DurabilityPolicy.TRANSIENT_LOCAL if t.durability == "transient_local"
                             else DurabilityPolicy.VOLATILE)
            self.publishers[t.name] = self.node.create_publisher(t.message_class, t.name, qos)
            if not best_effort:
                self._unacked[t.name] = 0
        self.clock_publisher = None
        if clock:
            from rosgraph_msgs.msg import Clock
            self.clock_publisher = self.node.create_publisher(Clock, CLOCK_TOPIC, QoSProfile(depth=DEPTH))
        self.played = 0
        self.dropped = 0
        self.passes = 0

    def wait_for_subscribers(self, count: int, timeout_s: float = 60.0) -> None:
        """Until every played topic has ``count`` subscribers (a reliable subscriber discovered
        late would miss what was published before)."""
        deadline = time.monotonic() + timeout_s
        while count and time.monotonic() < deadline and any(
                p.get_subscription_count() < count for p in self.publishers.values()):
            time.sleep(0.05)
        short = [name for name, p in self.publishers.items() if p.get_subscription_count() < count]
        if short:
            log.warning(f"--wait-for-subscribers: fewer than {count} subscriber(s) on {', '.join(short)} after "
                        f"{timeout_s:g} s; playing anyway")

    def _send(self, publisher, data: bytes, topic: str | None = None) -> None:
        """Publish; a reliable subscriber too slow for the rate can make DDS refuse the write
        (after blocking): on a reliable topic it is published again once the subscribers have
        acknowledged what is queued; refused again (or on /clock, ``topic`` None), it is dropped
        and counted."""
        try:
            publisher.publish(data)
            return
        except self._error as exc:
            error = exc
        if topic in self._unacked:
            self._wait_for_acknowledgement(topic)
            try:
                publisher.publish(data)
                return
            except self._error as exc:
                error = exc
        self.dropped += 1
        if self.dropped == 1 or self.dropped % 1000 == 0:
            log.warning(f"{self.dropped} message(s) dropped, e.g. on {publisher.topic_name} "
                        f"({str(error).split(',')[0]}): a subscriber cannot keep up; lower --rate")

    def play(self) -> None:
        names = [t.name for t in self.topics]
        first = last = None
        start = time.monotonic()
        last_clock = -1
        offset = 0  # ns added to the log times of this pass
        while True:
            for topic, log_ns, data in self.bag.messages(names):
                if first is None:
                    first = log_ns
                if last is None or log_ns > last:
                    last = log_ns
                when = log_ns + offset
                if self.rate > 0:
                    delay = start + (when - first) / 1e9 / self.rate - time.monotonic()
                    if delay > 0:
                        time.sleep(delay)
                if self.clock_publisher is not None and when > last_clock:
                    self._send(self.clock_publisher, clock_bytes(when))
                    last_clock = when
                self._send(self.publishers[topic], data, topic)
                self.played += 1
                if topic in self._unacked:
                    self._unacked[topic] += 1
                    if self.rate == 0 and self._unacked[topic] >= WINDOW:
                        self._wait_for_acknowledgement(topic)
            self.passes += 1
            if not self.loop or first is None:
                return
            if last == first:
                log.warning("the bag spans 0 s of log time: not looping (it would publish without pause)")
                return
            offset += last - first

    def _wait_for_acknowledgement(self, topic: str) -> None:
        """Until every subscriber of ``topic`` has acknowledged what was published on it, as
        long as that takes; PlaybackStalled after ``stall_s`` wall seconds without."""
        from rclpy.duration import Duration

        publisher, started = self.publishers[topic], time.monotonic()
        while not publisher.wait_for_all_acked(Duration(seconds=ACK_SLICE_S)):
            if time.monotonic() - started > self.stall_s:
                raise PlaybackStalled(
                    f"{topic}: a subscriber had not acknowledged the last {self._unacked[topic]} message(s) after "
                    f"{self.stall_s:g} s: playback given up after {self.played} messages, the rest is lost to it")
        self._unacked[topic] = 0

    def finish(self) -> None:
        """Wait until the reliable subscribers have acknowledged every message (PlaybackStalled
        if one is stuck), give the generated /clock a moment, then destroy the node."""
        from rclpy.duration import Duration

        try:
            for topic in self._unacked:
                self._wait_for_acknowledgement(topic)
            if self.clock_publisher is not None and not self.clock_publisher.wait_for_all_acked(
                    Duration(seconds=CLOCK_ACK_TIMEOUT_S)):
                log.warning(f"{self.clock_publisher.topic_name}: not acknowledged by every subscriber within "
                            f"{CLOCK_ACK_TIMEOUT_S:g} s; a subscriber may miss the last clock messages")
        finally:
            self.node.destroy_node()


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="fowt-sim play", description="Publish a bag's messages (recorded CDR bytes) in log-time order at the "
                                          "recorded pace scaled by --rate. ROS arguments go after --ros-args.",
        epilog="--clock publishes /clock = log time before the first message of each log time; --loop offsets the "
               "log times of each further pass by the bag's span, so that clock keeps going forward.")
    p.add_argument("bag", help="rosbag2 directory (MCAP storage)")
    p.add_argument("--rate", type=float, default=1.0, help="speed factor over the recorded pace; 0 = as fast as "
                                                           "possible (default 1)")
    p.add_argument("--clock", action="store_true", help="also publish rosgraph_msgs/Clock on /clock with the log time")
    p.add_argument("--topics", nargs="+", metavar="T", help="play only these topics (default: all)")
    p.add_argument("--loop", action="store_true", help="start again at the end, until stopped")
    p.add_argument("--start-delay", type=float, default=1.0, metavar="S",
                   help="wall seconds between creating the publishers and the first message, so subscribers "
                        "can discover them (default 1)")
    p.add_argument("--wait-for-subscribers", type=int, default=0, metavar="N",
                   help="before playing, wait (at most 60 wall seconds) until every played topic has N "
                        "subscribers (default 0: do not wait)")
    p.add_argument("--stall-timeout", type=float, default=STALL_S, metavar="S",
                   help=f"give the playback up (exit 1) when a subscriber acknowledges nothing for S wall seconds "
                        f"(default {STALL_S:g})")
    return p


def main(argv: list[str] | None = None) -> int:
    """``fowt-sim play BAG [options] [--ros-args ...]``; exit 0 when done or stopped (Ctrl-C,
    SIGTERM), 1 when messages were lost to a subscriber (the playback given up on a stuck
    subscriber, or messages the middleware refused), 2 for bad input (one line on stderr)."""
    logging.basicConfig(level=logging.INFO, format="[%(levelname)s] [%(name)s]: %(message)s")
    own, ros_args = split_ros_args(sys.argv[1:] if argv is None else list(argv))
    try:
        args = parser().parse_args(own)
    except SystemExit as exc:  # usage or --help, printed by argparse
        return int(exc.code or 0)
    try:
        if not (args.rate >= 0 and args.rate != float("inf")):
            raise ValueError(f"--rate must be a finite number >= 0, got {args.rate:g}")
        if not (0 <= args.start_delay < float("inf")):
            raise ValueError(f"--start-delay must be a finite number >= 0, got {args.start_delay:g}")
        if not (0 < args.stall_timeout < float("inf")):
            raise ValueError(f"--stall-timeout must be a finite number > 0, got {args.stall_timeout:g}")
        bag, topics = open_bag(args.bag, args.topics, args.clock)
    except (BagError, ValueError) as exc:
        log.error(f"fowt-sim play: {exc}".splitlines()[0])
        return 2

    import rclpy
    from rclpy.executors import ExternalShutdownException

    from fowt_hydro_sim.ros.startup import init_ros

    try:
        init_ros(["fowt-sim", *ros_args])
    except Exception as exc:  # bad ROS arguments
        log.error(f"fowt-sim play: ROS arguments: {type(exc).__name__}: {exc}".splitlines()[0])
        rclpy.try_shutdown()
        return 2
    player = None
    code: int | None = 0  # None: stopped by the user
    start = time.monotonic()
    try:
        player = Player(bag, topics, args.rate, args.clock, args.loop, args.stall_timeout)
        count = sum(bag.topics[t.name].message_count for t in topics)
        log.info(f"playing {bag.path}: {count} messages on {len(topics)} topic(s) ({', '.join(t.name for t in topics)})"
                 f", rate {'as fast as possible' if args.rate == 0 else f'{args.rate:g}'}"
                 + (", with /clock" if args.clock else "") + (", looping" if args.loop else ""))
        player.wait_for_subscribers(args.wait_for_subscribers)
        time.sleep(args.start_delay)
        start = time.monotonic()
        player.play()
    except (KeyboardInterrupt, ExternalShutdownException):
        log.info("stopped")
        code = None  # stopped by the user: exit 0, without waiting for acknowledgements
    except PlaybackStalled as exc:
        log.error(f"fowt-sim play: {exc}")
        code = 1
    except (BagError, McapError, ZstdError, struct.error, ValueError, OSError, EOFError) as exc:  # damaged data
        log.error(f"fowt-sim play: {exc}".splitlines()[0])
        code = 2
    finally:
        if player is not None:
            wall = time.monotonic() - start
            try:
                if code == 0:
                    player.finish()
                else:
                    player.node.destroy_node()
            except (KeyboardInterrupt, ExternalShutdownException):
                pass
            except PlaybackStalled as exc:
                log.error(f"fowt-sim play: {exc}")
                code = 1
            if player.dropped and not code:
                log.error(f"fowt-sim play: {player.dropped} message(s) refused by the middleware, lost to a "
                          f"subscriber")
                code = 1
            log.info(f"played {player.played} messages"
                     + (f" ({player.passes} complete pass(es))" if args.loop else "")
                     + (f", {player.dropped} dropped" if player.dropped else "") + f" in {wall:.2f} s wall time")
        rclpy.try_shutdown()
    return code or 0
