"""The platform model: waves, Morison strips, drag filters, load components, rigid-body
dynamics; no ROS, no bags, no studies.

The package's compiled kernels are cached by numba in a folder named after a digest of this
package's sources (``kernel_cache_dir``: under ``NUMBA_CACHE_DIR``, or the user's cache
folder): numba checks only the file of a cached function itself, so a change in a function it
calls from another module (a new load component in the registry, say) would otherwise leave a
stale kernel in the cache. A cache locator placed first in numba's list does this for the
functions of files inside the package only; numba's own configuration is left as it was.
"""
from __future__ import annotations

import functools
import hashlib
import os
from pathlib import Path

from numba.core import caching

PACKAGE = Path(__file__).resolve().parents[1]  # fowt_hydro_sim


@functools.cache
def kernel_cache_dir() -> str:
    """The folder of the package's cached kernels: ``kernels-<digest of the physics sources>``
    under ``NUMBA_CACHE_DIR``, or else ``$XDG_CACHE_HOME/fowt_hydro_sim`` (``~/.cache``)."""
    here = Path(__file__).resolve().parent
    digest = hashlib.blake2b(digest_size=8)
    for source in sorted(here.rglob("*.py")) + [PACKAGE / "frames.py"]:
        digest.update(source.read_bytes())
    base = os.environ.get("NUMBA_CACHE_DIR") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache"), "fowt_hydro_sim")
    return os.path.join(base, f"kernels-{digest.hexdigest()}")


class _KernelCacheLocator(caching._SourceFileBackedLocatorMixin, caching._CacheLocator):
    """Numba cache locator of the functions in the package's files: ``kernel_cache_dir``."""

    def __init__(self, py_func, py_file: str):
        self._py_file = py_file
        self._lineno = py_func.__code__.co_firstlineno
        self._cache_path = os.path.join(kernel_cache_dir(), self.get_suitable_cache_subpath(py_file))

    def get_cache_path(self) -> str:
        return self._cache_path

    @classmethod
    def from_function(cls, py_func, py_file: str) -> _KernelCacheLocator | None:
        if not Path(py_file).resolve().is_relative_to(PACKAGE):
            return None
        return super().from_function(py_func, py_file)


_LOCATORS = (getattr(caching, "CacheImpl", None) or caching._CacheImpl)._locator_classes
if _KernelCacheLocator not in _LOCATORS:
    _LOCATORS.insert(0, _KernelCacheLocator)
