"""The rigid floating system's mass properties from an OpenFAST ElastoDyn deck.

With every flexible DOF frozen (tower undeflected, rotor parked at zero azimuth, nacelle yaw
0), ElastoDyn's structure is a rigid body made of: the platform (``PtfmMass`` at
``PtfmCM*t``, its roll, pitch and yaw inertias about that point), the tower (``TMassDen`` of
the tower file along its height from ``TowerBsHt`` to ``TowerHt``, a line mass), the yaw
bearing (``YawBrMass`` at the tower top), the nacelle (``NacMass`` at the tower top plus
``NacCM*n``, ``NacYIner`` about the yaw axis), the hub (``HubMass`` at the rotor apex,
``HubIner`` about the shaft), the generator (``GenIner`` times ``GBRatio^2`` about the shaft)
and the blades (``BMassDen`` of the blade file from ``HubRad`` to ``TipRad``, coned by
``PreCone``, at azimuths 0, 120 and 240 deg). The rotor apex is ``OverHang`` along the shaft
(tilted by ``ShftTilt``) from ``Twr2Shft`` above the tower top (``hub_point``).

The result is about the system's centre of mass, in the platform's axes (x downwind, z up),
coordinates from the platform reference point (``PtfmRef*t``).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.config import MassProperties


def deck_fields(path: Path) -> tuple[dict[str, str], list[str]]:
    """The ``value NAME - comment`` fields of an OpenFAST input file and its lines."""
    try:
        lines = path.read_text().splitlines()
    except OSError as exc:
        raise InputError(f"{path}: cannot be read ({exc.strerror or exc})") from None
    fields: dict[str, str] = {}
    for line in lines:
        parts = line.split()
        if len(parts) >= 2 and not parts[0].startswith("--"):
            fields.setdefault(parts[1], parts[0].strip('"'))
    return fields, lines


def deck_number(fields: dict[str, str], name: str, path: Path) -> float:
    """The number in field ``name`` of ``deck_fields``; one line naming the file and field if absent or not a number."""
    try:
        return float(fields[name])
    except KeyError:
        raise InputError(f"{path}: no field {name}") from None
    except ValueError:
        raise InputError(f"{path}: {name} is not a number ({fields[name]!r})") from None


def deck_table(lines: list[str], header: str, n_rows: int, path: Path) -> np.ndarray:
    """The ``n_rows`` numeric rows after the line holding ``header`` and its units line."""
    start = next((k for k, line in enumerate(lines) if line.split()[:1] == [header]), None)
    if start is None:
        raise InputError(f"{path}: no table headed {header}")
    try:
        return np.array([[float(v) for v in lines[start + 2 + r].split()] for r in range(n_rows)])
    except (ValueError, IndexError):
        raise InputError(f"{path}: the {header} table does not hold {n_rows} rows of numbers") from None


def _point(mass: float, at: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    return mass, at, np.zeros((3, 3))


def _line_mass(density: np.ndarray, start: np.ndarray, direction: np.ndarray, length: float,
               samples: int = 2001) -> tuple[float, np.ndarray, np.ndarray]:
    """A line mass (density (n, 2): fraction, kg/m, interpolated linearly): mass, centre and
    inertia about its centre."""
    s = np.linspace(0.0, 1.0, samples)
    dm = np.interp(s, density[:, 0], density[:, 1]) * length
    w = np.full(samples, 1.0 / (samples - 1))
    w[[0, -1]] /= 2
    mass = float(np.sum(w * dm))
    points = start + np.outer(s * length, direction)
    centre = (w * dm) @ points / mass
    r = points - centre
    inertia = np.einsum("n,nij->ij", w * dm, np.einsum("ni,ni->n", r, r)[:, None, None] * np.eye(3)
                        - np.einsum("ni,nj->nij", r, r))
    return mass, centre, inertia


def hub_point(elastodyn_path: Path | str) -> tuple[float, float, float]:
    """The rotor apex (m, from the platform reference point): ``OverHang`` along the shaft,
    tilted by ``ShftTilt``, from ``Twr2Shft`` above the tower top."""
    path = Path(elastodyn_path)
    ed, _ = deck_fields(path)
    num = lambda name: deck_number(ed, name, path)  # noqa: E731
    tilt = math.radians(num("ShftTilt"))
    apex = np.array([num("OverHang") * math.cos(tilt), 0.0,
                     num("TowerHt") - num("PtfmRefzt") + num("Twr2Shft") + num("OverHang") * math.sin(tilt)])
    return tuple(float(v) for v in apex)


def system_mass_properties(elastodyn_path: Path | str, blade_path: Path | str | None = None) -> MassProperties:
    """The rigid system's mass, centre of mass and inertia about it (see the module docstring);
    ``blade_path`` overrides the deck's ``BldFile1`` (resolved relative to the deck)."""
    path = Path(elastodyn_path)
    ed, _ = deck_fields(path)
    num = lambda name: deck_number(ed, name, path)  # noqa: E731
    ref = np.array([num("PtfmRefxt"), num("PtfmRefyt"), num("PtfmRefzt")])
    parts = []
    platform_cm = np.array([num("PtfmCMxt"), num("PtfmCMyt"), num("PtfmCMzt")]) - ref
    parts.append((num("PtfmMass"), platform_cm, np.array([[num("PtfmRIner"), 0, 0], [0, num("PtfmPIner"), 0],
                                                         [0, 0, num("PtfmYIner")]], float)))
    tower_path = path.parent / ed["TwrFile"]
    tw, tw_lines = deck_fields(tower_path)
    tower = deck_table(tw_lines, "HtFract", int(deck_number(tw, "NTwInpSt", tower_path)), tower_path)
    base = np.array([0.0, 0.0, num("TowerBsHt")]) - ref
    top = np.array([0.0, 0.0, num("TowerHt")]) - ref
    tower_density = np.stack([tower[:, 0], tower[:, 1] * deck_number(tw, "AdjTwMa", tower_path)], axis=1)
    parts.append(_line_mass(tower_density, base, np.array([0.0, 0.0, 1.0]), float(top[2] - base[2])))
    parts.append(_point(num("YawBrMass"), top))
    nacelle = top + np.array([num("NacCMxn"), num("NacCMyn"), num("NacCMzn")])
    nacelle_yaw = num("NacYIner") - num("NacMass") * (nacelle[0] ** 2 + nacelle[1] ** 2)  # about its own CM
    parts.append((num("NacMass"), nacelle, np.diag([0.0, 0.0, nacelle_yaw])))
    tilt = math.radians(num("ShftTilt"))
    shaft = np.array([math.cos(tilt), 0.0, math.sin(tilt)])  # downwind along the shaft (the apex of the
    # IEA 15 MW rotor, OverHang -12.098 m at ShftTilt -6 deg, is then 150 m up: its hub height)
    apex = top + np.array([0.0, 0.0, num("Twr2Shft")]) + num("OverHang") * shaft
    spin = num("HubIner") + num("GenIner") * num("GBRatio") ** 2
    parts.append((num("HubMass"), apex + num("HubCM") * shaft, spin * np.outer(shaft, shaft)))
    blade_path = Path(blade_path) if blade_path is not None else path.parent / ed["BldFile1"]
    bl, bl_lines = deck_fields(blade_path)
    blade = deck_table(bl_lines, "BlFract", int(deck_number(bl, "NBlInpSt", blade_path)), blade_path)
    density = np.stack([blade[:, 0], blade[:, 2] * deck_number(bl, "AdjBlMs", blade_path)], axis=1)
    span = num("TipRad") - num("HubRad")
    for k in range(int(num("NumBl"))):
        cone = math.radians(num(f"PreCone({k + 1})"))
        azimuth = 2 * math.pi * k / num("NumBl")
        # in the rotor plane, up at azimuth 0; a positive PreCone tilts the blade downwind (ElastoDyn)
        radial = np.array([0.0, -math.sin(azimuth), math.cos(azimuth)])
        radial = radial - shaft * (shaft @ radial)
        radial /= np.linalg.norm(radial)
        direction = math.cos(cone) * radial + math.sin(cone) * shaft
        parts.append(_line_mass(density, apex + num("HubRad") * direction, direction, span))
    mass = sum(m for m, _, _ in parts)
    cog = sum(m * c for m, c, _ in parts) / mass
    inertia = np.zeros((3, 3))
    for m, c, i in parts:
        r = c - cog
        inertia += i + m * (r @ r * np.eye(3) - np.outer(r, r))
    return MassProperties(float(mass), tuple(float(v) for v in cog), tuple(tuple(float(v) for v in row)
                                                                           for row in inertia))
