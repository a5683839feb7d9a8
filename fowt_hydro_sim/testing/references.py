"""Reference results of other codes for the physics tests (OpenFAST HydroDyn driver outputs),
kept in the repository's test data (test/data/openfast_hydrodyn, with their README)."""
from __future__ import annotations

import dataclasses
import importlib.util
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.config import Platform, load_platform
from fowt_hydro_sim.physics.platform_edits import uniform_drag
from fowt_hydro_sim.testing import REPO

HYDRODYN = REPO / "test" / "data" / "openfast_hydrodyn"
PRESCRIBED_STILL_CASE = "windmoor12_prescribed_still"  # the 6-DOF prescribed motion in still water


def hydrodyn_case(name: str) -> Path:
    """The folder of the reference case ``name`` (FileNotFoundError if it is missing)."""
    folder = HYDRODYN / name
    if not folder.is_dir():
        raise FileNotFoundError(f"reference case {folder} is missing from the repository's test data")
    return folder


def read_hydrodyn_out(path: Path) -> dict[str, np.ndarray]:
    """OpenFAST driver output: 6 preamble lines, channel names, units, then rows."""
    lines = path.read_text().splitlines()
    header = next(i for i, line in enumerate(lines) if line.split()[:1] == ["Time"])
    names = lines[header].split()
    data = np.loadtxt(lines[header + 2:])
    return {name: data[:, i] for i, name in enumerate(names)}


def hydrodyn_hull() -> Platform:
    """windmoor12 as in the reference decks: columns Cd 0.8, pontoons Cd 2.0 both ways, 0.5 m strips."""
    p = load_platform("windmoor12")
    members = tuple(dataclasses.replace(uniform_drag(m, 0.8, 0.8) if m.section == "circular"
                                        else uniform_drag(m, 2.0, 2.0), strip_length_m=0.5) for m in p.members)
    return dataclasses.replace(p, members=members)


def reference_motion() -> np.ndarray:
    """The reference's PRP file (19 columns), regenerated with its own gen_motion.py."""
    spec = importlib.util.spec_from_file_location("gen_motion", hydrodyn_case(PRESCRIBED_STILL_CASE) / "gen_motion.py")
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    t = np.round(np.arange(0, round(gen.TEND / gen.DT) + 1) * gen.DT, 10)
    x = [a + b for a, b in zip(gen.harmonic(t, 4.0, 0.01), gen.harmonic(t, 0.8, 0.09))]
    dofs = (x, gen.harmonic(t, 0.02, 0.02), gen.harmonic(t, 0.6, 0.07, 0.3), gen.harmonic(t, 0.02, 0.02),
            gen.harmonic(t, 0.04, 0.035, 0.5), gen.harmonic(t, 0.02, 0.02))
    return np.column_stack([t] + [dof[order] for order in range(3) for dof in dofs])


RAFT_UNMODELLED = ("tower_aerodyn", "wind_shear_exponent")  # RAFT loads its tower only under water


def turbine_without_tower_drag(turbine: str, folder: Path) -> Path:
    """A turbine file in ``folder``: the packaged ``turbine`` without the wind's drag on its
    tower (RAFT, whose response it is compared with, has none)."""
    import yaml

    from fowt_hydro_sim.turbine.description import turbine_path

    data = yaml.safe_load(turbine_path(turbine).read_text())
    path = folder / f"{turbine}_without_tower_drag.yaml"
    path.write_text(yaml.safe_dump({k: v for k, v in data.items() if k not in RAFT_UNMODELLED}))
    return path
