"""Reference results of other codes for the physics tests (OpenFAST HydroDyn driver outputs),
kept in the repository's test data (test/data/openfast_hydrodyn, with their README)."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from fowt_hydro_sim.testing import REPO

HYDRODYN = REPO / "test" / "data" / "openfast_hydrodyn"


def hydrodyn_case(name: str) -> Path:
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

