"""The independent benchmark's development and held-out scenarios: the split file's sets,
fixed (the held-out set's content is pinned by its digest), disjoint in seeds and
strengths, each with baseline-term scenarios and agreement nulls, and ``diagnose-benchmark
--set`` running either and saying which it ran."""
from __future__ import annotations

import hashlib
import itertools
import json
from pathlib import Path

import pytest
import yaml

from fowt_hydro_sim.cli import main
from fowt_hydro_sim.studies.diagnosis import benchmark

# sha256 of the held-out entries as canonical JSON: a change to the held-out set is deliberate.
# Changed once, before the set was ever run: its baseline-term scenarios (drift x0.7, x1.6;
# drag x0.7, x1.4) and two agreement nulls added.
HELD_OUT_DIGEST = "dce3804cb93bb5993b6b39647f38d5e8a865bf747d4e75b489485cd18499d0e0"
# The second held-out set: fixed after the first's run and before any rule change after it.
HELD_OUT_2_DIGEST = "2954d28c91d4dfbae000dab2b448c066d0d516e136f8a8e5b32587059d674d4c"
# The third: fixed after the second's run and before any rule change after it.
HELD_OUT_3_DIGEST = "27530986799c233a9262473399e5c6e8d36ed63d2b1e1bf3526290ae6a8edb45"
# The fourth: fixed while the third was being run, before any rule change after its results.
HELD_OUT_4_DIGEST = "319ceade35b260fcba96b2f0172036d955f057f5e3391713b30ad968a7a3b8d4"
# The fifth: fixed while the fourth was being run, before any rule change after its results.
HELD_OUT_5_DIGEST = "4bfc4aded12757e76ada8520f1516d482db8df760dc95f32cf6e9b3b8f392407"
# The sixth: fixed while the fifth was being run, before any rule change after its results.
HELD_OUT_6_DIGEST = "52834e7b75ffe50a0784d532c8d050a051fcc148505a4223f23517f12a4efb65"
# The seventh: fixed before the sixth was run, before any rule change after its results.
HELD_OUT_7_DIGEST = "3426a20c42057c5af5a8cfff2120d3b05aa94e333f4415626dbcb802eb3427a6"
# The eighth: fixed before the seventh was run, before any rule change after its results.
HELD_OUT_8_DIGEST = "55b4d3b3dfa123d02b149eafad9b1a84d3745b327d2cd4bfb3d7c61fe87ea5d3"
# The ninth: fixed while the seventh was run, before any rule change after its results.
HELD_OUT_9_DIGEST = "e014b09eaf23cdaf289850a166820bb1e8c23278524d3853e3629dfc795b761d"


def _digest(entries: list[dict]) -> str:
    return hashlib.sha256(json.dumps(entries, sort_keys=True).encode()).hexdigest()


def test_the_development_set_is_every_scenario_the_rules_were_looked_at_on():
    development = benchmark.split_scenarios("development")
    generated = (benchmark.independent_scenarios(None, 2, 10, 2, 2000)
                 + benchmark.independent_scenarios(None, 0, 7, 0, 3000))
    key = lambda s: (s.kind, s.effect, s.values, s.seed, s.accepted, s.tuning_cases, s.blind_cases,  # noqa: E731
                     s.baseline)
    assert [key(s) for s in development[:len(generated)]] == [key(s) for s in generated]
    # then the baseline terms and the agreement nulls
    assert [(s.kind, s.baseline, s.accepted) for s in development[len(generated):]] == [
        ("baseline_term", {"drift_scale": 0.55}, ("model_slow_drift",)),
        ("baseline_term", {"drift_scale": 1.8}, ("model_slow_drift",)),
        ("baseline_term", {"cd_factor": 1.5}, ("model_drag",)),
        ("null", {"spread": False}, ()), ("null", {"spread": False}, ())]


@pytest.mark.parametrize("key, digest", [("held_out", HELD_OUT_DIGEST), ("held_out_2", HELD_OUT_2_DIGEST),
                                         ("held_out_3", HELD_OUT_3_DIGEST), ("held_out_4", HELD_OUT_4_DIGEST),
                                         ("held_out_5", HELD_OUT_5_DIGEST), ("held_out_6", HELD_OUT_6_DIGEST),
                                         ("held_out_7", HELD_OUT_7_DIGEST),
                                         ("held_out_8", HELD_OUT_8_DIGEST), ("held_out_9", HELD_OUT_9_DIGEST)])
def test_each_held_out_set_is_fixed(key: str, digest: str):
    assert _digest(yaml.safe_load(benchmark.SPLIT_FILE.read_text())[key]) == digest


def test_the_sets_are_apart_in_seeds_names_and_strengths_and_alike_in_make_up():
    sets = {name: benchmark.split_scenarios(name) for name in benchmark.SPLIT_SETS}
    strengths = lambda scenarios: {(s.effect, json.dumps(s.values, sort_keys=True),  # noqa: E731
                                    json.dumps(s.baseline, sort_keys=True)) for s in scenarios if s.kind != "null"}
    for a, b in itertools.combinations(sets.values(), 2):
        assert not {s.seed for s in a} & {s.seed for s in b}
        assert not {s.name for s in a} & {s.name for s in b}
        assert not strengths(a) & strengths(b)
    for scenarios in sets.values():
        assert {s.accepted for s in scenarios if s.kind == "baseline_term"} == {
            (term.candidate,) for term in benchmark.BASELINE_TERMS.values()}
        assert sum(s.baseline == {"spread": False} for s in scenarios if s.kind == "null") >= 2
    for name in benchmark.SPLIT_SETS[1:]:
        held_out = sets[name]
        kinds = [s.kind for s in held_out]
        assert kinds.count("null") >= 12 and kinds.count("baseline_term") == 4
        assert kinds.count("out_of_catalogue") >= 2 and kinds.count("injected") == 9
        assert {s.effect for s in held_out if s.kind == "injected"} == set(benchmark.INDEPENDENT_INJECTIONS)
        assert all(s.accepted == benchmark.INDEPENDENT_INJECTIONS[s.effect].accepted
                   for s in held_out if s.kind == "injected")
        assert {s.tuning_cases for s in held_out} == {("lc5.1", "lc5.2", "lc5.3"), ("lc5.2", "lc5.3", "lc5.4")}


@pytest.mark.parametrize("args, message", [
    (["--set", "held-out"], "--set: the split file's sets (development, held-out, held-out-2, "
                           "held-out-3, held-out-4, held-out-5, held-out-6, held-out-7, held-out-8, held-out-9) are "
                           "the independent source's"),
    (["--source", "independent", "--set", "held-out", "--scenarios", "null#99"], "--scenarios: not in the held-out"),
    (["--source", "independent", "--set", "development", "--seed", "5"], "--seed: the seeds of a --set are fixed"),
    (["--source", "independent", "--set", "development", "--nulls", "3"], "--nulls: the scenarios of a --set"),
    (["--source", "independent", "--scenarios", "null#h1"], "--scenarios: picks scenarios of a --set"),
])
def test_set_options_given_wrongly_are_one_line(tmp_path: Path, capsys, args: list[str], message: str):
    assert main(["diagnose-benchmark", *args, "-o", str(tmp_path)]) == 2
    error = capsys.readouterr().err
    assert message in error and len(error.strip().splitlines()) == 1, error


def test_a_set_is_run_with_each_scenarios_own_load_cases_and_the_benchmark_says_which_set():
    chosen, line = benchmark.chosen_scenarios("independent", scenario_set="held-out", names=["null#h2", "null#h3"])
    assert line == "scenario set: held-out (2 scenarios of split.yaml)"
    assert [(s.name, c, w) for s, c, w in benchmark.truth_jobs(chosen)] == [
        ("null#h2", c, True) for c in ("lc5.2", "lc5.3", "lc5.4", "lc6.1", "lc6.4")] + [
        ("null#h3", c, True) for c in ("lc5.1", "lc5.2", "lc5.3", "lc6.1", "lc6.4")]
    chosen, line = benchmark.chosen_scenarios("independent", ["mixed_damping"], scenario_set="held-out")
    assert line == "scenario set: held-out (17 scenarios of split.yaml)"
    assert {s.effect for s in chosen if s.kind == "injected"} == {"mixed_damping"}
    injected = [s for s in chosen if s.kind == "injected"][1]
    assert [c for s, c, w in benchmark.truth_jobs([injected]) if not w] == ["lc5.2", "lc5.3", "lc5.4"]
    _, line = benchmark.chosen_scenarios("independent", strengths=1, nulls=1, out_of_catalogue=0)
    assert line.startswith("scenario set: generated (4 scenarios")


def test_scenarios_are_picked_in_the_order_given():
    names = ["null#h2", "baseline_drift#h1", "frequency_dependent_drift#h1"]
    assert [s.name for s in benchmark.split_scenarios("held-out", names=names)] == names


def test_a_benchmark_run_again_into_its_folder_keeps_the_scores_made_with_the_same_settings(tmp_path: Path):
    """What ``diagnose-benchmark`` resumes from: the scores of ``scenarios.jsonl`` when the
    folder's settings are the run's; another run's settings empty it."""
    document = {"scenario_set": "held-out", "duration_s": 3600.0, "scenarios": ["null#h1", "null#h2"]}
    assert benchmark.scored_before(tmp_path, document) == {}
    score = benchmark.Score("null#h1", "null", None, True, "baseline mismatch", None, True, wall_s=12.0)
    (tmp_path / "scenarios.jsonl").write_text(json.dumps(score.__dict__) + "\n")
    assert benchmark.scored_before(tmp_path, document) == {"null#h1": score}
    assert benchmark.scored_before(tmp_path, {**document, "duration_s": 10800.0}) == {}
    assert not (tmp_path / "scenarios.jsonl").exists()
    assert benchmark.scored_before(tmp_path, document) == {}  # the folder now holds the other run's settings
