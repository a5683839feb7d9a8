"""How the step loop is compiled: numba's nopython mode without its runtime (NRT).

Without the runtime a function cannot allocate (an allocation is a compile error, so the
step loop provably allocates nothing) and numba emits no reference counting of the arrays it
reads: with the runtime, every array taken from the kernel data and workspace tuples was
counted up and down at every call, a third of a right-hand side. A ``step_loop`` function
therefore takes arrays and returns numbers, tuples of numbers or nothing; its scratch
arrays come from ``dynamics.Workspace``. Array-to-array assignment (``a[:] = b``) may make a
temporary copy in numba, so it copies with ``copy_into``. Small helpers stay
``inline="always"`` njit functions, compiled into their callers.

A product and a sum may fuse into one multiply-add (LLVM's ``contract``, the only fast-math
flag: one rounding instead of two, so results differ from unfused arithmetic at round-off;
no reassociation, no assumptions about NaN or infinities).
"""
from __future__ import annotations

import numpy as np
from numba import njit

step_loop = njit(cache=True, _nrt=False, fastmath={"contract"})


@njit(cache=True, inline="always")
def copy_into(source, out) -> None:
    """out[...] = source, element by element (arrays of one shape)."""
    for index in np.ndindex(out.shape):
        out[index] = source[index]


@njit(cache=True, inline="always")
def add_force_minus_stiffness(params, first, y, out) -> None:
    """out += F - K q, with F = params[first:first + 6] and the 6x6 K row by row after it,
    q = y[0:6] (a load of the form F0 - C q: preloads with their restoring matrices)."""
    for i in range(6):
        acc = params[first + i]
        for j in range(6):
            acc -= params[first + 6 + 6 * i + j] * y[j]
        out[i] += acc
