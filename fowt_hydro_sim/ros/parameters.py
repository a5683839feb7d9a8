"""ROS parameters derived from settings (``fowt_hydro_sim.settings``): each is declared with
its setting's default, description and range, and read back checked against it.

Every parameter is declared with dynamic typing and a value given for it (``-p name:=value``
or a ``--params-file``) is checked against its setting before rclpy sees it: a refused value
is the project's one line, "parameter NAME: must be ...", whatever the type or range, and
``-p duration_s:=60`` (an integer, as users type it) is taken as 60.0. A value given for a
parameter the node does not have is refused too (``refuse_unknown``), naming the nearest
known one.
"""
from __future__ import annotations

import dataclasses
import difflib
from typing import Any

from rcl_interfaces.msg import FloatingPointRange, IntegerRange, ParameterDescriptor

from fowt_hydro_sim.errors import ConfigError
from fowt_hydro_sim.settings import Described, SettingError, check, described


def descriptor(item: Described) -> ParameterDescriptor:
    s, kind = item.setting, item.scalar_type
    out = ParameterDescriptor(description=s.description, additional_constraints=s.range_text(),
                              dynamic_typing=True)
    low, high = s.ge, s.le
    if low is not None and high is not None and item.size is None:
        if kind is float:
            out.floating_point_range = [FloatingPointRange(from_value=float(low), to_value=float(high), step=0.0)]
        elif kind is int:
            out.integer_range = [IntegerRange(from_value=int(low), to_value=int(high), step=0)]
    return out


def _ros_value(value: Any) -> Any:
    return list(value) if isinstance(value, tuple) else value


def _python_value(value: Any) -> Any:
    """A parameter value as the settings take it (ROS arrays come as array.array or lists)."""
    if not isinstance(value, (str, bytes)) and hasattr(value, "__iter__"):
        return tuple(value)
    return value


def given(node) -> dict[str, Any]:
    """The values given to ``node`` on its command line or in parameter files, by name.
    rclpy keeps them (its "parameter overrides") but has no public accessor."""
    return {name: parameter.value for name, parameter in node._parameter_overrides.items()}


def _checked(name: str, item: Described, value: Any) -> Any:
    try:
        return check(item, _python_value(value))
    except SettingError as exc:
        raise ConfigError(f"parameter {name}: {exc}") from None


def declare(node, cls: type) -> None:
    """Declare every setting of the dataclass ``cls`` as a parameter of ``node``, each given
    value checked first (ConfigError names a bad one)."""
    values = given(node)
    for name, item in described(cls).items():
        if name in values:
            _checked(name, item, values[name])
        node.declare_parameter(name, _ros_value(item.default), descriptor(item))


def refuse_unknown(node) -> None:
    """After every parameter of ``node`` is declared: ConfigError naming each given value
    whose parameter the node does not have, with the nearest known name."""
    unknown = [name for name in given(node) if not node.has_parameter(name)]
    if not unknown:
        return
    known = list(node.get_parameters_by_prefix(""))
    texts = []
    for name in unknown:
        near = difflib.get_close_matches(name, known, n=1)
        texts.append(f"parameter {name}: unknown to {node.get_name()}"
                     + (f" (did you mean {near[0]}?)" if near else ""))
    raise ConfigError("; ".join(texts))


def read(node, cls: type):
    """The parameters' values as a ``cls``; ConfigError names a bad parameter."""
    return cls(**{name: _checked(name, item, node.get_parameter(name).value)
                  for name, item in described(cls).items()})


def values(settings) -> dict[str, Any]:
    """The settings as parameter values (for a bag's run configuration)."""
    return {f.name: _ros_value(getattr(settings, f.name)) for f in dataclasses.fields(settings)}
