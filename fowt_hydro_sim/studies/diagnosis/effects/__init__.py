"""The catalogue of candidate unmodelled effects for the gap diagnosis: one module each,
named like its effect, registered by one line in ``MODULES`` (the catalogue's order is
theirs). An effect is a parametrised, switchable change of a model variant (base.Effect).
Each module holds:

- ``EFFECT``: its ``base.Effect``, named like the module;
- ``TWIN_INJECTIONS``: the values the benchmark's twin injects it at, one scenario each
  (at least one);
- ``INDEPENDENT_INJECTION``: its form in the independent benchmark's basin
  (``base.IndependentInjection``), or None where the basin has none of its own.

A module that lacks one of them, or whose effect is named otherwise, stops the import
with one line naming it."""
from __future__ import annotations

import importlib
from types import ModuleType

from fowt_hydro_sim.studies.diagnosis.effects.base import Effect, IndependentInjection, Parameter

MODULES = (
    "frequency_dependent_drag",
    "slow_drift",
    "linear_damping",
    "quadratic_damping",
    "mooring_stiffness",
    "added_mass_error",
    "kc_dependent_drag",
    "wave_measurement_delay",
    "model_slow_drift",
    "model_drag",
    "model_restoring",
)


def registered(name: str, module: ModuleType) -> ModuleType:
    """The effect module ``name`` checked: ValueError naming what it lacks (``EFFECT`` named
    ``name``, a non-empty ``TWIN_INJECTIONS`` of the effect's parameters,
    ``INDEPENDENT_INJECTION`` None or accepting the effect)."""
    effect = getattr(module, "EFFECT", None)
    if not isinstance(effect, Effect) or effect.name != name:
        raise ValueError(f"effect module {name}: needs EFFECT, an Effect named {name!r}")
    twin = getattr(module, "TWIN_INJECTIONS", ())
    if not isinstance(twin, tuple) or not twin:
        raise ValueError(f"effect module {name}: needs TWIN_INJECTIONS, the benchmark twin's values (one or more)")
    names = {p.name for p in effect.parameters}
    for values in twin:
        unknown = set(values) - names
        if unknown:
            raise ValueError(f"effect module {name}: TWIN_INJECTIONS sets {', '.join(sorted(unknown))}, not "
                             f"parameters of {name} ({', '.join(sorted(names))})")
    if not hasattr(module, "INDEPENDENT_INJECTION"):
        raise ValueError(f"effect module {name}: needs INDEPENDENT_INJECTION, its form in the independent basin "
                         "(an IndependentInjection), or None where the basin has none")
    independent = module.INDEPENDENT_INJECTION
    if independent is not None and (not isinstance(independent, IndependentInjection)
                                    or name not in independent.accepted or not independent.strengths):
        raise ValueError(f"effect module {name}: INDEPENDENT_INJECTION must be None or an IndependentInjection "
                         f"with strengths that accepts {name}")
    return module


EFFECT_MODULES: dict[str, ModuleType] = {name: registered(name, importlib.import_module(f"{__name__}.{name}"))
                                         for name in MODULES}
CATALOGUE: dict[str, Effect] = {name: module.EFFECT for name, module in EFFECT_MODULES.items()}

__all__ = ["CATALOGUE", "EFFECT_MODULES", "MODULES", "Effect", "IndependentInjection", "Parameter", "registered"]
