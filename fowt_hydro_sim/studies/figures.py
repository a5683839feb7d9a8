"""Figures: matplotlib's pyplot on the non-interactive Agg backend, or None when matplotlib
(the ``plots`` extra) is not installed, said once, so that a study still writes its tables
and numbers without it."""
from __future__ import annotations

import logging
from functools import cache
from types import ModuleType

_log = logging.getLogger(__name__)


@cache
def pyplot() -> ModuleType | None:
    """``matplotlib.pyplot`` (Agg), or None with one warning if matplotlib is not installed."""
    try:
        import matplotlib
    except ImportError:
        _log.warning("figures not drawn: matplotlib is not installed (pip install 'fowt_hydro_sim[plots]')")
        return None
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt
