"""ROS parameters derived from settings (``fowt_hydro_sim.settings``): each is declared with
its setting's default, description and range, and read back checked against it.

Floating-point parameters are declared with dynamic typing, so that ``-p duration_s:=60``
(an integer, as users type it) is taken as 60.0.
"""
from __future__ import annotations

import dataclasses
from typing import Any

from rcl_interfaces.msg import FloatingPointRange, IntegerRange, ParameterDescriptor

from fowt_hydro_sim.physics.config import ConfigError
from fowt_hydro_sim.settings import Described, SettingError, check, described


def descriptor(item: Described) -> ParameterDescriptor:
    s, kind = item.setting, item.scalar_type
    out = ParameterDescriptor(description=s.description, additional_constraints=s.range_text(),
                              dynamic_typing=kind is float)
    low, high = s.ge, s.le
    if low is not None and high is not None and item.size is None:
        if kind is float:
            out.floating_point_range = [FloatingPointRange(from_value=float(low), to_value=float(high), step=0.0)]
        elif kind is int:
            out.integer_range = [IntegerRange(from_value=int(low), to_value=int(high), step=0)]
    return out


def _ros_value(value: Any) -> Any:
    return list(value) if isinstance(value, tuple) else value


def declare(node, cls: type) -> None:
    """Declare every setting of the dataclass ``cls`` as a parameter of ``node``."""
    for name, item in described(cls).items():
        node.declare_parameter(name, _ros_value(item.default), descriptor(item))


def read(node, cls: type):
    """The parameters' values as a ``cls``; ConfigError names a bad parameter."""
    values = {}
    for name, item in described(cls).items():
        value = node.get_parameter(name).value
        if not isinstance(value, (str, bytes)) and hasattr(value, "__iter__"):  # lists come as array.array
            value = tuple(value)
        try:
            values[name] = check(item, value)
        except SettingError as exc:
            raise ConfigError(f"parameter {name}: {exc}") from None
    return cls(**values)


def values(settings) -> dict[str, Any]:
    """The settings as parameter values (for a bag's run configuration)."""
    return {f.name: _ros_value(getattr(settings, f.name)) for f in dataclasses.fields(settings)}
