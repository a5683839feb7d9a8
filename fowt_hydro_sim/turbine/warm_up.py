"""The turbine's kernels compiled ahead of a first coupled run (``fowt-sim compile``; see
``physics/warm_up.py``)."""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

from fowt_hydro_sim.io.aerodyn import TowerTable
from fowt_hydro_sim.turbine.tower import tower_drag, tower_points


def _tower_drag() -> None:
    table = TowerTable(np.array([10.0, 100.0]), np.array([6.0, 4.0]), np.array([0.5, 0.5]))
    tower_drag(tower_points(table, 100.0, 0.1), 1.225, 10.0, 0.0, 0.0, 0.0)


def entry_points() -> dict[str, Callable[[dict], None]]:
    """What to call, by name (``physics.warm_up.warm_kernels`` calls them)."""
    return {"tower drag (coupled loop)": lambda made: _tower_drag()}
