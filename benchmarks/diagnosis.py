"""Benchmark of the gap diagnosis (``fowt-sim diagnose``'s internals) on seven 3-hour runs.

The runs are the twin benchmark's "measured" runs (``benchmark.truth_run``: the model with
slow drift injected, 1 % sensor noise, small property errors, a finer step): tuning LC5.0-5.4,
blind LC6.1 and LC6.2, made once and kept in ``out/bench_diagnosis/`` (not timed).

Prints: the wall time of one diagnosis of the seven runs (every catalogue effect), its
verdict, the model runs made (full-length and fit-window replays) and the cost per replay;
then the scaling of a fixed batch of replays on 1, 2 and 4 workers of a LocalCluster (one
thread each) with speed-up and efficiency, beside the same batch on as many plain processes
(no Dask: the ceiling the cores set), and what a 16-worker cluster would take for the
diagnosis (its work spread over 16 workers, but no shorter than its chain of dependent
replays). The machine's cores and load average are printed beside each figure.

    python benchmarks/diagnosis.py [--hours 3] [--workers 2] [--scaling 1 2 4] [--skip-diagnosis]
"""
from __future__ import annotations

import argparse
import logging
import math
import os
import pickle
import time
from pathlib import Path

from fowt_hydro_sim.physics.config import load_platform
from fowt_hydro_sim.studies.cluster import dask_client, map_with_progress
from fowt_hydro_sim.studies.diagnosis.benchmark import Scenario, truth_run
from fowt_hydro_sim.studies.diagnosis.gap import GapSettings
from fowt_hydro_sim.studies.diagnosis.method import FIT_WINDOW_S, diagnose, job_duration_s, job_s
from fowt_hydro_sim.studies.diagnosis.runner import REPLAY_DT_S, Progress, cluster_evaluate, replay_job
from fowt_hydro_sim.studies.replay import PREROLL_S, Variant, replay

TUNING = ("lc5.0", "lc5.1", "lc5.2", "lc5.3", "lc5.4")
BLIND = ("lc6.1", "lc6.2")
SCENARIO = Scenario("slow_drift#2", "injected", "slow_drift", {"drift_coefficient_n_m2": 3.0e5}, 1017)
CACHE = Path("out/bench_diagnosis")


def _truth(case: str, platform, duration_s: float):
    return truth_run(SCENARIO, case, platform, duration_s)


def measured_runs(hours: float, workers: int) -> list:
    """The seven runs (tuning then blind), made on a LocalCluster the first time, then read back."""
    path = CACHE / f"runs_{hours:g}h.pkl"
    if path.exists():
        return pickle.loads(path.read_bytes())
    platform = load_platform("windmoor12")
    with dask_client(None, workers) as client:
        runs = map_with_progress(client, _truth, TUNING + BLIND, "measured runs", platform=platform,
                                 duration_s=3600.0 * hours)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(pickle.dumps(runs))
    return runs


class Recorder:
    """``evaluate`` that counts the replays it sends (whole records, fit windows) and their
    replayed seconds, and times each call (for the chain of dependent calls)."""

    def __init__(self, evaluate, runs: list):
        self.evaluate, self.runs = evaluate, runs
        self.calls: list[tuple[str, int, float, float]] = []  # description, jobs, longest job [s], wall [s]
        self.whole = self.window = 0
        self.replayed_s = 0.0

    def __call__(self, jobs: list, description: str = "") -> list:
        start = time.perf_counter()
        results = self.evaluate(jobs, description)
        seconds = [job_s(j, self.runs) for j in jobs]
        self.calls.append((description, len(jobs), max(seconds), time.perf_counter() - start))
        self.whole += sum(job_duration_s(j) is None for j in jobs)
        self.window += sum(job_duration_s(j) is not None for j in jobs)
        self.replayed_s += sum(seconds)
        return results

    def chain_s(self, cost_s_per_s: float, workers: int) -> float:
        """The longest chain of dependent calls (the plain model, one candidate's calls in
        turn, the chosen effect on all runs), each call as rounds of its jobs on ``workers``."""
        per: dict[str, float] = {}
        for description, n, longest_s, _ in self.calls:
            key = description.split(":")[0].replace(", fit window", "")
            per[key] = per.get(key, 0.0) + math.ceil(n / workers) * longest_s * cost_s_per_s
        fixed = sum(v for k, v in per.items() if k == "plain model" or k.endswith("all runs"))
        chosen = [k for k in per if k.endswith("all runs")]
        return fixed + max((v for k, v in per.items() if k != "plain model" and k not in chosen), default=0.0)


def _warm(runs: list, platform) -> None:
    """Compile the kernel and build every run's kinematics table on this worker."""
    for run in runs:
        replay(Variant(platform), run, REPLAY_DT_S, duration_s=60.0)


def replay_cost(runs: list, platform, window_s: float) -> tuple[float, float]:
    """Wall seconds of one whole-record replay and one fit-window replay here (warm)."""
    _warm(runs[:1], platform)
    out = []
    for duration in (None, window_s):
        start = time.perf_counter()
        replay(Variant(platform), runs[0], REPLAY_DT_S, duration)
        out.append(time.perf_counter() - start)
    return out[0], out[1]


def table_cost(run, platform) -> float:
    """Wall seconds to build one run's kinematics table."""
    from fowt_hydro_sim.studies import replay as replay_module
    replay_module._tables.clear()
    start = time.perf_counter()
    _warm([run], platform)
    return time.perf_counter() - start


_SHARED: dict = {}


def _share(runs: list, platform, settings: GapSettings) -> None:
    """A plain worker process's start: keep the runs, platform and settings, sent once."""
    _SHARED.update(runs=runs, platform=platform, settings=settings)


def _plain_replay(job: tuple):
    return replay_job(job, **_SHARED)


def _plain_processes_wall(jobs: list, tuning: list, platform, settings: GapSettings, n: int) -> float:
    """Wall seconds of the jobs on ``n`` plain worker processes (no Dask; the runs sent once
    to each, as the cluster scatters them): the batch run twice, the second timed (the
    first compiles and builds the tables in every process)."""
    from concurrent.futures import ProcessPoolExecutor
    from multiprocessing import get_context
    with ProcessPoolExecutor(n, mp_context=get_context("spawn"), initializer=_share,
                             initargs=(tuning, platform, settings)) as pool:
        list(pool.map(_plain_replay, jobs))
        start = time.perf_counter()
        list(pool.map(_plain_replay, jobs))
        return time.perf_counter() - start


def scaling(runs: list, platform, workers: list[int], window_s: float, variants: int) -> None:
    """The same batch of fit-window replays (slow drift at ``variants`` values on every
    tuning run) on each worker count, tables built and kernels compiled beforehand: on a
    LocalCluster, and on as many plain processes (what the cores give this work without
    Dask, the ceiling of the cluster's speed-up on this machine)."""
    settings = GapSettings()
    tuning = runs[:len(TUNING)]
    os.environ.update({k: "1" for k in ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS")})  # the
    # plain processes start with one BLAS thread each, as Dask's nanny starts its workers
    jobs = [("slow_drift", {"drift_coefficient_n_m2": 5e4 * (k + 1)}, i, False, window_s)
            for k in range(variants) for i in range(len(tuning))]
    print(f"\nscaling: {len(jobs)} replays of {window_s:g} s (+{PREROLL_S:g} s pre-roll), {os.cpu_count()} cores")
    print(f"{'workers':>8s}{'Dask wall [s]':>15s}{'replays/min':>13s}{'speed-up':>10s}{'efficiency':>12s}"
          f"{'plain wall [s]':>16s}{'speed-up':>10s}{'Dask/plain':>12s}{'load':>7s}")
    base = plain_base = None
    for n in workers:
        with dask_client(None, n) as client:
            client.run(_warm, tuning, platform)
            evaluate = cluster_evaluate(client, tuning, platform, settings)
            start = time.perf_counter()
            evaluate(jobs)
            wall = time.perf_counter() - start
        plain = _plain_processes_wall(jobs, tuning, platform, settings, n)
        base, plain_base = base or wall * workers[0], plain_base or plain * workers[0]
        print(f"{n:8d}{wall:15.1f}{60 * len(jobs) / wall:13.1f}{base / wall:10.2f}{base / wall / n:12.2f}"
              f"{plain:16.1f}{plain_base / plain:10.2f}{plain / wall:12.2f}{os.getloadavg()[0]:7.1f}", flush=True)


def diagnosis(runs: list, platform, workers: int, window_s: float) -> Recorder:
    """One diagnosis of the seven runs (every catalogue effect) on ``workers``, timed."""
    settings = GapSettings()
    tuning, blind = runs[:len(TUNING)], runs[len(TUNING):]
    print(f"diagnosis: {len(TUNING)} tuning + {len(BLIND)} blind runs of {runs[0].motion_time_s[-1] / 3600:.1f} h, "
          f"{workers} workers, fit window {window_s:g} s, {os.cpu_count()} cores, load before "
          f"{os.getloadavg()[0]:.1f}", flush=True)
    with dask_client(None, workers) as client:
        recorder = Recorder(cluster_evaluate(client, runs, platform, settings), runs)
        start = time.perf_counter()
        result = diagnose(tuning, blind, recorder, settings, fit_window_s=window_s, progress=Progress())
        wall = time.perf_counter() - start
    print(f"  wall {wall / 60:.1f} min (load after {os.getloadavg()[0]:.1f}); verdict {result.verdict}: "
          f"{result.chosen} {result.reason}")
    if result.chosen:
        print(f"  values {result.candidate(result.chosen).values}, tuning closure "
              f"{result.candidate(result.chosen).closure:.0%}, blind closure {result.blind_closure:.0%}")
    for c in result.candidates:
        print(f"  {c.effect:<26} score {c.score:8.1f} closure {c.closure:6.0%} runs {c.model_runs:4d} "
              f"{'screened' if c.window_s else ''} {'; '.join(c.concerns)}")
    print(f"  replays: {recorder.whole} whole records + {recorder.window} fit windows = "
          f"{recorder.whole + recorder.window} ({result.model_runs} counted by the diagnosis), "
          f"{recorder.replayed_s / 3600:.0f} h replayed, "
          f"{recorder.replayed_s / wall:.0f} x real time")
    recorder.wall_s = wall
    return recorder


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--hours", type=float, default=3.0, help="record length per run")
    parser.add_argument("--workers", type=int, default=2, help="workers of the timed diagnosis")
    parser.add_argument("--fit-window", type=float, default=FIT_WINDOW_S, help="0: fit on whole records")
    parser.add_argument("--scaling", type=int, nargs="*", default=[1, 2, 4], help="worker counts of the scaling test")
    parser.add_argument("--variants", type=int, default=4, help="slow-drift values per run in the scaling batch")
    parser.add_argument("--skip-diagnosis", action="store_true")
    args = parser.parse_args()
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(message)s")
    logging.getLogger("distributed").setLevel(logging.WARNING)
    platform = load_platform("windmoor12")
    runs = measured_runs(args.hours, args.workers)
    whole_s, window_s = replay_cost(runs, platform, args.fit_window)
    table_s = table_cost(runs[1], platform)
    print(f"one replay here (warm, load {os.getloadavg()[0]:.1f}): whole record {whole_s:.1f} s, "
          f"fit window {window_s:.1f} s; a run's kinematics table {table_s:.1f} s (once per run and worker)")
    if not args.skip_diagnosis:
        recorder = diagnosis(runs, platform, args.workers, args.fit_window)
        cost = whole_s / (PREROLL_S + runs[0].motion_time_s[-1])  # wall s per replayed s, one worker
        for n in (16,):
            estimate = max(recorder.replayed_s * cost / n, recorder.chain_s(cost, n)) + len(runs) * table_s
            print(f"  {n} workers (estimate: the work spread over {n}, no less than the chain of dependent "
                  f"replays, plus each worker's {len(runs)} tables): {estimate / 60:.1f} min")
    if args.scaling:
        scaling(runs, platform, args.scaling, args.fit_window if args.fit_window else 1800.0, args.variants)


if __name__ == "__main__":
    main()
