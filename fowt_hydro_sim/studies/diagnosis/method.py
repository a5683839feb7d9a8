"""The sim-to-real gap diagnosis: where the model and measured runs differ, which unmodelled
effect of the catalogue (effects/) explains it, and how far the gap shrinks once that
effect is added, on the tuning runs and, without refitting, on blind runs.

1. Every run is replayed with its own elevation (replay.py) and its gap cells measured
   (gap.py); cells that are significant and beyond tolerance are flagged.
2. Each candidate effect's parameters are fitted to all tuning runs at once (bounded least
   squares on the cells' residuals in tolerance units; one parameter set for every sea
   state, so how the gap scales with Hs is part of the fit). Its score is a BIC,
   n ln(mean r^2 + floor^2) + p ln n, which charges every extra parameter.
   Baseline first: cells of one sign in every tuning run, significant pooled over the runs,
   are baseline mismatches (``gap.consistent``); every flagged cell that no candidate at
   plausible values explains is set aside as the baseline's (``unexplained_cells``) and the
   candidates are fitted again on what remains, each charged for how far it moves the
   cells set aside (``residuals``). Every variant is judged in the cells the plain model is
   judged in (``judged_as_plain``): a fit moves the cells' values, never the set of cells.
3. The best-scoring candidate is named if it beats the plain model by ``MIN_EVIDENCE``,
   closes at least ``MIN_CLOSURE`` of the gap and raises no concern (``concerns``: values
   outside their plausible range or at the edge of the fit's bounds, a scale of one of the
   model's terms too close to 1 to be worth naming, a signature that moves
   the model the wrong way, a blind closure below ``BLIND_SHARE`` of the tuning closure);
   candidates with a concern rank after the others (a fit outside its plausible range
   that a plausible point explains nearly as well, its nearest plausible values or its fit
   again with the parameters outside held at their ranges' ends, takes that point,
   ``plausible_refit``).
   Otherwise the gap is the baseline's ("baseline mismatch"), or "unexplained" where a
   set-aside cell's band holds a measured response the waves do not drive
   (``undriven_cells``).
   Candidates within ``TIE`` of the best both fit: the wave-response coherence decides
   (a low-frequency response the measurement shows but the waves do not explain points
   to a load quadratic in the waves, e.g. slow drift).
   With a baseline mismatch left, an effect is named "additionally" only if it explains a
   flagged cell outside the mismatch's (``additional_cells``), and a mismatch that a scale
   of one of the model's own terms explains is read as that term's error
   (``term_reading``: "the model's slow drift is 10 times too strong"); a term explaining
   every mismatch cell that one explains and more, with no more parameters, reads the
   mismatch instead (``wider_reading``).
   A fit worse than the plain model is restarted from other points, and reported as failed
   if it stays so; lag-type parameters are fitted on a grid (``fit_effect``).

This module is the method alone: it reads no files and starts no cluster. Model runs go
through ``evaluate(jobs, description) -> results``, which the caller gives (runner.py: in
process, or on a Dask cluster; a job is ``Job``); each candidate's fit runs in its own
thread so that every candidate's runs are in flight together. Records longer than the fit
window are fitted on their first ``FIT_WINDOW_S`` (the replays of the least-squares steps
and Jacobians are short); the fitted values are then replayed over the whole records,
which score and judge the candidate. A candidate that closes less than ``SCREEN_CLOSURE``
of the gap in the fit window cannot be named and is not replayed at full length (it keeps
its fit-window figures). The model runs done and still expected are counted in a ``Work``
(runner.Progress logs them).
"""
from __future__ import annotations

import math
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field, replace

import numpy as np
import scipy.optimize
import scipy.signal

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.config import Platform
from fowt_hydro_sim.studies.diagnosis.decay import check_decay
from fowt_hydro_sim.studies.diagnosis.effects import CATALOGUE, Effect, Parameter
from fowt_hydro_sim.studies.diagnosis.effects.base import MATERIAL_SCALE
from fowt_hydro_sim.studies.diagnosis.gap import (
    NEGLIGIBLE_BAND,
    Gap,
    GapSettings,
    band_mean,
    band_share,
    coherent_share,
    consistent,
    judged_as,
    spectra,
)
from fowt_hydro_sim.studies.replay import PREROLL_S, MeasuredRun

FLOOR = 0.25  # residual floor in tolerance units: fits closer than this are not told apart
MIN_EVIDENCE = 6.0  # BIC improvement over the plain model to name an effect ("strong")
MIN_CLOSURE = 0.5  # share of the gap an effect must close to be named
TIE = 2.0  # BIC difference below which two candidates both fit
COHERENCE_DEFICIT = 0.1  # measured low-frequency coherence this far below the model's: incoherent load
UNDRIVEN_SHARE = 0.1  # measured wave-coherent share this far below the model's: a load the waves do not drive
FD_STEP = 0.1  # forward-difference step, in units of each parameter's scale
EDGE = 0.01  # a fitted value this close to a bound (share of the bounds' span) sits at the edge
BLIND_SHARE = 0.5  # a blind closure below this share of the tuning closure disqualifies the effect
FIT_WINDOW_S = 1800.0  # longer tuning records are fitted on their first FIT_WINDOW_S, then replayed whole
SCREEN_CLOSURE = 0.25  # closing less than this in the fit window: not replayed at full length
FAILED_CLOSURE = -0.01  # a fit closing less than this is worse than the plain model beyond round-off: failed
PLAUSIBLE_SHARE = 0.9  # a fit outside its plausible range is moved into it if it keeps this share of its closure

Job = tuple  # (effect name or None, parameter values, run index, with spectra[, duration [s]: a part of the record])


def record_s(run: MeasuredRun) -> float:
    """The span a whole-record replay covers (elevation start to last motion sample)."""
    return float(run.motion_time_s[-1] - run.elevation_time_s[0])


def model_s(run: MeasuredRun, duration_s: float | None = None) -> float:
    """Model seconds a replay of the run takes: the pre-roll and the record (or its first
    ``duration_s``); a decay, its record, whole."""
    if run.decay_dof is not None:
        return record_s(run)
    return PREROLL_S + (duration_s if duration_s is not None else record_s(run))


def wave_runs(runs: list[MeasuredRun]) -> list[int]:
    """The indices of the runs in waves (not free decays)."""
    return [i for i, r in enumerate(runs) if r.decay_dof is None]


def fit_window(runs: list[MeasuredRun], window_s: float | None) -> float | None:
    """The fit window if every run in waves is longer than it, else None (fit on whole
    records); decays are replayed whole."""
    waves = [runs[i] for i in wave_runs(runs)]
    return window_s if window_s and all(record_s(r) > window_s for r in waves) else None


class Work:
    """Model runs done of those expected, and the same in replayed seconds (pre-roll
    included). The expected runs are each phase's most; ``expect`` with a negative count
    gives back what a phase did not use. ``reported`` is called after each ``done`` (here it
    does nothing; runner.Progress logs a line)."""

    def __init__(self) -> None:
        self.runs_done = self.runs_expected = 0
        self.work_done_s = self.work_expected_s = 0.0
        self._lock = threading.Lock()

    def expect(self, runs: int, work_s: float) -> None:
        """Add ``runs`` (of ``work_s`` replayed seconds) to those expected."""
        with self._lock:
            self.runs_expected += runs
            self.work_expected_s += work_s

    def done(self, runs: int, work_s: float, final: bool = False) -> None:
        """Count ``runs`` (of ``work_s`` replayed seconds) done; ``final``: the diagnosis ends."""
        with self._lock:
            self.runs_done += runs
            self.work_done_s += work_s
            self.reported(final)

    def reported(self, final: bool) -> None:
        """Called (under the lock) after each ``done``."""


def tracked(evaluate: Callable, runs: list[MeasuredRun], work: Work) -> Callable:
    """``evaluate`` that counts its finished jobs in ``work``."""
    def run(jobs: list[Job], description: str = "") -> list:
        results = evaluate(jobs, description)
        work.done(len(jobs), sum(job_s(j, runs) for j in jobs))
        return results
    return run


def judged_as_plain(evaluate: Callable, plain: list[Gap], window_s: float | None = None,
                    plain_window: list[Gap] | None = None) -> Callable:
    """``evaluate`` whose gaps are judged in the cells the plain model's gap of the same run
    and span is (``gap.judged_as``): ``plain`` over whole records, ``plain_window`` over
    their first ``window_s``."""
    by_span = {(i, None): g for i, g in enumerate(plain)} | {(i, window_s): g for i, g in enumerate(plain_window or [])}

    def run(jobs: list[Job], description: str = "") -> list:
        results = evaluate(jobs, description)
        return [(judged_as(g, by_span[job[2], job_duration_s(job)]), *rest) for job, (g, *rest) in zip(jobs, results)]
    return run


def job_duration_s(job: Job) -> float | None:
    """The part of the record a job replays [s] (None: the whole record)."""
    return job[4] if len(job) > 4 else None


def job_s(job: Job, runs: list[MeasuredRun]) -> float:
    """Model seconds a job replays, pre-roll included."""
    return model_s(runs[job[2]], job_duration_s(job))


# ---------------------------------------------------------------------- fitting one candidate
# a candidate's fit again with some parameters held: (held values, start) -> (values, gaps, model runs)
Refit = Callable[[dict[str, float], dict[str, float]], tuple[dict[str, float], list[Gap], int]]

@dataclass
class CandidateFit:
    """One candidate effect fitted to the tuning runs."""

    effect: str
    values: dict[str, float]
    gaps: list[Gap]  # tuning runs, at the fitted values
    score: float
    closure: float  # share of the tuning gap closed
    model_runs: int
    fits: bool = False  # beats the plain model, closes enough, and raises no concern
    concerns: list[str] = field(default_factory=list)  # why the fit is not physically plausible
    window_s: float | None = None  # screened out: gaps, score and closure on the fit window only
    size_concern: str = ""  # an added term too small beside the model's own to name (``share_concern``)

    @property
    def failed(self) -> bool:
        """Whether the fit leaves the gap larger than the plain model (a closure below
        FAILED_CLOSURE, -1 %) from every start (``fit_effect``): a fit that found no minimum, never an answer."""
        return self.closure < FAILED_CLOSURE

    def value_concerns(self, effect: Effect) -> list[str]:
        """Why its fitted values are no finding: ``range_concerns`` and its size concern."""
        return range_concerns(effect, self.values) + ([self.size_concern] if self.size_concern else [])

    @property
    def screened(self) -> str:
        """Why the candidate was not replayed at full length ('' if it was)."""
        return "" if self.window_s is None else (
            f"closes {self.closure:.0%} in the first {self.window_s:g} s, less than {SCREEN_CLOSURE:.0%}: "
            "not replayed at full length")

    def as_dict(self, settings: GapSettings) -> dict:
        return {"effect": self.effect, "values": self.values, "score": self.score, "closure": self.closure,
                "fits": self.fits, "failed": self.failed, "concerns": self.concerns, "model_runs": self.model_runs,
                "window_s": self.window_s, "screened": self.screened,
                "gaps": [g.as_dict(settings) for g in self.gaps]}


def moved(before: Gap, after: Gap, cells: np.ndarray) -> np.ndarray:
    """How far an effect moves the model's value of ``cells`` from the plain model's, in
    tolerance units (0 in a cell not judged)."""
    return (after.value - before.value)[cells] / after.tolerance[cells]


def residuals(gaps: list[Gap], mask: np.ndarray | None = None, before: list[Gap] | None = None) -> np.ndarray:
    """The residuals a fit minimises, over the runs: the gap in tolerance units in the cells
    of ``mask`` (default all) and, in the cells set aside as the baseline's (outside
    ``mask``), how far the effect moves the model from the plain model (``before``): an
    effect is charged for moving cells it cannot explain. (An added-mass error that closes a
    surge frequency gap while it shifts the set-aside heave and pitch frequencies is not a
    mooring stiffness that closes it and leaves them.)"""
    if mask is None:
        return np.concatenate([g.residual for g in gaps])
    return np.concatenate([np.concatenate([a.residual[mask], moved(b, a, ~mask)]) for b, a in zip(before, gaps)])


def score(gaps: list[Gap], n_parameters: int, mask: np.ndarray | None = None,
          before: list[Gap] | None = None) -> float:
    """BIC of a model's residuals (``residuals``): n ln(mean r^2 + floor^2) + p ln n."""
    r = residuals(gaps, mask, before)
    return float(r.size * math.log(np.mean(r ** 2) + FLOOR ** 2) + n_parameters * math.log(r.size))


def closure(before: list[Gap], after: list[Gap], mask: np.ndarray | None = None) -> float:
    """Share of the gap closed: 1 - sum r_after^2 / sum r_before^2 over the cells flagged
    before or beyond tolerance after (an effect that opens new gaps is charged for them),
    among the cells of ``mask`` (default all); the cells outside ``mask`` (set aside as the
    baseline's) charge the effect for moving them (``moved``)."""
    share = window_closure(before, before, after, mask)
    return 0.0 if math.isnan(share) else share


def cells_closure(before: list[Gap], after: list[Gap], cells: np.ndarray | int) -> float:
    """Share of the gap of ``cells`` (a mask or one index) closed over the runs:
    1 - sum r_after^2 / sum r_before^2."""
    den = float(sum(np.sum(b.residual[cells] ** 2) for b in before))
    return 1.0 - float(sum(np.sum(a.residual[cells] ** 2) for a in after)) / den if den > 0 else 0.0


def explains(before: list[Gap], after: list[Gap], i: int) -> bool:
    """Whether an effect explains a baseline mismatch cell: it closes at least MIN_CLOSURE of
    the cell's gap over the tuning runs. (Not "within tolerance in every run": an effect of
    the catalogue's form, e.g. a constant drift coefficient, cannot match a real effect's
    dependence on the sea state (a frequency-dependent drift) to 5 % in each of several sea
    states, yet it is what takes a 4x gap to a 20 % one.)"""
    return cells_closure(before, after, i) >= MIN_CLOSURE


def window_closure(flagged: list[Gap], before: list[Gap], after: list[Gap], mask: np.ndarray | None = None) -> float:
    """``closure`` in a fit window: over the cells flagged on the whole records (``flagged``)
    or beyond tolerance after, the residuals of the window's gaps; NaN if the window shows
    none of it."""
    num = den = 0.0
    for f, b, a in zip(flagged, before, after):
        cells = (f.flagged | a.material) & (mask if mask is not None else True)
        num += float(np.sum(a.residual[cells] ** 2))
        den += float(np.sum(b.residual[cells] ** 2))
        if mask is not None:
            num += float(np.sum(moved(b, a, ~mask) ** 2))
    return 1.0 - num / den if den > 0 else math.nan


def at_edge(p: Parameter, value: float) -> bool:
    """Whether a fitted value sits at a bound of the fit's range (within EDGE of its span) that
    is not the parameter's off value: a bound where the term is off (no extra damping in one
    DOF of a per-DOF effect, no drift) is a physical limit and a legitimate answer, not a sign
    that the parameter absorbs something else."""
    span = p.high - p.low
    return ((value - p.low <= EDGE * span and p.low != p.off)
            or (p.high - value <= EDGE * span and p.high != p.off))


def range_concerns(effect: Effect, values: dict[str, float]) -> list[str]:
    """Why fitted values are implausible: a parameter outside the range a real platform's
    lies in, or at the edge of the fit's bounds (it absorbs something else); or a scale of
    one of the model's terms whose every material parameter (``Parameter.material``) lies
    closer to its off value than is worth naming (the term is right, as far as the
    diagnosis can tell)."""
    out = []
    for p in effect.parameters:
        value, (low, high) = values[p.name], p.plausible_range
        if not low <= value <= high:
            out.append(f"{p.name} = {value:.4g} lies outside its plausible {low:g} to {high:g} ({p.why})")
        elif at_edge(p, value):
            out.append(f"{p.name} = {value:.4g} sits at the edge of the fitted range {p.low:g} to {p.high:g}")
    material = [p for p in effect.parameters if p.material]
    if material and all(abs(values[p.name] - p.off) < p.material for p in material):
        out.append(", ".join(f"{p.name} = {values[p.name]:.4g}" for p in material)
                   + f": within {material[0].material:g} of the model's own {material[0].off:g}, no difference "
                     "worth naming")
    return out


def nearest_plausible(effect: Effect, values: dict[str, float]) -> dict[str, float]:
    """The values with each parameter outside its plausible range moved to the range's
    nearer end."""
    return {p.name: float(np.clip(values[p.name], *p.plausible_range)) for p in effect.parameters}


def kept_share(plain: list[Gap], fitted: list[Gap], explained: np.ndarray,
               closure_of: Callable[[list[Gap]], float]) -> Callable[[list[Gap]], float]:
    """How much of what a fit explains other values keep: over the cells ``explained`` (the
    flagged cells the fit's gaps ``fitted`` explain against the plain model's ``plain``,
    ``explained_cells``), their closure as a share of the fit's; over every cell
    (``closure_of``) if it explains none. A catenary's fit that closes 55 % of the surge
    low-frequency frequency gap and 0.5 % of a gap carried by cells the two simulators
    differ in structurally is judged by that cell, not by the noise of the others."""
    if explained.any():
        own = cells_closure(plain, fitted, explained)
        return lambda gaps: cells_closure(plain, gaps, explained) / own
    own = closure_of(fitted)
    return lambda gaps: closure_of(gaps) / own


def plausible_refit(candidate: CandidateFit, effect: Effect, evaluate_at: Callable[[dict[str, float]], list[Gap]],
                    closure_of: Callable[[list[Gap]], float], score_of: Callable[[list[Gap]], float],
                    kept: Callable[[list[Gap]], float] | None = None, refit_within: Refit | None = None
                    ) -> CandidateFit:
    """A fit that lands outside its plausible range, but which a plausible point explains
    nearly as well, at that point: the range asks whether a plausible value explains the
    gap, and a hardening of -0.005 that closes the gap no better than 0 is a catenary's.
    Nearly as well: the point keeps at least PLAUSIBLE_SHARE of what the fit explains
    (``kept(gaps)``, a share; ``kept_share``; default, of its closure) and is better than
    the plain model (a positive closure). The point is first its nearest plausible values
    (``nearest_plausible``), then, for an effect with parameters left inside their ranges,
    its fit again with the others held at their ranges' nearer ends (``refit_within``
    (held, start) -> (values, gaps, model runs); it starts from the nearest plausible
    values): wave runs about a mean offset see a catenary's asymmetry and hardening
    together, and one fitted at a hardening of -0.1 with an asymmetry of +0.14 is read as
    well by a hardening of 0 and a smaller asymmetry. A fit that needs its implausible
    value (a drift ten times too strong) keeps it, and its concern. ``evaluate_at`` gives
    the gaps at given values over the candidate's span (its fit window's, if screened),
    ``closure_of`` and ``score_of`` judge them as the candidate was judged."""
    moved = nearest_plausible(effect, candidate.values)
    if moved == candidate.values or candidate.failed or candidate.closure <= 0:
        return candidate
    kept = kept or (lambda g: closure_of(g) / candidate.closure)

    def explains_as_well(gaps: list[Gap]) -> bool:
        return closure_of(gaps) > 0 and kept(gaps) >= PLAUSIBLE_SHARE

    gaps = evaluate_at(moved)
    runs = candidate.model_runs + len(gaps)
    held = {name: value for name, value in moved.items() if value != candidate.values[name]}
    if not explains_as_well(gaps) and refit_within is not None and len(held) < len(moved):
        moved, gaps, count = refit_within(held, moved)
        runs += count
    if range_concerns(effect, moved) or not explains_as_well(gaps):
        return replace(candidate, model_runs=runs)
    return replace(candidate, values=moved, gaps=gaps, score=score_of(gaps), closure=closure_of(gaps),
                   model_runs=runs)


def share_concern(effect: Effect, values: dict[str, float], runs: list[MeasuredRun],
                  platform: Platform | None) -> str:
    """For an effect that adds to a term the model has (``Effect.own_share``): why the fitted
    addition is no finding, if its mean share of the model's own term over ``runs`` is under
    MATERIAL_SCALE ('' otherwise, or without the platform)."""
    if effect.own_share is None or platform is None or not runs:
        return ""
    share = float(np.mean([effect.own_share(values, run, platform) for run in runs]))
    if share >= MATERIAL_SCALE:
        return ""
    return (f"it adds {share:.0%} to the model's own term on the tuning runs: within {MATERIAL_SCALE:.0%} of it, no "
            "difference worth naming")


def concerns(effect: Effect, values: dict[str, float], before: list[Gap], settings: GapSettings,
             mask: np.ndarray | None = None) -> list[str]:
    """Why a fitted effect is implausible: its values (``range_concerns``); or a gap it
    cannot close, because its signature moves the model the wrong way in the cells that
    carry most of the flagged gap."""
    out = range_concerns(effect, values)
    cells = [f"{dof}.{metric}" for dof, metric in settings.cells()]
    right = wrong = 0.0
    for g in before:
        for i in np.flatnonzero(g.flagged & (mask if mask is not None else True)):
            sign = effect.signature.get(cells[i])
            if sign is not None:
                weight = float(g.residual[i] ** 2)
                right, wrong = (right + weight, wrong) if np.sign(g.value[i]) == -sign else (right, wrong + weight)
    if wrong > right:
        moved = ", ".join(f"{'raises' if s > 0 else 'lowers'} {cell}" for cell, s in effect.signature.items())
        out.append(f"it {moved}, the wrong way for most of the flagged gap")
    return out


def plain_gaps(candidate: CandidateFit, before: list[Gap], window_before: list[Gap]) -> list[Gap]:
    """The plain model's tuning gaps over the span the candidate's gaps cover: the fit
    window's (``window_before``) for a candidate screened out in the window, whose gaps are
    the window's; else the whole records' (``before``)."""
    return window_before if candidate.window_s is not None else before


def unexplained_cells(before: list[Gap], candidates: list[CandidateFit], effects: dict[str, Effect],
                      window_before: list[Gap]) -> np.ndarray:
    """Cells flagged in a tuning run that no candidate at plausible values (no
    ``range_concerns``) and better than the plain model (a positive closure) explains
    (``explains``), fitted on every cell: the baseline's, set
    aside before the effects are tested on what remains. They are the consistent mismatches
    no effect explains and differences flagged in some runs only, e.g. of a sign that
    changes with the sea state (a response of another form, such as strip theory against
    a panel method's), which no effect of the catalogue moves: left in, they would dilute
    every candidate's closure, and an effect that closes its own cells would not be named.
    (Whether an effect moves a cell the right way is judged by the cell's closure; a
    signature concern over all flagged cells would count the cells being set aside.)
    A fit that leaves the flagged gap larger than the plain model's did not find its effect
    in the data, and the cells it happens to close are by-products: slow drift at a
    coefficient that halves a pitch gap while it multiplies the surge one eighty-fold
    explains neither.
    A candidate screened out in the fit window is compared with the plain model in the same
    window (``plain_gaps``): against the whole records, a cell's gap differing between the
    window and the record would read as closed by a candidate that moves nothing."""
    flagged = np.any([g.flagged for g in before], axis=0)
    plausible = [c for c in candidates if not c.value_concerns(effects[c.effect]) and c.closure > 0]
    return np.array([bool(flagged[i]) and not any(explains(plain_gaps(c, before, window_before), c.gaps, i)
                                                  for c in plausible)
                     for i in range(flagged.size)])


def grid(effect: Effect) -> list[np.ndarray]:
    """A grid-fitted effect's first points (every parameter a ``Parameter.grid_step``): each
    parameter's plausible range at its step, counted from its off value (the off value among
    them)."""
    axes = []
    for p in effect.parameters:
        low, high = p.plausible_range
        steps = np.arange(math.ceil((low - p.off) / p.grid_step), math.floor((high - p.off) / p.grid_step) + 1)
        axes.append(np.union1d(p.off + p.grid_step * steps, [p.off]))
    return [np.array(point) for point in np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, len(axes))]


def refinement(effect: Effect, best: np.ndarray) -> list[np.ndarray]:
    """The points that refine a grid fit around its best point: each parameter a quarter and
    a half of its step either side (within its bounds)."""
    out = []
    for k, p in enumerate(effect.parameters):
        for shift in (-0.5, -0.25, 0.25, 0.5):
            point = best.copy()
            point[k] = float(np.clip(best[k] + shift * p.grid_step, p.low, p.high))
            out.append(point)
    return out


def grid_fitted(effect: Effect) -> bool:
    """Whether the effect is fitted by a grid (every parameter lag-type, ``Parameter.grid_step``)."""
    return all(p.grid_step for p in effect.parameters)


# a residual the model gives no finite value for (it diverged) counts as this many tolerances off
DIVERGED_RESIDUAL = 1e3


def restarts(u0: np.ndarray, bounds: tuple[np.ndarray, np.ndarray]) -> list[np.ndarray]:
    """Other starting points of a fit (in units of each parameter's scale from its off value)
    for one that left the gap larger than the plain model: the first start mirrored about
    the off value (the off value itself where that is a bound: a term that is not there),
    a quarter of the first start, and twice it, within the bounds."""
    out: list[np.ndarray] = []
    for point in (-u0, 0.25 * u0, 2.0 * u0):
        point = np.clip(point, *bounds)
        if not any(np.array_equal(point, q) for q in [u0, *out]):
            out.append(point)
    return out


def fit_effect(effect: Effect, evaluate: Callable, tuning: list[int], max_evaluations: int = 4,
               description: str = "", mask: np.ndarray | None = None,
               window_s: float | None = None, before: list[Gap] | None = None,
               restarted: Callable[[], None] | None = None, fixed: dict[str, float] | None = None,
               start: dict[str, float] | None = None) -> tuple[dict[str, float], list[Gap], int]:
    """Fit the effect's parameters to the tuning runs' cells of ``mask`` (default all; the
    cells outside it charge the effect for moving them from the plain model's gaps
    ``before``, see ``residuals``), on the runs' first ``window_s`` (default: whole
    records): (values, gaps at them, model runs).

    Bounded least squares from the parameters' ``start``; a fit that ends with a larger
    sum of squares than the plain model's (``before``), or a negative closure against it,
    did not find its minimum, and is restarted from other points (``restarts``) until one
    ends better than the plain model (``restarted`` is called before each restart); a start
    at which the model diverges is passed over, and a point where it does is as far off as
    DIVERGED_RESIDUAL in each cell it gives no finite value for. A lag-type effect
    (``grid_fitted``), whose gaps a forward difference sees as flat, is fitted instead by a
    grid over its plausible range (``grid``), refined around the best point.
    The parameters named in ``fixed`` are held at the values it gives; ``start`` replaces
    the others' own starting values."""
    fixed = fixed or {}
    params = [p for p in effect.parameters if p.name not in fixed]
    off = np.array([p.off for p in params])
    scale = np.array([p.scale for p in params])
    u0 = (np.array([(start or {}).get(p.name, p.start) for p in params]) - off) / scale
    bounds = ((np.array([p.low for p in params]) - off) / scale, (np.array([p.high for p in params]) - off) / scale)
    cache: dict[bytes, list[Gap]] = {}

    def values(u: np.ndarray) -> dict[str, float]:
        free = {p.name: float(v) for p, v in zip(params, off + u * scale)}
        return {p.name: free.get(p.name, fixed.get(p.name)) for p in effect.parameters}

    def gaps_at(us: list[np.ndarray]) -> list[list[Gap]]:
        todo = list({u.tobytes(): u for u in us if u.tobytes() not in cache}.values())
        jobs = [(effect.name, values(u), i, False) + ((window_s,) if window_s else ()) for u in todo for i in tuning]
        results = evaluate(jobs, description) if jobs else []
        for k, u in enumerate(todo):
            cache[u.tobytes()] = [g for g, _ in results[k * len(tuning):(k + 1) * len(tuning)]]
        return [cache[u.tobytes()] for u in us]

    def finite_residuals(gaps: list[Gap]) -> np.ndarray:
        """The residuals, a cell the model gives no finite value for (it diverges at these
        values: a mooring that softens into a negative stiffness) as far off as DIVERGED_RESIDUAL."""
        r = residuals(gaps, mask, before)
        return np.nan_to_num(r, nan=DIVERGED_RESIDUAL, posinf=DIVERGED_RESIDUAL, neginf=-DIVERGED_RESIDUAL)

    def residual(u: np.ndarray) -> np.ndarray:
        return finite_residuals(gaps_at([u])[0])

    def jacobian(u: np.ndarray) -> np.ndarray:
        steps = [np.clip(u + FD_STEP * e, *bounds) for e in np.eye(len(u))]
        steps = [s if np.any(s != u) else u - FD_STEP * e for s, e in zip(steps, np.eye(len(u)))]
        base, *shifted = gaps_at([u, *steps])
        r0 = finite_residuals(base)
        return np.column_stack([(finite_residuals(gs) - r0) / (s - u).sum() for gs, s in zip(shifted, steps)])

    def diverged(u: np.ndarray) -> bool:
        return not np.all(np.isfinite(residuals(gaps_at([u])[0], mask, before)))

    def cost(key: bytes) -> float:
        return float(np.sum(finite_residuals(cache[key]) ** 2))

    if grid_fitted(effect) and not fixed:
        gaps_at([(point - off) / scale for point in grid(effect)])
        best = min(cache, key=cost)
        gaps_at([(point - off) / scale for point in refinement(effect, off + np.frombuffer(best) * scale)])
    else:
        def failed(key: bytes) -> bool:
            """Worse than the plain model (if given): a larger sum of squares, or a negative closure
            (a fit back at the off value, the plain model itself, is not)."""
            if before is None:
                return False
            plain = float(np.sum(residuals(before, mask, before) ** 2))
            return (cost(key) > (1.0 - FAILED_CLOSURE) * plain
                    or window_closure(before, before, cache[key], mask) < FAILED_CLOSURE)

        for k, start in enumerate([u0, *restarts(u0, bounds)]):
            if k and restarted is not None:
                restarted()
            if diverged(start):  # the model diverges there: no start
                continue
            scipy.optimize.least_squares(residual, start, jac=jacobian, bounds=bounds, method="trf",
                                         max_nfev=max_evaluations, xtol=1e-3, ftol=1e-3)
            if not failed(min(cache, key=cost)):
                break
    # the best point evaluated (the solver's, or a step of its last Jacobian)
    best = min(cache, key=cost)
    return values(np.frombuffer(best)), cache[best], len(cache) * len(tuning)


# ---------------------------------------------------------------------- the diagnosis
@dataclass
class Mismatch:
    """A cell the plain model misses in the same direction in every tuning run (significant
    pooled over the runs, ``gap.consistent``): a baseline mismatch (coefficients,
    conventions, a missing physics term) rather than noise; with
    how it scales with the sea state (a least-squares slope of the value against Hs and Tp)."""

    dof: str
    metric: str
    values: list[float]  # per tuning run
    hs_m: list[float]
    tp_s: list[float]
    explained_by: str | None = None  # the named effect, if it explains the cell (``explains``)
    term: str = ""  # the model's own term that a candidate's scale closes it with (``term_reading``), in words
    term_by: str | None = None  # that candidate (the named effect's, or a first fit's)
    term_values: dict[str, float] = field(default_factory=dict)  # its fitted values

    @property
    def sign(self) -> int:
        return 1 if self.values[0] > 0 else -1

    def slope(self, x: list[float]) -> float:
        return float(np.polyfit(x, self.values, 1)[0]) if len(set(x)) > 1 else float("nan")

    def text(self) -> str:
        lo, hi = min(self.values), max(self.values)
        ratio = self.metric.startswith(("std.", "frequency.", "decay_"))
        size = (f"{1 + lo:.2g}x to {1 + hi:.2g}x the measured" if ratio else f"{lo:+.3g} to {hi:+.3g}")
        scaling = (f"; change per m of Hs {self.slope(self.hs_m):+.3g}, per s of Tp {self.slope(self.tp_s):+.3g}"
                   if self.hs_m else "")
        runs = "free decay" if self.metric.startswith("decay_") else "run"
        return (f"{self.dof} {self.metric}: model {'above' if self.sign > 0 else 'below'} the measurement in every "
                f"{runs} ({size}{scaling})"
                + (f", explained by {self.explained_by}" + (f": {self.term}" if self.term else "")
                   if self.explained_by else f": {self.term}" if self.term
                   else ", not explained by any catalogue effect"))


@dataclass
class Diagnosis:
    """Where the gap lies, what explains it and how far it shrinks."""

    settings: GapSettings
    tuning: list[str]
    blind: list[str]
    baseline: list[Gap]  # tuning then blind runs, plain model
    candidates: list[CandidateFit]  # best score first
    verdict: str  # "no significant gap", "explained", "unexplained", "baseline mismatch"
    chosen: str | None
    reason: str
    blind_after: list[Gap] = field(default_factory=list)  # blind runs with the chosen effect, not refitted
    baseline_score: float = float("nan")
    coherence_deficit: float = float("nan")
    spectra: dict = field(default_factory=dict)  # run -> {"measured"|"model"|"model+effect": spectra}
    model_runs: int = 0
    mismatches: list[Mismatch] = field(default_factory=list)  # the baseline's, found before any effect
    fit_cells: np.ndarray | None = None  # the cells effects were fitted on (None: all; else all but those set aside)
    first_round: list[CandidateFit] = field(default_factory=list)  # the fits on every cell, if refitted without some
    # (DOF, metric, shares: measured, model)
    undriven: list[tuple[str, str, float, float]] = field(default_factory=list)
    window_before: list[Gap] = field(default_factory=list)  # tuning runs, plain model, in the fit window (if one)
    reading: CandidateFit | None = None  # nothing named: the term read off the baseline mismatch (``leading_reading``)
    reading_cells: np.ndarray | None = None  # the mismatch cells it reads
    reading_blind_after: list[Gap] = field(default_factory=list)  # blind runs at its values, not refitted

    @property
    def finding(self) -> CandidateFit | None:
        """What the diagnosis names: the chosen effect, else the term read off the baseline
        mismatch (a first fit, ``reading``), else None."""
        return self.candidate(self.chosen) if self.chosen else self.reading

    @property
    def reading_closure(self) -> tuple[float, float]:
        """The reading's share of its cells' gap closed: tuning (its fit), blind (not refitted)."""
        if self.reading is None:
            return math.nan, math.nan
        plain = plain_gaps(self.reading, self.tuning_before, self.window_before)
        return (cells_closure(plain, self.reading.gaps, self.reading_cells),
                cells_closure(self.blind_before, self.reading_blind_after, self.reading_cells)
                if self.reading_blind_after else math.nan)

    @property
    def reading_cell_names(self) -> list[tuple[str, str]]:
        """(DOF, metric) of each mismatch cell the reading reads ([] without a reading)."""
        if self.reading_cells is None:
            return []
        return [cell for cell, kept in zip(self.settings.cells(), self.reading_cells) if kept]

    @property
    def first_fits(self) -> list[CandidateFit]:
        """The candidates' fits on every cell: the first round if they were fitted again
        without some cells, else the candidates."""
        return self.first_round or self.candidates

    @property
    def tuning_before(self) -> list[Gap]:
        return self.baseline[:len(self.tuning)]

    @property
    def blind_before(self) -> list[Gap]:
        return self.baseline[len(self.tuning):]

    def candidate(self, name: str) -> CandidateFit:
        return next(c for c in self.candidates if c.effect == name)

    @property
    def differences(self) -> list[tuple[str, str]]:
        """Cells set aside as the baseline's (``unexplained_cells``) that are not consistent
        mismatches: flagged in some runs only, or of a sign that changes between runs."""
        if self.fit_cells is None:
            return []
        mismatched = {(m.dof, m.metric) for m in self.mismatches}
        return [cell for cell, kept in zip(self.settings.cells(), self.fit_cells)
                if not kept and cell not in mismatched]

    def differences_text(self) -> str:
        """The set-aside differences with their values per tuning run."""
        cells = self.settings.cells()

        def values(cell: tuple[str, str]) -> str:
            return ", ".join(f"{g.value[cells.index(cell)]:+.2g}" for g in self.tuning_before)
        return "; ".join(f"{dof} {metric} ({values((dof, metric))})" for dof, metric in self.differences)

    @property
    def blind_closure(self) -> float:
        return closure(self.blind_before, self.blind_after, self.fit_cells) if self.blind_after else float("nan")

    def flagged_cells(self, gaps: list[Gap]) -> list[tuple[str, str, str]]:
        """(run, DOF, metric) of every flagged cell."""
        cells = self.settings.cells()
        return [(g.run, *cells[i]) for g in gaps for i in np.flatnonzero(g.flagged)]

    def as_dict(self) -> dict:
        chosen = self.candidate(self.chosen) if self.chosen else None
        return {"verdict": self.verdict, "chosen": self.chosen, "reason": self.reason,
                "values": chosen.values if chosen else None,
                "tuning_runs": self.tuning, "blind_runs": self.blind,
                "tuning_closure": chosen.closure if chosen else None,
                "blind_closure": None if math.isnan(self.blind_closure) else self.blind_closure,
                "baseline_score": self.baseline_score, "coherence_deficit": self.coherence_deficit,
                "baseline_mismatches": [{**m.__dict__, "text": m.text()} for m in self.mismatches],
                "differences": [list(cell) for cell in self.differences],
                "undriven": [list(cell) for cell in self.undriven],
                "flagged": [list(c) for c in self.flagged_cells(self.baseline)],
                "baseline": [g.as_dict(self.settings) for g in self.baseline],
                "blind_after": [g.as_dict(self.settings) for g in self.blind_after],
                "candidates": [c.as_dict(self.settings) for c in self.candidates],
                "first_round": [{key: value for key, value in c.as_dict(self.settings).items() if key != "gaps"}
                                | {"cell_closure": {f"{dof}.{metric}": cells_closure(
                                    plain_gaps(c, self.tuning_before, self.window_before), c.gaps, i)
                                                    for i, (dof, metric) in enumerate(self.settings.cells())
                                                    if any(g.flagged[i] for g in self.tuning_before)}}
                                for c in self.first_round],
                "finding": self.finding_dict(),
                "model_runs": self.model_runs}

    def finding_dict(self) -> dict | None:
        """The named effect, or the term read off the mismatch, with its values and closures."""
        if self.chosen:
            c = self.candidate(self.chosen)
            return {"effect": c.effect, "values": c.values, "as": "effect", "tuning_closure": c.closure,
                    "blind_closure": None if math.isnan(self.blind_closure) else self.blind_closure}
        if self.reading is None:
            return None
        tuning, blind = self.reading_closure
        cells = [f"{dof}.{metric}" for dof, metric in self.reading_cell_names]
        return {"effect": self.reading.effect, "values": self.reading.values, "as": "term", "cells": cells,
                "tuning_closure": tuning, "blind_closure": None if math.isnan(blind) else blind}


def peak_period_s(run: MeasuredRun) -> float:
    """Tp of a run's elevation record: the period of its spectral peak (Welch, 10 min segments)."""
    step = run.elevation_step_s
    f, psd = scipy.signal.welch(run.elevation_m, fs=1.0 / step, nperseg=min(run.elevation_m.size, int(600 / step)))
    return float(1.0 / f[1:][np.argmax(psd[1:])])


def baseline_mismatches(tuning: list[MeasuredRun], gaps: list[Gap], settings: GapSettings) -> list[Mismatch]:
    """Cells the plain model misses the same way in every tuning run that measures them
    (``gap.consistent``), with their values in those runs and, for a run in waves, its sea
    state (Hs, Tp)."""
    sea = {i: (tuning[i].hs_m, peak_period_s(tuning[i])) for i in wave_runs(tuning)}
    out = []
    for i in np.flatnonzero(consistent(gaps)):
        runs = [k for k, g in enumerate(gaps) if g.covered[i]]
        out.append(Mismatch(*settings.cells()[i], [float(gaps[k].value[i]) for k in runs],
                            [sea[k][0] for k in runs if k in sea], [sea[k][1] for k in runs if k in sea]))
    return out


def coherence_deficit(measured: list[dict], model: list[dict], dof: str, band_hz: tuple[float, float]) -> float:
    """How far the measured wave-response coherence of ``dof`` in the band lies below the
    model's, averaged over runs."""
    return float(np.mean([band_mean(s["frequency_hz"], s[f"coherence.{dof}"], band_hz)
                          - band_mean(m["frequency_hz"], m[f"coherence.{dof}"], band_hz)
                          for m, s in zip(measured, model)]))


def cell_band(metric: str, settings: GapSettings) -> tuple[float, float] | None:
    """The band a metric is measured in (``lag``: the wave band's; ``offset``: none)."""
    if metric == "lag":
        return settings.bands_hz.get("wave", max(settings.bands_hz.values()))
    name = metric.partition(".")[2]
    return settings.bands_hz.get(name)


def undriven_cells(cells: np.ndarray, before: list[Gap], measured: list[dict], model: list[dict],
                   settings: GapSettings) -> list[tuple[str, str, float, float]]:
    """Of the ``cells`` (set aside: no catalogue effect explains them), those whose band in
    the measured runs holds a response the waves do not drive, beyond the model's: the
    coherent share (``gap.coherent_share``) lower than the model's by more than
    UNDRIVEN_SHARE on average over the tuning runs, in a band judged in every run (where
    neither side has energy, coherence is noise) that holds at least NEGLIGIBLE_BAND of the
    DOF's measured STD in every run (a band the measurement hardly has, judged only for a
    gross ratio, holds no response worth a load of its own: heave below the wave band). A
    transfer function of another form (a wrong coefficient, strip theory against a panel
    method) keeps the response linear in the waves; a load the model lacks and the waves do
    not drive (a rotor's 1P moment, wind) does not. (DOF, metric, measured share, model
    share)."""
    out = []
    for i in np.flatnonzero(cells):
        dof, metric = settings.cells()[i]
        band = cell_band(metric, settings)
        if (band is None or not all(g.judged[i] for g in before)
                or min(band_share(m, dof, band) for m in measured) < NEGLIGIBLE_BAND):
            continue
        share_measured = float(np.mean([coherent_share(m, dof, band) for m in measured]))
        share_model = float(np.mean([coherent_share(s, dof, band) for s in model]))
        if share_model - share_measured > UNDRIVEN_SHARE:
            out.append((dof, metric, share_measured, share_model))
    return out


def measured_spectra(run: MeasuredRun, settings: GapSettings) -> dict:
    return spectra((run.elevation_time_s, run.elevation_m), (run.motion_time_s, run.motion), settings)


def check_runs(runs: list[MeasuredRun], settings: GapSettings) -> None:
    """InputError naming a run that cannot be diagnosed: too short for the transient, or
    motion outside its elevation record; a decay with too few cycles (``decay.check_decay``)."""
    if not wave_runs(runs):
        raise InputError("diagnosis: no measured run in waves")
    if any(r.decay_dof is not None for r in runs) and not settings.decays:
        raise ValueError("diagnosis: decay runs need the gap settings' decay cells (GapSettings(decays=True))")
    for run in runs:
        if run.decay_dof is not None:
            check_decay(run.name, run.motion_time_s, run.motion, run.decay_dof)
            if run.decay_dof not in settings.dofs:
                raise InputError(f"decay {run.name}: {run.decay_dof} is not among the DOFs diagnosed "
                                 f"({', '.join(settings.dofs)})")
            continue
        span = float(run.motion_time_s[-1] - run.motion_time_s[0]) if run.motion_time_s.size else 0.0
        if span < settings.transient_s + 300.0:
            raise InputError(f"run {run.name}: {span:.0f} s of motion; the diagnosis needs the "
                             f"{settings.transient_s:g} s transient plus at least 300 s")
        if (run.motion_time_s[0] < run.elevation_time_s[0] - 60.0
                or run.motion_time_s[-1] > run.elevation_time_s[-1] + 60.0):
            raise InputError(f"run {run.name}: the motion ({run.motion_time_s[0]:.0f}-{run.motion_time_s[-1]:.0f} s) "
                             f"is not within the wave elevation record ({run.elevation_time_s[0]:.0f}-"
                             f"{run.elevation_time_s[-1]:.0f} s)")


def check_window(fit_window_s: float | None, settings: GapSettings) -> None:
    """InputError if the fit window is too short to measure a gap in."""
    if fit_window_s and fit_window_s < settings.transient_s + 300.0:
        raise InputError(f"fit window {fit_window_s:g} s: needs the {settings.transient_s:g} s transient plus at "
                         "least 300 s (or 0: fit on whole records)")


def fit_budget(effect: Effect, max_evaluations: int, held: int = 0) -> int:
    """The points a fit evaluates at most from its first start: each least-squares evaluation
    and its Jacobian's steps (over the parameters not ``held`` fixed); a grid fit's grid and
    refinement. (A restarted fit evaluates more; its count corrects the expected work.)"""
    if grid_fitted(effect) and not held:
        return len(grid(effect)) + 4 * len(effect.parameters)
    return max_evaluations * (1 + len(effect.parameters) - held)


def diagnose(tuning: list[MeasuredRun], blind: list[MeasuredRun], evaluate: Callable, settings: GapSettings,
             effects: dict[str, Effect] | None = None, max_evaluations: int = 4,
             fit_window_s: float | None = FIT_WINDOW_S, progress: Work | None = None,
             platform: Platform | None = None) -> Diagnosis:
    """Diagnose the gap between the model and the measured runs. ``evaluate(jobs,
    description)`` runs replay jobs (``Job``, e.g. runner.replay_job) over ``tuning +
    blind`` in that order. Tuning records longer than ``fit_window_s`` are fitted on their
    first ``fit_window_s`` (None or 0: whole records). The model runs are counted in
    ``progress`` (e.g. a runner.Progress, which logs them). ``platform``, the model's, sizes
    the effects that add to a term it has against its own (``share_concern``). Free decays
    (``MeasuredRun.decay_dof``; ``settings.decays``) are tuning runs: their cells join every
    fit; the spectra, the sea-state concerns and the fit window are the wave runs'."""
    blind_decays = [r.name for r in blind if r.decay_dof is not None]
    if blind_decays:
        raise InputError(f"decay {blind_decays[0]}: free decays are tuning runs, not blind ones")
    check_runs(tuning + blind, settings)
    check_window(fit_window_s, settings)
    steps = _Diagnosing(tuning, blind, evaluate, settings, effects or CATALOGUE, max_evaluations,
                       fit_window(tuning, fit_window_s), progress if progress is not None else Work(), platform)
    diagnosis = steps.plain()
    if not any(g.flagged.any() for g in diagnosis.tuning_before):
        return steps.nothing_flagged()
    steps.plain_in_window()
    candidates = steps.fit_all(None)
    # flagged cells no plausible candidate explains are the baseline's: set them aside and
    # test the effects on what remains
    unexplained = unexplained_cells(diagnosis.tuning_before, candidates, steps.effects, diagnosis.window_before)
    if unexplained.any():
        candidates = steps.fit_remaining(~unexplained, candidates)
    diagnosis.candidates = candidates
    return steps.chosen(candidates)


class _Diagnosing:
    """A diagnosis under way, step by step (``diagnose`` composes them): its runs, its model
    runs (``evaluate``, counted in ``progress``, each phase's most expected before it
    starts), the fit window (None: whole records) and the plain model's gaps."""

    def __init__(self, tuning: list[MeasuredRun], blind: list[MeasuredRun], evaluate: Callable,
                 settings: GapSettings, effects: dict[str, Effect], max_evaluations: int, window: float | None,
                 progress: Work, platform: Platform | None) -> None:
        self.tuning, self.blind, self.runs = tuning, blind, tuning + blind
        self.settings, self.effects, self.max_evaluations = settings, effects, max_evaluations
        self.window, self.progress, self.platform = window, progress, platform
        self.evaluate = tracked(evaluate, self.runs, progress)
        self.n_tuning = len(tuning)
        self.waves = wave_runs(tuning)
        self.whole_s = [model_s(r) for r in self.runs]
        self.fit_run_s = [model_s(r, window) for r in tuning]
        self.diagnosis: Diagnosis  # (``plain``)

    def expect_fits(self, sign: int = 1) -> None:
        """Every candidate's most runs: its fit's points, then its whole records (``sign`` -1:
        given back)."""
        n, window = self.n_tuning, self.window
        budget = sum(fit_budget(e, self.max_evaluations) for e in self.effects.values())
        self.progress.expect(sign * (budget * n + (len(self.effects) * n if window else 0)),
                             sign * (budget * sum(self.fit_run_s)
                                     + (len(self.effects) * sum(self.whole_s[:n]) if window else 0.0)))

    def plain(self) -> Diagnosis:
        """The plain model on every run: the diagnosis's gaps before any effect, its spectra,
        the coherence deficit and the baseline mismatches. The runs expected: the plain
        model (and its fit window), the fits, and the chosen effect on every run."""
        runs, n, window = self.runs, self.n_tuning, self.window
        self.progress.expect(2 * len(runs) + (n if window else 0),
                             2 * sum(self.whole_s) + (sum(self.fit_run_s) if window else 0.0))
        self.expect_fits()
        first = self.evaluate([(None, {}, i, i in self.waves) for i in range(len(runs))], "plain model")
        baseline = [g for g, _ in first]
        measured = [measured_spectra(self.tuning[i], self.settings) for i in self.waves]
        model_spectra = [first[i][1] for i in self.waves]
        lf = self.settings.bands_hz.get("low_frequency", min(self.settings.bands_hz.values()))
        deficit = coherence_deficit(measured, model_spectra, self.settings.dofs[0], lf)
        diagnosis = Diagnosis(self.settings, [r.name for r in self.tuning], [r.name for r in self.blind], baseline,
                              [], "no significant gap", None, "", baseline_score=score(baseline[:n], 0),
                              coherence_deficit=deficit, model_runs=len(runs))
        diagnosis.spectra = {self.tuning[i].name: {"measured": m, "model": s}
                             for i, m, s in zip(self.waves, measured, model_spectra)}
        diagnosis.mismatches = baseline_mismatches(self.tuning, diagnosis.tuning_before, self.settings)
        self.diagnosis = diagnosis
        return diagnosis

    def nothing_flagged(self) -> Diagnosis:
        """The diagnosis of runs none of whose cells is flagged: no fit; the runs expected for
        them given back."""
        n, window = self.n_tuning, self.window
        self.diagnosis.reason = "no cell of the tuning runs is both significant and beyond its tolerance"
        self.progress.expect(-len(self.runs) - (n if window else 0),
                             -sum(self.whole_s) - (sum(self.fit_run_s) if window else 0.0))
        self.expect_fits(-1)
        self.progress.done(0, 0.0, final=True)
        return self.diagnosis

    def plain_in_window(self) -> None:
        """The plain model over the fit window (if any); from here on every model run is
        judged in the cells the plain model of the same run and span is (``judged_as_plain``)."""
        window, diagnosis = self.window, self.diagnosis
        if window:
            jobs = [(None, {}, i, False, window) for i in range(self.n_tuning)]
            diagnosis.window_before = [g for g, _ in self.evaluate(jobs, "plain model, fit window")]
        diagnosis.model_runs += len(diagnosis.window_before)
        self.evaluate = judged_as_plain(self.evaluate, diagnosis.baseline, window, diagnosis.window_before)

    def fit_remaining(self, remaining: np.ndarray, first_round: list[CandidateFit]) -> list[CandidateFit]:
        """The candidates fitted again to the ``remaining`` flagged cells, the others set
        aside as the baseline's; with no flagged cell left, the first round's candidates,
        none of them fitting."""
        diagnosis = self.diagnosis
        diagnosis.fit_cells, diagnosis.first_round = remaining, first_round
        spectra = [diagnosis.spectra[self.tuning[i].name] for i in self.waves]
        diagnosis.undriven = undriven_cells(~remaining, [diagnosis.tuning_before[i] for i in self.waves],
                                            [s["measured"] for s in spectra], [s["model"] for s in spectra],
                                            self.settings)
        diagnosis.baseline_score = score(diagnosis.tuning_before, 0, remaining, diagnosis.tuning_before)
        if any((g.flagged & remaining).any() for g in diagnosis.tuning_before):
            self.expect_fits()
            return self.fit_all(remaining)
        for c in first_round:
            c.fits = False
        return first_round

    def fit_all(self, mask: np.ndarray | None) -> list[CandidateFit]:
        """Every candidate fitted to the flagged cells of ``mask`` (None: all), each in a
        thread of its own, judged; plausible fits ranked first, screened ones last."""
        before = self.diagnosis.tuning_before
        flagged = np.any([g.flagged for g in before], axis=0) & (mask if mask is not None else True)
        pool = ThreadPoolExecutor(max_workers=len(self.effects))
        try:
            fitted = list(pool.map(lambda effect: self.fit(effect, mask, flagged), self.effects.values()))
        finally:  # interrupted (Ctrl-C), the fits under way are not waited for: their runs end with the cluster
            pool.shutdown(wait=False, cancel_futures=True)
        base = score(before, 0, mask, before)
        for c in fitted:
            judge(c, self.effects[c.effect], base, before, self.settings, mask)
        self.diagnosis.model_runs += sum(c.model_runs for c in fitted)
        return sorted(fitted, key=rank)

    def fit(self, effect: Effect, mask: np.ndarray | None, flagged: np.ndarray) -> CandidateFit:
        """One candidate fitted in the fit window; replayed over the whole records unless it
        is screened out there (it then keeps the window's figures); moved into its plausible
        range if a plausible point explains nearly as well (``plausible_refit``)."""
        n, window, diagnosis = self.n_tuning, self.window, self.diagnosis
        before, window_before = diagnosis.tuning_before, diagnosis.window_before
        values, gaps, count = self.fitted_in_window(effect, mask)
        screened = bool(window) and window_closure(before, window_before, gaps, mask) < SCREEN_CLOSURE
        if screened:  # its figures stay the fit window's
            self.progress.expect(-n, -sum(self.whole_s[:n]))
        elif window:
            results = self.evaluate([(effect.name, values, i, False) for i in range(n)],
                                    f"{effect.name}: whole records")
            gaps, count = [g for g, _ in results], count + n
        span, plain = (window, window_before) if screened else (None, before)

        def closure_of(g: list[Gap]) -> float:
            return window_closure(before, window_before, g, mask) if screened else closure(before, g, mask)

        def refit_within(held: dict[str, float], start: dict[str, float]) -> tuple[dict[str, float], list[Gap], int]:
            """The fit again with ``held`` fixed (``Refit``), over the candidate's span."""
            budget = fit_budget(effect, self.max_evaluations, len(held))
            self.progress.expect(budget * n, budget * sum(self.fit_run_s))
            refitted, gaps, count = self.fitted_in_window(effect, mask, held, start,
                                                          f"{effect.name}: within its plausible range")
            if window and span is None:
                gaps, count = self.replayed(effect, refitted, None), count + n
            return refitted, gaps, count

        p = len(effect.parameters)
        fitted = CandidateFit(effect.name, values, gaps, score(gaps, p, mask, plain), closure_of(gaps), count,
                              window_s=span)
        explained = explained_cells(fitted, flagged, before, window_before)
        fitted = plausible_refit(fitted, effect, lambda v: self.replayed(effect, v, span), closure_of,
                                 lambda g: score(g, p, mask, plain),
                                 kept_share(plain, fitted.gaps, explained, closure_of), refit_within)
        return replace(fitted, size_concern=share_concern(effect, fitted.values, [self.tuning[i] for i in self.waves],
                                                          self.platform))

    def fitted_in_window(self, effect: Effect, mask: np.ndarray | None, held: dict[str, float] | None = None,
                         start: dict[str, float] | None = None, description: str | None = None
                         ) -> tuple[dict[str, float], list[Gap], int]:
        """``fit_effect`` on the fit window, its model runs expected and counted."""
        n, budget = self.n_tuning, fit_budget(effect, self.max_evaluations, len(held or {}))
        restarts_expected = []

        def restarted() -> None:  # a restart may take a fit's budget again
            restarts_expected.append(budget)
            self.progress.expect(budget * n, budget * sum(self.fit_run_s))

        plain = self.diagnosis.window_before if self.window else self.diagnosis.tuning_before
        values, gaps, count = fit_effect(effect, self.evaluate, list(range(n)), self.max_evaluations,
                                         description or effect.name, mask, self.window, plain, restarted, held, start)
        expected = budget + sum(restarts_expected)
        self.progress.expect(count - expected * n, (count / n - expected) * sum(self.fit_run_s))
        return values, gaps, count

    def replayed(self, effect: Effect, values: dict[str, float], duration_s: float | None) -> list[Gap]:
        """The tuning runs at ``values`` (their first ``duration_s``; None: whole), counted."""
        self.progress.expect(self.n_tuning, sum(model_s(r, duration_s) for r in self.tuning))
        jobs = [(effect.name, values, i, False) + ((duration_s,) if duration_s else ()) for i in range(self.n_tuning)]
        return [g for g, _ in self.evaluate(jobs, f"{effect.name}: nearest plausible values")]

    def chosen(self, candidates: list[CandidateFit]) -> Diagnosis:
        """The verdict: the best fitting candidate (``_choose``) replayed on every run, kept if
        its blind closure is at least BLIND_SHARE of its tuning closure, else the next one;
        none left: unexplained."""
        diagnosis, runs, n = self.diagnosis, self.runs, self.n_tuning
        first_choice = True
        while True:
            fitting = [c for c in candidates if c.fits]
            if not fitting:
                best = candidates[0]
                diagnosis.verdict, diagnosis.chosen = "unexplained", None
                diagnosis.reason = (f"no candidate closes {MIN_CLOSURE:.0%} of the gap with strong evidence and "
                                    f"plausible values; the nearest, {best.effect}, closes {best.closure:.0%}"
                                    + (f" in the first {best.window_s:g} s" if best.window_s else "")
                                    + (f" ({'; '.join(best.concerns)})" if best.concerns else ""))
                if first_choice:
                    self.progress.expect(-len(runs), -sum(self.whole_s))
                return self.confirmed(with_mismatches(diagnosis, None, self.effects))
            chosen, reason = _choose(fitting, self.effects, diagnosis.coherence_deficit, self.settings)
            diagnosis.verdict, diagnosis.chosen, diagnosis.reason = "explained", chosen.effect, reason
            jobs = [(chosen.effect, chosen.values, i, i in self.waves) for i in range(len(runs))]
            if not first_choice:
                self.progress.expect(len(runs), sum(self.whole_s))
            first_choice = False
            after = self.evaluate(jobs, f"{chosen.effect}: all runs")
            diagnosis.model_runs += len(jobs)
            diagnosis.blind_after = [g for g, _ in after[n:]]
            for i in self.waves:
                diagnosis.spectra[self.tuning[i].name]["model + effect"] = after[i][1]
            if not self.blind or diagnosis.blind_closure >= BLIND_SHARE * chosen.closure:
                return self.confirmed(with_mismatches(diagnosis, chosen, self.effects))
            chosen.concerns.append(f"its blind closure, {diagnosis.blind_closure:.0%}, is below {BLIND_SHARE:.0%} "
                                   f"of its tuning closure, {chosen.closure:.0%}")
            chosen.fits = False
            diagnosis.blind_after = []
            candidates.sort(key=rank)

    def confirmed(self, diagnosis: Diagnosis) -> Diagnosis:
        """The diagnosis, its term reading (if any) replayed on the blind runs and kept only
        if it closes there at least BLIND_SHARE of what it closes on the tuning runs, both
        over whole records: a reading screened out in the fit window is replayed on the
        tuning runs' whole records too (``whole_records``)."""
        reading, n = diagnosis.reading, self.n_tuning
        if reading is not None and self.blind:
            replayed = range(len(self.runs)) if reading.window_s is not None else range(n, len(self.runs))
            self.progress.expect(len(replayed), sum(self.whole_s[i] for i in replayed))
            after = [g for g, _ in self.evaluate([(reading.effect, reading.values, i, False) for i in replayed],
                                                 f"{reading.effect}: whole records")]
            diagnosis.model_runs += len(after)
            if reading.window_s is not None:
                diagnosis.reading = whole_records(reading, after[:n], diagnosis.tuning_before,
                                                  len(self.effects[reading.effect].parameters))
                after = after[n:]
            confirm_reading(diagnosis, after)
        self.progress.done(0, 0.0, final=True)
        return state_reading(diagnosis, self.effects)


def judge(candidate: CandidateFit, effect: Effect, base_score: float, before: list[Gap], settings: GapSettings,
          mask: np.ndarray | None = None) -> None:
    """Set a fitted candidate's concerns (``concerns``; a failed fit, ``CandidateFit.failed``,
    says so first) and whether it fits: it beats the plain model's score ``base_score`` by
    MIN_EVIDENCE, closes MIN_CLOSURE of the gap, raises no concern and was replayed whole."""
    c = candidate
    c.concerns = ([f"fit failed: it leaves the gap larger than the plain model (closure {c.closure:.0%}) from "
                   "every start"] if c.failed else []) + ([c.size_concern] if c.size_concern else []) + concerns(
        effect, c.values, before, settings, mask)
    c.fits = (c.score < base_score - MIN_EVIDENCE and c.closure >= MIN_CLOSURE and not c.concerns
              and c.window_s is None)


def rank(c: CandidateFit) -> tuple:
    """Candidates' order: plausible before those with a concern, fully replayed before
    screened ones, then by score."""
    return bool(c.concerns), c.window_s is not None, c.score


def scales_a_term(c: CandidateFit, effects: dict[str, Effect]) -> bool:
    """Whether a fit is of a candidate scaling one of the model's own terms (``Effect.term``)
    and did not fail."""
    effect = effects.get(c.effect)
    return effect is not None and effect.term is not None and not c.failed


def term_reading(i: int, candidates: list[CandidateFit], effects: dict[str, Effect], before: list[Gap],
                 window_before: list[Gap]) -> tuple[CandidateFit, str] | None:
    """Of the candidates that scale a term the model has (``Effect.term``) and whose fit did
    not fail, the one that closes most of cell ``i``'s gap, if it explains it (``explains``,
    whatever its plausibility): (that candidate, the cell read as that term's error, e.g. "the
    model's slow drift is 10 times too strong (model_slow_drift closes 92 % of it;
    drift_scale = 0.1 lies outside its plausible 0.5 to 2 (...))"). None if none does."""
    best: tuple[float, CandidateFit] | None = None
    for c in candidates:
        if not scales_a_term(c, effects):
            continue
        plain = plain_gaps(c, before, window_before)
        if explains(plain, c.gaps, i) and (best is None or cells_closure(plain, c.gaps, i) > best[0]):
            best = cells_closure(plain, c.gaps, i), c
    if best is None:
        return None
    share, c = best
    implausible = c.value_concerns(effects[c.effect])
    return c, (f"{effects[c.effect].term(c.values)} ({c.effect} closes {share:.0%} of it"
                      + "".join(f"; {concern}" for concern in implausible) + ")")


def leading_reading(left: list[Mismatch], cells: list[tuple[str, str]], before: list[Gap],
                    window_before: list[Gap], candidates: list[CandidateFit],
                    effects: dict[str, Effect]) -> tuple[CandidateFit | None, np.ndarray | None]:
    """Of the terms read off the baseline mismatches no effect explains (``Mismatch.term_by``,
    ``term_reading``), those at plausible and material values (no ``value_concerns``), the one
    whose cells carry most of the mismatch (sum of the plain model's squared residuals
    ``before``): (its first fit, the cells it reads); (None, None)
    if there is none. A mismatch that a scale of one of the model's own terms closes is what
    the diagnosis names when no effect is named: "the model's slow drift is 1.7 times too
    weak" is a finding, and the one an engineer acts on next. A term that explains every
    left mismatch cell that one explains and more, with no more parameters, reads the
    mismatch more fully and is the reading instead (``wider_reading``)."""
    found: dict[str, tuple[CandidateFit, np.ndarray]] = {}
    for m in left:
        c = next((c for c in candidates if c.effect == m.term_by), None)
        if c is None or c.value_concerns(effects[c.effect]):
            continue
        mask = found.setdefault(c.effect, (c, np.zeros(len(cells), dtype=bool)))[1]
        mask[cells.index((m.dof, m.metric))] = True
    if not found:
        return None, None

    best = max(found, key=lambda name: sum(float(g.residual[i] ** 2) for g in before
                                           for i in np.flatnonzero(found[name][1])))
    return wider_reading(found[best], left, cells, before, window_before, candidates, effects)


def mismatch_cells(mismatches: list[Mismatch], cells: list[tuple[str, str]]) -> np.ndarray:
    """The mask of the mismatches' cells among ``cells``."""
    mismatched = {(m.dof, m.metric) for m in mismatches}
    return np.array([cell in mismatched for cell in cells], dtype=bool)


def explained_cells(candidate: CandidateFit, among: np.ndarray, before: list[Gap],
                    window_before: list[Gap]) -> np.ndarray:
    """The cells of the mask ``among`` that a candidate's fit explains (``explains``)."""
    plain = plain_gaps(candidate, before, window_before)
    out = np.zeros(among.size, dtype=bool)
    for i in np.flatnonzero(among):
        out[i] = explains(plain, candidate.gaps, i)
    return out


def wider_reading(reading: tuple[CandidateFit, np.ndarray], left: list[Mismatch], cells: list[tuple[str, str]],
                  before: list[Gap], window_before: list[Gap], candidates: list[CandidateFit],
                  effects: dict[str, Effect]) -> tuple[CandidateFit, np.ndarray]:
    """The term reading, or the term at plausible and material values (no ``value_concerns``)
    that explains every left mismatch cell the reading's fit explains and more, with no more
    parameters (the one explaining most cells): (its fit, the left mismatch cells it
    explains). A drag too weak and a slow drift too strong move the low-frequency STDs
    alike (they fix only drift_scale^2 / cd_scale), and the drift may close those cells
    best; the free decays, which the drag moves and the drift does not, tell them apart
    only through cells the drift does not explain."""
    fit, _ = reading
    mismatch = mismatch_cells(left, cells)
    own = explained_cells(fit, mismatch, before, window_before)
    wider = []
    for c in candidates:
        if (not scales_a_term(c, effects) or c.effect == fit.effect or c.value_concerns(effects[c.effect])
                or len(effects[c.effect].parameters) > len(effects[fit.effect].parameters)):
            continue
        explained = explained_cells(c, mismatch, before, window_before)
        if not (own & ~explained).any() and (explained & ~own).any():
            wider.append((c, explained))
    return max(wider, key=lambda w: int(w[1].sum())) if wider else reading


def blind_checked_cells(diagnosis: Diagnosis, left: list[Mismatch]) -> np.ndarray:
    """For a term reading none of whose cells the blind runs measure (read off free decays
    alone; blind runs are in waves): the left mismatches' cells the blind runs measure that
    its fit explains on the tuning runs (``explains``), by which the blind runs check it;
    none otherwise."""
    cells = diagnosis.settings.cells()
    measured = np.all([g.covered for g in diagnosis.blind_before], axis=0)
    if (diagnosis.reading_cells & measured).any():
        return np.zeros(len(cells), dtype=bool)
    return explained_cells(diagnosis.reading, mismatch_cells(left, cells) & measured, diagnosis.tuning_before,
                           diagnosis.window_before)


def other_readings(diagnosis: Diagnosis, effects: dict[str, Effect]) -> list[tuple[CandidateFit, list[int]]]:
    """The other terms that read the named term reading's cells as well: each other
    candidate scaling one of the model's terms, whose first fit did not fail and lies at
    plausible and material values (no ``value_concerns``), with the reading's cells it
    explains (``explains``). A drag 1.6 times too strong and a slow drift 1.27 times too weak
    move the low-frequency STDs alike (they fix only drift_scale^2 / cd_scale): the verdict
    says so rather than let the first name stand alone."""
    if diagnosis.reading is None or diagnosis.reading_cells is None:
        return []
    out = []
    for c in diagnosis.first_fits:
        if (not scales_a_term(c, effects) or c.effect == diagnosis.reading.effect
                or c.value_concerns(effects[c.effect])):
            continue
        cells = np.flatnonzero(explained_cells(c, diagnosis.reading_cells, diagnosis.tuning_before,
                                               diagnosis.window_before)).tolist()
        if cells:
            out.append((c, cells))
    return out


def state_reading(diagnosis: Diagnosis, effects: dict[str, Effect]) -> Diagnosis:
    """The verdict's last words on the term reading kept (if any): the term's error it
    names, the share of its cells' gap it closes on the tuning runs, and the other terms
    that read its cells as well (``other_readings``), with the cells they do not explain."""
    if diagnosis.reading is not None:
        tuning_share, _ = diagnosis.reading_closure
        diagnosis.reason += (f"; named: {effects[diagnosis.reading.effect].term(diagnosis.reading.values)} "
                             f"({diagnosis.reading.effect} closes {tuning_share:.0%} of the gap of the mismatches it "
                             "reads)")
        cells = diagnosis.settings.cells()
        others, apart = [], True
        for c, read in other_readings(diagnosis, effects):
            unread = [i for i in np.flatnonzero(diagnosis.reading_cells) if i not in read]
            apart &= bool(unread)
            others.append(f"{effects[c.effect].term(c.values)} ({c.effect} explains "
                          + ", ".join(" ".join(cells[i]) for i in read)
                          + (", not " + ", ".join(" ".join(cells[i]) for i in unread) if unread else "") + ")")
        if others:
            diagnosis.reason += ("; read as well, at plausible values, as: " + "; ".join(others)
                                 + (": the cells they do not explain tell them apart" if apart
                                    else ": these runs do not tell them apart"))
    return diagnosis


def whole_records(candidate: CandidateFit, gaps: list[Gap], before: list[Gap], n_parameters: int) -> CandidateFit:
    """A candidate fitted on every cell and screened out in the fit window (its gaps, score
    and closure the window's) with its tuning gaps over the whole records, ``gaps`` (the
    plain model's: ``before``)."""
    return replace(candidate, gaps=gaps, score=score(gaps, n_parameters, None, before),
                   closure=closure(before, gaps), model_runs=candidate.model_runs + len(gaps), window_s=None)


def confirm_reading(diagnosis: Diagnosis, blind_after: list[Gap]) -> Diagnosis:
    """Keep the term reading (``Diagnosis.reading``) with its blind runs' gaps at its values
    (not refitted) if it closes some of its cells' gap on the tuning runs (over their whole
    records: a reading screened out in the fit window was read off the window) and closes on
    the blind runs at least BLIND_SHARE of that, as a named effect must; otherwise it is not
    named, and the verdict says why."""
    diagnosis.reading_blind_after = blind_after
    tuning_share, blind_share = diagnosis.reading_closure
    effect, why = diagnosis.reading.effect, None
    if not tuning_share > 0.0:
        why = f"{effect} closes {tuning_share:.0%} of its cells' gap on the tuning runs' whole records"
    elif blind_share < BLIND_SHARE * tuning_share:
        why = (f"{effect} closes {blind_share:.0%} of its cells' gap on the blind runs, below {BLIND_SHARE:.0%} of "
               f"its {tuning_share:.0%} on the tuning runs")
    if why:
        diagnosis.reason += f"; {why}: not named"
        diagnosis.reading, diagnosis.reading_cells, diagnosis.reading_blind_after = None, None, []
    return diagnosis


def additional_cells(before: list[Gap], after: list[Gap], mismatch: np.ndarray) -> np.ndarray:
    """The cells an effect explains (``explains``) that are flagged in a tuning run and lie
    outside the baseline mismatch's cells ``mismatch``: what an effect named "additionally"
    to a baseline mismatch must have."""
    flagged = np.any([g.flagged for g in before], axis=0)
    return np.array([bool(flagged[i]) and not mismatch[i] and explains(before, after, i)
                     for i in range(flagged.size)])


def with_mismatches(diagnosis: Diagnosis, chosen: CandidateFit | None, effects: dict[str, Effect]) -> Diagnosis:
    """The verdict with the baseline mismatches. Mark those the named effect explains
    (``explains``); any left make the verdict 'baseline mismatch', the effect (if any)
    coming 'additionally', and only if it explains a flagged cell outside the left
    mismatches' (``additional_cells``): one that closes only the mismatch's cells is not
    named. A left mismatch that a scale of one of the model's own terms explains (first
    fits, ``term_reading``) is read as that term's error ("the model's slow drift is 10
    times too strong") rather than as not explained. Differences set aside that are not
    consistent (``Diagnosis.differences``) are said; when nothing is named and they are all
    that is flagged, they too are the baseline's. A set-aside cell whose measured response
    the waves do not drive (``undriven_cells``) makes the verdict 'unexplained' when nothing
    is named."""
    cells = diagnosis.settings.cells()
    before = diagnosis.tuning_before
    if chosen is not None and effects[chosen.effect].term is not None:
        diagnosis.reason += f"; {effects[chosen.effect].term(chosen.values)}"
    for m in diagnosis.mismatches:
        i = cells.index((m.dof, m.metric))
        if chosen is not None and explains(before, chosen.gaps, i):
            m.explained_by = chosen.effect
            if effects[chosen.effect].term is not None:
                m.term, m.term_by = effects[chosen.effect].term(chosen.values), chosen.effect
                m.term_values = chosen.values
    left = [m for m in diagnosis.mismatches if m.explained_by is None]
    for m in left:
        reading = term_reading(cells.index((m.dof, m.metric)), diagnosis.first_fits, effects, before,
                               diagnosis.window_before)
        if reading:
            m.term, m.term_by, m.term_values = reading[1], reading[0].effect, reading[0].values
    if left and chosen is not None:
        mismatch = mismatch_cells(left, cells)
        if not additional_cells(before, chosen.gaps, mismatch).any():
            diagnosis.reason = (f"{chosen.effect} closes {chosen.closure:.0%} of the tuning gap but explains no "
                                "flagged cell beyond the baseline mismatch's: not named")
            diagnosis.chosen, diagnosis.blind_after, chosen = None, [], None
            for spectra in diagnosis.spectra.values():
                spectra.pop("model + effect", None)
    if chosen is None and left and not diagnosis.undriven:
        diagnosis.reading, diagnosis.reading_cells = leading_reading(
            left, cells, before, diagnosis.window_before, diagnosis.first_fits, effects)
        if diagnosis.reading is not None and diagnosis.blind_before:
            diagnosis.reading_cells |= blind_checked_cells(diagnosis, left)
    if left:
        effect = (f"; additionally {chosen.effect} explains part of the gap ({diagnosis.reason})" if chosen
                  else f"; no effect explains the rest ({diagnosis.reason})")
        diagnosis.verdict = "baseline mismatch"
        diagnosis.reason = "baseline: " + "; ".join(m.text() for m in left) + effect
    elif chosen is None and diagnosis.differences and not any(g.flagged[diagnosis.fit_cells].any()
                                                              for g in before):
        diagnosis.verdict = "baseline mismatch"  # every flagged cell is a difference no effect moves
    if diagnosis.differences:
        diagnosis.reason += ("; set aside as the baseline's, flagged in some runs only or of changing sign, no "
                             f"catalogue effect explaining them: {diagnosis.differences_text()}")
    if diagnosis.undriven:
        undriven = ", ".join(f"{dof} {metric} (coherent share {measured:.2f} measured, {model:.2f} modelled)"
                             for dof, metric, measured, model in diagnosis.undriven)
        if chosen is None:
            diagnosis.verdict = "unexplained"
        diagnosis.reason = (f"a response the waves do not drive, which neither the model nor the catalogue has, in "
                            f"{undriven}; " + diagnosis.reason)
    return diagnosis


def _choose(fitting: list[CandidateFit], effects: dict[str, Effect], deficit: float,
            settings: GapSettings) -> tuple[CandidateFit, str]:
    """The best fitting candidate; within TIE of it, the wave-response coherence decides."""
    tied = [c for c in fitting if c.score <= fitting[0].score + TIE]
    chosen, reason = fitting[0], f"best score, closes {fitting[0].closure:.0%} of the tuning gap"
    if len(tied) > 1:
        incoherent = deficit > COHERENCE_DEFICIT
        agreeing = [c for c in tied if effects[c.effect].wave_coherent != incoherent]
        if agreeing and agreeing[0] is not chosen:
            chosen = agreeing[0]
            reason = (f"ties with {fitting[0].effect} on score; the measured low-frequency {settings.dofs[0]} is "
                      f"{'less' if incoherent else 'no less'} coherent with the waves than the model's "
                      f"(deficit {deficit:.2f}), which points to a "
                      f"{'wave-incoherent' if incoherent else 'wave-coherent'} load")
        else:
            reason += f"; also fit: {', '.join(c.effect for c in tied if c is not chosen)}"
    return chosen, reason
