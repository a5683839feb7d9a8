"""Reading rosbag2 bags with MCAP storage: the API the offline tools share.

``Bag(path)`` checks the directory and its metadata and opens the MCAP files with the
``mcap`` library; ``series(topic)`` decodes a contract topic into numpy arrays (pose as 6
DOF: surge, sway, heave, roll, pitch, yaw), ``aligned`` puts several on one time base, and
``config`` is the run configuration the recorder stored. Problems are ``BagError``s
naming the file and what is wrong.
"""
from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import yaml
from mcap.data_stream import ReadDataStream
from mcap.exceptions import McapError
from mcap.reader import make_reader
from mcap.records import Chunk
from mcap.stream_reader import get_chunk_data_stream
from mcap.writer import MCAP0_MAGIC

from fowt_hydro_sim.frames import euler_from_quaternion
from fowt_hydro_sim.rosbag.writer import MESSAGE_HEAD, METADATA_FILE, RECORD_PREFIX_BYTES, RUN_CONFIG_KEY, BagError
from msg_adapters import topics as contract
from msg_adapters.cdr import decode_stamped

RECOVER_HINT = "`fowt-sim recover {path}` rebuilds it from its complete chunks"


@dataclass(frozen=True)
class TopicInfo:
    type: str
    message_count: int


@dataclass(frozen=True)
class Series:
    """A topic decoded: stamps [s], ascending and unique, and values (n, k)."""

    time_s: np.ndarray
    values: np.ndarray


COLUMNS = {  # names of a decoded series' columns, per type
    contract.POSE_STAMPED: ("surge", "sway", "heave", "roll", "pitch", "yaw"),
    contract.ODOMETRY: ("surge", "sway", "heave", "roll", "pitch", "yaw", "u", "v", "w", "p", "q", "r"),
    contract.POINT_STAMPED: ("x", "y", "z"),
    contract.TWIST_STAMPED: ("vx", "vy", "vz", "wx", "wy", "wz"),
    contract.ACCEL_STAMPED: ("ax", "ay", "az", "alpha_x", "alpha_y", "alpha_z"),
    contract.WRENCH_STAMPED: ("fx", "fy", "fz", "mx", "my", "mz"),
    contract.VECTOR3_STAMPED: ("x", "y", "z"),
    contract.CLOCK: (),
}


def _six_dof(doubles: np.ndarray) -> np.ndarray:
    """Position and quaternion (n, 7) to surge, sway, heave, roll, pitch, yaw."""
    return np.hstack([doubles[:, :3], euler_from_quaternion(doubles[:, 3:7])])


def _chunks_in_time_order(chunk_indexes: list) -> bool:
    """Whether each chunk's messages are logged no earlier than the previous chunk's."""
    ends = [c.message_end_time for c in chunk_indexes]
    starts = [c.message_start_time for c in chunk_indexes]
    return all(start >= end for start, end in zip(starts[1:], ends[:-1]))


def _indexed_messages(stream, summary, topics: list[str]) -> Iterator[tuple[str, int, bytes]]:
    """The messages of ``topics`` in one MCAP file, chunk by chunk, in log-time order within
    each chunk: the chunk's message indexes give the wanted records' offsets, and only those
    are read (the mcap library's reader parses every record of every chunk)."""
    wanted = {cid: c.topic for cid, c in summary.channels.items() if c.topic in topics}
    for index in summary.chunk_indexes:
        channels = [cid for cid in wanted if cid in index.message_index_offsets]
        if not channels:
            continue
        stream.seek(index.chunk_start_offset + RECORD_PREFIX_BYTES)
        data = get_chunk_data_stream(Chunk.read(ReadDataStream(stream)))[0].read(index.uncompressed_size)
        entries = []
        for cid in channels:
            stream.seek(index.message_index_offsets[cid] + RECORD_PREFIX_BYTES)
            head = stream.read(6)  # channel id, byte length of the (log time, offset) pairs
            pairs = np.frombuffer(stream.read(int.from_bytes(head[2:6], "little")), dtype="<u8").reshape(-1, 2)
            entries += [(int(t), int(offset), cid) for t, offset in pairs]
        for log_time, offset, cid in sorted(entries):
            length = int.from_bytes(data[offset + 1:offset + RECORD_PREFIX_BYTES], "little")
            yield wanted[cid], log_time, data[offset + MESSAGE_HEAD.size:offset + RECORD_PREFIX_BYTES + length]


class Bag:
    """A rosbag2 directory with MCAP storage, opened for reading."""

    def __init__(self, path: str | Path):
        self.path = Path(path)
        if not self.path.exists():
            raise BagError(f"bag {self.path}: no such directory")
        if not self.path.is_dir():
            raise BagError(f"bag {self.path}: not a directory (a rosbag2 bag is a directory with {METADATA_FILE})")
        meta_path = self.path / METADATA_FILE
        if not meta_path.is_file():
            raise BagError(f"bag {self.path}: no {METADATA_FILE}, so this directory is not a rosbag2 bag")
        try:
            info = yaml.safe_load(meta_path.read_text())["rosbag2_bagfile_information"]
            files = [self.path / Path(p).name for p in info["relative_file_paths"]]
            storage = info["storage_identifier"]
            custom = info.get("custom_data") or {}
        except (yaml.YAMLError, KeyError, TypeError) as exc:
            raise BagError(f"bag {self.path}: {METADATA_FILE} is not rosbag2 metadata "
                           f"({type(exc).__name__}: {exc})") from None
        if storage != "mcap":
            raise BagError(f"bag {self.path}: storage {storage!r}; only mcap bags are read")
        if missing := [f.name for f in files if not f.is_file()]:
            raise BagError(f"bag {self.path}: file(s) listed in {METADATA_FILE} missing: {', '.join(missing)}")
        self.files = files
        self.topics: dict[str, TopicInfo] = {}
        self._metadata: dict[str, dict[str, str]] = {}
        for file in files:
            self._read_summary(file)
        config_yaml = custom.get(RUN_CONFIG_KEY) or self._metadata.get(RUN_CONFIG_KEY, {}).get("yaml")
        self.config: dict | None = yaml.safe_load(config_yaml) if config_yaml else None

    def _read_summary(self, file: Path) -> None:
        with open(file, "rb") as stream:
            head = stream.read(len(MCAP0_MAGIC))
            stream.seek(max(0, file.stat().st_size - len(MCAP0_MAGIC)))
            tail = stream.read()
        if head != MCAP0_MAGIC:
            raise BagError(f"bag {self.path}: {file.name} is not an MCAP file")
        if tail != MCAP0_MAGIC or file.stat().st_size < 2 * len(MCAP0_MAGIC):
            raise BagError(f"bag {self.path}: {file.name} is truncated (its recording was not closed: killed, or "
                           f"the disk filled up); " + RECOVER_HINT.format(path=self.path))
        try:
            with open(file, "rb") as stream:
                reader = make_reader(stream)
                summary = reader.get_summary()
                if summary is None:
                    raise BagError(f"bag {self.path}: {file.name} has no summary (recording not closed); "
                                   + RECOVER_HINT.format(path=self.path))
                for record in reader.iter_metadata():
                    self._metadata[record.name] = dict(record.metadata)
        except (McapError, OSError, ValueError, EOFError) as exc:
            if isinstance(exc, BagError):
                raise
            raise BagError(f"bag {self.path}: {file.name} is truncated or not MCAP ({exc}); "
                           + RECOVER_HINT.format(path=self.path)) from None
        counts = summary.statistics.channel_message_counts if summary.statistics else {}
        for channel_id, channel in summary.channels.items():
            schema = summary.schemas.get(channel.schema_id)
            type_name = schema.name if schema else ""
            if channel.topic in self.topics and self.topics[channel.topic].type != type_name:
                raise BagError(f"bag {self.path}: topic {channel.topic} has two types "
                               f"({self.topics[channel.topic].type}, {type_name})")
            before = self.topics[channel.topic].message_count if channel.topic in self.topics else 0
            self.topics[channel.topic] = TopicInfo(type_name, before + counts.get(channel_id, 0))

    @property
    def message_count(self) -> int:
        return sum(t.message_count for t in self.topics.values())

    def summary(self) -> str:
        """Topics with their types and counts, and the run configuration (``fowt-sim info``)."""
        lines = [f"bag {self.path}: {self.message_count} messages"]
        lines += [f"  {topic}  {t.type}  {t.message_count}" for topic, t in sorted(self.topics.items())]
        if self.config:
            lines += ["configuration:", *("  " + line for line in yaml.safe_dump(
                {k: v for k, v in self.config.items() if k != "platform_yaml"}, sort_keys=False).splitlines())]
        return "\n".join(lines)

    def messages(self, topics: list[str] | None = None) -> Iterator[tuple[str, int, bytes]]:
        """(topic, log time [ns], CDR bytes) in log-time order, file by file. Some topics of
        a file whose chunks follow one another in time are read through the chunks' message
        indexes: only those topics' records are parsed."""
        for file in self.files:
            with open(file, "rb") as stream:
                reader = make_reader(stream)
                summary = reader.get_summary() if topics is not None else None
                if summary is not None and _chunks_in_time_order(summary.chunk_indexes):
                    yield from _indexed_messages(stream, summary, topics)
                    continue
                for _, channel, message in reader.iter_messages(topics=topics, log_time_order=True):
                    yield channel.topic, message.log_time, message.data

    def check_type(self, topic: str, expected: str | None = None) -> str:
        """The topic's type, checked against ``expected`` (default: the contract's)."""
        if topic not in self.topics:
            raise BagError(f"bag {self.path}: no topic {topic} (topics: {', '.join(sorted(self.topics)) or 'none'})")
        expected = expected or contract.type_of(topic)
        actual = self.topics[topic].type
        if expected and actual != expected:
            raise BagError(f"bag {self.path}: topic {topic} has type {actual}, expected {expected}")
        if self.topics[topic].message_count == 0:
            raise BagError(f"bag {self.path}: topic {topic} has no messages")
        return actual

    def series(self, topic: str) -> Series:
        """A stamped contract topic as arrays, sorted by stamp, duplicate stamps dropped (the
        first kept). Pose and odometry poses become 6 DOF (see ``COLUMNS``)."""
        type_name = self.check_type(topic)
        if type_name not in COLUMNS:
            raise BagError(f"bag {self.path}: topic {topic} has type {type_name}, which has no numeric series")
        data = [message for _, _, message in self.messages([topic])]
        try:
            time_s, values = decode_stamped(type_name, data)
        except ValueError as exc:
            raise BagError(f"bag {self.path}: topic {topic}: {exc}") from None
        if type_name == contract.POSE_STAMPED:
            values = _six_dof(values)
        elif type_name == contract.ODOMETRY:
            values = np.hstack([_six_dof(values[:, :7]), values[:, 43:49]])
        order = np.argsort(time_s, kind="stable")
        time_s, values = time_s[order], values[order]
        keep = np.concatenate([[True], np.diff(time_s) > 0])
        return Series(time_s[keep], values[keep])

    def scalar(self, topic: str) -> Series:
        """A quantity topic of the turbine (Vector3Stamped, the value in x) as stamps (n,)
        and values (n, 1), sorted by stamp, duplicates dropped."""
        self.check_type(topic, contract.VECTOR3_STAMPED)
        series = self.series(topic)
        return Series(series.time_s, series.values[:, :1])

    def aligned(self, topics: list[str], time_s: np.ndarray | None = None) -> tuple[np.ndarray, dict[str, np.ndarray]]:
        """Several topics on one time base (default: the first topic's stamps, where all
        topics have data), linearly interpolated; returns (time_s, {topic: values})."""
        series = {topic: self.series(topic) for topic in topics}
        if time_s is None:
            first = series[topics[0]].time_s
            start = max(s.time_s[0] for s in series.values())
            end = min(s.time_s[-1] for s in series.values())
            time_s = first[(first >= start) & (first <= end)]
        values = {topic: np.column_stack([np.interp(time_s, s.time_s, column) for column in s.values.T])
                  if s.values.shape[1] else np.empty((len(time_s), 0)) for topic, s in series.items()}
        return time_s, values

    def motion(self) -> Series:
        """The platform's 6-DOF motion from /platform/pose."""
        return self.series(contract.POSE)

    def elevation(self) -> Series:
        """The wave elevation samples of /waves/elevation: columns x, y, z (elevation)."""
        return self.series(contract.ELEVATION)
