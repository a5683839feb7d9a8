"""Mooring line tensions of a run: statistics, spectra and fatigue.

A line's damage-equivalent load (DEL) is the range of a constant-amplitude tension cycle that,
repeated at ``DEL_FREQUENCY_HZ`` over the analysed time, does the damage of the rainflow-counted
tension cycles (ASTM E1049 three-point rainflow counting, half cycles of the residue counted as
halves) under an S-N (T-N) curve N = K S^-m of slope ``m``:
DEL = (sum n_i S_i^m / (f T))^(1/m). The default slope, m = 3, is that of DNV-OS-E301's T-N
curves for studless and stud chain (the VolturnUS-S lines are chain); give another with
``slope`` (e.g. 4.8 for spiral strand wire rope, DNV's curve).
"""
from __future__ import annotations

import numpy as np

SN_SLOPE = 3.0  # DNV-OS-E301 T-N curve of studless chain
DEL_FREQUENCY_HZ = 1.0  # DELs per 1 Hz equivalent cycles


def reversals(x: np.ndarray) -> np.ndarray:
    """The turning points of a series (its first and last points included; flats dropped)."""
    x = np.asarray(x, dtype=float)
    x = x[np.concatenate([[True], np.diff(x) != 0])] if x.size else x
    if x.size < 3:
        return x
    slope = np.diff(x)
    turning = np.flatnonzero(slope[1:] * slope[:-1] < 0) + 1
    return x[np.concatenate([[0], turning, [x.size - 1]])]


def rainflow(x: np.ndarray) -> list[tuple[float, float]]:
    """ASTM E1049's rainflow counting: (range, count) pairs, count 1 for a full cycle and 0.5
    for a half cycle (the ranges the counting leaves open)."""
    cycles: list[tuple[float, float]] = []
    stack: list[float] = []
    for point in reversals(x):
        stack.append(float(point))
        while len(stack) >= 3:
            newest, previous = abs(stack[-1] - stack[-2]), abs(stack[-2] - stack[-3])
            if newest < previous:
                break
            if len(stack) == 3:  # the range holds the series' start: a half cycle
                cycles.append((previous, 0.5))
                stack.pop(0)
            else:
                cycles.append((previous, 1.0))
                del stack[-3:-1]
    cycles += [(abs(b - a), 0.5) for a, b in zip(stack[:-1], stack[1:])]
    return cycles


def damage_equivalent_load(x: np.ndarray, duration_s: float, slope: float = SN_SLOPE,
                           frequency_hz: float = DEL_FREQUENCY_HZ) -> float:
    """The DEL of series ``x`` analysed over ``duration_s``: (sum n S^m / (f T))^(1/m)."""
    cycles = rainflow(x)
    if not cycles or duration_s <= 0:
        return 0.0
    ranges, counts = np.array(cycles).T
    return float((np.sum(counts * ranges**slope) / (frequency_hz * duration_s)) ** (1.0 / slope))


def tension_rows(name: str, time_s: np.ndarray, tensions: dict[str, np.ndarray], transient_s: float,
                 slope: float = SN_SLOPE) -> list[dict]:
    """One row per tension series (``lineN_fairlead`` ...): mean, std, max and DEL [N] after
    ``transient_s``, with the S-N slope the DEL used."""
    keep = time_s >= time_s[0] + transient_s
    duration = float(time_s[keep][-1] - time_s[keep][0]) if keep.sum() > 1 else 0.0
    rows = []
    for channel, x in tensions.items():
        x = x[keep]
        x = x[np.isfinite(x)]
        if not x.size:
            continue
        rows.append({"run": name, "tension": channel, "mean_n": float(x.mean()), "std_n": float(x.std()),
                     "max_n": float(x.max()), "del_n": damage_equivalent_load(x, duration, slope),
                     "sn_slope": slope, "analysed_s": duration})
    return rows
