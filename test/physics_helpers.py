"""Helpers shared by the physics tests: reference files and platform variants."""
from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from fowt_hydro_sim.config import DragCoefficients, Member, Platform, load_platform

SHARED = Path(__file__).resolve().parents[2] / "shared"
HYDRODYN = SHARED / "reference" / "openfast_hydrodyn"


def hydrodyn_case(name: str) -> Path:
    folder = HYDRODYN / name
    if not folder.is_dir():
        pytest.skip(f"reference case {folder} is not present")
    return folder


def read_hydrodyn_out(path: Path) -> dict[str, np.ndarray]:
    """OpenFAST driver output: 6 preamble lines, channel names, units, then rows."""
    lines = path.read_text().splitlines()
    header = next(i for i, line in enumerate(lines) if line.split()[:1] == ["Time"])
    names = lines[header].split()
    data = np.loadtxt(lines[header + 2:])
    return {name: data[:, i] for i, name in enumerate(names)}


def uniform_drag(member: Member, cd_1: float, cd_2: float) -> Member:
    """One zone over the whole member, with one unfiltered Cd per direction."""
    zone = member.zones[-1]
    cds = (DragCoefficients(cd_1), DragCoefficients(cd_2))
    return dataclasses.replace(member, zones=(dataclasses.replace(zone, cd=cds, below_z_m=math.inf),))


def scaled_cd(cd: DragCoefficients, scale: float, band: int | None = None) -> DragCoefficients:
    """``cd`` with its constant and band Cds times ``scale``, or only band ``band``'s."""
    if band is not None:
        bands = None if cd.bands is None else tuple(c * scale if b == band else c for b, c in enumerate(cd.bands))
        return dataclasses.replace(cd, bands=bands)
    return DragCoefficients(scale * cd.constant, None if cd.bands is None else tuple(scale * c for c in cd.bands))


def with_cds(platform: Platform, change, **platform_changes) -> Platform:
    """The platform with every zone's DragCoefficients ``c`` replaced by ``change(c)``."""
    members = tuple(dataclasses.replace(m, zones=tuple(dataclasses.replace(z, cd=tuple(change(c) for c in z.cd))
                                                       for z in m.zones)) for m in platform.members)
    return dataclasses.replace(platform, members=members, **platform_changes)


def scaled_drag(platform: Platform, scale: float) -> Platform:
    """The platform with every drag coefficient (strips and end plates) times ``scale``."""
    def plate(p):
        return None if p is None else dataclasses.replace(p, cd=scale * p.cd)

    scaled = with_cds(platform, lambda c: scaled_cd(c, scale))
    members = tuple(dataclasses.replace(m, end_a_plate=plate(m.end_a_plate), end_b_plate=plate(m.end_b_plate))
                    for m in scaled.members)
    return dataclasses.replace(scaled, members=members)


def windmoor12() -> Platform:
    return load_platform("windmoor12")
