"""The ``moorpy`` mooring: each line's quasi-static fairlead and anchor forces, solved by
MoorPy's elastic catenary with seabed contact (``moorpy.Catenary.catenary``, as MoorPy's
``Line.staticSolve`` calls it) on a grid of fairlead-to-anchor spans, once per distinct line;
the kernel (``mooring.wrench``) interpolates the grid bicubically.

The grid spans the horizontal distance at rest +-``SPAN_H_M`` and the fairlead's height above
the anchor at rest +-``SPAN_V_M``, every ``STEP_M``: fairlead offsets of +-60 m
horizontally and +-25 m vertically, every 2.5 m, (surge, and heave plus pitch or roll at the fairlead
radius) before a fairlead leaves its table.
"""
from __future__ import annotations

import functools
import hashlib
import logging
import math
import os
from pathlib import Path

import numpy as np
from numba import njit

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.mooring.moordyn_file import CatenaryLine, read_lines

log = logging.getLogger(__name__)

MOORPY = 1.0  # the mooring component's params[0] for these lines
# params: [MOORPY, n lines, n_h, n_v, time a fairlead first left its table (-1: never), its
# line, then per line LINE_FIELDS values: fairlead (3, body), anchor (3, world), h0, dh, v0, dv]
HEADER, LINE_FIELDS = 6, 10
QUANTITIES = 4  # table blocks per line: fairlead H, fairlead V, anchor H, anchor V [N]

SPAN_H_M = 60.0
SPAN_V_M = 25.0
STEP_M = 2.5


@njit(cache=True, inline="always")
def _cubic(p0: float, p1: float, p2: float, p3: float, s: float) -> float:
    """Catmull-Rom cubic through p1 (s = 0) and p2 (s = 1)."""
    return p1 + 0.5 * s * (p2 - p0 + s * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3 + s * (3.0 * (p1 - p2) + p3 - p0)))


@njit(cache=True, inline="always")
def table_value(table: np.ndarray, first_row: int, n_h: int, n_v: int, u: float, w: float) -> float:
    """Bicubic (Catmull-Rom) interpolation of the block of ``n_h`` rows from ``first_row`` at
    fractional row ``u`` and column ``w`` (inside [1, n - 2])."""
    i = min(max(int(np.floor(u)), 1), n_h - 3)
    j = min(max(int(np.floor(w)), 1), n_v - 3)
    su, sw = u - i, w - j
    r0 = _cubic(table[first_row + i - 1, j - 1], table[first_row + i - 1, j], table[first_row + i - 1, j + 1],
                table[first_row + i - 1, j + 2], sw)
    r1 = _cubic(table[first_row + i, j - 1], table[first_row + i, j], table[first_row + i, j + 1],
                table[first_row + i, j + 2], sw)
    r2 = _cubic(table[first_row + i + 1, j - 1], table[first_row + i + 1, j], table[first_row + i + 1, j + 1],
                table[first_row + i + 1, j + 2], sw)
    r3 = _cubic(table[first_row + i + 2, j - 1], table[first_row + i + 2, j], table[first_row + i + 2, j + 1],
                table[first_row + i + 2, j + 2], sw)
    return _cubic(r0, r1, r2, r3, su)


@njit(cache=True, inline="always")
def span_coordinates(params: np.ndarray, line: int, h: float, v: float) -> tuple[float, float, bool]:
    """The table coordinates (row, column) of spans h, v of a line, held inside the table, and
    whether they were outside it."""
    n_h, n_v = params[2], params[3]
    k = HEADER + LINE_FIELDS * line
    u = (h - params[k + 6]) / params[k + 7]
    w = (v - params[k + 8]) / params[k + 9]
    outside = u < 1.0 or u > n_h - 2.0 or w < 1.0 or w > n_v - 2.0
    return min(max(u, 1.0), n_h - 2.0), min(max(w, 1.0), n_v - 2.0), outside


def line_spans(line: CatenaryLine) -> tuple[float, float]:
    """The horizontal distance and the fairlead's height above the anchor at rest [m]."""
    h = math.hypot(line.anchor_m[0] - line.fairlead_m[0], line.anchor_m[1] - line.fairlead_m[1])
    return h, line.fairlead_m[2] - line.anchor_m[2]


def seabed_parameter(line: CatenaryLine, depth_m: float) -> float:
    """MoorPy's CB: the friction coefficient with the anchor on the seabed, else minus the
    anchor's height above it."""
    return line.seabed_friction if line.anchor_m[2] <= -depth_m else -depth_m - line.anchor_m[2]


def solve(line: CatenaryLine, depth_m: float, h: float, v: float, guess: tuple[float, float] = (0.0, 0.0),
          tolerance: float = 1e-8) -> tuple[float, float, float, float]:
    """MoorPy's static solution of one line with the fairlead at horizontal distance ``h`` and
    height ``v`` above the anchor: (fairlead H, fairlead V, anchor H, anchor V) [N], the
    magnitudes of the forces the line puts on the fairlead (toward the anchor, down) and on
    the anchor (toward the fairlead, up)."""
    from moorpy.Catenary import CatenaryError, catenary

    try:
        f_ah, f_av, f_bh, f_bv, _ = catenary(h, v, line.length_m, line.ea_n, line.weight_n_m,
                                             CB=seabed_parameter(line, depth_m), HF0=guess[0], VF0=guess[1],
                                             Tol=tolerance, MaxIter=200, depth=depth_m)
    except CatenaryError as exc:
        raise InputError(f"line {line.number}: MoorPy's catenary fails at horizontal span {h:.2f} m, height "
                         f"{v:.2f} m ({exc})") from None
    return -f_bh, -f_bv, f_ah, f_av


@functools.lru_cache(maxsize=16)
def _grid(length_m: float, ea_n: float, weight_n_m: float, cb: float, depth_m: float, h0: float, v0: float,
          n_h: int, n_v: int) -> np.ndarray:
    """(QUANTITIES, n_h, n_v) forces over the grid h0 + i STEP_M, v0 + j STEP_M, solved once
    and kept in the kernels' cache folder (keyed by the line, the grid and MoorPy's version)."""
    from importlib.metadata import version

    from fowt_hydro_sim.physics import kernel_cache_dir

    key = repr((length_m, ea_n, weight_n_m, cb, depth_m, h0, v0, n_h, n_v, STEP_M, version("moorpy")))
    name = hashlib.blake2b(key.encode(), digest_size=12).hexdigest()
    path = Path(kernel_cache_dir()).parent / "mooring_tables" / f"{name}.npy"
    try:
        cached = np.load(path)
        if cached.shape == (QUANTITIES, n_h, n_v):
            return cached
    except (OSError, ValueError):
        pass
    out = _solve_grid(length_m, ea_n, weight_n_m, cb, depth_m, h0, v0, n_h, n_v)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        partial = path.with_suffix(f".{os.getpid()}.npy")
        np.save(partial, out)
        os.replace(partial, path)
    except OSError as exc:  # a read-only cache: solved again next time
        log.debug("mooring table not cached in %s: %s", path.parent, exc)
    return out


def _solve_grid(length_m: float, ea_n: float, weight_n_m: float, cb: float, depth_m: float, h0: float, v0: float,
                n_h: int, n_v: int) -> np.ndarray:
    """(QUANTITIES, n_h, n_v) forces over the grid, solved with MoorPy's catenary."""
    anchor_z = -depth_m if cb >= 0 else -depth_m - cb
    line = CatenaryLine(0, (0.0, 0.0, 0.0), (0.0, 0.0, anchor_z), length_m, ea_n, weight_n_m, max(cb, 0.0))
    out = np.empty((QUANTITIES, n_h, n_v))
    for j in range(n_v):
        guess = (0.0, 0.0)
        for i in range(n_h):
            out[:, i, j] = solve(line, depth_m, h0 + i * STEP_M, v0 + j * STEP_M, guess)
            guess = (out[0, i, j], out[1, i, j])
    return out


def grid_size() -> tuple[int, int]:
    """The table's rows (horizontal spans) and columns (heights), with one point beyond
    each edge for the bicubic stencil."""
    return int(round(2 * SPAN_H_M / STEP_M)) + 3, int(round(2 * SPAN_V_M / STEP_M)) + 3


def tabulated_params(file: str | Path, depth_m: float) -> tuple[np.ndarray, np.ndarray]:
    """The ``moorpy`` component's params and table for the lines of a MoorDyn input file."""
    lines = read_lines(file, depth_m)
    n_h, n_v = grid_size()
    params = [MOORPY, len(lines), n_h, n_v, -1.0, -1.0]
    blocks = []
    for line in lines:
        h, v = line_spans(line)
        h0, v0 = h - SPAN_H_M - STEP_M, v - SPAN_V_M - STEP_M
        if h0 <= 0:
            raise InputError(f"{file}: line {line.number}: fairlead within {SPAN_H_M + STEP_M:g} m of its anchor "
                             "horizontally; the moorpy model tabulates spans around the line's rest span")
        try:
            grid = _grid(line.length_m, line.ea_n, line.weight_n_m, seabed_parameter(line, depth_m), depth_m,
                         round(h0, 9), round(v0, 9), n_h, n_v)
        except InputError as exc:
            raise InputError(f"{file}: {exc}") from None
        params += [*line.fairlead_m, *line.anchor_m, h0, STEP_M, v0, STEP_M]
        blocks.append(grid.reshape(QUANTITIES * n_h, n_v))
    log.debug("moorpy mooring: %d lines of %s tabulated on %d x %d spans", len(lines), file, n_h, n_v)
    return np.array(params, dtype=float), np.vstack(blocks)


def line_forces(params: np.ndarray, table: np.ndarray, motion: np.ndarray) -> np.ndarray:
    """(n, lines, QUANTITIES): each line's fairlead H, V and anchor H, V [N] interpolated at the
    platform positions ``motion`` (n, 6: x, y, z [m], roll, pitch, yaw [rad]), as the kernel
    takes them; NaN where a fairlead is outside its table."""
    from fowt_hydro_sim.frames import rotation_matrix

    motion = np.atleast_2d(motion)
    n_lines, n_h, n_v = int(params[1]), int(params[2]), int(params[3])
    out = np.empty((len(motion), n_lines, QUANTITIES))
    rotations = rotation_matrix(motion[:, 3], motion[:, 4], motion[:, 5])  # (3, 3, n)
    for i in range(n_lines):
        k = HEADER + LINE_FIELDS * i
        fairlead = motion[:, 0:3] + np.einsum("ijn,j->ni", rotations, params[k:k + 3])
        h = np.hypot(params[k + 3] - fairlead[:, 0], params[k + 4] - fairlead[:, 1])
        v = fairlead[:, 2] - params[k + 5]
        for s in range(len(motion)):
            u, w, outside = span_coordinates(params, i, h[s], v[s])
            for q in range(QUANTITIES):
                out[s, i, q] = np.nan if outside else table_value(table, (QUANTITIES * i + q) * n_h, n_h, n_v, u, w)
    return out
