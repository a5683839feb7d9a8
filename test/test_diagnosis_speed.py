"""The diagnosis's speed-ups keep its verdicts: long records fitted on their first part and
then replayed whole, candidates that cannot pass screened out in the fit window, progress
logged as single lines, each run's kinematics table built once (at an FFT-friendly step,
which changes a replay by far less than the gap tolerances)."""
from __future__ import annotations

import logging
import re

import numpy as np
import pytest

from fowt_hydro_sim.physics.config import Platform, load_platform
from fowt_hydro_sim.physics.waves.components import from_elevation_record
from fowt_hydro_sim.physics.waves.kinematics import table_step
from fowt_hydro_sim.rosbag.measured import write_measured_bag
from fowt_hydro_sim.studies import replay as replay_module
from fowt_hydro_sim.studies.diagnosis.benchmark import Scenario, truth_run
from fowt_hydro_sim.studies.diagnosis.effects import CATALOGUE
from fowt_hydro_sim.studies.diagnosis.gap import GapSettings
from fowt_hydro_sim.studies.diagnosis.method import diagnose
from fowt_hydro_sim.studies.diagnosis.report import summary_lines
from fowt_hydro_sim.studies.diagnosis.runner import Progress, in_process
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant, fast_table_step, replay
from fowt_hydro_sim.testing import REPO, fowt_sim

RECORD_S = 1800.0
WINDOW_S = 900.0
DRIFT_N_M2 = 3.0e5


@pytest.fixture(scope="module")
def platform() -> Platform:
    return load_platform("windmoor12")


@pytest.mark.slow
def test_long_records_fitted_on_their_first_part_name_the_effect(platform, caplog):
    """Slow drift injected: fitted on the first 900 s of two 1800 s records, the drift is
    named with its coefficient, the fit's replays are all short, the fitted candidates are
    scored on whole records, and the wave delay, which cannot close a drift gap, is screened
    out in the window and never replayed whole. Progress lines count every run."""
    scenario = Scenario("drift", "injected", "slow_drift", {"drift_coefficient_n_m2": DRIFT_N_M2}, 7)
    runs = [truth_run(scenario, case, platform, RECORD_S) for case in ("lc5.2", "lc5.3")]
    settings = GapSettings()
    jobs: list[tuple] = []
    evaluate = in_process(runs, platform, settings)

    def recording(batch: list[tuple], description: str = "") -> list:
        jobs.extend(batch)
        return evaluate(batch, description)

    effects = {name: CATALOGUE[name] for name in ("slow_drift", "wave_measurement_delay")}
    with caplog.at_level(logging.INFO, logger="fowt_hydro_sim.studies.diagnosis.runner"):
        diagnosis = diagnose(runs, [], recording, settings, effects, fit_window_s=WINDOW_S, progress=Progress())
    assert diagnosis.verdict == "explained" and diagnosis.chosen == "slow_drift", diagnosis.reason
    drift = diagnosis.candidate("slow_drift")
    assert drift.values["drift_coefficient_n_m2"] == pytest.approx(DRIFT_N_M2, rel=0.3)
    assert drift.window_s is None and drift.closure > 0.8  # judged on the whole records
    delay = diagnosis.candidate("wave_measurement_delay")
    assert delay.window_s == WINDOW_S and not delay.fits and delay.closure < 0.25
    assert any("wave_measurement_delay" in line and "(screened: closes" in line for line in summary_lines(diagnosis))
    whole = [j for j in jobs if len(j) == 4]
    assert all(j[0] != "wave_measurement_delay" for j in whole)
    assert len(whole) == 2 + 2 + 2  # plain model, slow drift at its fitted values, slow drift "after"
    fit_jobs = [j for j in jobs if j[0] is not None and len(j) == 5]
    assert fit_jobs and all(j[4] == WINDOW_S for j in fit_jobs)
    assert diagnosis.model_runs == len(jobs)
    lines = [r.getMessage() for r in caplog.records if r.getMessage().startswith("diagnosis: ")]
    done, expected = map(int, re.match(r"diagnosis: (\d+)/(\d+) model runs", lines[-1]).groups())
    assert done == expected == len(jobs) and "(100% of the replayed time)" in lines[-1], lines
    assert all(re.search(r"\(\d+% of the replayed time\), (\d+\.\d min left|time left unknown)$", line)
               for line in lines), lines


def test_a_fast_table_step_changes_a_replay_by_far_less_than_the_tolerances(platform):
    """The replay's kinematics table step divides the record into an FFT-friendly number of
    samples; the motion barely differs from one with the default step."""
    from fowt_hydro_sim.rosbag.reader import Bag
    waves_bag = Bag(REPO / "bags" / "lc5.3").elevation()
    keep = waves_bag.time_s <= 1000.0
    t, eta = waves_bag.time_s[keep], waves_bag.values[keep, 2]
    env = platform.environment
    waves = from_elevation_record(t - t[0], eta, 0.0, 0.0, 0.0, env.water_depth_m, env.gravity_m_s2, f_max_hz=0.5)
    step = fast_table_step(waves)
    n = waves.period_s / step
    assert step <= table_step(waves) and abs(n - round(n)) < 1e-6
    assert max(int(p) for p in _prime_factors(int(round(n)))) <= 7
    run = MeasuredRun("lc53", t, eta, (0.0, 0.0), t, np.zeros((t.size, 6)))
    _, fast = replay(Variant(platform), run, 0.1, duration_s=600.0)
    default_step = replay_module.fast_table_step
    try:
        replay_module.fast_table_step = table_step
        _, slow = replay(Variant(platform), run, 0.1, duration_s=600.0)
    finally:
        replay_module.fast_table_step = default_step
    for dof in (0, 2, 4):
        assert np.std(fast[:, dof] - slow[:, dof]) < 1e-3 * np.std(slow[:, dof]), dof


def _prime_factors(n: int) -> list[int]:
    out, p = [], 2
    while p * p <= n:
        while n % p == 0:
            out.append(p)
            n //= p
        p += 1
    return out + ([n] if n > 1 else [])


@pytest.mark.slow
def test_every_run_of_a_diagnosis_keeps_its_kinematics_table(platform):
    """Seven runs replayed in turn, twice: each run's table is built once (a cache of fewer
    tables than runs would rebuild every one on every pass)."""
    replay_module._tables.clear()
    t = np.arange(0.0, 700.0, 0.1)
    runs = [MeasuredRun(f"r{k}", t, 0.5 * np.sin(2 * np.pi * (0.08 + 0.01 * k) * t), (0.0, 0.0), t,
                        np.zeros((t.size, 6))) for k in range(7)]
    built = []
    build = replay_module.KinematicsTable.build

    def counting(*args, **kwargs):
        built.append(1)
        return build(*args, **kwargs)
    replay_module.KinematicsTable.build = counting
    try:
        for _ in range(2):
            for run in runs:
                replay(Variant(platform), run, 0.1, duration_s=20.0)
    finally:
        replay_module.KinematicsTable.build = build
    assert len(built) == 7 and len(replay_module._tables) == 7


@pytest.mark.slow
def test_a_fit_window_too_short_gets_one_line(tmp_path):
    t = np.arange(0.0, 700.0, 0.5)
    bag = write_measured_bag(tmp_path / "run", t, 0.5 * np.sin(0.6 * t), (0.0, 0.0), t, np.zeros((t.size, 6)))
    result = fowt_sim("diagnose", "--measured", bag, "--fit-window", "100", "--workers", "1", "-o", tmp_path / "out",
                      timeout=120)
    assert result.returncode == 2 and "fit window 100 s" in result.stderr, result.stderr
    assert "Traceback" not in result.stderr and len(result.stderr.strip().splitlines()) == 1, result.stderr

