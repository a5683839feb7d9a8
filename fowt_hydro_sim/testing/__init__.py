"""Helpers shared by the tests and the benchmarks (not used by the simulator itself).

``REPO`` is the folder the package is run from: the repository root for a checkout, so
that child processes (``python -m fowt_hydro_sim.cli ...``) run the same code.
"""
from __future__ import annotations

from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
