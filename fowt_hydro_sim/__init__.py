"""fowt_hydro_sim: a floating offshore wind platform simulator (strip-theory Morison
hydrodynamics, 6-DOF rigid body) with ROS 2 interfaces. The model never imports rclpy.

The names a Python user needs are importable from here (``from fowt_hydro_sim import
PlatformModel, load_platform``); each is loaded on first use, so ``import fowt_hydro_sim``
loads neither numba nor rclpy.
"""
from __future__ import annotations

import importlib
from typing import Any

__version__ = "0.1.0"

# public name -> the module (under fowt_hydro_sim) that defines it
_PUBLIC = {
    # errors
    "InputError": "errors", "ConfigError": "physics.config", "BagError": "rosbag.writer",
    # platforms, sea states, load cases, run settings
    "Platform": "physics.config", "SeaState": "physics.config", "LoadCase": "physics.config",
    "HydroOptions": "physics.config", "RunConfig": "physics.config", "load_platform": "physics.config",
    "platform_from_dict": "physics.config", "platform_document": "physics.config", "load_case": "physics.config",
    "load_cases": "physics.config", "load_run_file": "physics.config",
    # the model and its waves
    "PlatformModel": "physics.model", "RunResult": "physics.model", "WaveComponents": "physics.waves.components",
    "synthesize": "physics.waves.components", "repeat_period": "physics.waves.components",
    "read_comp_file": "physics.waves.components", "run_with_elevation": "physics.wave_feed",
    # studies
    "simulate": "studies.simulate", "run_model": "studies.simulate", "sea_state_waves": "studies.simulate",
    "read_prp_motion": "studies.prescribed_motion", "prescribed_loads": "studies.prescribed_motion",
    "AnalysisSettings": "studies.analysis", "analyse": "studies.analysis", "analyze_bags": "studies.analysis",
    "load_run": "studies.analysis", "load_sweep_file": "studies.sweep", "run_sweep": "studies.sweep",
    # bags and turbines
    "Bag": "rosbag.reader", "BagWriter": "rosbag.writer", "load_turbine": "turbine.description",
}
__all__ = sorted(_PUBLIC)


def __getattr__(name: str) -> Any:
    """The public name ``name``, imported from its module on first use (PEP 562)."""
    if name not in _PUBLIC:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{_PUBLIC[name]}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
