"""MAP++ input decks (OpenFAST's quasi-static mooring module) into MoorPy.

A MAP++ deck holds a ``LINE DICTIONARY`` (name, diameter, mass per length in air, EA, seabed
friction CB, ...), ``NODE PROPERTIES`` (``fix`` anchors, ``vessel`` fairleads in the platform's
body frame, ``connect`` points; ``depth`` for the seabed), ``LINE PROPERTIES`` (line type,
unstretched length, anchor and fairlead node) and ``SOLVER OPTIONS``, whose ``repeat a1 a2 ...``
copies every line turned about the vertical axis by each angle [deg]. :func:`read_map_deck`
reads one; :func:`moorpy_system` builds the lines in a MoorPy ``System`` on one coupled body at
the reference point (the fairleads attached to it). MoorPy 1.2.1 solves them without seabed
friction whatever CB the deck gives (its ``Line.staticSolve`` replaces the line's ``cb`` by the
anchor's height above the seabed, zero for an anchor on it); MAP++ applies CB.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fowt_hydro_sim.errors import InputError


@dataclass(frozen=True)
class MapLineType:
    """One row of the LINE DICTIONARY: diameter [m], mass per length in air [kg/m], EA [N] and
    the seabed friction coefficient CB [-]."""

    name: str
    diameter_m: float
    mass_kg_m: float
    ea_n: float
    cb: float


@dataclass(frozen=True)
class MapLine:
    """One line: its type, unstretched length [m], anchor (world frame) and fairlead (body
    frame, relative to the reference point) [m]."""

    line_type: MapLineType
    length_m: float
    anchor_m: tuple[float, float, float]
    fairlead_m: tuple[float, float, float]


def turned(point: tuple[float, float, float], angle_deg: float) -> tuple[float, float, float]:
    """``point`` turned about the z axis by ``angle_deg``."""
    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    return c * point[0] - s * point[1], s * point[0] + c * point[1], point[2]


def _sections(path: Path) -> dict[str, list[list[str]]]:
    """The deck's data rows by section (the header and units rows left out)."""
    sections: dict[str, list[list[str]]] = {}
    current = None
    for raw in path.read_text(errors="replace").splitlines():
        line = raw.strip()
        if not line:
            continue
        if line.startswith("-"):
            name = line.strip("- \t").upper()
            current = next((key for key in ("LINE DICTIONARY", "NODE PROPERTIES", "LINE PROPERTIES",
                                            "SOLVER OPTIONS") if name.startswith(key)), None)
            if current is not None:
                sections[current] = []
            continue
        if current is not None:
            sections[current].append(line.split())
    return sections


def read_map_deck(path: str | Path, depth_m: float) -> list[MapLine]:
    """The lines of the MAP++ deck ``path`` (with its ``repeat`` copies, in MAP's order: the
    deck's lines, then their copies turned by each angle). ``depth_m`` [m] is the seabed depth
    that the deck's ``depth`` stands for (MAP++ takes it from the water depth of the model).
    Only anchor-to-fairlead lines are read; a deck with ``connect`` nodes is refused."""
    path = Path(path)
    sections = _sections(path)
    missing = [key for key in ("LINE DICTIONARY", "NODE PROPERTIES", "LINE PROPERTIES") if key not in sections]
    if missing:
        raise InputError(f"{path.name}: not a MAP++ deck (no {', '.join(missing)} section)")
    try:
        types = {row[0]: MapLineType(row[0], float(row[1]), float(row[2]), float(row[3]), float(row[4]))
                 for row in sections["LINE DICTIONARY"][2:]}
        nodes = {}
        for row in sections["NODE PROPERTIES"][2:]:
            kind = row[1].lower()
            if kind not in ("fix", "vessel"):
                raise InputError(f"{path.name}: node {row[0]} is of type {row[1]}; only fix and vessel nodes are read")
            xyz = tuple(-depth_m if value.lower() == "depth" else float(value) for value in row[2:5])
            nodes[row[0]] = (kind, xyz)
        lines = []
        for row in sections["LINE PROPERTIES"][2:]:
            (kind_a, anchor), (kind_b, fairlead) = nodes[row[3]], nodes[row[4]]
            if (kind_a, kind_b) != ("fix", "vessel"):
                raise InputError(f"{path.name}: line {row[0]} does not run from a fix node to a vessel node")
            lines.append(MapLine(types[row[1]], float(row[2]), anchor, fairlead))
    except InputError:
        raise
    except (IndexError, KeyError, ValueError) as error:
        raise InputError(f"{path.name}: MAP++ deck not readable ({type(error).__name__}: {error})") from None
    angles = [float(value) for row in sections.get("SOLVER OPTIONS", []) if row[0].lower() == "repeat"
              for value in row[1:]]
    return lines + [MapLine(line.line_type, line.length_m, turned(line.anchor_m, angle),
                            turned(line.fairlead_m, angle)) for angle in angles for line in lines]


def moorpy_system(lines: list[MapLine], depth_m: float, rho: float = 1025.0, g: float = 9.80665):
    """A MoorPy ``System`` of ``lines`` on one coupled body at the reference point (at rest),
    initialised: each line from its anchor (end A) to its fairlead (end B), its weight in water
    ``(m - rho pi d^2 / 4) g``. The type's CB is handed to MoorPy, which (1.2.1) solves lines
    with an anchor on the seabed without friction."""
    import moorpy as mp

    system = mp.System(depth=depth_m, rho=rho, g=g)
    system.addBody(-1, np.zeros(6))
    for line in lines:
        kind = line.line_type
        if kind.name not in system.lineTypes:
            weight = (kind.mass_kg_m - rho * math.pi / 4 * kind.diameter_m**2) * g
            system.lineTypes[kind.name] = {"name": kind.name, "d_vol": kind.diameter_m, "m": kind.mass_kg_m,
                                           "EA": kind.ea_n, "w": weight, "input_d": kind.diameter_m, "MBL": 0,
                                           "EI": 0, "Cd": 0, "Ca": 0, "CdAx": 0, "CaAx": 0}
        system.addPoint(1, line.anchor_m)
        system.addPoint(1, line.fairlead_m)
        system.bodyList[0].attachPoint(len(system.pointList), line.fairlead_m)
        system.addLine(line.length_m, kind.name, pointA=len(system.pointList) - 1, pointB=len(system.pointList),
                       cb=kind.cb)
    system.initialize()
    return system
