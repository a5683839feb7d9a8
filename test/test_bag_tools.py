"""``fowt-sim play`` and ``fowt-sim record`` over real DDS (loopback), as child processes,
with real bags on disk.

Oracles: a bag written here with known messages (``BagWriter``); the messages a listener
node in the test process receives (equal to the bag's, deserialised); the recorded bag
read back with this package's reader (byte for byte the source's) and with the
independent ``rosbags`` reader; the wall clock (loosely: the rate).

Isolation: the tests share the ROS domain with whatever else runs on it (conftest), so
their topics carry a per-process prefix and ``/clock`` is remapped under it
(``--ros-args -r /clock:=...``): no other test hears these messages or sends any to
these nodes. Only the all-topics recording also records whatever else is published on
the domain meanwhile (its checks look at this module's topics only).
"""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import yaml

pytest.importorskip("rclpy")
rosbags_highlevel = pytest.importorskip("rosbags.highlevel")

from geometry_msgs.msg import PointStamped, WrenchStamped  # noqa: E402
from rclpy.duration import Duration  # noqa: E402
from rclpy.qos import QoSProfile, ReliabilityPolicy  # noqa: E402
from rclpy.serialization import deserialize_message  # noqa: E402
from rosgraph_msgs.msg import Clock  # noqa: E402

from fowt_hydro_sim.rosbag.reader import Bag  # noqa: E402
from fowt_hydro_sim.rosbag.writer import BagWriter  # noqa: E402
from fowt_hydro_sim.testing import REPO  # noqa: E402
from fowt_hydro_sim.testing.ros import Listener, finish  # noqa: E402
from msg_adapters import cdr  # noqa: E402
from msg_adapters.sim_time import nanoseconds  # noqa: E402

PREFIX = f"/bag_tools_{os.getpid()}"
ELEVATION = f"{PREFIX}/waves/elevation"
WRENCH = f"{PREFIX}/platform/external_wrench"
CLOCK = f"{PREFIX}/clock"
BEST_EFFORT_TOPIC = f"{PREFIX}/best_effort"
BEST_EFFORT = QoSProfile(depth=100, reliability=ReliabilityPolicy.BEST_EFFORT)
REMAP_CLOCK = ["--ros-args", "-r", f"/clock:={CLOCK}"]
POINT_TYPE, WRENCH_TYPE = "geometry_msgs/msg/PointStamped", "geometry_msgs/msg/WrenchStamped"
N_ELEVATION, N_WRENCH, DT_S = 200, 50, 0.1
SPAN_NS = nanoseconds((N_ELEVATION - 1) * DT_S)  # 19.9 s: the last log time
START_DELAY = 3  # s: the players' time for discovery (usually well under 1 s; margin for a busy machine)


def elevation_z(i: int) -> float:
    return 2.0 * np.sin(0.3 * i) + 0.001 * i


def launch(command: str, *args: str) -> subprocess.Popen:
    """``fowt-sim <command> args...`` in a child process (stdout and stderr together)."""
    assert os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] == "LOCALHOST"
    return subprocess.Popen([sys.executable, "-m", "fowt_hydro_sim.cli", command, *map(str, args)], cwd=REPO,
                            stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def wait_exit(process: subprocess.Popen, timeout_s: float) -> tuple[int, str]:
    """Exit code and output; a process still running after timeout_s fails the test."""
    try:
        output, _ = process.communicate(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        output = finish(process, 5)
        pytest.fail(f"still running after {timeout_s} s:\n{output}")
    return process.returncode, output


def stop(process: subprocess.Popen, signum: int, timeout_s: float = 20.0) -> tuple[int, str]:
    process.send_signal(signum)
    return wait_exit(process, timeout_s)


def wait_for_line(process: subprocess.Popen, text: str, timeout_s: float) -> list[str]:
    """Read the child's output until a line containing ``text``; the lines read."""
    lines: list[str] = []
    deadline = time.monotonic() + timeout_s
    os.set_blocking(process.stdout.fileno(), False)
    while time.monotonic() < deadline:
        line = process.stdout.readline()
        if line:
            lines.append(line)
            if text in line:
                os.set_blocking(process.stdout.fileno(), True)
                return lines
        elif process.poll() is not None:
            break
        else:
            time.sleep(0.05)
    os.set_blocking(process.stdout.fileno(), True)
    rest = finish(process, 5)
    pytest.fail(f"no {text!r} within {timeout_s} s:\n{''.join(lines)}{rest}")


def write_source(path: Path) -> Path:
    """200 PointStamped on ELEVATION every 0.1 s and 50 WrenchStamped on WRENCH every 0.4 s,
    log time = stamp."""
    with BagWriter(path) as writer:
        elevation = writer.add_topic(ELEVATION, POINT_TYPE)
        wrench = writer.add_topic(WRENCH, WRENCH_TYPE)
        for i in range(N_ELEVATION):
            t = i * DT_S
            writer.write(elevation, nanoseconds(t), cdr.point(t, 10.0, -5.0, elevation_z(i)))
            if i % 4 == 0:
                writer.write(wrench, nanoseconds(t), cdr.six(t, [1e5 * i, 0.0, -2e4, 0.0, 3e6 + i, 0.0],
                                                             frame_id="platform"))
    return path


@pytest.fixture(scope="module")
def source(tmp_path_factory) -> Path:
    return write_source(tmp_path_factory.mktemp("bags") / "source")


def source_messages(bag_path: Path, topic: str) -> list[tuple[int, bytes]]:
    return [(t, data) for _, t, data in Bag(bag_path).messages([topic])]


def decoded(bag_path: Path, topic: str, kind: type) -> list:
    """The bag's messages deserialised by rclpy (received messages compare equal to them;
    serialising received ones again is no byte oracle: rclpy leaves alignment padding
    uninitialised)."""
    return [deserialize_message(data, kind) for _, data in source_messages(bag_path, topic)]


def clock_ns(msg: Clock) -> int:
    return msg.clock.sec * 1_000_000_000 + msg.clock.nanosec


def read_with_rosbags(path: Path) -> dict[str, list]:
    """The bag's messages per topic, deserialised by the independent ``rosbags`` reader."""
    found: dict[str, list] = {}
    with rosbags_highlevel.AnyReader([Path(path)]) as reader:
        for connection, _, raw in reader.messages():
            found.setdefault(connection.topic, []).append(reader.deserialize(raw, connection.msgtype))
    return found


# ---------------------------------------------------------------------- play
@pytest.mark.serial
@pytest.mark.slow
def test_play_publishes_every_message_in_order_with_the_clock(source: Path):
    listener = Listener({ELEVATION: PointStamped, WRENCH: WrenchStamped, CLOCK: Clock})
    try:
        player = launch("play", source, "--rate", 10, "--clock", "--start-delay", START_DELAY,
                        "--wait-for-subscribers", 1,
                        *REMAP_CLOCK)
        code, output = wait_exit(player, 60)
        received = listener.wait_for(lambda: len(listener.messages[ELEVATION]) >= N_ELEVATION
                                     and len(listener.messages[WRENCH]) >= N_WRENCH, 5.0)
    finally:
        listener.close()
    assert code == 0, output
    assert received, (len(listener.messages[ELEVATION]), len(listener.messages[WRENCH]),
                      [m.point.z for m in listener.messages[ELEVATION][:3]], output)
    assert "Traceback" not in output
    for topic, kind in ((ELEVATION, PointStamped), (WRENCH, WrenchStamped)):  # every message, in order, equal
        assert listener.messages[topic] == decoded(source, topic, kind), topic
    points = listener.messages[ELEVATION]
    assert [p.point.z for p in points] == [elevation_z(i) for i in range(N_ELEVATION)]
    assert [(p.header.stamp.sec, p.header.stamp.nanosec) for p in points] == \
        [divmod(nanoseconds(i * DT_S), 10**9) for i in range(N_ELEVATION)]
    clock = [clock_ns(m) for m in listener.messages[CLOCK]]
    assert clock == sorted(clock) and clock[-1] == SPAN_NS
    assert clock == sorted({t for t, _ in source_messages(source, ELEVATION)})  # once per log time
    arrival = listener.arrival[ELEVATION]
    wall_s, expected_s = arrival[-1] - arrival[0], SPAN_NS / 1e9 / 10
    assert 0.5 * expected_s < wall_s < 3.0 * expected_s, wall_s
    assert f"playing {source}: {N_ELEVATION + N_WRENCH} messages" in output
    assert f"played {N_ELEVATION + N_WRENCH} messages" in output


@pytest.mark.slow
def test_play_only_the_chosen_topics_as_fast_as_possible(source: Path):
    listener = Listener({ELEVATION: PointStamped, WRENCH: WrenchStamped})
    try:
        player = launch("play", source, "--topics", ELEVATION, "--rate", 0, "--start-delay", START_DELAY,
                        "--wait-for-subscribers", 1)
        code, output = wait_exit(player, 60)
        listener.wait_for(lambda: len(listener.messages[ELEVATION]) >= N_ELEVATION, 5.0)
        time.sleep(0.3)
    finally:
        listener.close()
    assert code == 0, output
    assert listener.messages[ELEVATION] == decoded(source, ELEVATION, PointStamped)
    assert listener.messages[WRENCH] == []
    assert "as fast as possible" in output and f"played {N_ELEVATION} messages" in output


@pytest.mark.slow
def test_play_loops_until_interrupted(source: Path):
    listener = Listener({WRENCH: WrenchStamped, CLOCK: Clock})
    try:
        player = launch("play", source, "--topics", WRENCH, "--loop", "--rate", 20, "--clock",
                        "--start-delay", START_DELAY, "--wait-for-subscribers", 1, *REMAP_CLOCK)
        looped = listener.wait_for(lambda: len(listener.messages[WRENCH]) > 1.5 * N_WRENCH, 30.0)
        code, output = stop(player, signal.SIGINT)
    finally:
        listener.close()
    assert looped, output
    assert code == 0, output
    assert "Traceback" not in output and "stopped" in output
    data = listener.messages[WRENCH]
    expected = decoded(source, WRENCH, WrenchStamped)
    assert data[:N_WRENCH] == expected and data[N_WRENCH:] == expected[:len(data) - N_WRENCH]  # pass 2 = pass 1
    clock = [clock_ns(m) for m in listener.messages[CLOCK]]
    wrench_span = nanoseconds((N_WRENCH - 1) * 4 * DT_S)
    assert clock == sorted(clock) and clock[-1] > wrench_span  # the clock goes on in the second pass
    assert set(clock) >= {wrench_span + t for t, _ in source_messages(source, WRENCH)[:N_WRENCH // 2]}


@pytest.mark.slow
def test_play_gives_up_on_a_stuck_subscriber_with_exit_code_1(tmp_path: Path):
    """A reliable keep-all subscriber that never takes a message (its queue fills up): the
    player waits for it (flow control), then, after a window unacknowledged for the stall
    timeout, says it gave up and exits 1, instead of exiting 0 with messages lost."""
    import rclpy
    from rclpy.qos import HistoryPolicy

    stall_s = 8.0
    path = tmp_path / "many"
    with BagWriter(path) as writer:
        channel = writer.add_topic(ELEVATION, POINT_TYPE)
        for i in range(20000):
            writer.write(channel, nanoseconds(i * DT_S), cdr.point(i * DT_S, 10.0, -5.0, elevation_z(i)))
    context = rclpy.Context()
    rclpy.init(context=context)
    node = rclpy.create_node(f"stuck_{os.getpid()}", context=context)
    try:
        node.create_subscription(PointStamped, ELEVATION, lambda msg: None,
                                 QoSProfile(depth=100, history=HistoryPolicy.KEEP_ALL,
                                            reliability=ReliabilityPolicy.RELIABLE))  # never spun
        player = launch("play", path, "--rate", 0, "--start-delay", START_DELAY, "--wait-for-subscribers", 1,
                        "--stall-timeout", stall_s)
        code, output = wait_exit(player, stall_s + 120)
    finally:
        node.destroy_node()
        context.try_shutdown()
    assert code == 1 and "Traceback" not in output, output
    assert "had not acknowledged the last" in output and f"after {stall_s:g} s: playback given up" in output, output


# ---------------------------------------------------------------------- record
@pytest.mark.slow
def test_record_what_play_publishes(source: Path, tmp_path: Path):
    out = tmp_path / "recorded"
    recorder = launch("record", "-o", out, "--topics", ELEVATION, WRENCH, CLOCK, *REMAP_CLOCK)
    try:
        seen = wait_for_line(recorder, "until stopped", 30)  # its node is up: it finds the player's topics
        # rate 2: a clock step is 50 ms of wall time, so that a busy machine delaying the recorder's
        # callbacks by a few ms does not make a message's log time lag its stamp by two steps
        player = launch("play", source, "--rate", 2, "--clock", "--start-delay", START_DELAY,
                        "--wait-for-subscribers", 1,
                        *REMAP_CLOCK)
        play_code, play_output = wait_exit(player, 90)
        time.sleep(0.5)
    finally:
        code, output = stop(recorder, signal.SIGINT)
    output = "".join(seen) + output
    assert play_code == 0, play_output
    assert code == 0, output
    assert "Traceback" not in output
    bag = Bag(out)
    assert {t: i.message_count for t, i in bag.topics.items()} == \
        {ELEVATION: N_ELEVATION, WRENCH: N_WRENCH, CLOCK: N_ELEVATION}
    assert bag.topics[ELEVATION].type == POINT_TYPE and bag.topics[CLOCK].type == "rosgraph_msgs/msg/Clock"
    for topic in (ELEVATION, WRENCH):  # byte for byte the source's, in order
        assert [d for _, _, d in bag.messages([topic])] == [d for _, d in source_messages(source, topic)], topic
    # log time = the latest /clock (simulation time): within one step of the stamp (DDS keeps no
    # order across topics: under load the next /clock may come in before the message it follows)
    recorded = [(t, data) for _, t, data in bag.messages([ELEVATION])]
    lag = np.array([stamp - t for (t, _), (stamp, _) in zip(recorded, source_messages(source, ELEVATION))])
    assert np.all(np.abs(lag) <= nanoseconds(DT_S)), lag
    assert np.mean(lag == 0) > 0.8
    assert bag.config["recorder"]["topics"] == [ELEVATION, WRENCH, CLOCK]
    assert f"{ELEVATION} {N_ELEVATION}" in output  # the per-topic summary
    rosbags = read_with_rosbags(out)
    assert [m.point.z for m in rosbags[ELEVATION]] == [elevation_z(i) for i in range(N_ELEVATION)]
    assert len(rosbags[WRENCH]) == N_WRENCH and rosbags[WRENCH][-1].wrench.torque.y == 3e6 + 196
    assert [m.clock.sec * 10**9 + m.clock.nanosec for m in rosbags[CLOCK]][-1] == SPAN_NS


@pytest.mark.slow
def test_record_on_a_full_disk_ends_in_one_line_with_a_readable_bag(small_disk):
    """``fowt-sim record`` of an accelerated node until its 1 MiB disk is full: one error
    line, exit 1, and a closed bag that both readers read to the end."""
    from fowt_hydro_sim.testing.ros import start
    out = small_disk / "graph"
    recorder = launch("record", "-o", out, "--topics", "/platform/pose", "/platform/odom", "/platform/loads/total")
    node = None
    try:
        seen = wait_for_line(recorder, "until stopped", 30)
        node = start("node", real_time_factor=0.0, duration_s=0.0)  # until stopped
        code, output = wait_exit(recorder, 240)
    finally:
        if node is not None:
            node.terminate()
            finish(node, 10)
        if recorder.poll() is None:
            stop(recorder, signal.SIGINT)
    output = "".join(seen) + output
    assert code == 1 and "Traceback" not in output, output
    assert sum("recording stopped at a failed write" in line for line in output.splitlines()) == 1, output
    bag = Bag(out)  # the topics the recorder had discovered when the disk filled (under load, not always all three)
    assert bag.message_count > 100, bag.summary()
    assert {topic: len(messages) for topic, messages in read_with_rosbags(out).items()} == {
        topic: info.message_count for topic, info in bag.topics.items() if info.message_count}


@pytest.mark.slow
@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_recorder_closes_the_bag_when_stopped(signum: int, tmp_path: Path):
    out = tmp_path / "stopped"
    listener = Listener({})
    recorder = launch("record", "-o", out, "--topics", ELEVATION, *REMAP_CLOCK)
    try:
        publisher = listener.publisher(PointStamped, ELEVATION)
        assert listener.wait_for(lambda: publisher.get_subscription_count() > 0, 20.0), "recorder never subscribed"
        sent = []
        for i in range(50):
            sent.append(cdr.point(0.1 * i, 0.0, 0.0, elevation_z(i)))
            publisher.publish(sent[-1])
        assert publisher.wait_for_all_acked(Duration(seconds=10))
        time.sleep(0.3)
    finally:
        try:
            code, output = stop(recorder, signum)
        finally:
            listener.close()
    assert code == 0, output
    assert "Traceback" not in output
    assert "log times are wall-clock time" in output  # no /clock here
    bag = Bag(out)
    assert [d for _, _, d in bag.messages([ELEVATION])] == sent
    times = np.array([t for _, t, _ in bag.messages([ELEVATION])])
    assert abs(times[-1] / 1e9 - time.time()) < 120  # wall clock, since no /clock
    assert len(read_with_rosbags(out)[ELEVATION]) == 50


@pytest.mark.slow
def test_record_all_topics_finds_topics_appearing_later(tmp_path: Path):
    """Default: every topic, looked for again every 0.5 s (subscribed best effort if its
    publisher offers only that)."""
    out = tmp_path / "all"
    listener = Listener({})
    recorder = launch("record", "-o", out, *REMAP_CLOCK)
    seen: list[str] = []  # its output read while waiting for a line
    try:
        elevation = listener.publisher(PointStamped, ELEVATION)
        assert listener.wait_for(lambda: elevation.get_subscription_count() > 0, 10.0), "recorder never subscribed"
        for i in range(20):
            elevation.publish(cdr.point(0.1 * i, 0.0, 0.0, elevation_z(i)))
        wrench = listener.publisher(WrenchStamped, WRENCH)  # appears later
        assert listener.wait_for(lambda: wrench.get_subscription_count() > 0, 10.0), "late topic never subscribed"
        best_effort = listener.node.create_publisher(PointStamped, BEST_EFFORT_TOPIC, BEST_EFFORT)
        seen += wait_for_line(recorder, f"recording {BEST_EFFORT_TOPIC} ", 10)
        assert listener.wait_for(lambda: best_effort.get_subscription_count() > 0, 10.0)
        for i in range(10):
            best_effort.publish(cdr.point(0.1 * i, 0.0, 0.0, 1.0))
        clock = listener.publisher(Clock, CLOCK)
        seen += wait_for_line(recorder, f"recording {CLOCK} ", 10)
        time.sleep(0.5)  # its recording subscription (which replaces the time-only one) matched
        clock.publish(cdr.clock(42.5))
        assert clock.wait_for_all_acked(Duration(seconds=10))
        time.sleep(0.3)
        for i in range(10):
            wrench.publish(cdr.six(0.1 * i, [i, 0, 0, 0, 0, 0]))
        assert wrench.wait_for_all_acked(Duration(seconds=10))
        time.sleep(0.3)
    finally:
        try:
            code, output = stop(recorder, signal.SIGTERM)
            output = "".join(seen) + output
        finally:
            listener.close()
    assert code == 0, output
    bag = Bag(out)
    assert bag.topics[ELEVATION].message_count == 20 and bag.topics[WRENCH].message_count == 10
    assert bag.topics[WRENCH].type == WRENCH_TYPE
    assert bag.topics[BEST_EFFORT_TOPIC].message_count > 0  # subscribed best effort: it matched
    offered = {entry["topic_metadata"]["name"]: entry["topic_metadata"]["offered_qos_profiles"][0]["reliability"]
               for entry in yaml.safe_load((out / "metadata.yaml").read_text())
               ["rosbag2_bagfile_information"]["topics_with_message_count"]}
    assert offered[BEST_EFFORT_TOPIC] == "best_effort" and offered[WRENCH] == "reliable"
    assert not {"/rosout", "/parameter_events"} & set(bag.topics)
    assert [t for _, t, _ in bag.messages([WRENCH])] == [nanoseconds(42.5)] * 10  # log time = /clock
    assert bag.config["recorder"]["topics"] == "all"
    assert "/clock received: log times are simulation time from now on" in output
    assert len(read_with_rosbags(out)[WRENCH]) == 10


@pytest.mark.serial
def test_record_stops_after_its_duration(tmp_path: Path):
    started = time.monotonic()
    code, output = wait_exit(launch("record", "-o", tmp_path / "short", "--duration", 1, "--topics", ELEVATION,
                                    *REMAP_CLOCK), 30)
    assert code == 0, output
    assert time.monotonic() - started < 15
    assert Bag(tmp_path / "short").message_count == 0  # nothing published: an empty, complete bag
    assert "recorded 0 messages" in output and f"{ELEVATION}: never recorded" in output


# ---------------------------------------------------------------------- bad input
def _truncated(tmp_path: Path, source: Path) -> Path:
    bag = tmp_path / "truncated"
    bag.mkdir()
    (bag / "metadata.yaml").write_bytes((source / "metadata.yaml").read_bytes())
    data = (source / "source_0.mcap").read_bytes()
    (bag / "source_0.mcap").write_bytes(data[: len(data) // 2])
    return bag


def _unknown_type(tmp_path: Path, source: Path) -> Path:
    with BagWriter(tmp_path / "unknown_type") as writer:
        channel = writer.add_topic("/odd", "no_such_msgs/msg/Thing", schema_text="float64 x\n")
        writer.write(channel, 0, b"\x00\x01\x00\x00" + bytes(8))
    return tmp_path / "unknown_type"


def _existing(tmp_path: Path, source: Path) -> Path:
    (tmp_path / "existing").mkdir()
    return tmp_path / "existing"


BAD_INPUT = {
    "missing bag": (["play", "{tmp}/nowhere"], "no such directory"),
    "no metadata.yaml": (["play", "{tmp}"], "no metadata.yaml"),
    "unknown topic": (["play", "{source}", "--topics", "/no/such/topic"], "no topic /no/such/topic"),
    "truncated bag": (["play", "{truncated}"], "truncated"),
    "unknown type": (["play", "{unknown_type}"], "no_such_msgs/msg/Thing: unknown"),
    "bad rate": (["play", "{source}", "--rate", "-1"], "--rate"),
    "existing output": (["record", "-o", "{existing}"], "already exists"),
}


@pytest.mark.parametrize("case", list(BAD_INPUT))
def test_bad_input_is_one_line_and_exit_code_2(case: str, source: Path, tmp_path: Path):
    argv, expected = BAD_INPUT[case]
    paths = {"tmp": tmp_path, "source": source, "truncated": _truncated(tmp_path, source),
             "unknown_type": _unknown_type(tmp_path, source), "existing": _existing(tmp_path, source)}
    argv = [a.format(**paths) for a in argv]
    code, output = wait_exit(launch(*argv), 30)
    assert code == 2, output
    lines = output.strip().splitlines()
    assert len(lines) == 1 and expected in lines[0] and "Traceback" not in output, output
    if case == "existing output":
        assert not any((tmp_path / "existing").iterdir())  # left alone
