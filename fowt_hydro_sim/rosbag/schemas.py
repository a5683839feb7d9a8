"""``ros2msg`` schemas for bags: a message definition with every dependency appended, as
rosbag2 writes them, so any reader decodes the bag without this package or ROS installed.

Definitions come from the installed ROS packages (``$AMENT_PREFIX_PATH`` and this Python's
prefix, ``<prefix>/share/<package>/msg/<Type>.msg``), else from the copies of the contract's
types packaged in ``rosbag/msg`` (so wave bags are written on a machine without ROS).
"""
from __future__ import annotations

import os
import re
import sys
from functools import cache
from importlib import resources
from pathlib import Path

from fowt_hydro_sim.errors import InputError

SEPARATOR = "=" * 80
BUILTIN_TYPES = {"bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16", "uint16", "int32",
                 "uint32", "int64", "uint64", "string", "wstring"}
_FIELD = re.compile(r"^\s*([A-Za-z][\w/]*)(?:<=\d+)?(?:\[[^\]]*\])?\s+\w+")


class SchemaError(InputError, LookupError):
    """A message type whose definition cannot be found."""


def split_type(type_name: str) -> tuple[str, str]:
    """('geometry_msgs', 'PoseStamped') from 'geometry_msgs/msg/PoseStamped' or 'geometry_msgs/PoseStamped'."""
    parts = type_name.split("/")
    if len(parts) == 3 and parts[1] == "msg":
        return parts[0], parts[2]
    if len(parts) == 2:
        return parts[0], parts[1]
    raise SchemaError(f"message type {type_name!r}: expected package/msg/Type")


def _search_roots() -> list[Path]:
    prefixes = [p for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p] + [sys.prefix]
    return [Path(p) / "share" for p in prefixes] + [Path(str(resources.files("fowt_hydro_sim.rosbag") / "msg"))]


@cache
def definition_text(package: str, name: str) -> str:
    """The text of ``package/msg/name.msg``."""
    for root in _search_roots():
        for path in (root / package / "msg" / f"{name}.msg", root / package / f"{name}.msg"):
            if path.is_file():
                return path.read_text()
    raise SchemaError(f"message type {package}/msg/{name}: no definition found (is its ROS package installed?)")


def dependencies(package: str, text: str) -> list[tuple[str, str]]:
    """The complex field types of a definition, in order of appearance."""
    found = []
    for line in text.splitlines():
        line = line.split("#", 1)[0]
        match = _FIELD.match(line)
        if not match or match.group(1) in BUILTIN_TYPES:  # constants are always of built-in types
            continue
        field_type = match.group(1)
        if field_type == "Header":
            found.append(("std_msgs", "Header"))
        elif "/" in field_type:
            found.append(split_type(field_type))
        else:
            found.append((package, field_type))
    return found


@cache
def schema(type_name: str) -> str:
    """The ``ros2msg`` schema of ``type_name``: its definition, then each dependency (depth
    first, once) after a separator line and ``MSG: package/Type``."""
    package, name = split_type(type_name)
    parts, seen = [definition_text(package, name)], set()

    def add(pkg: str, text: str) -> None:
        for dep in dependencies(pkg, text):
            if dep in seen:
                continue
            seen.add(dep)
            dep_text = definition_text(*dep)
            parts.append(f"{SEPARATOR}\nMSG: {dep[0]}/{dep[1]}\n{dep_text}")
            add(dep[0], dep_text)

    add(package, parts[0])
    return "\n".join(part.rstrip("\n") for part in parts) + "\n"
