"""Where a model and a measured run differ: the gap per DOF and metric, for a model replayed
with the run's own elevation (like for like), with confidence intervals from a paired
block test, plus the spectra the report shows (PSD ratio, wave-response coherence).

Metrics per DOF (values are model against measured):
- ``std.BAND``: band STD error, model / measured - 1;
- ``frequency.BAND``: mean frequency error in the band, sqrt(m2/m0) model / measured - 1
  (a shifted resonance: stiffness or inertia);
- ``offset``: mean offset, (model - measured) / the measured STD;
- ``lag``: time lag [s] of the model's wave-band response behind the measured one, judged
  only where it reads a delay (``lag_reads_delay``);
- with ``GapSettings.decays``, the cells of free-decay runs (decay.py): ``decay_period``,
  the decay's mean half-period error, and ``decay_damping``, its damping ratio error (model
  / measured - 1), judged only in a decay of that DOF (and the wave cells only in wave runs).

Because both runs see the same waves, sampling noise largely cancels in their ratio: the
record is cut into blocks, the metric's log ratio (or difference) is taken per block,
and its mean gets a Student-t interval. A cell is flagged when that interval excludes
zero (significant) and the value exceeds its tolerance (material). A band holding less
than ``NEGLIGIBLE_BAND`` of its DOF's STD in the measurement and in the model is not judged
(e.g. heave below the wave band, which sensor noise and small property errors swing by
tens of percent), unless the two differ by more than a factor ``GROSS_RATIO``: a model ten
times too lively in a band the measurement hardly has is a gap.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
import scipy.signal
import scipy.stats

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.model import DOF_NAMES
from fowt_hydro_sim.studies.psd import BANDS_HZ

GRID_STEP_S = 0.25
MAX_LAG_S = 10.0
TOLERANCES = {"std": 0.05, "frequency": 0.03, "offset": 0.2, "lag": 0.25,  # materiality, per metric kind
              "decay_period": 0.03, "decay_damping": 0.10}
DECAY_METRICS = ("decay_period", "decay_damping")
COHERENCE_SEGMENT_S = 300.0
MIN_BLOCK_S = 180.0  # a block spans nearly two surge periods: shorter blocks are not independent
NEGLIGIBLE_BAND = 0.15  # share of the DOF's STD below which a band's cells are not judged (on both sides)
GROSS_RATIO = (0.5, 2.0)  # a band STD ratio outside this is always judged and reported
SECOND_PEAK = 0.8  # a cross-correlation peak this share of the highest makes the lag ambiguous


@dataclass(frozen=True)
class GapSettings:
    transient_s: float = 300.0  # discarded at the start of each run
    dofs: tuple[str, ...] = ("surge", "heave", "pitch")
    bands_hz: dict[str, tuple[float, float]] = field(default_factory=lambda: dict(BANDS_HZ))
    blocks: int = 8  # at most; fewer for records too short for blocks of MIN_BLOCK_S
    confidence: float = 0.90
    tolerances: dict[str, float] = field(default_factory=lambda: dict(TOLERANCES))
    decays: bool = False  # the free-decay cells too (the diagnosis has decay runs)

    def metrics(self) -> list[str]:
        return ([f"std.{b}" for b in self.bands_hz] + [f"frequency.{b}" for b in self.bands_hz]
                + ["offset", "lag"] + (list(DECAY_METRICS) if self.decays else []))

    def covered(self, decay_dof: str | None) -> np.ndarray:
        """The cells a run measures: a wave run's every wave cell, a decay's its DOF's decay cells."""
        if decay_dof is None:
            return np.array([metric not in DECAY_METRICS for _, metric in self.cells()])
        return np.array([dof == decay_dof and metric in DECAY_METRICS for dof, metric in self.cells()])

    def cells(self) -> list[tuple[str, str]]:
        """(DOF, metric) of every cell, in the order of ``gap`` arrays."""
        return [(dof, metric) for dof in self.dofs for metric in self.metrics()]

    def tolerance(self, metric: str) -> float:
        return self.tolerances[metric.split(".")[0]]


@dataclass(frozen=True)
class Gap:
    """One run's gap cells (``GapSettings.cells`` order): value, confidence interval,
    tolerance (infinite for a cell not judged); and the residual value / tolerance that
    fits minimise. ``covers``: the cells the run measures (``GapSettings.covered``; None:
    every cell); the others are not judged. ``decay_dof``: the DOF of a free-decay run."""

    run: str
    value: np.ndarray
    low: np.ndarray
    high: np.ndarray
    tolerance: np.ndarray
    covers: np.ndarray | None = None
    decay_dof: str | None = None

    @property
    def covered(self) -> np.ndarray:
        return np.ones(self.value.size, dtype=bool) if self.covers is None else self.covers

    @property
    def significant(self) -> np.ndarray:
        return (self.low > 0) | (self.high < 0)

    @property
    def material(self) -> np.ndarray:
        return np.abs(self.value) > self.tolerance

    @property
    def flagged(self) -> np.ndarray:
        return self.significant & self.material

    def gross(self, settings: GapSettings) -> np.ndarray:
        """STD cells whose model/measurement ratio lies outside GROSS_RATIO (reported always)."""
        is_std = np.array([metric.startswith("std.") for _, metric in settings.cells()])
        ratio = 1.0 + self.value
        return is_std & ((ratio < GROSS_RATIO[0]) | (ratio > GROSS_RATIO[1]))

    @property
    def residual(self) -> np.ndarray:
        return self.value / self.tolerance

    @property
    def judged(self) -> np.ndarray:
        return np.isfinite(self.tolerance)

    def as_dict(self, settings: GapSettings) -> dict:
        return {"run": self.run, "cells": [
            {"dof": dof, "metric": metric, "value": float(v), "low": float(lo), "high": float(hi),
             "tolerance": float(tol) if np.isfinite(tol) else None, "significant": bool(s), "flagged": bool(f)}
            for (dof, metric), v, lo, hi, tol, s, f in zip(settings.cells(), self.value, self.low, self.high,
                                                        self.tolerance, self.significant, self.flagged)]}


def judged_as(gap: Gap, plain: Gap) -> Gap:
    """A variant's gap judged in the cells the plain model's gap of the same run (``plain``)
    is judged in. Whether a cell is judged depends on the model's record (a band's share of
    its DOF's STD, a gross ratio, a lag's clear peak), so a variant judged on its own could
    close a gap by stepping over a threshold: a heave low-frequency STD at 0.499x the
    measured is judged as a gross gap, at 0.501x not at all. Judged as the plain model is,
    the cells a fit sees are the same at every point of it, and only their values move."""
    return replace(gap, tolerance=plain.tolerance)


def consistent(gaps: list[Gap]) -> np.ndarray:
    """Cells the model misses the same way in every run that measures them (``Gap.covers``;
    at least two for a wave cell, a decay's own cycles are its repeats): judged in every
    such run, flagged in at least one, of one sign in every one, and, pooled over them (the
    mean value, its interval's half-width sqrt(sum h_i^2) / n from the runs' independent
    intervals), significant and beyond tolerance. A cell flagged in each run is consistent;
    so is one flagged in some runs whose other runs agree in sign but are too short or too
    noisy to be significant alone (a 1200 s record gives five blocks per interval)."""
    if not gaps:
        return np.zeros(0, dtype=bool)
    covers = np.array([g.covered for g in gaps])
    n = covers.sum(axis=0)
    value = np.where(covers, [g.value for g in gaps], 0.0)
    half = np.where(covers, [(g.high - g.low) / 2.0 for g in gaps], 0.0)
    judged = np.all([g.judged | ~c for g, c in zip(gaps, covers)], axis=0)
    flagged = np.any([g.flagged & c for g, c in zip(gaps, covers)], axis=0)
    one_sign = np.abs(np.sign(value).sum(axis=0)) == n
    runs = np.maximum(n, 1)
    mean = value.sum(axis=0) / runs
    pooled_half = np.sqrt((half ** 2).sum(axis=0)) / runs
    decay = np.array([g.decay_dof is not None for g in gaps])
    needed = np.where(np.any(covers & decay[:, None], axis=0), 1, 2)  # a decay's cells: one run
    tolerance = np.min([np.where(c, g.tolerance, np.inf) for g, c in zip(gaps, covers)], axis=0)
    return ((n >= needed) & judged & flagged & one_sign & (np.abs(mean) > pooled_half)
            & (np.abs(mean) > tolerance))


def common_grid(measured: tuple[np.ndarray, np.ndarray], model: tuple[np.ndarray, np.ndarray],
                transient_s: float) -> tuple[np.ndarray, np.ndarray]:
    """Both motions (n, 6) on one grid over their common span after the transient."""
    start = max(measured[0][0], model[0][0]) + transient_s
    end = min(measured[0][-1], model[0][-1])
    if end - start < 256 * GRID_STEP_S:
        raise InputError(f"gap: the runs overlap for {max(0.0, end - start + transient_s):.0f} s, too little "
                         f"after the {transient_s:g} s transient")
    grid = np.arange(start, end, GRID_STEP_S)
    return tuple(np.column_stack([np.interp(grid, t, column) for column in x.T]) for t, x in (measured, model))


def band_passed(signal: np.ndarray, band_hz: tuple[float, float], step_s: float = GRID_STEP_S) -> np.ndarray:
    """The signal's content in the band (FFT mask, mean removed)."""
    spectrum = np.fft.rfft(signal - signal.mean())
    f = np.fft.rfftfreq(len(signal), step_s)
    spectrum[(f < band_hz[0]) | (f > band_hz[1])] = 0.0
    return np.fft.irfft(spectrum, len(signal))


def cross_correlation(model: np.ndarray, measured: np.ndarray, step_s: float = GRID_STEP_S
                      ) -> tuple[np.ndarray, np.ndarray]:
    """The cross-correlation of ``model`` with ``measured`` at lags within +-MAX_LAG_S, in
    increasing order: (lags [samples], values)."""
    n = len(model)
    correlation = np.fft.irfft(np.fft.rfft(model, 2 * n) * np.conj(np.fft.rfft(measured, 2 * n)), 2 * n)
    reach = int(MAX_LAG_S / step_s)
    return np.arange(-reach, reach + 1), np.concatenate([correlation[-reach:], correlation[:reach + 1]])


def block_lag_s(model: np.ndarray, measured: np.ndarray, step_s: float = GRID_STEP_S) -> float:
    """Lag of ``model`` behind ``measured`` [s]: the cross-correlation's peak, refined by a
    parabola, within +-MAX_LAG_S."""
    lags, values = cross_correlation(model, measured, step_s)
    i = int(np.clip(np.argmax(values), 1, len(values) - 2))
    y0, y1, y2 = values[i - 1:i + 2]
    curvature = y0 - 2 * y1 + y2
    shift = 0.5 * (y0 - y2) / curvature if curvature < 0 else 0.0
    return float((lags[i] + shift) * step_s)


def correlation_peaks(model: np.ndarray, measured: np.ndarray, step_s: float = GRID_STEP_S
                      ) -> tuple[np.ndarray, np.ndarray]:
    """The local maxima of the cross-correlation of ``model`` with ``measured`` within
    +-MAX_LAG_S: (lags [s], heights), the highest first."""
    lags, values = cross_correlation(model, measured, step_s)
    peaks, _ = scipy.signal.find_peaks(values)
    order = peaks[np.argsort(values[peaks])[::-1]]
    return lags[order] * step_s, values[order]


def lag_reads_delay(model: np.ndarray, measured: np.ndarray, step_s: float = GRID_STEP_S) -> bool:
    """Whether the wave-band lag of ``model`` behind ``measured`` reads a delay: one clear
    cross-correlation peak (no other one SECOND_PEAK of its height) within half the
    measured record's mean period of zero. A narrow-band response's peaks lie a period
    apart at nearly one height, and a response in anti-phase peaks half a period off: there
    the lag jumps between peaks with the smallest change in either record, a cycle slip
    rather than a delay, and the cell is not judged (as a band without energy is not)."""
    lags, heights = correlation_peaks(model, measured, step_s)
    if heights.size == 0 or heights[0] <= 0:
        return False
    period_s = 2.0 * math.pi * step_s / mean_frequency(measured)
    return bool(abs(lags[0]) < 0.5 * period_s and (heights.size == 1 or heights[1] < SECOND_PEAK * heights[0]))


def judged_band(measured_band: np.ndarray, model_band: np.ndarray, measured: np.ndarray, model: np.ndarray) -> bool:
    """A band's cells are judged where either side has energy there (its share of that side's
    STD at least NEGLIGIBLE_BAND), or where the two differ grossly (a ratio beyond 2 or below
    1/2), whatever the shares."""
    m_std, s_std = measured_band.std(), model_band.std()
    shares = (m_std / (measured.std() or 1.0), s_std / (model.std() or 1.0))
    ratio = s_std / m_std if m_std > 0 else np.inf
    return max(shares) >= NEGLIGIBLE_BAND or not GROSS_RATIO[0] <= ratio <= GROSS_RATIO[1]


def mean_frequency(x: np.ndarray) -> float:
    """sqrt(m2 / m0) of a zero-mean record [rad per sample]."""
    return float(np.diff(x).std() / x[:-1].std())


def mean_interval(samples: np.ndarray, confidence: float) -> tuple[float, float]:
    """The mean of ``samples`` and its Student-t interval's half-width."""
    k = len(samples)
    half = scipy.stats.t.ppf(0.5 + confidence / 2, k - 1) * samples.std(ddof=1) / math.sqrt(k)
    return float(samples.mean()), float(half)


def gap(name: str, measured: tuple[np.ndarray, np.ndarray], model: tuple[np.ndarray, np.ndarray],
        settings: GapSettings) -> Gap:
    """The gap cells of a model run (time, motion (n, 6)) against a measured run."""
    x_measured, x_model = common_grid(measured, model, settings.transient_s)
    n_blocks = max(3, min(settings.blocks, int(len(x_measured) * GRID_STEP_S // MIN_BLOCK_S)))
    blocks = np.array_split(np.arange(len(x_measured)), n_blocks)
    rows, judged = [], []
    for dof in settings.dofs:
        j = DOF_NAMES.index(dof)
        m, s = x_measured[:, j], x_model[:, j]
        scale = float(m.std()) or 1.0
        passed = {name: (band_passed(m, band), band_passed(s, band)) for name, band in settings.bands_hz.items()}
        band_judged = [judged_band(mb, sb, m, s) for mb, sb in passed.values()]
        decay_cells = len(DECAY_METRICS) if settings.decays else 0  # measured by decay runs, not here
        wave_band = passed["wave"] if "wave" in passed else passed[max(settings.bands_hz, key=settings.bands_hz.get)]
        judged += band_judged * 2 + [True, lag_reads_delay(wave_band[1], wave_band[0])] + [False] * decay_cells
        for mb, sb in passed.values():  # std.BAND
            per_block = np.array([0.5 * math.log(sb[b].var() / mb[b].var()) for b in blocks])
            _, half = mean_interval(per_block, settings.confidence)
            overall = 0.5 * math.log(sb.var() / mb.var())
            rows.append((math.expm1(overall), math.expm1(overall - half), math.expm1(overall + half)))
        for mb, sb in passed.values():  # frequency.BAND
            per_block = np.array([math.log(mean_frequency(sb[b]) / mean_frequency(mb[b])) for b in blocks])
            _, half = mean_interval(per_block, settings.confidence)
            overall = math.log(mean_frequency(sb) / mean_frequency(mb))
            rows.append((math.expm1(overall), math.expm1(overall - half), math.expm1(overall + half)))
        per_block = np.array([(s[b].mean() - m[b].mean()) / scale for b in blocks])  # offset
        centre, half = mean_interval(per_block, settings.confidence)
        rows.append((centre, centre - half, centre + half))
        mb, sb = wave_band
        per_block = np.array([block_lag_s(sb[b], mb[b]) for b in blocks])  # lag
        centre, half = mean_interval(per_block, settings.confidence)
        rows.append((centre, centre - half, centre + half))
        rows += [(0.0, 0.0, 0.0)] * decay_cells
    value, low, high = (np.array(column) for column in zip(*rows))
    tolerance = np.array([settings.tolerance(metric) if ok else np.inf
                          for (_, metric), ok in zip(settings.cells(), judged)])
    return Gap(name, value, low, high, tolerance, settings.covered(None) if settings.decays else None)


def spectra(elevation: tuple[np.ndarray, np.ndarray], motion: tuple[np.ndarray, np.ndarray],
            settings: GapSettings) -> dict[str, np.ndarray]:
    """Welch PSD of each analysed DOF and its coherence with the wave elevation (one run):
    ``frequency_hz``, ``psd.DOF``, ``coherence.DOF``."""
    start = max(elevation[0][0], motion[0][0]) + settings.transient_s
    grid = np.arange(start, min(elevation[0][-1], motion[0][-1]), GRID_STEP_S)
    eta = np.interp(grid, *elevation)
    n = int(COHERENCE_SEGMENT_S / GRID_STEP_S)
    out = {}
    for dof in settings.dofs:
        x = np.interp(grid, motion[0], motion[1][:, DOF_NAMES.index(dof)])
        f, p = scipy.signal.welch(x, fs=1 / GRID_STEP_S, nperseg=n)
        _, c = scipy.signal.coherence(eta, x, fs=1 / GRID_STEP_S, nperseg=n)
        out["frequency_hz"], out[f"psd.{dof}"], out[f"coherence.{dof}"] = f, p, c
    return out


def coherent_share(spectra_: dict[str, np.ndarray], dof: str, band_hz: tuple[float, float]) -> float:
    """The share of a DOF's variance in the band that is linear in the waves (``spectra``'s
    coherence weighted by the PSD): a narrow response the waves do not drive (a rotor's 1P
    moment) lowers it however few frequency bins it takes."""
    f = spectra_["frequency_hz"]
    keep = (f >= band_hz[0]) & (f <= band_hz[1])
    psd = spectra_[f"psd.{dof}"][keep]
    return float(np.sum(spectra_[f"coherence.{dof}"][keep] * psd) / np.sum(psd)) if np.sum(psd) > 0 else math.nan


def band_share(spectra_: dict[str, np.ndarray], dof: str, band_hz: tuple[float, float]) -> float:
    """The band's share of the DOF's STD (``spectra``' PSD): sqrt(band variance / variance)."""
    f, psd = spectra_["frequency_hz"], spectra_[f"psd.{dof}"]
    total = float(np.sum(psd))
    return math.sqrt(float(np.sum(psd[(f >= band_hz[0]) & (f <= band_hz[1])])) / total) if total > 0 else 0.0


def band_mean(frequency_hz: np.ndarray, values: np.ndarray, band_hz: tuple[float, float]) -> float:
    keep = (frequency_hz >= band_hz[0]) & (frequency_hz <= band_hz[1])
    return float(values[keep].mean())
