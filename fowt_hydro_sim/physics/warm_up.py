"""Compiling the kernels ahead of a first run (``fowt-sim compile``, run by the set-up).

numba compiles a kernel on its first call with each set of argument types and caches the
machine code on disk (``physics/__init__.py`` says where); compiling the model's kernels
takes 20-40 s, which a first ``simulate`` or node would otherwise spend before its first
step. Every entry point the model calls from Python (the set-up's derivative, the time
loop, the analyses' static loads, strip velocities, prescribed motion and displaced kinematics) is called here
once with the argument types of a real run; the argument types do not depend on the
platform, the drag model or the waves, so one warm-up serves every later run in any process.
Each package with kernels of its own has a ``warm_up`` module with ``entry_points()``
(``cli/compile.py`` lists them); ``warm_kernels`` calls them.
"""
from __future__ import annotations

import logging
import time
from collections.abc import Callable, Mapping

import numpy as np

from fowt_hydro_sim.physics.config import DEFAULT_PLATFORM, SeaState, load_platform
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import synthesize
from fowt_hydro_sim.physics.waves.kinematics import moving_point_kinematics

log = logging.getLogger(__name__)


def _model(drag_model: str) -> PlatformModel:
    """A small model: the packaged platform in a short-period sea (its derivative at t = 0)."""
    waves = synthesize(SeaState(2.0, 8.0, repeat_period_s=60.0), 60.0)
    return PlatformModel(load_platform(DEFAULT_PLATFORM), waves, drag_model=drag_model)


def _prescribed(model: PlatformModel) -> None:
    t = np.arange(4) * model.dt_s
    model.prescribed_motion_loads(t, np.zeros((4, 6)), np.zeros((4, 6)), np.zeros((4, 6)))


def entry_points() -> dict[str, Callable[[dict], None]]:
    """What to call, by name, in order; each step may use the models made before (``made``)."""
    return {
        "set-up (derivative)": lambda made: made.update(filtered=_model("filtered")),
        "time loop (integrate)": lambda made: made["filtered"].run(4 * made["filtered"].dt_s),
        "natural periods (static loads)": lambda made: made["filtered"].natural_periods_s(),
        "strip velocities": lambda made: made["filtered"].strip_velocities(),
        "prescribed motion": lambda made: _prescribed(_model("constant")),
        "displaced kinematics": lambda made: moving_point_kinematics(
            made["filtered"].waves, np.zeros((1, 3)), np.zeros(1), 100.0, 9.81, 1025.0),
    }


def warm_kernels(points: Mapping[str, Callable[[dict], None]]) -> dict[str, float]:
    """Compile (or load from the cache) every kernel entry point of ``points`` (a package's
    ``entry_points()``); wall seconds per entry point."""
    made: dict = {}
    timings = {}
    for name, call in points.items():
        start = time.perf_counter()
        call(made)
        timings[name] = time.perf_counter() - start
        log.debug("%s: %.1f s", name, timings[name])
    return timings
