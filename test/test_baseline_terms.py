"""The independent basin's baseline terms that the model has too (its drift table's strength,
its Cd factor) as scenario values: they reach the basin run and its cache key; a drift-scaled
run's mean surge offset is the closed form's (the mean drift sum a^2 D(w) over the spring
lines' surge stiffness); a baseline-term scenario is scored right only when its term's
candidate is named within 25 % of the right scale."""
from __future__ import annotations

import hashlib
import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.config import load_case, load_platform
from fowt_hydro_sim.studies.diagnosis import benchmark
from fowt_hydro_sim.studies.diagnosis.gap import GapSettings
from fowt_hydro_sim.studies.diagnosis.independent import basin, cummins, drift_study
from fowt_hydro_sim.studies.diagnosis.method import CandidateFit, Diagnosis

CASE, DURATION_S = "lc5.2", 900.0


@pytest.fixture(scope="module")
def platform():
    return load_platform("windmoor12")


@pytest.fixture(scope="module")
def drift_runs(platform, tmp_path_factory) -> tuple[benchmark.Scenario, Path, dict]:
    """The development set's stronger drift scenario and the same scenario with the basin's
    drift at 1, each run through the benchmark's own task into a cache folder."""
    scenario = next(s for s in benchmark.split_scenarios("development") if s.name == "baseline_drift#2")
    cache = tmp_path_factory.mktemp("runs")
    runs = {s.terms.drift_scale: benchmark.scenario_run((s, CASE, True), platform, DURATION_S, "independent", cache)
            for s in (scenario, replace(scenario, baseline={}))}
    return scenario, cache, runs


def test_the_terms_set_the_basins_cd_and_drift_and_only_a_changed_term_changes_the_key(platform):
    drawn = basin.baseline(4034)
    scaled = basin.baseline(4034, terms=basin.BaselineTerms(cd_factor=1.5))
    assert scaled.cd_scale == pytest.approx(1.5 * drawn.cd_scale)
    assert (scaled.added_mass_scale, scaled.strip_length_m) == (drawn.added_mass_scale, drawn.strip_length_m)
    weaker = basin.baseline(4034, terms=basin.BaselineTerms(drift_scale=0.55))
    assert [d for _, d in weaker.drift_coefficient_n_m2] == pytest.approx(
        [0.55 * d for _, d in drawn.drift_coefficient_n_m2])
    agreeing = basin.baseline(4034, terms=basin.BaselineTerms(spread=False))
    assert (agreeing.cd_scale, agreeing.added_mass_scale, agreeing.strip_length_m) == (1.0, 1.0, None)
    assert agreeing.drift_coefficient_n_m2 == drawn.drift_coefficient_n_m2

    args = (None, {}, 4034, CASE, DURATION_S, True, basin.BASELINE_DRIFT, platform)
    keys = {basin.run_key(*args, terms) for terms in (basin.BaselineTerms(), basin.BaselineTerms(cd_factor=1.5),
                                                      basin.BaselineTerms(drift_scale=1.5),
                                                      basin.BaselineTerms(spread=False))}
    assert len(keys) == 4
    # the default terms leave the key of the runs cached before the terms existed
    legacy = json.dumps([basin.VERSION, *args[:-1], repr(platform)], sort_keys=True, default=str)
    assert basin.run_key(*args) == hashlib.blake2b(legacy.encode(), digest_size=12).hexdigest()


@pytest.mark.slow
def test_a_drift_scaled_basin_runs_mean_surge_offset_is_the_closed_forms(platform, drift_runs):
    """Mean offset = sum a_j^2 D(w_j) / K (Newman's mean drift on the spring lines' linear
    surge stiffness): the run at 1.8 less the run at 1 is 0.8 times it, and the run at 1 is it."""
    scenario, cache, runs = drift_runs
    sea = load_case(CASE).sea_state
    case_seed = scenario.seed + int(hashlib.blake2b(CASE.encode(), digest_size=2).hexdigest(), 16)
    waves = cummins.jonswap_waves(sea.hs_m, sea.tp_s, sea.gamma, DURATION_S, case_seed, sea.heading_deg)
    table = np.asarray(basin.BASELINE_DRIFT)
    mean_drift_n = float(np.sum(waves.amplitude_m ** 2 * np.interp(waves.omega_rad_s, table[:, 0], table[:, 1])))
    offset_m = mean_drift_n / drift_study.surge_stiffness_n_m(platform)
    assert offset_m > 1.0  # metres' worth, far above the 1 % sensor noise's share of the mean
    mean = {scale: float(run.motion[:, 0].mean()) for scale, run in runs.items()}
    assert mean[1.8] - mean[1.0] == pytest.approx(0.8 * offset_m, rel=0.03)
    assert mean[1.0] == pytest.approx(offset_m, rel=0.03)
    # each run is cached under its own key, the scaled one with its term in it
    for scale in runs:
        terms = basin.BaselineTerms(drift_scale=scale)
        key = basin.run_key(None, {}, scenario.seed, CASE, DURATION_S, True, basin.BASELINE_DRIFT, platform, terms)
        assert (cache / f"{key}.npz").exists()


def _diagnosis(named: str | None, values: dict[str, float]) -> Diagnosis:
    candidates = [CandidateFit(named, values, [], 0.0, 0.9, 10, fits=True)] if named else []
    return Diagnosis(GapSettings(), [], [], [], candidates, "explained" if named else "baseline mismatch", named, "")


@pytest.mark.parametrize("named, share, right", [
    ("model_drag", 1.24, True), ("model_drag", 0.76, True), ("model_drag", 1.26, False),
    ("model_drag", 0.74, False), ("slow_drift", 1.0, False), (None, 1.0, False)])
def test_a_drag_scenario_is_right_with_model_drag_within_25_percent_of_the_basins_cd_ratio(named, share, right):
    scenario = next(s for s in benchmark.split_scenarios("development") if s.name == "baseline_drag#1")
    cd = basin.baseline(scenario.seed, terms=scenario.terms).cd_scale  # 1.5 x the drawn share 0.92
    assert scenario.right_scale == {"cd_scale": cd}
    assert cd == pytest.approx(1.5 * basin.baseline(scenario.seed).cd_scale)
    score = benchmark.score_scenario(scenario, _diagnosis(named, {"cd_scale": share * cd}), [], 1.0)
    assert score.correct is right
    assert score.right_scale == scenario.right_scale and score.baseline == {"cd_factor": 1.5}


@pytest.mark.parametrize("fitted, right", [(0.55, True), (0.6875, True), (0.41, False), (0.70, False)])
def test_a_drift_scenario_is_right_with_model_slow_drift_within_25_percent(fitted: float, right: bool):
    scenario = next(s for s in benchmark.split_scenarios("development") if s.name == "baseline_drift#1")
    assert scenario.right_scale == {"drift_scale": 0.55 * basin.MODEL_DRIFT_RATIO}
    assert benchmark.score_scenario(scenario, _diagnosis("model_slow_drift", {"drift_scale": fitted}), [],
                                    1.0).correct is right


def test_the_summary_counts_baseline_terms_and_agreement_nulls_apart():
    development = {s.name: s for s in benchmark.split_scenarios("development")}
    scores = [benchmark.score_scenario(development[name], _diagnosis(named, values), [], 1.0)
              for name, named, values in [("baseline_drift#1", "model_slow_drift", {"drift_scale": 0.6}),
                                          ("baseline_drift#2", "model_slow_drift", {"drift_scale": 1.0}),
                                          ("agreement_null#1", None, {}), ("agreement_null#2", "model_drag",
                                                                          {"cd_scale": 1.0}),
                                          ("null#1", None, {})]]
    figures = benchmark.summary(scores)
    assert (figures["baseline_term"], figures["baseline_term_right_scale"]) == (2, 0.5)
    assert (figures["agreement_null"], figures["agreement_null_false_alarms"]) == (1 + 1, 1)
    assert (figures["null"], figures["false_alarm_rate"]) == (3, pytest.approx(1 / 3))
    assert figures["injected"] == 0 and figures["top1_accuracy"] is None


@pytest.mark.parametrize("baseline, message", [
    ({"drift": 0.5}, "unknown baseline term drift"),
    ({"cd_factor": -1}, "baseline cd_factor must be a number above 0"),
    ({"spread": "no"}, "baseline spread must be true or false"),
    ({"drift_scale": 0.5, "cd_factor": 1.5}, "changes exactly one of drift_scale, cd_factor"),
])
def test_a_wrong_baseline_term_in_a_split_file_is_one_line(tmp_path: Path, baseline: dict, message: str):
    entry = {"name": "x#1", "kind": "baseline_term", "baseline": baseline, "seed": 1,
             "tuning": ["lc5.1", "lc5.2", "lc5.3"], "blind": ["lc6.1"]}
    path = tmp_path / "split.yaml"
    path.write_text(json.dumps({"development": [entry], "held_out": []}))
    with pytest.raises(InputError, match=message) as error:
        benchmark.split_scenarios("development", path=path)
    assert len(str(error.value).splitlines()) == 1


def test_every_candidates_fit_starts_off_its_off_value_within_its_bounds():
    """The fit steps in units of start - off: a start at the off value gave a zero unit, a NaN
    first guess and a crashed diagnosis (model_drag's low-frequency scale, whose baseline-drag
    scenarios fit it)."""
    from fowt_hydro_sim.studies.diagnosis.effects import CATALOGUE
    for effect in CATALOGUE.values():
        for p in effect.parameters:
            assert p.scale > 0 and p.low <= p.start <= p.high, (effect.name, p.name)
