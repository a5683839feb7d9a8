"""Bags (rosbag2 directories, MCAP storage): what the node records, read back by two
independent readers (``mcap`` + ``mcap-ros2-support``, and ``rosbags``); recordings that
lose nothing, survive SIGINT/SIGTERM and, after SIGKILL, are recovered; the wave bag
source against the offline model; bad bags with clear errors.

Real nodes in child processes over DDS on loopback, real files."""
from __future__ import annotations

import re
import shutil
import signal
import subprocess
import time
from pathlib import Path

import numpy as np
import pytest
import yaml
from mcap.data_stream import RecordBuilder
from mcap.reader import make_reader
from mcap.records import Message, MessageIndex
from mcap_ros2.decoder import DecoderFactory
from rosbags.highlevel import AnyReader

from fowt_hydro_sim.physics.config import load_case, load_platform
from fowt_hydro_sim.physics.loads import COMPONENTS, PUBLISHED
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.wave_feed import run_with_elevation
from fowt_hydro_sim.rosbag.reader import Bag
from fowt_hydro_sim.rosbag.writer import BagError, BagWriter, message_index
from fowt_hydro_sim.studies.wave_bags import write_wave_bag
from fowt_hydro_sim.testing import REPO, fowt_sim
from fowt_hydro_sim.testing.ros import Listener, finish, start
from msg_adapters import cdr, topics

OUTPUT_TOPICS = [topic for topic, _ in topics.outputs(PUBLISHED).values()]
# the default platform's mooring lines: one tension topic each
TENSION_TOPICS = [topics.tension_topic(line) for line in range(1, len(load_platform("windmoor12").mooring.lines) + 1)]


def published_count(log: str) -> int:
    return int(re.search(r"(\d+) messages published", log).group(1))


@pytest.fixture(scope="module")
def recorded_run(tmp_path_factory) -> tuple[Path, str]:
    """30 s of the default node, as fast as possible, recorded; with its log."""
    bag = tmp_path_factory.mktemp("runs") / "default"
    log = finish(start("node", real_time_factor=0.0, duration_s=30.0, record=str(bag)), timeout_s=180)
    assert "stepping ended" in log, log
    return bag, log


@pytest.mark.slow
@pytest.mark.ros
def test_a_recorded_run_holds_exactly_the_messages_published(recorded_run):
    bag, log = recorded_run
    counts = {topic: info.message_count for topic, info in Bag(bag).topics.items()}
    rows = int(round(30.0 / 0.05)) + 1  # the start and every publish period
    published = OUTPUT_TOPICS + TENSION_TOPICS
    assert {topic: counts[topic] for topic in published} == {topic: rows for topic in published}
    assert sum(counts[t] for t in published) == published_count(log) == rows * len(published)


@pytest.mark.ros
def test_every_load_component_is_published_recorded_and_summed(recorded_run):
    """The load registry drives the node: each published component has its recorded topic,
    an unpublished one none, and /platform/loads/total is the sum of the summed components
    at every sample (the node sums them in the registry's order)."""
    bag = Bag(recorded_run[0])
    for component in COMPONENTS:
        assert (topics.load_topic(component.name) in bag.topics) == component.published, component.name
    summed = [c.name for c in COMPONENTS if c.summed]
    assert set(summed) <= set(PUBLISHED)  # the total is checkable from the bag alone
    _, loads = bag.aligned([topics.load_topic(name) for name in (topics.TOTAL, *summed)])
    total = loads.pop(topics.load_topic(topics.TOTAL))
    np.testing.assert_allclose(total, sum(loads.values()), rtol=1e-12, atol=1e-6)
    assert np.abs(total).max() > 1e6  # buoyancy and waves: a real sum


@pytest.mark.ros
def test_two_independent_readers_read_every_message_and_schema(recorded_run):
    bag, _ = recorded_run
    ours = Bag(bag)
    with open(next(bag.glob("*.mcap")), "rb") as stream:  # mcap + mcap-ros2-support
        reader = make_reader(stream, decoder_factories=[DecoderFactory()])
        assert reader.get_header().profile == "ros2"
        summary = reader.get_summary()
        assert all(s.encoding == "ros2msg" for s in summary.schemas.values())
        assert all(c.message_encoding == "cdr" and yaml.safe_load(c.metadata["offered_qos_profiles"])[0]["reliability"]
                   == "reliable" for c in summary.channels.values())
        assert all(chunk.compression == "zstd" for chunk in summary.chunk_indexes)
        decoded: dict[str, list] = {}
        for _, channel, message, msg in reader.iter_decoded_messages(log_time_order=True):
            decoded.setdefault(channel.topic, []).append((message.log_time, msg))
    assert {t: len(v) for t, v in decoded.items()} == {t: i.message_count for t, i in ours.topics.items()
                                                      if i.message_count}
    pose = decoded[topics.POSE]
    assert all(log_time == m.header.stamp.sec * 10**9 + m.header.stamp.nanosec for log_time, m in pose)
    series = ours.series(topics.POSE)
    np.testing.assert_array_equal(series.values[:, 0], [m.pose.position.x for _, m in pose])
    odom = decoded["/platform/odom"][-1][1]
    assert odom.child_frame_id == "platform" and len(odom.twist.covariance) == 36

    with AnyReader([bag]) as reader:  # rosbags
        assert {c.topic: c.msgcount for c in reader.connections} == {t: i.message_count for t, i in ours.topics.items()}
        assert all(c.msgdef.data for c in reader.connections)  # every schema carried in the bag
        n = 0
        for connection, _timestamp, raw in reader.messages():
            msg = reader.deserialize(raw, connection.msgtype)
            n += 1
        assert n == ours.message_count
        assert reader.connections[0].ext.offered_qos_profiles[0].depth == 1000


@pytest.mark.slow
@pytest.mark.ros
def test_the_run_configuration_in_the_bag_reproduces_the_run(recorded_run, tmp_path):
    bag, _ = recorded_run
    config = Bag(bag).config
    assert config["software"]["fowt_hydro_sim"] and config["parameters"]["seed"] == 1
    assert config["sea_state"]["hs_m"] == 11.0 and "members" in yaml.safe_load(config["platform_yaml"])
    params = tmp_path / "rerun.yaml"
    result = fowt_sim("info", str(bag), "--params-file", str(params))
    assert result.returncode == 0 and "/platform/pose" in result.stdout, result.stderr
    rerun = fowt_sim("node", "--ros-args", "--params-file", params, "-p", f"record:={tmp_path / 'again'}",
                     timeout=180)
    assert "stepping ended" in rerun.stderr + rerun.stdout
    first, again = Bag(bag).motion(), Bag(tmp_path / "again").motion()
    np.testing.assert_array_equal(first.time_s, again.time_s)
    np.testing.assert_array_equal(first.values, again.values)


def test_message_records_are_the_mcap_librarys(tmp_path):
    """The writer packs Message records itself: the same bytes as mcap.records.Message."""
    with BagWriter(tmp_path / "b") as writer:
        channel = writer.add_topic(topics.POSE, topics.POSE_STAMPED)
        data = cdr.pose(1.25, [1, 2, 3, 0.1, 0.2, 0.3])
        writer.write(channel, 1_250_000_000, data)
        packed = bytes(writer._chunk)
    builder = RecordBuilder()
    Message(channel_id=channel, log_time=1_250_000_000, publish_time=1_250_000_000, data=data,
            sequence=0).write(builder)
    assert packed == builder.end()


def test_a_batch_written_as_arrays_is_the_same_bag_as_message_by_message(tmp_path):
    """write_blocks (the node's batches) against write_rows of the same messages: the same
    .mcap and metadata.yaml byte for byte, over several chunks; the message indexes are
    mcap.records.MessageIndex's bytes, and both independent readers read every message."""
    outputs = topics.outputs(PUBLISHED)
    bags = {}
    for how in ("rows", "blocks"):
        rng = np.random.default_rng(5)  # the same messages both ways
        with BagWriter(tmp_path / how, config={"case": 1}, chunk_size_bytes=20_000, chunk_interval_s=1e9) as writer:
            channels = [writer.add_topic(topic, kind) for topic, kind in outputs.values()]
            for batch in range(6):
                n = 7 + batch
                time_s = 0.05 * np.arange(batch * 20, batch * 20 + n) + 1e5 * (batch == 5)
                motion = np.hstack([rng.normal(0, 5, (n, 3)), rng.uniform(-1, 1, (n, 3))])
                values = [rng.normal(0, 1e6, (n, 6)) for _ in range(2)]
                args = (time_s, motion, *values, rng.normal(0, 1e6, (n, len(PUBLISHED), 6)), rng.normal(0, 1e6, (n, 6)),
                        rng.normal(0, 2, n), "world", "platform")
                if how == "rows":
                    writer.write_rows((int(round(t * 1e9)), zip(channels, messages))
                                      for t, messages in zip(time_s.tolist(), cdr.outputs(*args)))
                else:
                    writer.write_blocks(np.rint(time_s * 1e9).astype(np.int64), channels, cdr.output_blocks(*args))
        bags[how] = tmp_path / how
    for name in ("rows_0.mcap", "metadata.yaml"):
        ours = (bags["blocks"] / name.replace("rows", "blocks")).read_bytes()
        reference = (bags["rows"] / name).read_bytes()
        assert ours == (reference.replace(b"rows_0", b"blocks_0") if name == "metadata.yaml" else reference)
    recorded = Bag(bags["blocks"])
    with open(bags["blocks"] / "blocks_0.mcap", "rb") as stream:
        assert len(make_reader(stream).get_summary().chunk_indexes) > 3
    assert recorded.message_count == len(outputs) * sum(7 + b for b in range(6))
    with AnyReader([bags["blocks"]]) as reader:
        assert sum(1 for _ in reader.messages()) == recorded.message_count
    builder = RecordBuilder()
    MessageIndex(channel_id=3, records=[(5, 17), (2**63, 9)]).write(builder)
    assert message_index(3, [5, 2**63], [17, 9]) == builder.end()


def test_topics_read_through_the_message_indexes_are_the_mcap_librarys(tmp_path):
    """Oracle: the mcap library's reader (every record of every chunk, merged by log time).
    Some topics of a bag of many chunks, read through the chunks' message indexes: the same
    (topic, log time, bytes) in the same order."""
    rng = np.random.default_rng(2)
    with BagWriter(tmp_path / "b", chunk_size_bytes=3_000, chunk_interval_s=1e9) as writer:
        pose = writer.add_topic(topics.POSE, topics.POSE_STAMPED)
        elevation = writer.add_topic(topics.ELEVATION, topics.POINT_STAMPED)
        clock = writer.add_topic("/clock", topics.CLOCK)
        for step in range(400):
            t = 0.05 * step
            ns = int(round(t * 1e9))
            writer.write(pose, ns, cdr.pose(t, rng.normal(0, 1, 6)))
            if step % 3 == 0:
                writer.write(elevation, ns, cdr.point(t, 0.0, 0.0, rng.normal()))
            writer.write(clock, ns, cdr.clock(t))
    bag = Bag(tmp_path / "b")
    with open(bag.files[0], "rb") as stream:
        assert len(make_reader(stream).get_summary().chunk_indexes) > 10
    for wanted in ([topics.POSE], [topics.ELEVATION, topics.POSE], ["/clock", topics.ELEVATION]):
        with open(bag.files[0], "rb") as stream:
            reference = [(c.topic, m.log_time, m.data)
                         for _, c, m in make_reader(stream).iter_messages(topics=wanted, log_time_order=True)]
        assert len(reference) >= 400 and list(bag.messages(wanted)) == reference


@pytest.fixture(scope="module")
def wave_bag(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("waves") / "lc53"
    result = fowt_sim("waves", "--load-case", "lc5.3", "--duration", "200", "--seed", "3", "-o", str(path))
    assert result.returncode == 0, result.stderr
    return path


def test_a_wave_bag_has_the_sea_states_elevation(wave_bag):
    bag = Bag(wave_bag)
    elevation = bag.elevation()
    assert len(elevation.time_s) == 2001 and np.allclose(np.diff(elevation.time_s), 0.1)
    sea = load_case("lc5.3").sea_state
    assert bag.config["waves"]["sea_state"]["hs_m"] == sea.hs_m and bag.config["waves"]["sea_state"]["seed"] == 3
    assert 0.6 * sea.hs_m < 4 * elevation.values[:, 2].std() < 1.4 * sea.hs_m  # 200 s of an 11 m sea


@pytest.mark.slow
@pytest.mark.ros
def test_bag_wave_source_gives_the_offline_models_motion_and_records_the_same_samples(wave_bag, tmp_path):
    record = tmp_path / "run"
    log = finish(start("node", real_time_factor=0.0, wave_source="bag", wave_bag=str(wave_bag),
                       drag_model="constant", record=str(record)), timeout_s=180)
    assert "wave bag" in log and "ends" in log, log
    recorded = Bag(record)
    source = [data for _, _, data in Bag(wave_bag).messages()]
    again = [data for _, _, data in recorded.messages([topics.ELEVATION])]
    assert again == source[:len(again)] and len(again) > 0.9 * len(source)  # bit for bit

    motion = recorded.motion()
    elevation = Bag(wave_bag).elevation()
    samples = [(t, x, y, z, "world") for t, (x, y, z) in zip(elevation.time_s, elevation.values)]
    offline = run_with_elevation(PlatformModel(load_platform(), None, drag_model="constant"), samples, (0.0, 0.0),
                                 "world", 0.1, 60.0, 0.0, motion.time_s[-1], 0.05)
    np.testing.assert_allclose(offline.time_s, motion.time_s, atol=1e-9, rtol=0)
    np.testing.assert_array_equal(offline.motion[:, :3], motion.values[:, :3])
    np.testing.assert_allclose(offline.motion[:, 3:], motion.values[:, 3:], atol=1e-12, rtol=0)
    assert offline.motion[:, 0].std() > 0.1  # the waves moved it


def recording_node(bag: Path, real_time_factor: float, run_s: float) -> subprocess.Popen:
    """A node recording to ``bag``, running for about ``run_s`` wall seconds after its second
    chunk reached the bag: the first holds the messages of the start (t = 0), the second
    those of a wall second of stepping, however long a loaded machine took between them."""
    process = start("node", real_time_factor=real_time_factor, record=str(bag))
    deadline = time.monotonic() + 180

    def size() -> int:
        return sum(f.stat().st_size for f in bag.glob("*.mcap"))
    while time.monotonic() < deadline and not (bag / "metadata.yaml").exists():
        time.sleep(0.2)
    time.sleep(0.5)
    for _ in range(2):  # header, schemas and channels; then each chunk of messages
        written = size()
        while time.monotonic() < deadline and size() <= written:
            time.sleep(0.2)
    time.sleep(run_s)
    return process


@pytest.mark.slow
@pytest.mark.ros
@pytest.mark.parametrize("stop", [signal.SIGINT, signal.SIGTERM])
def test_an_interrupted_recording_is_a_complete_bag(stop, tmp_path):
    bag = tmp_path / "run"
    process = recording_node(bag, real_time_factor=5.0, run_s=4.0)
    process.send_signal(stop)
    log = finish(process, timeout_s=30)
    assert process.returncode == 0, log
    counts = Bag(bag).topics
    assert counts[topics.POSE].message_count > 20, log
    with AnyReader([bag]) as reader:
        assert sum(1 for _ in reader.messages()) == sum(t.message_count for t in counts.values())


@pytest.mark.slow
@pytest.mark.ros
@pytest.mark.parametrize("on_failure", ["stop", "continue"])
def test_a_full_disk_ends_the_recording_with_one_line_and_a_readable_bag(small_disk, on_failure):
    """The disk fills up: one error line, no traceback; the bag is closed with what was written
    (both readers open it, every message readable); stepping stops or goes on as
    record_failure says; the exit code says the recording is incomplete."""
    bag = small_disk / "run"
    process = start("node", real_time_factor=0.0, duration_s=600.0, record=str(bag), record_failure=on_failure)
    log = finish(process, timeout_s=300)
    assert process.returncode == 1 and "Traceback" not in log and "OSError" not in log, log
    failures = [line for line in log.splitlines() if "recording stopped at a failed write" in line]
    assert len(failures) == 1 and "No space left on device" in failures[0], log
    ended = float(re.search(r"stepping ended at t = ([\d.]+) s", log).group(1))
    assert (ended < 590.0) if on_failure == "stop" else (ended == 600.0 and "duration 600 s reached" in log), log
    recorded = Bag(bag)
    assert recorded.topics[topics.POSE].message_count > 100, log
    assert int(re.search(r"closed with the (\d+) messages", failures[0]).group(1)) == recorded.message_count
    with AnyReader([bag]) as reader:
        assert sum(1 for _ in reader.messages()) == recorded.message_count
    pose = recorded.series(topics.POSE)
    assert np.all(np.diff(pose.time_s) > 0) and pose.time_s[-1] < 600.0


@pytest.mark.serial
@pytest.mark.slow
@pytest.mark.ros
def test_a_killed_recording_is_recovered_up_to_its_last_chunk(tmp_path):
    bag = tmp_path / "run"
    process = recording_node(bag, real_time_factor=10.0, run_s=5.0)
    process.kill()
    finish(process)
    with pytest.raises(BagError, match="truncated.*fowt-sim recover"):
        Bag(bag)
    result = fowt_sim("recover", str(bag))
    assert result.returncode == 0, result.stderr
    recovered = Bag(bag)
    assert recovered.topics[topics.POSE].message_count > 50  # ~5 s at 10x, chunks closed every wall second
    assert recovered.config["parameters"]["real_time_factor"] == 10.0
    assert list(bag.glob("*.mcap.damaged"))
    with AnyReader([bag]) as reader:
        assert sum(1 for _ in reader.messages()) == recovered.message_count


def test_recover_leaves_an_intact_bag_alone(wave_bag, tmp_path):
    bag = tmp_path / "intact"
    shutil.copytree(wave_bag, bag)
    before = {f.name: f.read_bytes() for f in bag.iterdir()}
    result = fowt_sim("recover", str(bag))
    assert result.returncode == 0, result.stderr
    assert "intact" in result.stderr and "recovered" not in result.stderr
    assert {f.name: f.read_bytes() for f in bag.iterdir()} == before  # no *.damaged, nothing rewritten


@pytest.mark.parametrize("content", [b"", bytes(range(256)) * 20], ids=["empty", "random"])
def test_recover_refuses_a_file_that_is_not_an_mcap_recording(wave_bag, tmp_path, content):
    """An empty or foreign .mcap in a bag: one line naming the file, exit 2, nothing
    written or renamed; given the file itself, the same line."""
    bag = tmp_path / "bag"
    shutil.copytree(wave_bag, bag)
    mcap = next(bag.glob("*.mcap"))
    mcap.write_bytes(content)
    before = sorted(p.name for p in tmp_path.rglob("*"))
    for target in (bag, mcap):
        result = fowt_sim("recover", str(target))
        assert result.returncode == 2, result.stderr
        lines = result.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith(f"fowt-sim recover: error: {mcap}: not an MCAP recording ("), \
            result.stderr
        assert sorted(p.name for p in tmp_path.rglob("*")) == before and mcap.read_bytes() == content


def _bad_bags(root: Path, good: Path) -> dict[str, tuple[Path, str]]:
    truncated = root / "truncated"
    shutil.copytree(good, truncated)
    mcap = next(truncated.glob("*.mcap"))
    mcap.write_bytes(mcap.read_bytes()[: mcap.stat().st_size // 2])
    no_metadata = root / "no_metadata"
    shutil.copytree(good, no_metadata)
    (no_metadata / "metadata.yaml").unlink()
    not_a_bag = root / "not_a_bag"
    not_a_bag.mkdir()
    (not_a_bag / "notes.txt").write_text("hello")
    garbage = root / "garbage"
    shutil.copytree(good, garbage)
    next(garbage.glob("*.mcap")).write_bytes(b"not an mcap file at all")
    return {"truncated": (truncated, "truncated"), "no metadata": (no_metadata, "no metadata.yaml"),
            "not a bag": (not_a_bag, "no metadata.yaml"), "garbage": (garbage, "not an MCAP file"),
            "missing": (root / "nothing_here", "no such directory"), "file": (root / "not_a_bag" / "notes.txt",
                                                                          "not a directory")}


@pytest.mark.slow
def test_bad_bags_give_a_clear_error(wave_bag, tmp_path):
    for name, (path, message) in _bad_bags(tmp_path, wave_bag).items():
        with pytest.raises(BagError, match=message):
            Bag(path)
        result = fowt_sim("info", str(path))
        assert result.returncode == 2 and message in result.stderr and "Traceback" not in result.stderr, name


@pytest.mark.slow
@pytest.mark.ros
def test_wrong_topic_types_and_empty_bags_are_named(tmp_path):
    with BagWriter(tmp_path / "wrong") as writer:
        channel = writer.add_topic(topics.POSE, topics.POINT_STAMPED)  # a pose topic of the wrong type
        writer.write(channel, 0, cdr.point(0.0, 1.0, 2.0, 3.0))
    with pytest.raises(BagError, match="/platform/pose has type geometry_msgs/msg/PointStamped, expected "
                                       "geometry_msgs/msg/PoseStamped"):
        Bag(tmp_path / "wrong").motion()
    BagWriter(tmp_path / "empty").close()
    with pytest.raises(BagError, match="no topic /waves/elevation"):
        Bag(tmp_path / "empty").elevation()
    log = finish(start("node", wave_source="bag", wave_bag=str(tmp_path / "wrong"), real_time_factor=0.0))
    assert "no topic /waves/elevation" in log and "Traceback" not in log


@pytest.mark.slow
@pytest.mark.ros
def test_an_existing_bag_is_not_overwritten_unless_asked(recorded_run, tmp_path):
    bag, _ = recorded_run
    before = {p.name: p.stat().st_mtime_ns for p in bag.iterdir()}
    log = finish(start("node", real_time_factor=0.0, duration_s=1.0, record=str(bag)))
    assert "already exists" in log and "Traceback" not in log
    assert {p.name: p.stat().st_mtime_ns for p in bag.iterdir()} == before
    with pytest.raises(BagError, match="not a bag"):
        not_a_bag = tmp_path / "precious"
        not_a_bag.mkdir()
        (not_a_bag / "data.csv").write_text("1,2\n")
        BagWriter(not_a_bag, overwrite=True)
    assert (tmp_path / "precious" / "data.csv").exists()


def test_a_wave_bag_measured_away_from_the_origin(tmp_path):
    n = write_wave_bag(tmp_path / "w", load_case("lc5.0").sea_state, 10.0, load_platform().environment,
                       sample_dt_s=0.5, point_xy_m=(-50.0, 0.0))
    elevation = Bag(tmp_path / "w").elevation()
    assert n == 21 and np.all(elevation.values[:, 0] == -50.0)


@pytest.mark.parametrize("case", ["lc5.0", "lc5.1", "lc5.2", "lc5.3", "lc5.4", "lc6.1", "lc6.2", "lc6.3", "lc6.4",
                                  "lc6.5"])
def test_the_shipped_sample_bags_hold_their_load_cases(case):
    """bags/README.md: 1800 s every 0.1 s at (0, 0), seed 1; the record's Hs near the case's
    (30 minutes of a random sea: within 15 %)."""
    bag = Bag(REPO / "bags" / case)
    sea = load_case(case).sea_state
    assert bag.config["waves"]["sea_state"]["hs_m"] == sea.hs_m and bag.config["waves"]["sea_state"]["seed"] == 1
    elevation = bag.elevation()
    assert len(elevation.time_s) == 18001 and np.all(elevation.values[:, :2] == 0.0)
    assert abs(4 * elevation.values[:, 2].std() / sea.hs_m - 1) < 0.15


@pytest.mark.slow
@pytest.mark.ros
def test_a_wave_bag_played_on_the_topic_is_recorded_again_bit_for_bit(wave_bag, tmp_path):
    """fowt-sim play into the node (wave_source topic, recording): the samples the node
    recorded are the bag's, byte for byte, and in order."""
    record = tmp_path / "run"
    from rosgraph_msgs.msg import Clock

    from msg_adapters.stamps import seconds
    listener = Listener({"/clock": Clock})
    node = start("node", real_time_factor=0.0, wave_source="topic", drag_model="constant", record=str(record),
                 wave_timeout_s=5.0)  # as fast as possible the node waits while the player publishes; once
    # the player has left, 5 s of silence take it past the last sample in still water
    last_sample_s = Bag(wave_bag).elevation().time_s[-1]

    def simulated_s() -> float:
        return max((seconds(m.clock) for m in listener.messages["/clock"]), default=-1.0)
    try:
        try:
            # the player waits for the node's subscription (the node's first /clock, at t = 0 before any
            # wave, may be published before the listener is matched: it is no sign of life to wait for)
            player = fowt_sim("play", str(wave_bag), "--rate", "0", "--wait-for-subscribers", "1", timeout=180)
            assert player.returncode == 0, player.stderr
            # the node has taken every sample once its simulated time is past the last one
            assert listener.wait_for(lambda: simulated_s() > last_sample_s, 180.0), simulated_s()
        finally:
            listener.close()
        node.send_signal(signal.SIGINT)
    finally:
        log = finish(node, timeout_s=60)  # the node is never left running
    assert "stepping ended" in log, log
    source = [data for _, _, data in Bag(wave_bag).messages()]
    recorded = [data for _, _, data in Bag(record).messages([topics.ELEVATION])]
    assert len(recorded) == len(source) and recorded == source, log
