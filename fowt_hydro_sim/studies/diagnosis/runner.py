"""Running the gap diagnosis (method.py): the model runs it asks for (``replay_job``: a
measured run replayed by the plain model or with an effect, and its gap), evaluated in
process or on a Dask cluster; its progress logged as single lines (model runs done of
those expected, time left); and ``fowt-sim diagnose``: measured bags read, diagnosed on a
cluster, the report written."""
from __future__ import annotations

import logging
import math
import time
from collections.abc import Callable

from fowt_hydro_sim.physics.config import HydroOptions, Platform
from fowt_hydro_sim.studies.cluster import dask_client, scatter
from fowt_hydro_sim.studies.diagnosis.decay import decay_gap, replay_decay
from fowt_hydro_sim.studies.diagnosis.effects import CATALOGUE, Effect
from fowt_hydro_sim.studies.diagnosis.gap import Gap, GapSettings, gap, spectra
from fowt_hydro_sim.studies.diagnosis.method import (
    FIT_WINDOW_S,
    Job,
    Work,
    check_runs,
    check_window,
    diagnose,
    job_duration_s,
)
from fowt_hydro_sim.studies.diagnosis.report import summary_lines, write_report
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant, measured_run, replay

log = logging.getLogger(__name__)

REPLAY_DT_S = 0.1  # the replays' step (a basin's motion at 4 Hz needs no finer one)
PROGRESS_EVERY_S = 10.0  # at most one progress line this often


def replay_job(job: Job, runs: list[MeasuredRun], platform: Platform, settings: GapSettings,
               effects: dict[str, Effect] | None = None, dt_s: float = REPLAY_DT_S,
               options: HydroOptions | None = None) -> tuple[Gap, dict | None]:
    """One model run (a cluster task): run ``index`` replayed by the plain model (with
    ``options``) or with an effect at the given values (over the whole record, or its first
    ``duration`` seconds; a decay over its whole record); its gap, and its spectra if asked
    (none for a decay)."""
    name, values, index, with_spectra = job[:4]
    duration_s = job_duration_s(job)
    run = runs[index]
    variant = Variant(platform, options=options)
    if name is not None:
        variant = (effects or CATALOGUE)[name].apply(variant, run, values)
    if run.decay_dof is not None:
        time_s, motion = replay_decay(variant, run, dt_s)
        return decay_gap(run.name, (run.motion_time_s, run.motion), (time_s, motion), run.decay_dof, settings), None
    time_s, motion = replay(variant, run, dt_s, duration_s)
    result = gap(run.name, (run.motion_time_s, run.motion), (time_s, motion), settings)
    if not with_spectra:
        return result, None
    return result, spectra((run.elevation_time_s, run.elevation_m), (time_s, motion), settings)


def in_process(runs: list[MeasuredRun], platform: Platform, settings: GapSettings,
               effects: dict[str, Effect] | None = None, dt_s: float = REPLAY_DT_S,
               options: HydroOptions | None = None) -> Callable[[list[Job], str], list]:
    """``evaluate`` that runs every job here, one after another."""
    return lambda jobs, description="": [replay_job(j, runs, platform, settings, effects, dt_s, options) for j in jobs]


def cluster_evaluate(client, runs: list[MeasuredRun], platform: Platform, settings: GapSettings,
                     effects: dict[str, Effect] | None = None, dt_s: float = REPLAY_DT_S,
                     options: HydroOptions | None = None) -> Callable[[list[Job], str], list]:
    """``evaluate`` that sends the jobs to a Dask cluster (the runs and platform sent once;
    the diagnosis logs the progress of all candidates' runs together)."""
    shared = {"runs": scatter(client, runs), "platform": scatter(client, platform),
              "settings": scatter(client, settings), "effects": scatter(client, effects), "dt_s": dt_s,
              "options": options}

    def evaluate(jobs: list[Job], description: str = "") -> list:
        return client.gather(client.map(replay_job, jobs, pure=False, **shared))
    return evaluate


class Progress(Work):
    """The diagnosis's model runs (``method.Work``) with the time left at the pace so far
    (in replayed seconds), logged as one line at most every ``every_s`` and at the end."""

    def __init__(self, every_s: float = PROGRESS_EVERY_S) -> None:
        super().__init__()
        self.every_s = every_s
        self.start = time.monotonic()
        self._last = -math.inf

    def reported(self, final: bool) -> None:
        """Log ``line`` if ``final`` or ``every_s`` has passed since the last one."""
        now = time.monotonic()
        if final or now - self._last >= self.every_s:
            self._last = now
            log.info(self.line())

    def seconds_left(self) -> float:
        """The time left at the pace so far (NaN before any run is done)."""
        elapsed = time.monotonic() - self.start
        if not self.work_done_s:
            return math.nan
        return elapsed * max(0.0, self.work_expected_s - self.work_done_s) / self.work_done_s

    def line(self) -> str:
        """'diagnosis: 12/40 model runs (25% of the replayed time), 3.0 min left'."""
        left = self.seconds_left()
        share = self.work_done_s / self.work_expected_s if self.work_expected_s else 1.0
        return (f"diagnosis: {self.runs_done}/{self.runs_expected} model runs "
                f"({min(1.0, share):.0%} of the replayed time), "
                + ("time left unknown" if math.isnan(left) else f"{left / 60:.1f} min left"))


def diagnose_bags(tuning: list[str], blind: list[str], platform: Platform, settings: GapSettings,
                  effects: dict[str, Effect], output: str, heading_deg: float = 0.0, max_evaluations: int = 4,
                  dt_s: float = REPLAY_DT_S, scheduler: str | None = None, workers: int | None = None,
                  fit_window_s: float | None = FIT_WINDOW_S, decays: list[tuple[str, str]] | None = None) -> list[str]:
    """``fowt-sim diagnose``: measured bags diagnosed on a Dask cluster, the report written to
    ``output``; returns the summary's lines. ``decays``: (DOF, bag) of free decays, tuning
    runs too (``settings.decays`` must be set)."""
    tuning_runs = ([measured_run(p, heading_deg) for p in tuning]
                   + [measured_run(p, heading_deg, decay_dof=dof) for dof, p in decays or []])
    blind_runs = [measured_run(p, heading_deg) for p in blind]
    check_runs(tuning_runs + blind_runs, settings)  # before any cluster starts
    check_window(fit_window_s, settings)
    with dask_client(scheduler, workers) as client:
        evaluate = cluster_evaluate(client, tuning_runs + blind_runs, platform, settings, effects, dt_s)
        diagnosis = diagnose(tuning_runs, blind_runs, evaluate, settings, effects, max_evaluations, fit_window_s,
                             Progress(), platform)
    return summary_lines(diagnosis) + [f"report: {write_report(diagnosis, output)}"]
