"""The curated public API of ``fowt_hydro_sim``: every name resolves and is documented, and
importing the package loads neither numba nor rclpy (the names are loaded on first use)."""
from __future__ import annotations

import subprocess
import sys

import pytest

import fowt_hydro_sim
from fowt_hydro_sim.testing import REPO


def test_importing_the_package_loads_neither_numba_nor_rclpy():
    code = ("import sys, fowt_hydro_sim; assert fowt_hydro_sim.__all__; "
            "print(' '.join(sorted(m for m in sys.modules if m.split('.')[0] in ('numba', 'rclpy'))))")
    done = subprocess.run([sys.executable, "-c", code], cwd=REPO, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == []


@pytest.mark.parametrize("name", fowt_hydro_sim.__all__)
def test_each_public_name_resolves_and_has_a_docstring(name: str):
    value = getattr(fowt_hydro_sim, name)
    doc = (value.__doc__ or "").strip()
    assert doc and not doc.startswith(f"{name}("), f"{name}: no docstring (a dataclass's generated one does not count)"


def test_an_unknown_name_is_an_attribute_error():
    with pytest.raises(AttributeError, match="no attribute 'nothing_here'"):
        fowt_hydro_sim.nothing_here  # noqa: B018


def test_the_model_and_the_node_start_without_scipys_statistics_signal_or_quadrature():
    """Every node, CLI run and Dask worker imports the model: it loads neither scipy.stats,
    scipy.signal nor scipy.integrate (about 1 s of a process's start between them), which
    only the analyses and one hydrostatics option use, importing them when called."""
    code = ("import sys, fowt_hydro_sim.physics.model, fowt_hydro_sim.ros.node; "
            "print(' '.join(sorted(m for m in sys.modules if m.startswith(('scipy.stats', 'scipy.signal', "
            "'scipy.integrate')))))")
    done = subprocess.run([sys.executable, "-c", code], cwd=REPO, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == []
