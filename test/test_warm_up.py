"""``fowt-sim compile``: after it, a first ``simulate`` in a new process (either drag model, a
node-style stepping, an analysis) compiles no kernel: every one is loaded from the cache."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from fowt_hydro_sim.testing import REPO

# a fresh process: run the command under numba's compile-event recorder (cache misses only)
# and print how many kernels it had to compile
COUNT_COMPILES = """
import sys
from numba.core import event
from fowt_hydro_sim.cli import main
with event.install_recorder("numba:compile") as recorder:
    code = main(sys.argv[1:])
starts = [e for _, e in recorder.buffer if e.is_start]
print("compiled:", len(starts), sorted({e.data["dispatcher"].py_func.__name__ for e in starts}))
sys.exit(code)
"""


def run(args: list[str], cache: Path, count: bool = False) -> subprocess.CompletedProcess:
    command = [sys.executable, "-c", COUNT_COMPILES] if count else [sys.executable, "-m", "fowt_hydro_sim.cli"]
    return subprocess.run(command + args, capture_output=True, text=True, timeout=900, cwd=REPO,
                          env={**os.environ, "NUMBA_CACHE_DIR": str(cache)})


@pytest.mark.slow
def test_after_compile_a_first_simulate_compiles_nothing(tmp_path: Path):
    cache = tmp_path / "cache"
    warm = run(["compile"], cache, count=True)
    assert warm.returncode == 0, warm.stderr
    assert "integrate" in warm.stdout and "derivative" in warm.stdout  # (the counter sees compiling)
    assert "kernels ready" in warm.stdout and str(cache) in warm.stdout
    assert any(p.suffix == ".nbi" for p in cache.rglob("*"))  # numba's cache index files
    for drag in ("constant", "filtered"):
        done = run(["simulate", "--load-case", "lc5.1", "--drag", drag, "--duration", "30", "-o",
                    str(tmp_path / drag)], cache, count=True)
        assert done.returncode == 0, done.stderr
        assert "compiled: 0 []" in done.stdout, done.stdout
    again = run(["compile"], cache, count=True)  # a second warm-up only loads
    assert again.returncode == 0 and "compiled: 0 []" in again.stdout, again.stdout + again.stderr

