"""Helpers shared by the tests and the benchmarks (not used by the simulator itself).

``REPO`` is the folder the package is run from: the repository root for a checkout, so
that child processes (``python -m fowt_hydro_sim.cli ...``) run the same code; ``fowt_sim``
runs the command line so, for every test and benchmark.
"""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def fowt_sim(*args: object, timeout: float = 600, **kwargs) -> subprocess.CompletedProcess:
    """``fowt-sim ARGS`` as a user runs it: a child process started from ``REPO`` (the same
    code as the caller's), its output captured as text; ``kwargs`` go to ``subprocess.run``
    (e.g. ``env``, ``input``)."""
    return subprocess.run([sys.executable, "-m", "fowt_hydro_sim.cli", *map(str, args)], cwd=REPO,
                          capture_output=True, text=True, timeout=timeout, **kwargs)
