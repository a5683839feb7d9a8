"""The mooring lines, as the platform's mooring section (or the run) chooses
(``config.MOORING_MODELS``); ``params[0]`` says which:

- ``spring`` (0), the paper's: massless linear springs from body fairleads to fixed anchors.
  Tension T = T0 + k (L - L0) along the line toward the anchor, L the current fairlead-to-
  anchor distance, so the geometry (and the pretension's geometric stiffness) follows the
  body's motion.
- ``moorpy`` (1): quasi-static elastic catenaries with seabed contact (MoorPy's ``catenary``),
  tabulated once per line over the fairlead-to-anchor horizontal and vertical spans
  (``physics.mooring.catenary_tables``) and interpolated here (bicubic); a fairlead outside its table is
  held at the table's edge and reported (``outside_table``).
- ``moordyn`` (2): MoorDyn's lumped-mass lines, stepped in Python (``physics.mooring.moordyn_lines``);
  the wrench of its fairlead forces is written into ``params[1:7]`` before each evaluation.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from fowt_hydro_sim.physics.jit import step_loop
from fowt_hydro_sim.physics.mooring.catenary_tables import (
    HEADER,
    LINE_FIELDS,
    MOORPY,
    QUANTITIES,
    span_coordinates,
    table_value,
    tabulated_params,
)

SPRING, MOORDYN = 0.0, 2.0


@njit(cache=True, inline="always")
def _rotated(rotation: np.ndarray, params: np.ndarray, f: int) -> tuple[float, float, float]:
    """The body-frame point params[f:f + 3] in world axes (about the reference point)."""
    return (rotation[0, 0] * params[f] + rotation[0, 1] * params[f + 1] + rotation[0, 2] * params[f + 2],
            rotation[1, 0] * params[f] + rotation[1, 1] * params[f + 1] + rotation[1, 2] * params[f + 2],
            rotation[2, 0] * params[f] + rotation[2, 1] * params[f + 1] + rotation[2, 2] * params[f + 2])


@njit(cache=True, inline="always")
def _add_force_at(out: np.ndarray, r0: float, r1: float, r2: float, f0: float, f1: float, f2: float) -> None:
    """out += the force (f0, f1, f2) applied at r and its moment r x f about the reference point."""
    out[0] += f0
    out[1] += f1
    out[2] += f2
    out[3] += r1 * f2 - r2 * f1
    out[4] += r2 * f0 - r0 * f2
    out[5] += r0 * f1 - r1 * f0


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """spring: [0, k, T0, L0, fairleads (3 n, body frame), anchors (3 n, world frame)];
    moorpy: the header, the lines and their tables (``catenary_tables.tabulate``);
    moordyn: [2, wrench (6)]."""
    mooring = inputs.platform.mooring
    if mooring.model == "moorpy":
        return tabulated_params(mooring.file, inputs.platform.environment.water_depth_m)
    if mooring.model == "moordyn":
        return np.concatenate([[MOORDYN], np.zeros(6)]), np.zeros((1, 1))
    return np.concatenate([[SPRING, mooring.stiffness_n_m, mooring.pretension_n, mooring.unstretched_length_m],
                           np.ravel([line.fairlead_m for line in mooring.lines]),
                           np.ravel([line.anchor_m for line in mooring.lines])]), np.zeros((1, 1))


def outside_table(params: np.ndarray) -> tuple[float, int] | None:
    """moorpy: (time [s], line index) when a fairlead first went outside its line's table
    (the force then held at the table's edge), or None."""
    if params[0] != MOORPY or params[4] < 0:
        return None
    return float(params[4]), int(params[5])


def reset_outside(params: np.ndarray) -> None:
    """Forget that a fairlead went outside its table (a new run)."""
    if params[0] == MOORPY:
        params[4], params[5] = -1.0, -1.0


@step_loop
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    """Force and moment (world axes, about the reference point) of all lines."""
    if params[0] == MOORDYN:
        for i in range(6):
            out[i] += params[1 + i]
    elif params[0] == MOORPY:
        _catenaries(t, y, rotation, params, table, out)
    else:
        _springs(y, rotation, params, out)


@njit(cache=True, inline="always")
def _springs(y: np.ndarray, rotation: np.ndarray, params: np.ndarray, out: np.ndarray) -> None:
    stiffness, pretension, unstretched = params[1], params[2], params[3]
    n = (params.size - 4) // 6
    for i in range(n):  # written out: no temporaries in the step loop
        f, a = 4 + 3 * i, 4 + 3 * n + 3 * i  # the fairlead (body frame) and anchor (world frame)
        r0, r1, r2 = _rotated(rotation, params, f)
        l0, l1, l2 = params[a] - y[0] - r0, params[a + 1] - y[1] - r1, params[a + 2] - y[2] - r2
        length = np.sqrt(l0 * l0 + l1 * l1 + l2 * l2)
        scale = (pretension + stiffness * (length - unstretched)) / length
        f0, f1, f2 = scale * l0, scale * l1, scale * l2
        _add_force_at(out, r0, r1, r2, f0, f1, f2)


@njit(cache=True, inline="always")
def _catenaries(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
                out: np.ndarray) -> None:
    n, n_h, n_v = int(params[1]), int(params[2]), int(params[3])
    for i in range(n):
        f, a = HEADER + LINE_FIELDS * i, HEADER + LINE_FIELDS * i + 3
        r0, r1, r2 = _rotated(rotation, params, f)
        l0, l1 = params[a] - y[0] - r0, params[a + 1] - y[1] - r1
        h = np.sqrt(l0 * l0 + l1 * l1)
        v = y[2] + r2 - params[a + 2]
        u, w, outside = span_coordinates(params, i, h, v)
        if outside and params[4] < 0.0:
            params[4], params[5] = t, i
        block = QUANTITIES * n_h * i
        horizontal = table_value(table, block, n_h, n_v, u, w)
        vertical = table_value(table, block + n_h, n_h, n_v, u, w)
        f0, f1, f2 = horizontal * l0 / h, horizontal * l1 / h, -vertical
        _add_force_at(out, r0, r1, r2, f0, f1, f2)
