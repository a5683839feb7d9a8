"""Typed changes of a platform: new ``Platform`` values made with ``dataclasses.replace``
(the calibration's coefficients, the gap diagnosis's effects, the benchmarks' perturbations).

Coefficients are named by path, as on the platform YAML: ``MEMBERS.ZONE.FIELD[.BAND]`` with a
shell-style pattern for the members, e.g. ``column*.submerged.cd.low_frequency``,
``pontoon*.submerged.cd_horizontal.wave``, ``pontoon*.submerged.cd_vertical`` (a Cd without
bands), ``column*.submerged.cd.constant`` (the constant-Cd model's value), or
``MEMBERS.end_a_plate.cd``. FIELD is ``cd`` / ``ca`` (circular sections: both directions),
``cd_horizontal`` / ``ca_horizontal`` or ``cd_vertical`` / ``ca_vertical`` (rectangular).
"""
from __future__ import annotations

import fnmatch
from collections.abc import Callable
from dataclasses import replace

from fowt_hydro_sim.physics.config import ConfigError, DragCoefficients, EndPlate, Member, Platform, Zone

PLATES = ("end_a_plate", "end_b_plate")
_DIRECTIONS = {"": (0, 1), "_horizontal": (0,), "_vertical": (1,)}  # field suffix -> section directions


# ---------------------------------------------------------------------- whole-platform scalings
def scaled_cd(cd: DragCoefficients, scale: float, band: int | None = None) -> DragCoefficients:
    """``cd`` with its constant and band Cds times ``scale``, or only band ``band``'s."""
    if band is not None:
        bands = None if cd.bands is None else tuple(c * scale if b == band else c for b, c in enumerate(cd.bands))
        return replace(cd, bands=bands)
    return DragCoefficients(scale * cd.constant, None if cd.bands is None else tuple(scale * c for c in cd.bands))


def map_zones(platform: Platform, change: Callable[[Zone], Zone], **platform_changes) -> Platform:
    """The platform with every member's zones replaced by ``change(zone)``."""
    members = tuple(replace(m, zones=tuple(change(z) for z in m.zones)) for m in platform.members)
    return replace(platform, members=members, **platform_changes)


def map_plates(platform: Platform, change: Callable[[EndPlate], EndPlate]) -> Platform:
    """The platform with every end plate replaced by ``change(plate)``."""
    def plates(m: Member) -> dict:
        return {end: None if getattr(m, end) is None else change(getattr(m, end)) for end in PLATES}
    return replace(platform, members=tuple(replace(m, **plates(m)) for m in platform.members))


def with_cds(platform: Platform, change: Callable[[DragCoefficients], DragCoefficients],
             **platform_changes) -> Platform:
    """The platform with every zone's DragCoefficients ``c`` replaced by ``change(c)``."""
    return map_zones(platform, lambda z: replace(z, cd=tuple(change(c) for c in z.cd)), **platform_changes)


def scaled_drag(platform: Platform, scale: float) -> Platform:
    """Every drag coefficient (strips, every band, and end plates) times ``scale``."""
    return map_plates(with_cds(platform, lambda c: scaled_cd(c, scale)), lambda p: replace(p, cd=scale * p.cd))


def scaled_added_mass(platform: Platform, scale: float) -> Platform:
    """Every added-mass coefficient Ca (strips and end plates) times ``scale``."""
    scaled = map_zones(platform, lambda z: replace(z, ca=tuple(scale * c for c in z.ca)))
    return map_plates(scaled, lambda p: replace(p, ca=scale * p.ca))


def scaled_mooring_stiffness(platform: Platform, scale: float) -> Platform:
    """The mooring lines' axial stiffness times ``scale``."""
    return replace(platform, mooring=replace(platform.mooring, stiffness_n_m=scale * platform.mooring.stiffness_n_m))


def uniform_drag(member: Member, cd_1: float, cd_2: float) -> Member:
    """One zone over the whole member (the last one's Ca), with one unfiltered Cd per direction."""
    zone = member.zones[-1]
    return replace(member, zones=(replace(zone, cd=(DragCoefficients(cd_1), DragCoefficients(cd_2)),
                                          below_z_m=float("inf")),))


def band_split(platform: Platform, low_frequency_ratio: float) -> Platform:
    """Every per-band Cd with its low-pass bands at ``low_frequency_ratio`` x its constant Cd
    and its other bands at the constant Cd."""
    low_pass = [b.kind == "lowpass" for b in platform.drag_bands]

    def split(cd: DragCoefficients) -> DragCoefficients:
        if cd.bands is None:
            return cd
        return replace(cd, bands=tuple(low_frequency_ratio * cd.constant if low else cd.constant for low in low_pass))
    return with_cds(platform, split)


def widest_circular_diameter_m(platform: Platform) -> float:
    """D of Hs/D and of the Keulegan-Carpenter number: the largest circular member's diameter."""
    diameters = [m.width_m for m in platform.members if m.section == "circular"]
    if not diameters:
        raise ConfigError(f"platform {platform.name}: no circular member to take a diameter D from")
    return max(diameters)


# ---------------------------------------------------------------------- coefficients by path
def _parse(path: str) -> tuple[str, str, str, str | None]:
    parts = path.split(".")
    if len(parts) not in (3, 4):
        raise ConfigError(f"parameter {path!r}: expected MEMBERS.ZONE.FIELD[.BAND] or MEMBERS.end_a_plate.cd")
    return parts[0], parts[1], parts[2], parts[3] if len(parts) == 4 else None


def _members(platform: Platform, path: str, pattern: str) -> list[int]:
    found = [i for i, m in enumerate(platform.members) if fnmatch.fnmatch(m.name, pattern)]
    if not found:
        raise ConfigError(f"parameter {path!r}: no member matches {pattern!r}")
    return found


def _band_index(platform: Platform, path: str, where: str, cd: DragCoefficients, band: str | None) -> int | None:
    """None for the constant Cd, else the band's index; ConfigError if the Cd has no such value."""
    if band is None:
        if cd.bands is not None:
            raise ConfigError(f"parameter {path!r}: {where} has a Cd per band; name one (constant, "
                              f"{', '.join(b.name for b in platform.drag_bands)})")
        return None
    if band == "constant":
        return None
    names = [b.name for b in platform.drag_bands]
    if cd.bands is None or band not in names:
        raise ConfigError(f"parameter {path!r}: {where} has no band {band!r}")
    return names.index(band)


def _zone_field(path: str, member: Member, zone_name: str, field: str) -> tuple[int, str, tuple[int, ...]]:
    """(zone index, 'cd' or 'ca', directions) of a zone field; ConfigError if the member lacks it."""
    kind, suffix = field[:2], field[2:]
    zone = next((k for k, z in enumerate(member.zones) if z.name == zone_name), None)
    circular = member.section == "circular"
    valid = kind in ("cd", "ca") and suffix in _DIRECTIONS and (suffix == "") == circular
    if zone is None or not valid:
        raise ConfigError(f"parameter {path!r}: member {member.name} has no {zone_name}.{field}")
    return zone, kind, _DIRECTIONS[suffix]


def coefficient(platform: Platform, path: str) -> float:
    """A coefficient's value (the first matching member's)."""
    pattern, zone_name, field, band = _parse(path)
    member = platform.members[_members(platform, path, pattern)[0]]
    if zone_name in PLATES:
        plate = getattr(member, zone_name)
        if plate is None or field not in ("cd", "ca", "cp"):
            raise ConfigError(f"parameter {path!r}: member {member.name} has no {zone_name}.{field}")
        return getattr(plate, field)
    zone, kind, directions = _zone_field(path, member, zone_name, field)
    value = getattr(member.zones[zone], kind)[directions[0]]
    if kind == "ca":
        return value
    index = _band_index(platform, path, f"{member.name}.{zone_name}.{field}", value, band)
    return value.constant if index is None else value.bands[index]


def _set_cd(cd: DragCoefficients, index: int | None, value: float) -> DragCoefficients:
    if index is None:
        return replace(cd, constant=value)
    return replace(cd, bands=tuple(value if b == index else c for b, c in enumerate(cd.bands)))


def with_coefficients(platform: Platform, values: dict[str, float]) -> Platform:
    """The platform with each coefficient path set to its value, on every matching member."""
    members = list(platform.members)
    for path, value in values.items():
        pattern, zone_name, field, band = _parse(path)
        value = float(value)
        for i in _members(platform, path, pattern):
            member = members[i]
            if zone_name in PLATES:
                plate = getattr(member, zone_name)
                if plate is None or field not in ("cd", "ca", "cp"):
                    raise ConfigError(f"parameter {path!r}: member {member.name} has no {zone_name}.{field}")
                members[i] = replace(member, **{zone_name: replace(plate, **{field: value})})
                continue
            zone, kind, directions = _zone_field(path, member, zone_name, field)
            coefficients = list(getattr(member.zones[zone], kind))
            for k in directions:
                if kind == "ca":
                    coefficients[k] = value
                else:
                    where = f"{member.name}.{zone_name}.{field}"
                    coefficients[k] = _set_cd(coefficients[k],
                                              _band_index(platform, path, where, coefficients[k], band), value)
            zones = list(member.zones)
            zones[zone] = replace(member.zones[zone], **{kind: tuple(coefficients)})
            members[i] = replace(member, zones=tuple(zones))
    return replace(platform, members=tuple(members))
