"""Writing rosbag2 bags with MCAP storage (contract: docs/ros_interface.md).

A bag is a directory holding ``metadata.yaml`` and one ``.mcap`` file: profile ``ros2``,
``cdr`` messages, ``ros2msg`` schemas with every dependency, ``offered_qos_profiles`` in
the channel metadata, log time = simulation time [ns], zstd-compressed chunks.

The records are the ``mcap`` library's, except the Message and MessageIndex records (the
same bytes as ``mcap.records.Message.write`` and ``MessageIndex.write``): the library's
per-message path costs about 5 us, too much for a node publishing ~10^5 messages per wall
second. A Message record is packed with one ``struct`` call (``write_rows``), or a batch of
them as one array (``write_blocks``: the node's outputs, about 0.2 us a message), and the
message indexes as arrays. Schema and channel records go straight to the file, and each chunk is written
as soon as it is full or ``chunk_interval_s`` old, so after a crash everything up to the
last written chunk can be recovered (``recover``).

A write that fails (disk full, file-size limit: ``OSError``) ends the recording there: the
file is cut back to its last complete chunk and closed with its summary (dropping the last
chunks if even the summary does not fit), so that the bag stays readable, and the write
raises ``RecordingStopped`` once; later writes are ignored.
"""
from __future__ import annotations

import logging
import shutil
import struct
import threading
import time
import zlib
from collections import defaultdict
from collections.abc import Iterable
from pathlib import Path

import numpy as np
import yaml
import zstandard
from mcap.data_stream import RecordBuilder
from mcap.opcode import Opcode
from mcap.records import (
    Channel,
    Chunk,
    ChunkIndex,
    DataEnd,
    Footer,
    Header,
    Metadata,
    MetadataIndex,
    Schema,
    Statistics,
    SummaryOffset,
)
from mcap.writer import MCAP0_MAGIC

from fowt_hydro_sim import __version__
from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.files import replace_text
from fowt_hydro_sim.rosbag.schemas import schema

log = logging.getLogger(__name__)

METADATA_FILE = "metadata.yaml"
BAG_VERSION = 9  # rosbag2_bagfile_information version (Jazzy)
RUN_CONFIG_KEY = "fowt_hydro_sim.run_config"  # metadata.yaml custom_data and MCAP metadata name
MESSAGE_HEAD = struct.Struct("<BQHIQQ")  # opcode, record length, channel, sequence, log time, publish time
RECORD_PREFIX_BYTES = 9  # every MCAP record's opcode (1 byte) and length (8)
_LOG_TIME = 15  # byte offsets of the log and publish times in a Message record
_PUBLISH_TIME = 23
_INFINITE = {"sec": 9223372036, "nsec": 854775807}


def message_index(channel_id: int, log_times_ns: list[int], offsets: list[int]) -> bytes:
    """A MessageIndex record: (log time, offset in the chunk) of each message of a channel."""
    records = np.empty((len(offsets), 2), dtype="<u8")
    records[:, 0], records[:, 1] = log_times_ns, offsets
    body = struct.pack("<HI", channel_id, records.nbytes) + records.tobytes()
    return struct.pack("<BQ", Opcode.MESSAGE_INDEX, len(body)) + body


def message_records(log_times_ns: np.ndarray, channels: list[int], blocks: list[np.ndarray]) -> np.ndarray:
    """Message records of a batch, one row (n, bytes) per log time: for each channel in
    order its record head and its message (row i of its block (n, length))."""
    n = len(log_times_ns)
    times = np.ascontiguousarray(log_times_ns, dtype="<u8").view(np.uint8).reshape(n, 8)
    rows = np.empty((n, sum(MESSAGE_HEAD.size + b.shape[1] for b in blocks)), dtype=np.uint8)
    column = 0
    for channel_id, messages in zip(channels, blocks):
        length = messages.shape[1]
        head = MESSAGE_HEAD.pack(Opcode.MESSAGE, MESSAGE_HEAD.size - RECORD_PREFIX_BYTES + length, channel_id, 0, 0, 0)
        rows[:, column:column + MESSAGE_HEAD.size] = np.frombuffer(head, dtype=np.uint8)
        rows[:, column + _LOG_TIME:column + _LOG_TIME + 8] = times
        rows[:, column + _PUBLISH_TIME:column + _PUBLISH_TIME + 8] = times
        column += MESSAGE_HEAD.size
        rows[:, column:column + length] = messages
        column += length
    return rows


class BagError(InputError):
    """A bag that cannot be written or read; the message names the problem."""


class RecordingStopped(BagError):
    """The bag could not be written further (e.g. disk full); it was closed, readable, with
    the messages written before."""


def qos_profiles(reliability: str = "reliable", durability: str = "volatile", depth: int = 1000) -> list[dict]:
    """``offered_qos_profiles`` of one publisher, in the rosbag2 (version 9) layout."""
    return [{"history": "keep_last", "depth": int(depth), "reliability": reliability, "durability": durability,
             "deadline": dict(_INFINITE), "lifespan": dict(_INFINITE), "liveliness": "automatic",
             "liveliness_lease_duration": dict(_INFINITE), "avoid_ros_namespace_conventions": False}]


def prepare_directory(path: Path, overwrite: bool) -> None:
    """Create the bag directory; an existing one is replaced only with ``overwrite`` and
    only if it is a bag (holds metadata.yaml) or empty."""
    if path.exists():
        if not path.is_dir():
            raise BagError(f"{path} is a file, not a bag directory: choose another path")
        if any(path.iterdir()) and not (path / METADATA_FILE).exists():
            raise BagError(f"{path} is a directory that is not a bag (no {METADATA_FILE}): choose another path; "
                           f"it is never overwritten")
        if not overwrite:
            raise BagError(f"bag {path} already exists; choose another path or allow overwriting")
        shutil.rmtree(path)
    path.mkdir(parents=True)


class BagWriter:
    """A rosbag2 bag being written. Thread-safe; ``close()`` (or the context manager)
    writes the summary and the final metadata.yaml."""

    def __init__(self, path: str | Path, config: dict | None = None, overwrite: bool = False,
                 chunk_size_bytes: int = 1 << 20, chunk_interval_s: float = 1.0, mcap_name: str | None = None):
        self.path = Path(path)
        prepare_directory(self.path, overwrite)
        self.mcap_path = self.path / (mcap_name or f"{self.path.name}_0.mcap")
        self._file = open(self.mcap_path, "wb", buffering=0)  # unbuffered: a failed write leaves nothing pending
        self.failure: str | None = None  # why the recording stopped early
        self._chunk_counts: list[dict[int, int]] = []  # messages per channel of each written chunk
        self._write_bytes(MCAP0_MAGIC)
        self._config_yaml = yaml.safe_dump(config, sort_keys=False) if config is not None else None
        self._chunk_size = chunk_size_bytes
        self._chunk_interval_s = chunk_interval_s
        self._compressor = zstandard.ZstdCompressor(level=1)
        self._lock = threading.Lock()
        self._schemas: dict[str, Schema] = {}
        self._channels: dict[str, Channel] = {}
        self._types: dict[int, str] = {}
        self._qos: dict[int, list[dict]] = {}
        self.counts: dict[int, int] = defaultdict(int)  # per channel, in written chunks
        self._chunk_indexes: list[ChunkIndex] = []
        self._metadata_indexes: list[MetadataIndex] = []
        self._start_ns, self._end_ns = 2**63 - 1, 0
        self._new_chunk()
        self._append(Header(profile="ros2", library=f"fowt_hydro_sim {__version__} (mcap-python)"))
        if self._config_yaml is not None:
            self._add_metadata(RUN_CONFIG_KEY, {"yaml": self._config_yaml})
        self._write_metadata_yaml()
        self._closed = False

    # ------------------------------------------------------------------ set-up
    def add_topic(self, topic: str, type_name: str, qos: list[dict] | None = None,
                  schema_text: str | None = None) -> int:
        """Register a topic (idempotent); returns its channel id. The schema is looked up
        from the type unless given."""
        with self._lock:
            if topic in self._channels:
                channel = self._channels[topic]
                if self._types[channel.id] != type_name:
                    raise BagError(f"topic {topic}: already recorded as {self._types[channel.id]}, not {type_name}")
                return channel.id
            if type_name not in self._schemas:
                self._schemas[type_name] = Schema(id=len(self._schemas) + 1, name=type_name, encoding="ros2msg",
                                                  data=(schema_text or schema(type_name)).encode())
                self._append(self._schemas[type_name])
            qos = qos or qos_profiles()
            channel = Channel(id=len(self._channels) + 1, topic=topic, message_encoding="cdr",
                              schema_id=self._schemas[type_name].id,
                              metadata={"offered_qos_profiles": yaml.safe_dump(qos, sort_keys=False)})
            self._channels[topic], self._types[channel.id], self._qos[channel.id] = channel, type_name, qos
            self._append(channel)
            self._write_metadata_yaml()
            return channel.id

    # ------------------------------------------------------------------ messages
    def write(self, channel_id: int, log_time_ns: int, data: bytes) -> None:
        """One message (CDR bytes) with its log time (simulation time) in ns."""
        self.write_rows([(log_time_ns, [(channel_id, data)])])

    def write_rows(self, rows: Iterable[tuple[int, Iterable[tuple[int, bytes]]]]) -> None:
        """Messages grouped by log time: (log time [ns], [(channel id, CDR bytes), ...]) rows.
        Ignored once the recording stopped."""
        with self._lock:
            if self._closed:
                return
            chunk, offsets, pack = self._chunk, self._offsets, MESSAGE_HEAD.pack
            for log_time_ns, messages in rows:
                for channel_id, data in messages:
                    times, places = offsets[channel_id]
                    times.append(log_time_ns)
                    places.append(len(chunk))
                    chunk += pack(Opcode.MESSAGE, 22 + len(data), channel_id, 0, log_time_ns, log_time_ns)
                    chunk += data
                self._chunk_start_ns = min(self._chunk_start_ns, log_time_ns)
                self._chunk_end_ns = max(self._chunk_end_ns, log_time_ns)
            self._maybe_write_chunk()

    def write_blocks(self, log_times_ns: np.ndarray, channels: list[int], blocks: list[np.ndarray]) -> None:
        """A batch of messages as arrays: for each log time [ns] (n,) one message on each
        channel, row i of its block (n, length) of CDR bytes; the same records as
        ``write_rows`` of the rows. Ignored once the recording stopped."""
        if not len(log_times_ns):
            return
        records = message_records(log_times_ns, channels, blocks)
        times = np.asarray(log_times_ns, dtype=np.int64).tolist()
        with self._lock:
            if self._closed:
                return
            start = len(self._chunk)
            self._chunk += records.data
            row_starts = start + records.shape[1] * np.arange(len(times))
            column = 0
            for channel_id, messages in zip(channels, blocks):
                channel_times, places = self._offsets[channel_id]
                channel_times.extend(times)
                places.extend((row_starts + column).tolist())
                column += MESSAGE_HEAD.size + messages.shape[1]
            self._chunk_start_ns = min(self._chunk_start_ns, min(times))
            self._chunk_end_ns = max(self._chunk_end_ns, max(times))
            self._maybe_write_chunk()

    def _maybe_write_chunk(self) -> None:
        if len(self._chunk) >= self._chunk_size or time.monotonic() - self._chunk_opened > self._chunk_interval_s:
            try:
                self._write_chunk()
            except OSError as exc:
                self._stop_recording(exc)

    def _write_bytes(self, data: bytes) -> None:
        """All of ``data`` at the file's position (an unbuffered write may be partial); then
        the file's end is that of a complete record."""
        view = memoryview(data)
        while view:
            view = view[self._file.write(view):]
        self._good_end = self._file.tell()

    def _new_chunk(self) -> None:
        self._chunk = bytearray()
        self._offsets: dict[int, tuple[list[int], list[int]]] = defaultdict(lambda: ([], []))  # log times, places
        self._chunk_start_ns, self._chunk_end_ns = 2**63 - 1, 0
        self._chunk_opened = time.monotonic()

    def _write_chunk(self) -> None:
        if not self._offsets:
            self._chunk_opened = time.monotonic()
            return
        data = bytes(self._chunk)
        compressed = self._compressor.compress(data)
        start = self._file.tell()
        builder = RecordBuilder()
        Chunk(compression="zstd", data=compressed, message_start_time=self._chunk_start_ns,
              message_end_time=self._chunk_end_ns, uncompressed_crc=zlib.crc32(data),
              uncompressed_size=len(data)).write(builder)
        records, index_offsets = [builder.end()], {}
        chunk_length = position = len(records[0])
        for channel_id, (times, places) in self._offsets.items():
            index_offsets[channel_id] = start + position
            records.append(message_index(channel_id, times, places))
            position += len(records[-1])
        index = ChunkIndex(
            chunk_start_offset=start, chunk_length=chunk_length, message_index_offsets=index_offsets,
            message_index_length=position - chunk_length, compression="zstd",
            compressed_size=len(compressed), uncompressed_size=len(data),
            message_start_time=self._chunk_start_ns, message_end_time=self._chunk_end_ns)
        self._write_bytes(b"".join(records))
        self._chunk_indexes.append(index)
        self._chunk_counts.append({channel_id: len(places) for channel_id, (_, places) in self._offsets.items()})
        for channel_id, (_, places) in self._offsets.items():
            self.counts[channel_id] += len(places)
        self._start_ns = min(self._start_ns, self._chunk_start_ns)
        self._end_ns = max(self._end_ns, self._chunk_end_ns)
        self._new_chunk()

    def _append(self, record) -> None:
        """A record outside the chunks, written to the file at once."""
        builder = RecordBuilder()
        record.write(builder)
        self._write_bytes(builder.end())

    def _add_metadata(self, name: str, values: dict[str, str]) -> None:
        start = self._file.tell()
        builder = RecordBuilder()
        Metadata(name=name, metadata=values).write(builder)
        self._metadata_indexes.append(MetadataIndex(offset=start, length=builder.count, name=name))
        self._write_bytes(builder.end())

    # ------------------------------------------------------------------ closing
    @property
    def message_count(self) -> int:
        """Messages written so far (in the file or in the open chunk)."""
        return sum(self.counts.values()) + sum(len(places) for _, places in self._offsets.values())

    def close(self) -> None:
        """Write the last chunk, the summary and the final metadata.yaml."""
        with self._lock:
            if self._closed:
                return
            self._closed = True
            try:
                self._write_chunk()
                self._finish_mcap()
            except OSError as exc:
                self._stop_recording(exc, raise_=False)
                return
            self._file.close()
            self._write_metadata_yaml()
        log.info(f"bag {self.path}: {self.message_count} messages on {len(self._channels)} topics")

    def _stop_recording(self, exc: OSError, raise_: bool = True) -> None:
        """After a failed write: close the file at its last complete chunk with its summary,
        dropping the last chunks while even the summary does not fit; raise RecordingStopped."""
        self._closed = True
        self._new_chunk()  # the messages not written are lost
        end = self._good_end
        while True:
            try:
                self._file.truncate(end)
                self._file.seek(end)
                self._finish_mcap()
                break
            except OSError:
                if not self._chunk_indexes:
                    break  # not even the summary fits: the bag needs ``recover``
                dropped = self._chunk_indexes.pop()
                for channel_id, n in self._chunk_counts.pop().items():
                    self.counts[channel_id] -= n
                end = dropped.chunk_start_offset
        self._file.close()
        try:
            self._write_metadata_yaml()
        except OSError:
            pass  # the failure below is what the user is told; the last metadata.yaml stays whole
        self.failure = (f"bag {self.path}: recording stopped at a failed write ({exc.strerror or exc}); "
                        f"closed with the {self.message_count} messages written before")
        if raise_:
            raise RecordingStopped(self.failure) from None
        log.error(self.failure)

    def _finish_mcap(self) -> None:
        self._append(DataEnd(data_section_crc=0))
        summary_start = self._file.tell()
        builder, offsets = RecordBuilder(), []
        groups = [(Opcode.SCHEMA, list(self._schemas.values())), (Opcode.CHANNEL, list(self._channels.values())),
                  (Opcode.STATISTICS, [self._statistics()]), (Opcode.CHUNK_INDEX, self._chunk_indexes),
                  (Opcode.METADATA_INDEX, self._metadata_indexes)]
        for opcode, records in groups:
            if not records:
                continue
            group_start = builder.count
            for record in records:
                record.write(builder)
            offsets.append(SummaryOffset(group_opcode=opcode, group_start=summary_start + group_start,
                                         group_length=builder.count - group_start))
        summary_offset_start = summary_start + builder.count
        for offset in offsets:
            offset.write(builder)
        Footer(summary_start=summary_start, summary_offset_start=summary_offset_start, summary_crc=0).write(builder)
        self._write_bytes(builder.end() + MCAP0_MAGIC)

    def _statistics(self) -> Statistics:
        return Statistics(
            message_count=self.message_count, schema_count=len(self._schemas), channel_count=len(self._channels),
            attachment_count=0, metadata_count=len(self._metadata_indexes), chunk_count=len(self._chunk_indexes),
            message_start_time=self._start_ns if self.message_count else 0, message_end_time=self._end_ns,
            channel_message_counts=dict(self.counts))

    def _write_metadata_yaml(self) -> None:
        """metadata.yaml as rosbag2 writes it (replaced atomically): written at the start too,
        so an interrupted recording is still a bag directory."""
        count = self.message_count
        start = self._start_ns if count else 0
        duration = max(0, self._end_ns - self._start_ns) if count else 0
        topics = [{"topic_metadata": {"name": c.topic, "type": self._types[c.id], "serialization_format": "cdr",
                                      "offered_qos_profiles": self._qos[c.id], "type_description_hash": ""},
                   "message_count": self.counts[c.id]} for c in self._channels.values()]
        info = {"version": BAG_VERSION, "storage_identifier": "mcap", "duration": {"nanoseconds": duration},
                "starting_time": {"nanoseconds_since_epoch": start}, "message_count": count,
                "topics_with_message_count": topics, "compression_format": "", "compression_mode": "",
                "relative_file_paths": [self.mcap_path.name],
                "files": [{"path": self.mcap_path.name, "starting_time": {"nanoseconds_since_epoch": start},
                           "duration": {"nanoseconds": duration}, "message_count": count}],
                "custom_data": {RUN_CONFIG_KEY: self._config_yaml} if self._config_yaml is not None else {},
                "ros_distro": "jazzy"}
        replace_text(self.path / METADATA_FILE, yaml.safe_dump({"rosbag2_bagfile_information": info}, sort_keys=False))

    def __enter__(self) -> BagWriter:
        return self

    def __exit__(self, *exc) -> None:
        self.close()
