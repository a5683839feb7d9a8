"""``fowt-sim recover BAG``: rebuild a bag whose recording was killed (SIGKILL, power loss)
before it could write its summary. Every message of a complete chunk is kept, with the
schemas, channels and run configuration; the damaged file is kept beside it."""
from __future__ import annotations

import logging
import shutil
import struct
from pathlib import Path

import yaml
from mcap.exceptions import McapError
from mcap.records import Channel, Message, Metadata, Schema
from mcap.stream_reader import StreamReader

from fowt_hydro_sim.rosbag.writer import METADATA_FILE, RUN_CONFIG_KEY, BagError, BagWriter

log = logging.getLogger(__name__)

MAGIC = b"\x89MCAP0\r\n"  # the first 8 bytes of every MCAP file (mcap.writer.MCAP0_MAGIC)


def check_mcap(file: Path) -> None:
    """BagError unless ``file`` begins as an MCAP file does: an empty or foreign file holds
    no recording to recover."""
    with open(file, "rb") as stream:
        head = stream.read(len(MAGIC))
    if head != MAGIC:
        what = ("an empty file" if not head else f"{file.stat().st_size} bytes, starting {head[:4].hex(' ')} "
                "instead of the MCAP magic")
        raise BagError(f"{file}: not an MCAP recording ({what})")


def _salvage(file: Path) -> tuple[dict, dict, list, list]:
    """Schemas, channels, metadata and messages readable from the start of an MCAP file."""
    schemas, channels, metadata, messages = {}, {}, [], []
    with open(file, "rb") as stream:
        try:
            for record in StreamReader(stream, validate_crcs=True).records:
                if isinstance(record, Schema):
                    schemas[record.id] = record
                elif isinstance(record, Channel):
                    channels[record.id] = record
                elif isinstance(record, Metadata):
                    metadata.append(record)
                elif isinstance(record, Message):
                    messages.append(record)
        except (McapError, struct.error, ValueError, EOFError) as exc:
            log.info(f"{file.name}: readable up to a damaged or incomplete record ({type(exc).__name__})")
    return schemas, channels, metadata, messages


def is_intact(path: Path) -> bool:
    """Whether the bag at ``path`` opens as a complete bag (metadata and every file's summary)."""
    from fowt_hydro_sim.rosbag.reader import Bag
    try:
        Bag(path)
    except BagError:
        return False
    return True


def recover(path: str | Path) -> int | None:
    """Rewrite the bag at ``path`` as a complete bag; returns the messages recovered, or None
    for an intact bag, which is left untouched. BagError, with nothing written, when a file
    of the bag is not an MCAP recording at all (empty, or another format)."""
    path = Path(path)
    if path.is_file():
        check_mcap(path)
        raise BagError(f"{path}: a file; give the bag directory that holds it and its {METADATA_FILE}")
    if not (path / METADATA_FILE).is_file():
        raise BagError(f"bag {path}: no {METADATA_FILE}; not a bag this tool can recover")
    files = sorted(path.glob("*.mcap"))
    if not files:
        raise BagError(f"bag {path}: no .mcap file to recover")
    for file in files:  # before anything is written
        check_mcap(file)
    if is_intact(path):
        log.info(f"bag {path}: intact (every file complete with its summary); left as it is")
        return None
    salvaged = [_salvage(f) for f in files]
    config = next((yaml.safe_load(m.metadata["yaml"]) for _, _, meta, _ in salvaged for m in meta
                   if m.name == RUN_CONFIG_KEY), None)
    staging = path.with_name(path.name + ".recovering")
    count = 0
    with BagWriter(staging, config=config, overwrite=True, mcap_name=f"{path.name}_0.mcap") as writer:
        for schemas, channels, _, messages in salvaged:
            ids = {}
            for channel in channels.values():
                schema = schemas[channel.schema_id]
                qos = yaml.safe_load(channel.metadata.get("offered_qos_profiles", "")) or None
                ids[channel.id] = writer.add_topic(channel.topic, schema.name, qos, schema.data.decode())
            for message in messages:
                writer.write(ids[message.channel_id], message.log_time, message.data)
            count += len(messages)
    for file in files:
        file.rename(file.with_name(file.name + ".damaged"))
    for item in staging.iterdir():
        shutil.move(str(item), path / item.name)
    staging.rmdir()
    log.info(f"bag {path}: {count} messages recovered; the damaged file(s) kept as *.mcap.damaged")
    return count
