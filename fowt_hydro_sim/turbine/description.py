"""The turbine description: rotor, drivetrain, pitch actuator, performance table and
controller input file, read from packaged YAML (``turbine/data``) or a file and validated
like the platform (each field's range written once as a setting)."""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from importlib import resources
from pathlib import Path

import yaml

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.io.aerodyn import TowerTable, tower_table
from fowt_hydro_sim.physics.config import ConfigError
from fowt_hydro_sim.settings import REQUIRED, SettingError, check, described, setting
from fowt_hydro_sim.turbine.rosco import discon_text, parse_changes
from fowt_hydro_sim.turbine.tower import TowerPoints, tower_points

ROSCO_PREFIX = "rosco:"  # a path relative to the test cases installed with the rosco wheel


@dataclass(frozen=True, kw_only=True)
class TurbineDescription:
    name: str = setting(REQUIRED, "turbine name")
    rotor_radius_m: float = setting(REQUIRED, "rotor radius (hub centre to blade tip) [m]", gt=0.0)
    hub_height_m: float = setting(REQUIRED, "hub height above the still water line, where the thrust acts [m]",
                                  gt=0.0)
    drivetrain_inertia_kg_m2: float = setting(REQUIRED, "rotor and generator inertia on the low-speed shaft "
                                                        "[kg m^2]", gt=0.0)
    gearbox_ratio: float = setting(REQUIRED, "generator speed / rotor speed [-]", ge=1.0)
    gearbox_efficiency: float = setting(1.0, "gearbox efficiency [-]", gt=0.0, le=1.0)
    generator_efficiency: float = setting(REQUIRED, "generator efficiency, mechanical to electrical [-]",
                                          gt=0.0, le=1.0)
    air_density_kg_m3: float = setting(1.225, "air density [kg/m^3]", gt=0.0)
    rated_rotor_speed_rad_s: float = setting(REQUIRED, "rated rotor speed [rad/s]", gt=0.0)
    rated_power_w: float = setting(REQUIRED, "rated electrical power [W]", gt=0.0)
    optimal_tsr: float = setting(REQUIRED, "tip-speed ratio of the most power below rated [-]", gt=0.0)
    min_pitch_rad: float = setting(0.0, "lowest blade pitch of the actuator [rad]", ge=-0.5, le=1.6)
    max_pitch_rad: float = setting(1.57, "highest blade pitch of the actuator [rad]", ge=-0.5, le=1.6)
    max_pitch_rate_rad_s: float = setting(REQUIRED, "blade pitch rate limit of the actuator [rad/s]", gt=0.0)
    controller_dt_s: float = setting(0.05, "controller (and rotor) step [s]", gt=0.0, le=1.0)
    performance_table: str = setting(REQUIRED, "Cp/Ct/Cq table in ROSCO's text format (path; rosco: = in the "
                                               "rosco wheel's test cases)")
    discon: str = setting(REQUIRED, "ROSCO DISCON.IN of the turbine (path; rosco: = in the rosco wheel's "
                                    "test cases)")
    discon_changes: str = setting("", "DISCON.IN entries replaced, 'NAME=VALUE; NAME=VALUE' (VALUE: the entry's "
                                      "numbers, space-separated for a list), e.g. 'Fl_Kp=-5.0'; the file is "
                                      "left as it is")
    tower_aerodyn: str = setting("", "AeroDyn 15 input file whose tower table (TwrElev above the still water line, "
                                     "TwrDiam, TwrCd; TwrAero True) gives the wind's drag on the tower (path; "
                                     "rosco: = in the rosco wheel's test cases); empty: no tower drag")
    wind_shear_exponent: float = setting(0.0, "power-law exponent of the wind's profile below the hub, for the "
                                              "tower's drag (InflowWind's PLexp) [-]", ge=0.0, le=1.0)

    def __post_init__(self) -> None:
        if self.min_pitch_rad >= self.max_pitch_rad:
            raise ConfigError(f"turbine {self.name}: min_pitch_rad must be below max_pitch_rad")
        if self.discon_changes:
            self.controller_file()  # a name the file has not, or a list of another length: refused now
        if self.tower_aerodyn:
            try:
                _ = self.tower  # read once, here: a table that cannot be used is refused now
            except InputError as exc:
                raise ConfigError(f"turbine {self.name}: tower_aerodyn: {exc}") from None

    @property
    def changes(self) -> dict[str, str]:
        """``discon_changes`` as ``{NAME: VALUE}``."""
        return parse_changes(self.discon_changes)

    def controller_file(self) -> str:
        """The text of the DISCON.IN the controller reads: the file with ``discon_changes`` made."""
        return discon_text(self.discon_path, self.changes)

    @property
    def rated_generator_torque_nm(self) -> float:
        return self.rated_power_w / (self.rated_rotor_speed_rad_s * self.gearbox_ratio * self.generator_efficiency)

    @property
    def performance_path(self) -> Path:
        return resolve(self.performance_table)

    @property
    def discon_path(self) -> Path:
        return resolve(self.discon)

    def tower_table(self) -> TowerTable | None:
        """The tower's aerodynamic table (``tower_aerodyn``), read from its file; None without
        tower drag."""
        return tower_table(resolve(self.tower_aerodyn)) if self.tower_aerodyn else None

    @cached_property
    def tower(self) -> TowerPoints | None:
        """The quadrature of the wind's drag on the tower (``tower_table`` at this hub height
        and shear), computed once per description; None without tower drag."""
        table = self.tower_table()
        return None if table is None else tower_points(table, self.hub_height_m, self.wind_shear_exponent)


def resolve(path: str) -> Path:
    """A file path; ``rosco:...`` relative to the test cases installed with rosco."""
    if path.startswith(ROSCO_PREFIX):
        import rosco  # only for its location: the test cases are installed beside it

        return Path(rosco.__file__).resolve().parents[1] / "Examples" / "Test_Cases" / path[len(ROSCO_PREFIX):]
    return Path(path).expanduser()


def packaged_turbines() -> list[str]:
    folder = resources.files("fowt_hydro_sim.turbine") / "data"
    return sorted(p.name[:-5] for p in folder.iterdir() if p.name.endswith(".yaml"))


def turbine_path(name_or_path: str) -> Path:
    """The YAML file of a packaged turbine (by name) or a turbine file."""
    if name_or_path in packaged_turbines():
        return Path(str(resources.files("fowt_hydro_sim.turbine") / "data" / f"{name_or_path}.yaml"))
    path = Path(name_or_path)
    if not path.is_file():
        raise ConfigError(f"turbine {name_or_path!r}: no such file and not a packaged turbine "
                          f"({', '.join(packaged_turbines())})")
    return path


def turbine_from_dict(data: object, where: str, **overrides: float | str) -> TurbineDescription:
    """A validated description; ``overrides`` replace fields (e.g. ``hub_height_m``; the
    ``discon_changes`` given are made after the file's own). Relative file paths are taken
    relative to the YAML file's folder (``where``)."""
    if not isinstance(data, dict):
        raise ConfigError(f"{where}: expected a mapping, got {type(data).__name__}")
    if overrides.get("discon_changes") and data.get("discon_changes"):
        overrides = {**overrides, "discon_changes": f"{data['discon_changes']}; {overrides['discon_changes']}"}
    items = described(TurbineDescription)
    unknown = sorted(set(data) - set(items))
    if unknown:
        raise ConfigError(f"{where}: unknown field(s) {', '.join(unknown)}")
    values = {}
    for name, item in items.items():
        value = overrides.get(name, data.get(name, None if item.default is REQUIRED else item.default))
        if value is None:
            raise ConfigError(f"{where}: {name}: missing")
        try:
            values[name] = check(item, value)
        except SettingError as exc:
            raise ConfigError(f"{where}: {name}: {exc}") from None
    folder = Path(where).parent
    for name in ("performance_table", "discon", "tower_aerodyn"):
        path = values[name]
        if not path:
            continue
        if not path.startswith(ROSCO_PREFIX) and not Path(path).is_absolute():
            values[name] = str(folder / path)
        if not resolve(values[name]).is_file():
            raise ConfigError(f"{where}: {name}: no such file {str(resolve(values[name]))!r}")
    return TurbineDescription(**values)


def load_turbine(name_or_path: str = "iea15_umaine", **overrides: float | str) -> TurbineDescription:
    """A packaged turbine by name (``iea15_umaine``) or a turbine YAML file; ``overrides``
    given (not empty) replace its fields (``discon_changes`` is added to the file's own)."""
    path = turbine_path(name_or_path)
    try:
        data = yaml.safe_load(path.read_text())
    except (OSError, yaml.YAMLError) as exc:
        raise ConfigError(f"{path}: cannot be read: {str(exc).splitlines()[0]}") from None
    return turbine_from_dict(data, str(path), **{k: v for k, v in overrides.items() if v})
