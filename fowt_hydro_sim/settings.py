"""Typed settings: a dataclass field's default, meaning and allowed values, written once.

A field made with ``setting(default, description, ge=..., gt=..., le=..., choices=...)``
carries what every front end needs, so that a default or a range is written in one place:

- YAML files validate their fields with ``check`` (``physics.config``);
- the command line derives its options, help texts and checks (``cli.options``);
- the ROS node declares its parameters with the same descriptions and ranges
  (``ros.parameters``).

``unset``: a value meaning "not given" (e.g. 0 for an Hs that defaults to the load
case's), which bypasses the range check.
"""
from __future__ import annotations

import dataclasses
import math
import typing
from dataclasses import dataclass
from typing import Any

from fowt_hydro_sim.errors import InputError

_NOTHING = object()
REQUIRED = dataclasses.MISSING  # ``setting(REQUIRED, ...)``: a field without a default


class SettingError(InputError):
    """A value outside its setting's type or range; the message says what is allowed."""


@dataclass(frozen=True)
class Setting:
    description: str
    ge: float | None = None
    gt: float | None = None
    le: float | None = None
    lt: float | None = None
    choices: tuple | None = None
    unset: Any = _NOTHING

    def range_text(self) -> str:
        """The allowed values in words: 'a positive number', 'zero or more', '0 to 1', 'one of a, b'."""
        if self.choices:
            return "one of " + ", ".join(map(str, self.choices))
        if self.ge is not None and self.le is not None:
            return f"{self.ge:g} to {self.le:g}"
        if (self.le, self.lt) == (None, None) and (self.gt, self.ge) in ((0, None), (None, 0)):
            return "a positive number" if self.gt == 0 else "zero or more"
        low = f">= {self.ge:g}" if self.ge is not None else f"> {self.gt:g}" if self.gt is not None else ""
        high = f"<= {self.le:g}" if self.le is not None else f"< {self.lt:g}" if self.lt is not None else ""
        return " and ".join(filter(None, (low, high)))


def setting(default: Any, description: str, **limits: Any) -> Any:
    """A dataclass field with a default (``REQUIRED``: none) and its ``Setting``."""
    metadata = {"setting": Setting(description, **limits)}
    if default is REQUIRED:
        return dataclasses.field(metadata=metadata)
    return dataclasses.field(default=default, metadata=metadata)


def like(cls: type, name: str, default: Any = _NOTHING, note: str = "", **changes: Any) -> Any:
    """A field with the setting of ``cls.name``, its default, description (plus ``note``) or
    range changed where given: a front end's variant of a setting written elsewhere."""
    item = described(cls)[name]
    description = changes.pop("description", item.setting.description) + note
    s = dataclasses.replace(item.setting, description=description, **changes)
    return dataclasses.field(default=item.default if default is _NOTHING else default, metadata={"setting": s})


def validate(instance: Any, where: str) -> None:
    """Check every setting of a dataclass instance; ConfigError-like ValueError naming it."""
    for item in described(type(instance)).values():
        try:
            check(item, getattr(instance, item.name))
        except SettingError as exc:
            raise SettingError(f"{where}: {item.name}: {exc}") from None


@dataclass(frozen=True)
class Described:
    """One setting of a dataclass: name, type, default and its ``Setting``."""

    name: str
    kind: Any
    default: Any
    setting: Setting

    @property
    def scalar_type(self) -> type:
        """float, int, str or bool (of a tuple or an optional value: its element type)."""
        kind = self.kind
        args = [a for a in typing.get_args(kind) if a is not type(None) and a is not Ellipsis]
        return args[0] if args else kind

    @property
    def optional(self) -> bool:
        return type(None) in typing.get_args(self.kind)

    @property
    def size(self) -> int | None:
        """The length of a tuple setting (from its default), else None."""
        return len(self.default) if typing.get_origin(self.kind) is tuple else None


def described(cls: type, names: tuple[str, ...] | None = None) -> dict[str, Described]:
    """The settings of a dataclass (all, or ``names`` in that order)."""
    hints = typing.get_type_hints(cls)
    found = {f.name: Described(f.name, hints[f.name], f.default, f.metadata["setting"])
             for f in dataclasses.fields(cls) if "setting" in f.metadata}
    return found if names is None else {name: found[name] for name in names}


def _scalar(value: Any, kind: type) -> Any:
    if kind is bool:
        if isinstance(value, bool):
            return value
        raise SettingError(f"must be true or false, got {value!r}")
    if kind is str:
        if isinstance(value, (dict, list, tuple)):
            raise SettingError(f"must be text, got {value!r}")
        return str(value)
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise SettingError(f"must be a number, got {value!r}")
    try:
        number = float(value)
    except ValueError:
        raise SettingError(f"must be a number, got {value!r}") from None
    if not math.isfinite(number):
        raise SettingError(f"must be finite, got {value!r}")
    if kind is int:
        if number != int(number):
            raise SettingError(f"must be a whole number, got {value!r}")
        return int(number)
    return number


def _limits(value: Any, s: Setting) -> None:
    if s.choices is not None and value not in s.choices:
        raise SettingError(f"must be {s.range_text()}, got {value!r}")
    if ((s.ge is not None and value < s.ge) or (s.gt is not None and value <= s.gt)
            or (s.le is not None and value > s.le) or (s.lt is not None and value >= s.lt)):
        raise SettingError(f"must be {s.range_text()}, got {value:g}")


def check(item: Described, value: Any) -> Any:
    """``value`` converted to the setting's type and checked against its range (an int for
    a float setting is taken as a float); SettingError says what is wrong."""
    s = item.setting
    if value is None and item.optional:
        return None
    if s.unset is not _NOTHING and value == s.unset:
        return s.unset
    kind = item.scalar_type
    if item.size is not None:
        if not isinstance(value, (list, tuple)) or len(value) != item.size:
            what = "numbers" if kind in (float, int) else "values"
            raise SettingError(f"must be a list of {item.size} {what}, got {value!r}")
        values = tuple(_scalar(v, kind) for v in value)
        for v in values:
            _limits(v, s)
        return values
    value = _scalar(value, kind)
    _limits(value, s)
    return value
