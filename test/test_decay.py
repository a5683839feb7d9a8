"""Free decays as diagnosis runs: the half-cycle analysis against a damped oscillator's closed
form; the decay cells of a model against a measured decay; a decay's cells consistent on
their own; the independent simulator's and the model's decays against the closed form of an
added linear damping; ``fowt-sim diagnose --decay`` on a decay bag; bad decay input in one
line."""
from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.config import Platform, load_platform
from fowt_hydro_sim.physics.platform_edits import scaled_drag
from fowt_hydro_sim.studies.diagnosis import benchmark, method
from fowt_hydro_sim.studies.diagnosis.decay import check_decay, decay_gap, half_cycles, replay_decay
from fowt_hydro_sim.studies.diagnosis.effects import CATALOGUE
from fowt_hydro_sim.studies.diagnosis.gap import Gap, GapSettings, consistent
from fowt_hydro_sim.studies.diagnosis.independent import basin, cummins
from fowt_hydro_sim.studies.diagnosis.method import CandidateFit, Diagnosis, Mismatch
from fowt_hydro_sim.studies.replay import MeasuredRun, Variant
from fowt_hydro_sim.testing import fowt_sim

SETTINGS = GapSettings(decays=True)
STEP_S = 0.25


def oscillator(zeta: float, period_s: float, amplitude: float, duration_s: float, hold_s: float = 0.0
               ) -> tuple[np.ndarray, np.ndarray]:
    """A linear oscillator released at rest from ``amplitude`` after a hold: its closed-form decay."""
    t = np.arange(0.0, duration_s, STEP_S)
    w = 2.0 * math.pi / period_s
    wd = w * math.sqrt(1.0 - zeta ** 2)
    s = np.clip(t - hold_s, 0.0, None)
    x = amplitude * np.exp(-zeta * w * s) * (np.cos(wd * s) + zeta / math.sqrt(1.0 - zeta ** 2) * np.sin(wd * s))
    return t, x


def motion(x: np.ndarray, dof: int = 0) -> np.ndarray:
    out = np.zeros((x.size, 6))
    out[:, dof] = x
    return out


@pytest.fixture(scope="module")
def platform() -> Platform:
    return load_platform("windmoor12")


def test_half_cycles_give_the_oscillators_period_and_damping():
    """Half-period pi / w_d; ln(H_k / H_k+1) / pi = zeta / sqrt(1 - zeta^2) for every k."""
    for zeta, period in ((0.05, 96.0), (0.02, 27.0), (0.10, 16.0)):
        t, x = oscillator(zeta, period, 10.0, 12 * period)
        tau, damping = half_cycles(t, x)
        wd = 2.0 * math.pi / period * math.sqrt(1.0 - zeta ** 2)
        assert tau == pytest.approx(np.full(tau.size, math.pi / wd), rel=2e-3)
        assert damping == pytest.approx(np.full(damping.size, zeta / math.sqrt(1.0 - zeta ** 2)), rel=1e-2)
        assert tau.size == damping.size >= 3  # down to a fifth of the first height


def test_a_hold_before_the_release_and_sensor_noise_leave_the_analysis_unchanged():
    t, x = oscillator(0.05, 96.0, 10.0, 1200.0)
    held_t, held = oscillator(0.05, 96.0, 10.0, 1300.0, hold_s=100.0)
    noisy = held + np.random.default_rng(3).normal(0.0, 0.01 * held.std(), held.size)
    tau, damping = half_cycles(t, x)
    tau_held, damping_held = half_cycles(held_t, noisy)
    assert tau_held.size == tau.size
    assert tau_held.mean() == pytest.approx(tau.mean(), rel=0.01)
    assert damping_held.mean() == pytest.approx(damping.mean(), rel=0.03)


def test_the_decay_cells_are_the_models_period_and_damping_against_the_measured():
    """A model decaying 5 % faster in frequency and with 1.2 times the damping: period -5 %,
    damping +20 %, both flagged; no other cell judged; the plain model nil."""
    t, measured = oscillator(0.05, 96.0, 10.0, 1000.0)
    _, model = oscillator(0.06, 96.0 / 1.05, 10.0, 1000.0)
    g = decay_gap("surge decay", (t, motion(measured)), (t, motion(model)), "surge", SETTINGS)
    cells = SETTINGS.cells()
    period, damping = cells.index(("surge", "decay_period")), cells.index(("surge", "decay_damping"))
    wd = lambda z, p: 2 * math.pi / p * math.sqrt(1 - z ** 2)  # noqa: E731
    assert g.value[period] == pytest.approx(wd(0.05, 96.0) / wd(0.06, 96.0 / 1.05) - 1.0, abs=2e-3)
    ratio = (0.06 / math.sqrt(1 - 0.06 ** 2)) / (0.05 / math.sqrt(1 - 0.05 ** 2))
    assert g.value[damping] == pytest.approx(ratio - 1.0, abs=0.01)
    assert g.flagged[period] and g.flagged[damping]
    assert np.flatnonzero(g.judged).tolist() == [period, damping] and g.decay_dof == "surge"
    same = decay_gap("surge decay", (t, motion(measured)), (t, motion(measured)), "surge", SETTINGS)
    assert not same.flagged.any() and np.allclose(same.value, 0.0)


def gap_of(cells: dict[tuple[str, str], float], covers: np.ndarray, decay_dof: str | None = None) -> Gap:
    names = SETTINGS.cells()
    value = np.array([cells.get(c, 0.0) for c in names])
    tolerance = np.array([SETTINGS.tolerance(m) if cover else np.inf for (_, m), cover in zip(names, covers)])
    return Gap("run", value, value - 0.01, value + 0.01, tolerance, covers, decay_dof)


def test_a_decay_cell_is_consistent_in_its_one_decay_a_wave_cell_needs_two_runs():
    surge_damping, surge_std = ("surge", "decay_damping"), ("surge", "std.low_frequency")
    waves = SETTINGS.covered(None)
    wave_run = gap_of({surge_std: 0.5}, waves)
    decay = gap_of({surge_damping: -0.3}, SETTINGS.covered("surge"), "surge")
    cells = SETTINGS.cells()
    found = lambda gaps: [cells[i] for i in np.flatnonzero(consistent(gaps))]  # noqa: E731
    assert found([wave_run, decay]) == [surge_damping]  # one wave run: nothing to be consistent with
    assert found([wave_run, wave_run, decay]) == [surge_std, surge_damping]
    opposite = gap_of({surge_std: -0.5}, waves)
    assert found([wave_run, opposite, decay]) == [surge_damping]  # a sign that changes between runs


def test_the_independent_simulators_decay_damping_rises_by_the_closed_form_of_an_added_linear_damping(platform):
    """Without drag (which would damp less as the added damping shrinks the cycles): an added
    linear surge damping b raises the surge decay's damping ratio by b / (2 (m + A_11(w)) w)
    at the decay's frequency w (BEM added mass), the release at rest from +10 m; the period
    unchanged."""
    b = 2.0e5
    database = basin._database()
    no_drag = replace(basin.baseline(1, terms=basin.BaselineTerms(spread=False)), cd_scale=1e-9)
    runs = {}
    for extra in (0.0, b):
        effects = cummins.Effects(linear_damping=(extra, 0.0, 0.0, 0.0, 0.0, 0.0))
        trajectory = cummins.integrate(platform, database, None, 1500.0, 0.05, no_drag, effects,
                                       initial=np.array([10.0, 0, 0, 0, 0, 0]))
        runs[extra] = half_cycles(trajectory.time_s, trajectory.position[:, 0], 8)
    (tau, zeta), (tau_b, zeta_b) = runs[0.0], runs[b]
    w = math.pi / tau.mean()
    mass = cummins.rigid_body_mass(platform)[0, 0] + np.interp(w, database.omega_rad_s, database.added_mass[:, 0, 0])
    assert (zeta_b - zeta).mean() == pytest.approx(b / (2.0 * mass * w), rel=0.03)
    assert tau_b.mean() == pytest.approx(tau.mean(), rel=0.01)


def recorded_decay(variant: Variant, hold_s: float = 20.0) -> MeasuredRun:
    """The variant's own surge decay from +10 m, held ``hold_s`` first, with 1 % sensor noise."""
    time_s = np.arange(0.0, 1200.0, STEP_S)
    start = MeasuredRun("release", time_s, np.zeros(time_s.size), (0.0, 0.0), time_s,
                        np.tile([10.0, 0, 0, 0, 0, 0], (time_s.size, 1)), decay_dof="surge")
    t, x = replay_decay(variant, start, 0.1)
    held = np.arange(0.0, hold_s, t[1] - t[0])
    time_s = np.concatenate([held, t + hold_s])
    recorded = np.vstack([np.tile(x[0], (held.size, 1)), x])
    recorded = recorded + np.random.default_rng(5).normal(0.0, 1.0, recorded.shape) * 0.01 * recorded.std(axis=0)
    return MeasuredRun("surge decay", time_s, np.zeros(time_s.size), (0.0, 0.0), time_s, recorded, decay_dof="surge")


def test_a_decay_replayed_by_the_plain_model_from_its_release_matches_it(platform):
    run = recorded_decay(Variant(platform))
    g = decay_gap(run.name, (run.motion_time_s, run.motion), replay_decay(Variant(platform), run, 0.1), "surge",
                  SETTINGS)
    assert not g.flagged.any() and np.all(np.abs(g.value) < 0.02)


def test_a_decay_with_linear_damping_decays_at_its_ratio_of_critical(platform):
    """Without drag: the catalogue's linear surge damping at a ratio r of critical (of the
    model's linear modes) gives the decay a damping ratio r (and the little the hull's own
    radiation adds); a model at r = 2 % against a measurement at 4 % has a damping cell of
    (2 % + z0) / (4 % + z0) - 1, z0 the plain hull's."""
    no_drag = Variant(scaled_drag(platform, 1e-9))
    effect = CATALOGUE["linear_damping"]

    def damped(ratio: float) -> Variant:
        return effect.apply(no_drag, None, {p.name: p.off for p in effect.parameters} | {"surge_damping_ratio": ratio})

    own = half_cycles(*(lambda r: (r.motion_time_s, r.motion[:, 0]))(recorded_decay(no_drag)), 8)[1].mean()
    measured = recorded_decay(damped(0.04))
    zeta = half_cycles(measured.motion_time_s, measured.motion[:, 0])[1].mean()
    assert abs(own) < 0.005 and zeta == pytest.approx(0.04 + own, rel=0.05)
    g = decay_gap(measured.name, (measured.motion_time_s, measured.motion), replay_decay(damped(0.02), measured, 0.1),
                  "surge", SETTINGS)
    damping = SETTINGS.cells().index(("surge", "decay_damping"))
    assert g.value[damping] == pytest.approx((0.02 + own) / (0.04 + own) - 1.0, abs=0.03)
    assert g.flagged[damping]


def test_bad_decays_get_one_line():
    t, x = oscillator(0.3, 96.0, 10.0, 300.0)  # heavily damped and short: two half-cycles
    with pytest.raises(InputError, match="half-cycles of surge above 20% of the first height; the diagnosis needs 4"):
        check_decay("surge decay", t, motion(x), "surge")
    with pytest.raises(InputError, match="unknown DOF 'swell'"):
        check_decay("decay", t, motion(x), "swell")



def test_the_benchmark_leaves_out_a_decay_too_damped_to_read_and_says_so(caplog):
    t, damped = oscillator(0.3, 96.0, 10.0, 300.0)
    t2, light = oscillator(0.05, 96.0, 10.0, 1000.0)
    runs = [MeasuredRun(name, time_s, np.zeros(time_s.size), (0.0, 0.0), time_s, motion(x), decay_dof="surge")
            for name, time_s, x in (("s#1/decay surge", t, damped), ("s#2/decay surge", t2, light))]
    assert [r.name for r in benchmark.analysable(runs)] == ["s#2/decay surge"]
    [line] = [r.getMessage() for r in caplog.records]
    assert "decay s#1/decay surge: 2 half-cycles" in line and line.endswith("left out of the scenario")

def test_bad_decay_options_get_one_line(tmp_path):
    bag = tmp_path / "missing"
    cases = [(["diagnose", "--measured", bag, "--decay", "surge"], "--decay: need DOF=BAG"),
             (["diagnose", "--measured", bag, "--decay", "swell=x"], "'swell' is not a DOF of the gap"),
             (["diagnose", "--measured", bag, "--decay", "yaw=x", "--dofs", "surge"], "'yaw' is not a DOF of the gap"),
             (["diagnose-benchmark", "--no-decays", "--nulls", "0"], "only the independent source has free decays")]
    for args, message in cases:
        result = fowt_sim(*args, "-o", tmp_path / "out", timeout=120)
        assert result.returncode == 2 and message in result.stderr, (args, result.stderr)
        assert "Traceback" not in result.stderr and len(result.stderr.strip().splitlines()) == 1, result.stderr


@pytest.mark.slow
@pytest.mark.dask
def test_diagnose_reads_a_decay_bag_and_reports_its_cells(platform, tmp_path):
    """``fowt-sim diagnose --decay surge=BAG``: a wave run of the model with its drag 1.4
    times stronger and that model's own surge decay (bags without a wave topic): the decay's
    cells are measured, flagged, in the report, and the model's drag is read at its scale."""
    from fowt_hydro_sim.rosbag.measured import write_measured_bag
    from fowt_hydro_sim.studies.diagnosis.benchmark import Scenario, truth_run

    scenario = Scenario("drag", "injected", "model_drag", {"cd_scale": 1.4}, 7)
    bags = []
    for case in ("lc5.2", "lc5.3"):
        run = truth_run(scenario, case, platform, 1800.0)
        bags.append(write_measured_bag(tmp_path / case, run.elevation_time_s, run.elevation_m, run.point_xy_m,
                                       run.motion_time_s, run.motion))
    decay = recorded_decay(Variant(scaled_drag(platform, 1.4)))
    decay_bag = write_measured_bag(tmp_path / "surge_decay", np.zeros(0), np.zeros(0), (0.0, 0.0),
                                   decay.motion_time_s, decay.motion)
    out = tmp_path / "report"
    result = fowt_sim("diagnose", "--measured", *bags, "--decay", f"surge={decay_bag}", "--effects", "model_drag",
                      "model_slow_drift", "--max-evaluations", "3", "--workers", "2", "-o", out, timeout=1800)
    assert result.returncode == 0, result.stderr
    data = json.loads((out / "diagnosis.json").read_text())
    assert data["tuning_runs"] == ["lc5.2", "lc5.3", "surge_decay"]
    flagged = {(run, dof, metric) for run, dof, metric in data["flagged"]}
    assert ("surge_decay", "surge", "decay_damping") in flagged, flagged
    assert data["finding"]["effect"] == "model_drag", result.stdout
    assert data["finding"]["values"]["cd_scale"] == pytest.approx(1.4, rel=0.15)
    report = (out / "report.md").read_text()
    assert "| surge_decay | surge | decay_damping |" in report and "free decays: half-period 3 %" in report


def test_a_term_read_off_a_decay_alone_is_checked_on_the_blind_runs_by_the_wave_cells_it_explains():
    """The surge decay's damping 0.81x the measured and the surge low-frequency STD 1.14x in
    every wave run: the model's drag at 1.41 closes both, its slow drift at 0.87 (within 0.2
    of 1: no finding) the STD alone. The drag is read off the decay; blind runs have no
    decay, so they check it on the STD it explains too: kept where it closes it there,
    not named where it does not."""
    std, damping = ("surge", "std.low_frequency"), ("surge", "decay_damping")
    waves, decay = SETTINGS.covered(None), SETTINGS.covered("surge")
    wave_gaps = lambda value: [gap_of({std: value}, waves) for _ in range(3)]  # noqa: E731
    before = wave_gaps(0.14) + [gap_of({damping: -0.185}, decay, "surge")]
    drag = CandidateFit("model_drag", {"cd_scale": 1.41}, wave_gaps(0.02) + [gap_of({damping: -0.01}, decay, "surge")],
                        score=-50.0, closure=0.9, model_runs=4)
    drift = CandidateFit("model_slow_drift", {"drift_scale": 0.87},
                         wave_gaps(0.0) + [gap_of({damping: -0.185}, decay, "surge")], score=-50.0, closure=0.4,
                         model_runs=4)
    cells = SETTINGS.cells()
    for blind_after, kept in ((0.03, True), (0.14, False)):
        d = Diagnosis(SETTINGS, ["lc5.1", "lc5.2", "lc5.3", "surge decay"], ["lc6.1"],
                      before + [gap_of({std: 0.14}, waves)], [drag, drift], "unexplained", None, "no candidate fits")
        d.mismatches = [Mismatch(*cells[i], [float(g.value[i]) for g in before if g.covered[i]], [], [])
                        for i in np.flatnonzero(consistent(before))]
        assert [(m.dof, m.metric) for m in d.mismatches] == [std, damping]
        d = method.with_mismatches(d, None, CATALOGUE)
        assert d.reading is drag and d.reading_cells[cells.index(std)], d.reason
        method.confirm_reading(d, [gap_of({std: blind_after}, waves)])
        assert (d.finding is drag) is kept, d.reason
