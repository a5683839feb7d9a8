"""The platform model: waves, Morison strips, drag filters, load components, rigid-body
dynamics; no ROS, no bags, no studies.

Compiled kernels are cached by numba in a folder named after a digest of this package's
sources (under ``NUMBA_CACHE_DIR``, or the user's cache folder): numba checks only the file
of a cached function itself, so a change in a function it calls from another module (a new
load component in the registry, say) would otherwise leave a stale kernel in the cache.
"""
from __future__ import annotations

import hashlib
import os
from pathlib import Path

import numba


def _kernel_cache_dir() -> str:
    here = Path(__file__).resolve().parent
    digest = hashlib.blake2b(digest_size=8)
    for source in sorted(here.rglob("*.py")) + [here.parent / "frames.py"]:
        digest.update(source.read_bytes())
    base = os.environ.get("NUMBA_CACHE_DIR") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache"), "fowt_hydro_sim")
    return os.path.join(base, f"kernels-{digest.hexdigest()}")


numba.config.CACHE_DIR = _kernel_cache_dir()
