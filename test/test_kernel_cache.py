"""Where compiled kernels are cached: the package's in the folder named after its sources'
digest, without changing numba's configuration for the rest of the process."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from fowt_hydro_sim.testing import REPO

# a fresh process: numba's cache folder before and after importing the model, one package
# kernel and one function of a file outside the package compiled with cache=True
CHECK = """
import json, sys
import numba
import numpy as np
before = numba.config.CACHE_DIR
import fowt_hydro_sim.physics.model
from fowt_hydro_sim.physics import kernel_cache_dir
from fowt_hydro_sim.physics.jit import copy_into
sys.path.insert(0, sys.argv[1])
from outside import twice
out = np.zeros(3)
copy_into(np.arange(3.0), out)
print(json.dumps({"before": before, "after": numba.config.CACHE_DIR, "kernels": kernel_cache_dir(),
                  "copied": out.tolist(), "twice": twice(2.0)}))
"""
OUTSIDE = """
from numba import njit


@njit(cache=True)
def twice(x):
    return 2.0 * x
"""


@pytest.mark.slow
def test_the_model_caches_its_kernels_in_the_digest_folder_only(tmp_path: Path):
    (tmp_path / "code").mkdir()
    (tmp_path / "code" / "outside.py").write_text(OUTSIDE)
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    done = subprocess.run([sys.executable, "-c", CHECK, str(tmp_path / "code")], capture_output=True, text=True,
                          timeout=300, cwd=REPO, env={**env, "XDG_CACHE_HOME": str(tmp_path / "cache")})
    assert done.returncode == 0, done.stderr
    seen = json.loads(done.stdout.splitlines()[-1])
    assert seen["after"] == seen["before"] == ""  # numba's global setting untouched
    assert seen["copied"] == [0.0, 1.0, 2.0] and seen["twice"] == 4.0
    kernels = Path(seen["kernels"])
    assert kernels.parent == tmp_path / "cache" / "fowt_hydro_sim" and kernels.name.startswith("kernels-")
    assert any(p.name.startswith("jit.copy_into") and p.suffix == ".nbi" for p in kernels.rglob("*"))
    assert not any("twice" in p.name for p in kernels.rglob("*"))  # another file's function: numba's place
    assert any(p.name.startswith("outside.twice") for p in (tmp_path / "code" / "__pycache__").iterdir())
