"""The ``moordyn`` mooring: MoorDyn-C (the ``moordyn`` wheel) coupled as OpenFAST couples it,
fairlead kinematics in, fairlead forces out, MoorDyn's own sub-steps (its ``dtM`` and time
scheme, from the input file) inside each of the model's steps.

The model calls ``wrench(t, y, commit)`` at every evaluation of its equations of motion.
MoorDyn's state is advanced once per step, at the step's final evaluation (``commit``: the
corrected state at the step's end), from the previous step's end: the fairleads move on a
straight line at constant velocity from where they were to where the state puts them
(MoorDyn-C takes a start position and a velocity). The other evaluations within a step (the
Adams-Bashforth-Moulton predictor; the Runge-Kutta stages of the first three steps) take the
fairlead forces extrapolated linearly in time from the last two committed steps, as
OpenFAST's glue code extrapolates a module's outputs. At the committed time itself the
committed forces are used.

MoorDyn reads a copy of the file (its dtM replaced when a time step is given: the platform's
``mooring.moordyn_dt_s``) with its OUTPUTS list emptied (``without_outputs``: nothing
reads MoorDyn's channel files, which grow by a row at every step for as long as a node runs);
what it still writes goes into a temporary folder, removed with the object.
MoorDyn-C prints its progress to the process's standard output at every
step; that output is discarded (standard output is redirected while MoorDyn steps). What it
writes while reading the file goes to the log at debug level; after that its verbosity is
set to errors only, and its errors name the failure in the one-line message.
"""
from __future__ import annotations

import contextlib
import ctypes
import logging
import math
import os
import re
import shutil
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path

import numpy as np
from numba import njit

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.mooring.moordyn_file import readable_copy, with_time_step, without_outputs
from fowt_hydro_sim.physics.rigid_body import rotation_matrix

log = logging.getLogger(__name__)
_LIBC = ctypes.CDLL(None)


@contextlib.contextmanager
def _redirected(out_fd: int, err_fd: int) -> Iterator[None]:
    """While MoorDyn runs: the process's standard output into ``out_fd`` and standard error
    into ``err_fd`` (descriptors held open by the caller: nothing is opened per step)."""
    sys.stdout.flush()
    sys.stderr.flush()
    _LIBC.fflush(None)
    saved = [os.dup(1), os.dup(2)]
    try:
        os.dup2(out_fd, 1)
        os.dup2(err_fd, 2)
        yield
    finally:
        _LIBC.fflush(None)
        for fd, old in zip((1, 2), saved):
            os.dup2(old, fd)
            os.close(old)


def _forward(text: str) -> None:
    """What was written to standard error while MoorDyn stepped: MoorDyn's own lines (ERR, WRN,
    MSG, DBG and their continuations) to the log at debug level, anything else (another
    thread's) back to standard error."""
    theirs = [line for line in text.splitlines() if line.strip()]
    mine = [line for line in theirs if re.match(r"(ERR|WRN|MSG|DBG) |Line \d+$", line)]
    if mine:
        log.debug("MoorDyn: %s", " | ".join(mine))
    others = [line for line in theirs if line not in mine]
    if others:
        sys.stderr.write("\n".join(others) + "\n")


def _last_error(text: str) -> str:
    """MoorDyn's last error (an ``ERR`` line without its source location, and the line after
    it when it goes on there), or its last line."""
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    errors = [i for i, line in enumerate(lines) if line.startswith("ERR")]
    if not errors:
        return lines[-1] if lines else "no message"
    i = errors[-1]
    message = lines[i].split("(): ", 1)[-1]
    if message.endswith(":") and i + 1 < len(lines):
        message += " " + lines[i + 1]
    return message


class MoorDynLines:
    """MoorDyn's lines of one input file, their fairleads on the platform (the file's coupled or
    vessel points: body frame, relative to the reference point at rest)."""

    def __init__(self, file: str | Path, dt_s: float | None = None):
        """``dt_s``: MoorDyn's internal time step in place of the file's dtM (None: the file's)."""
        import moordyn

        self._md = moordyn  # held: closing at interpreter exit imports nothing
        self.file = Path(file)
        self._folder = Path(tempfile.mkdtemp(prefix="fowt_moordyn_"))
        self._system = None
        self._log = self._folder / "moordyn_messages.txt"
        self._capture = os.open(self._log, os.O_WRONLY | os.O_CREAT | os.O_APPEND)  # MoorDyn's messages
        self._null = os.open(os.devnull, os.O_WRONLY)  # its progress, printed at every step
        try:
            copy = without_outputs(readable_copy(self.file, self._folder))
            if dt_s is not None:
                with_time_step(copy, dt_s)
            try:
                with _redirected(self._capture, self._capture):
                    self._system = moordyn.Create(str(copy))
            except Exception:  # the wheel raises RuntimeError (or anything) on a file it refuses
                raise InputError(f"{self.file}: MoorDyn cannot read it ({self._error()})") from None
            system = self._system
            moordyn.SetVerbosity(system, moordyn.LEVEL_ERR)  # from here on: its errors only
            points = [moordyn.GetPoint(system, i) for i in range(1, moordyn.GetNumberPoints(system) + 1)]
            self._points = [p for p in points if moordyn.GetPointType(p) == -1]  # coupled (vessel) points
            if moordyn.NCoupledDOF(system) != 3 * len(self._points) or not self._points:
                raise InputError(f"{self.file}: MoorDyn couples {moordyn.NCoupledDOF(system)} degrees of freedom; "
                                 "the moordyn model needs the fairleads as coupled (vessel) points and no coupled "
                                 "bodies or rods")
            self.fairleads_m = np.array([moordyn.GetPointPos(p) for p in self._points], dtype=float)
            self.n_lines = moordyn.GetNumberLines(system)
            self._line_points = []  # each line's coupled point (index into fairleads), -1: none
            for number in range(1, self.n_lines + 1):
                line_id = moordyn.GetLineID(moordyn.GetLine(system, number))
                found = -1
                for k, p in enumerate(self._points):
                    for a in range(moordyn.GetPointNAttached(p)):
                        if moordyn.GetLineID(moordyn.GetPointAttached(p, a)[0]) == line_id:
                            found = k
                self._line_points.append(found)
        except BaseException:
            self.close()
            raise
        self.moordyn_s = 0.0  # wall seconds spent in MoorDyn's steps
        self.moordyn_cpu_s = 0.0  # and this process's CPU seconds
        self._time = 0.0
        self._x = np.zeros(3 * len(self._points))
        self._forces = np.zeros((len(self._points), 3))
        self._previous: tuple[float, np.ndarray] | None = None
        self.times: list[float] = []  # the committed times
        self._raw: list[tuple] = []  # at each committed time: _raw_tensions

    def _messages(self) -> str:
        try:
            return self._log.read_text(errors="replace")
        except OSError:
            return ""

    def _error(self) -> str:
        """MoorDyn's last error, naming the file as given (MoorDyn reads a copy)."""
        return _last_error(self._messages()).replace(str(self._folder / self.file.name), self.file.name)

    def close(self) -> None:
        """Free MoorDyn's system and remove its folder."""
        if self._system is not None:
            with _redirected(self._null, self._null):
                self._md.Close(self._system)
            self._system = None
        for fd in (self._capture, self._null):
            with contextlib.suppress(OSError):
                os.close(fd)
        self._capture = self._null = -1
        shutil.rmtree(self._folder, ignore_errors=True)

    def __del__(self) -> None:
        try:
            self.close()
        except Exception:  # noqa: BLE001 (at interpreter exit the file functions may be gone: nothing left to free)
            pass

    def _kinematics(self, y: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Fairlead positions and velocities (world, flattened) and lever arms (n, 3) at state y."""
        n = len(self.fairleads_m)
        positions, velocities, arms = np.empty(3 * n), np.empty(3 * n), np.empty((n, 3))
        _fairlead_kinematics(y, self.fairleads_m, positions, velocities, arms)
        return positions, velocities, arms

    def reset(self, t: float, y: np.ndarray) -> None:
        """Start at time t with the fairleads at state y: MoorDyn finds its lines' static
        equilibrium there (its dynamic relaxation, the file's TmaxIC and threshIC)."""
        import moordyn

        x, v, _ = self._kinematics(y)
        os.ftruncate(self._capture, 0)
        try:
            with _redirected(self._capture, self._capture):
                status = moordyn.Init(self._system, list(x), list(v))
        except Exception:
            status = -1
        if status != 0:
            raise InputError(f"{self.file}: MoorDyn's initial equilibrium failed ({self._error()})")
        log.debug("MoorDyn %s initialised: %s", self.file, self._messages().strip()[-2000:])
        os.ftruncate(self._capture, 0)
        self._time, self._x, self._previous = t, x, None
        self._forces = np.array([moordyn.GetPointForce(p) for p in self._points], dtype=float)
        self.times, self._raw = [t], [self._raw_tensions()]

    def _raw_tensions(self) -> tuple:
        """What the tensions are made of at the committed step: the coupled points' forces and
        MoorDyn's anchor forces (horizontal, vertical)."""
        _, _, anchor_h, anchor_v = self._md.GetFASTtens(self._system, self.n_lines)
        return self._forces, anchor_h, anchor_v

    @property
    def tensions(self) -> list[np.ndarray]:
        """At each committed time: (lines, 2) each line's fairlead tension (the magnitude of
        the force on its coupled point) and anchor tension [N]."""
        points = np.array(self._line_points)
        out = []
        for forces, anchor_h, anchor_v in self._raw:
            rows = np.empty((self.n_lines, 2))
            rows[:, 0] = np.where(points >= 0, np.linalg.norm(forces[points], axis=1), np.nan)
            rows[:, 1] = np.hypot(anchor_h, anchor_v)
            out.append(rows)
        return out

    def wrench(self, t: float, y: np.ndarray, commit: bool) -> np.ndarray:
        """The lines' wrench (world axes, about the reference point) at time t and state y;
        ``commit``: y is the state at the end of a step, MoorDyn advances to t."""
        moordyn = self._md
        x, v, arms = self._kinematics(y)
        forces = self._forces
        if t > self._time + 1e-9 and commit:
            dt = t - self._time
            velocity = (x - self._x) / dt
            started, started_cpu = time.perf_counter(), time.process_time()
            try:
                with _redirected(self._null, self._capture):  # Step returns the coupled points' forces
                    forces = np.array(moordyn.Step(self._system, self._x.tolist(), velocity.tolist(), self._time,
                                                   dt), dtype=float).reshape(-1, 3)
            except Exception:
                raise InputError(f"{self.file}: MoorDyn failed at t = {self._time:g} s ({self._error()})") from None
            finally:
                self.moordyn_s += time.perf_counter() - started
                self.moordyn_cpu_s += time.process_time() - started_cpu
            if os.fstat(self._capture).st_size:
                _forward(self._messages())
                os.ftruncate(self._capture, 0)
            if not math.isfinite(forces.sum()):
                raise InputError(f"{self.file}: MoorDyn failed at t = {self._time:g} s (non-finite fairlead forces)")
            self._previous = (self._time, self._forces)
            self._time, self._x, self._forces = t, x, forces
            self.times.append(t)
            self._raw.append(self._raw_tensions())
        elif t > self._time + 1e-9 and self._previous is not None:
            t0, f0 = self._previous
            forces = forces + (forces - f0) * (t - self._time) / (self._time - t0)
        wrench = np.empty(6)
        _wrench_of(forces, arms, wrench)
        return wrench

    def forget_before(self, time_s: float) -> None:
        """Drop the committed steps before ``time_s`` (their tensions): a long run holds only
        what its latest part needs."""
        keep = int(np.searchsorted(np.asarray(self.times), time_s - 1e-9))
        del self.times[:keep], self._raw[:keep]

    def tensions_at(self, time_s: np.ndarray) -> np.ndarray:
        """(n, lines, 2): each line's fairlead and anchor tension [N] at the committed times
        ``time_s`` (the latest committed time at or before each; NaN before the first)."""
        times = np.asarray(self.times)
        rows = np.searchsorted(times, np.asarray(time_s, dtype=float) + 1e-9, side="right") - 1
        out = np.full((len(rows), self.n_lines, 2), np.nan)
        needed = np.unique(rows[rows >= 0])
        if not needed.size:
            return out
        raw, self._raw = self._raw, [self._raw[i] for i in needed]
        try:
            table = np.asarray(self.tensions)
        finally:
            self._raw = raw
        out[rows >= 0] = table[np.searchsorted(needed, rows[rows >= 0])]
        return out


@njit(cache=True)
def _fairlead_kinematics(y: np.ndarray, fairleads: np.ndarray, positions: np.ndarray, velocities: np.ndarray,
                         arms: np.ndarray) -> None:
    """Fairlead world positions and velocities (flattened) and their arms R p (n, 3) at state y."""
    rotation = rotation_matrix(y[3], y[4], y[5])
    for k in range(fairleads.shape[0]):
        for i in range(3):
            arms[k, i] = rotation[i, 0] * fairleads[k, 0] + rotation[i, 1] * fairleads[k, 1] \
                + rotation[i, 2] * fairleads[k, 2]
        positions[3 * k:3 * k + 3] = y[0:3] + arms[k]
        velocities[3 * k] = y[6] + y[10] * arms[k, 2] - y[11] * arms[k, 1]
        velocities[3 * k + 1] = y[7] + y[11] * arms[k, 0] - y[9] * arms[k, 2]
        velocities[3 * k + 2] = y[8] + y[9] * arms[k, 1] - y[10] * arms[k, 0]


@njit(cache=True)
def _wrench_of(forces: np.ndarray, arms: np.ndarray, out: np.ndarray) -> None:
    """The wrench about the reference point of forces (n, 3) at arms (n, 3)."""
    out[:] = 0.0
    for k in range(forces.shape[0]):
        out[0:3] += forces[k]
        out[3] += arms[k, 1] * forces[k, 2] - arms[k, 2] * forces[k, 1]
        out[4] += arms[k, 2] * forces[k, 0] - arms[k, 0] * forces[k, 2]
        out[5] += arms[k, 0] * forces[k, 1] - arms[k, 1] * forces[k, 0]
