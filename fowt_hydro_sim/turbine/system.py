"""Named systems: a platform, a turbine with its controller and a mooring model that belong
together, one YAML file each (``turbine/data/systems``; a file of your own works the same),
so that one name selects them in ``fowt-sim simulate``, ``fowt-sim closed-loop`` and the
nodes (``-p system:=NAME``). A system fills the platform, turbine and mooring settings left
at their defaults; a platform or turbine given otherwise than the system says is an error,
a mooring model given is taken (another model of the system's lines, e.g. moordyn)."""
from __future__ import annotations

from dataclasses import dataclass, fields, replace
from importlib import resources
from pathlib import Path
from typing import Any, TypeVar

import yaml

from fowt_hydro_sim.physics.config import MOORING_MODELS, ConfigError

FIELDS = ("platform", "turbine", "mooring")  # what a system sets
S = TypeVar("S")


@dataclass(frozen=True)
class System:
    name: str
    description: str
    platform: str
    turbine: str
    mooring: str


def packaged_systems() -> list[str]:
    """The names of the packaged systems."""
    folder = resources.files("fowt_hydro_sim.turbine") / "data" / "systems"
    return sorted(p.name[:-5] for p in folder.iterdir() if p.name.endswith(".yaml"))


def _relative(value: str, folder: Path, packaged: bool) -> str:
    """A packaged name as it is; a path relative to the system file's folder."""
    if packaged or not value or "/" not in value and not value.endswith((".yaml", ".yml")):
        return value
    path = Path(value)
    return str(path if path.is_absolute() else folder / path)


def load_system(name_or_path: str) -> System:
    """A packaged system by name (``iea15_volturnus_s``) or a system YAML file."""
    packaged = name_or_path in packaged_systems()
    path = (Path(str(resources.files("fowt_hydro_sim.turbine") / "data" / "systems" / f"{name_or_path}.yaml"))
            if packaged else Path(name_or_path))
    if not packaged and not path.is_file():
        raise ConfigError(f"system {name_or_path!r}: no such file and not a packaged system "
                          f"({', '.join(packaged_systems())})")
    try:
        data = yaml.safe_load(path.read_text())
    except (OSError, yaml.YAMLError) as exc:
        raise ConfigError(f"system {path}: cannot be read: {str(exc).splitlines()[0]}") from None
    if not isinstance(data, dict):
        raise ConfigError(f"system {path}: expected a mapping of platform, turbine, mooring")
    unknown = sorted(set(data) - {*FIELDS, "description"})
    missing = [f for f in ("platform", "turbine") if not data.get(f)]
    if unknown or missing:
        raise ConfigError(f"system {path}: " + (f"unknown field(s) {', '.join(unknown)}" if unknown
                                                 else f"missing {', '.join(missing)}"))
    mooring = str(data.get("mooring") or "")
    if mooring and mooring not in MOORING_MODELS:
        raise ConfigError(f"system {path}: mooring {mooring!r}: must be one of {', '.join(MOORING_MODELS)}")
    folder = path.parent
    return System(path.stem, str(data.get("description", "")), _relative(str(data["platform"]), folder, packaged),
                  _relative(str(data["turbine"]), folder, packaged), mooring)


def system_values(name_or_path: str, given: dict[str, Any], defaults: dict[str, Any]) -> dict[str, Any]:
    """``given`` (settings by name) with the system's platform, turbine and mooring for those
    of them in ``defaults`` left at their default (or None); ConfigError if the platform or
    turbine is given otherwise than the system says (a mooring given is kept)."""
    if not name_or_path:
        return given
    system = load_system(name_or_path)
    out = dict(given)
    for name in FIELDS:
        if name not in defaults:
            continue
        value, wanted = given.get(name), getattr(system, name)
        if value is None or value == defaults[name]:
            out[name] = wanted
        elif value != wanted and name != "mooring":  # another model of the same lines is the user's choice
            raise ConfigError(f"system {system.name} sets {name} {wanted!r}; {name} {value!r} was given too")
    return out


def filled(cls: type, values: dict[str, Any]) -> dict[str, Any]:
    """Settings of ``cls`` by name (e.g. a node's parameters) with the system they name
    (``values["system"]``) filled in (``system_values``)."""
    defaults = {f.name: f.default for f in fields(cls) if f.name in FIELDS}
    return system_values(values.get("system") or "", values, defaults)


def with_system(settings: S) -> S:
    """Settings (a dataclass with a ``system`` field and some of ``FIELDS``) with their
    system's values filled in (``system_values``)."""
    system = getattr(settings, "system", "")
    if not system:
        return settings
    names = [f.name for f in fields(settings) if f.name in FIELDS]
    defaults = {f.name: f.default for f in fields(settings) if f.name in names}
    values = system_values(system, {n: getattr(settings, n) for n in names}, defaults)
    return replace(settings, **values)
