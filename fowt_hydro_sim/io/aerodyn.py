"""The tower's aerodynamic table from an OpenFAST AeroDyn 15 input file.

AeroDyn loads the tower with the wind's drag when ``TwrAero`` is True: per unit length
1/2 rho ``TwrCd`` ``TwrDiam`` |u| u at each height ``TwrElev`` (above the still water line
offshore), linear between the ``NumTwrNds`` rows of its tower table.
"""
from __future__ import annotations

from pathlib import Path
from typing import NamedTuple

import numpy as np

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.io.elastodyn import deck_fields, deck_number, deck_table


class TowerTable(NamedTuple):
    """AeroDyn's tower table: heights above the still water line [m], diameters [m] and drag
    coefficients [-] at them (increasing heights)."""

    heights_m: np.ndarray
    diameters_m: np.ndarray
    drag_coefficients: np.ndarray


def tower_table(path: Path) -> TowerTable | None:
    """The tower table of the AeroDyn 15 file ``path``, None when its ``TwrAero`` is False
    (AeroDyn then puts no load on the tower); one line naming the file and field when the
    table cannot be read."""
    fields, lines = deck_fields(path)
    flag = fields.get("TwrAero", "").lower()
    if flag not in ("true", "false", "t", "f"):
        raise InputError(f"{path}: TwrAero is not True or False ({fields.get('TwrAero')!r})")
    if flag.startswith("f"):
        return None
    n = int(deck_number(fields, "NumTwrNds", path))
    if n < 2:
        raise InputError(f"{path}: NumTwrNds must be at least 2, got {n}")
    rows = deck_table(lines, "TwrElev", n, path)
    if rows.shape[1] < 3:
        raise InputError(f"{path}: the TwrElev table needs TwrElev, TwrDiam and TwrCd columns")
    heights, diameters, cd = rows[:, 0], rows[:, 1], rows[:, 2]
    if np.any(np.diff(heights) <= 0):
        raise InputError(f"{path}: TwrElev must increase down the tower table")
    if np.any(diameters <= 0) or np.any(cd < 0):
        raise InputError(f"{path}: TwrDiam must be positive and TwrCd not negative")
    return TowerTable(heights, diameters, cd)
