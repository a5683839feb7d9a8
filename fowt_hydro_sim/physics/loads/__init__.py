"""The platform's load components: one registry naming every row of the loads the model
computes (world axes, about the reference point), in row order.

Each entry says whether the component is part of the contract's ``total`` and whether it
has a topic of its own (``/platform/loads/NAME``); the compiled kernel, the model's
results, the node's publishers and recording, the offline outputs and the reference tables
(docs/reference/) all read this table.

The Morison strip model (``physics.morison``) fills the first rows itself. Every other
component is a module of this package, named by its entry, with

- ``parameters(inputs: ComponentInputs) -> (params, table)``: its data as one float array
  and one 2-D float table (periodic samples, if it has any), built once per model;
- ``wrench(t, y, rotation, params, table, out, mass)``: compiled (numba), adds its wrench
  at state y and time t to ``out`` (6,) and any mass it puts on the left-hand side of the
  equations of motion to ``mass`` (6, 6); its row then also holds -mass a.

Adding a component is one such module and one ``LoadComponent`` line below
(docs/contributing.md).
"""
from __future__ import annotations

import importlib
import warnings
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numba import literal_unroll
from numba.core.errors import NumbaExperimentalFeatureWarning

from fowt_hydro_sim.physics.config import HydroOptions, Platform
from fowt_hydro_sim.physics.jit import step_loop
from fowt_hydro_sim.physics.loads.extension import Extension
from fowt_hydro_sim.physics.loads.hydrostatic import Hydrostatics
from fowt_hydro_sim.physics.strips import Discretisation
from fowt_hydro_sim.physics.waves.components import WaveComponents

# the kernel calls the components through a tuple of compiled functions (literal_unroll)
warnings.filterwarnings("ignore", category=NumbaExperimentalFeatureWarning)


@dataclass(frozen=True)
class LoadComponent:
    """One row of the loads: its name, a one-line summary (the reference tables' and the
    topic's meaning), whether it is summed into the total and published on a topic of its
    own, the module computing it (``fowt_hydro_sim.physics.loads.<module>``), and whether it
    is a static restoring load (a function of the position alone in still water, at rest: the
    model's restoring matrix differentiates these rows)."""

    name: str
    summary: str
    summed: bool  # part of the contract's total (/platform/loads/total)
    published: bool  # a topic of its own, /platform/loads/NAME
    module: str | None = None  # None: a row of the Morison strip model
    restoring: bool = False  # in PlatformModel.restoring_matrix


COMPONENTS = (
    LoadComponent("drag", "Morison drag on the relative velocity (constant or band-filtered Cd)", True, True),
    LoadComponent("inertia", "Froude-Krylov and added-mass force from the fluid acceleration", True, True),
    LoadComponent("added_mass", "strip added mass on the body acceleration (-A a; it sits on the mass side of the "
                                "equations) and its centripetal part", False, True),
    LoadComponent("hydrostatic", "buoyancy and hydrostatic restoring", True, True, "hydrostatic", restoring=True),
    LoadComponent("mooring", "mooring lines", True, True, "mooring", restoring=True),
    LoadComponent("gravity", "weight at the centre of gravity", False, True, "gravity", restoring=True),
    LoadComponent("external", "external wrench (controller, rotor) as applied, moved to the reference point",
                  True, True, "external"),
    LoadComponent("drift", "second-order slow drift (Newman's approximation from the platform's drift table; "
                           "zero with slow_drift none, streamed waves or no table)", True, True, "drift"),
    LoadComponent("potential_hydrostatic", "a potential-flow hull's hydrostatics: rho g PtfmVol0 at the centre of "
                                           "buoyancy minus the WAMIT .hst restoring C q", True, True,
                  "potential_hydrostatic", restoring=True),
    LoadComponent("radiation", "a potential-flow hull's radiation: A_inf on the mass side (-A_inf a) and the "
                               "memory, the convolution of the retardation kernel from B(w) or the WAMIT .ss "
                               "state space", True, True, "radiation"),
    LoadComponent("excitation", "a potential-flow hull's first-order wave excitation from the WAMIT .3 file",
                  True, True, "excitation"),
    LoadComponent("added_matrices", "HydroDyn's additional preload, stiffness and damping of a potential-flow hull "
                                    "(AddF0, AddCLin, AddBLin, AddBQuad)", True, True, "added_matrices",
                  restoring=True),
    LoadComponent("added_quadratic_bands", "a potential-flow hull's AddBQuad split into the drag bands (one matrix "
                                           "per band on the band-filtered velocity; filtered drag model)", True,
                  True, "added_quadratic_bands"),
    LoadComponent("linear_mooring", "a mooring given as a wrench at rest and a 6x6 stiffness (F0 - K q)", True, True,
                  "linear_mooring", restoring=True),
    LoadComponent("extension", "loads beyond the Morison model (the gap diagnosis's effects)", False, False,
                  "extension"),
    LoadComponent("user", "a Python force passed to the model (PlatformModel user_force)", False, False, "user"),
)

NAMES = tuple(c.name for c in COMPONENTS)
N_LOADS = len(COMPONENTS)
ROW = {name: row for row, name in enumerate(NAMES)}
SUMMED = tuple(c.name for c in COMPONENTS if c.summed)
PUBLISHED = tuple(c.name for c in COMPONENTS if c.published)
RESTORING = tuple(c.name for c in COMPONENTS if c.restoring)
MODULE_COMPONENTS = tuple(c for c in COMPONENTS if c.module is not None)
FIRST_MODULE_ROW = ROW[MODULE_COMPONENTS[0].name]
if any(c.module is None for c in COMPONENTS[FIRST_MODULE_ROW:]):
    raise ImportError("load registry: the Morison strip model's rows must come before the module components")
_MODULES = tuple(importlib.import_module(f"{__name__}.{c.module}") for c in MODULE_COMPONENTS)
_WRENCHES = tuple(m.wrench for m in _MODULES)


class ComponentInputs(NamedTuple):
    """What the components' ``parameters`` read."""

    platform: Platform
    geometry: Discretisation
    hydrostatics: Hydrostatics
    extension: Extension
    options: HydroOptions
    waves: WaveComponents | None = None
    dt_s: float = 0.05  # the model's time step (a radiation kernel's step)
    drag_model: str = "constant"  # the model's drag model (``filtered``: the band-split AddBQuad)


def component_data(inputs: ComponentInputs) -> tuple[tuple[np.ndarray, ...], tuple[np.ndarray, ...]]:
    """Every module component's (params, table), in registry order, as the kernel takes them."""
    data = [m.parameters(inputs) for m in _MODULES]
    return (tuple(np.ascontiguousarray(p, dtype=float) for p, _ in data),
            tuple(np.ascontiguousarray(np.atleast_2d(t), dtype=float) for _, t in data))


def params_of(name: str, params: tuple[np.ndarray, ...]) -> np.ndarray:
    """The params array of the module component ``name`` (mutable: e.g. the external wrench)."""
    return params[ROW[name] - FIRST_MODULE_ROW]


@step_loop
def component_loads(t: float, y: np.ndarray, rotation: np.ndarray, params: tuple, tables: tuple,
                    loads: np.ndarray, masses: np.ndarray) -> None:
    """Each module component's wrench into its row of ``loads`` (set, not added) and its
    left-hand-side mass into ``masses[k]`` (k counting module components)."""
    k = 0
    for wrench in literal_unroll(_WRENCHES):
        row = FIRST_MODULE_ROW + k
        loads[row, :] = 0.0
        masses[k, :, :] = 0.0
        wrench(t, y, rotation, params[k], tables[k], loads[row], masses[k])
        k += 1
