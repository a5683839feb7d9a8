"""The independent benchmark: the simulator's FFT synthesis against the direct sum, its
pre-roll against a run started earlier, the catenary mooring against the inextensible
catenary's closed form and the mooring candidate's form, the run cache, and a small ``diagnose-benchmark --source
independent`` with its verdicts asserted."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

from fowt_hydro_sim.physics.config import load_platform
from fowt_hydro_sim.studies.diagnosis import benchmark
from fowt_hydro_sim.studies.diagnosis.independent import basin, bem, catenary, cummins
from fowt_hydro_sim.testing import fowt_sim

PLATFORM = load_platform("windmoor12")
DATABASE = bem.load_database()
ENV = PLATFORM.environment


def test_fft_synthesis_is_the_direct_sum():
    waves = cummins.jonswap_waves(6.0, 10.0, 3.3, 300.0, seed=4)
    grid = np.arange(3000) * 0.1
    direct = cummins.Waves(waves.omega_rad_s, waves.amplitude_m, waves.phase_rad)  # no period: direct sum
    hull = cummins.strips(PLATFORM)
    fast = cummins.forcing(DATABASE, PLATFORM, hull, waves, grid, cummins.Effects())
    slow = cummins.forcing(DATABASE, PLATFORM, hull, direct, grid, cummins.Effects())
    assert np.allclose(fast.excitation, slow.excitation, rtol=0, atol=1e-6 * np.abs(slow.excitation).max())
    assert np.allclose(fast.fluid_velocity_m_s, slow.fluid_velocity_m_s, atol=1e-5)
    times = np.arange(0.0, 600.0, 0.1)  # two periods: the FFT's periodic extension
    eta_fast = cummins.elevation(waves, times, 0.0, 0.0, ENV.water_depth_m, ENV.gravity_m_s2)
    eta_slow = cummins.elevation(direct, times, 0.0, 0.0, ENV.water_depth_m, ENV.gravity_m_s2)
    assert np.allclose(eta_fast, eta_slow, atol=1e-9)
    drift = ((0.3, 1e4), (1.5, 2e5))
    assert np.allclose(cummins.drift_force_n(drift, waves, grid), cummins.drift_force_n(drift, direct, grid),
                       rtol=1e-9, atol=1e-6)


@pytest.mark.slow
def test_the_pre_roll_is_a_run_started_earlier_in_the_periodic_sea():
    """A run of 200 s after a 100 s pre-roll equals the last 200 s of a 300 s run in the same
    sea shifted by 100 s (phases - w 100 s)."""
    waves = cummins.jonswap_waves(6.0, 10.0, 3.3, 200.0, seed=5)
    shifted = cummins.Waves(waves.omega_rad_s, waves.amplitude_m, waves.phase_rad - waves.omega_rad_s * 100.0)
    pre = cummins.integrate(PLATFORM, DATABASE, waves, 200.0, preroll_s=100.0)
    whole = cummins.integrate(PLATFORM, DATABASE, shifted, 300.0)
    assert pre.time_s[0] == 0.0 and pre.time_s[-1] == pytest.approx(200.0)
    tail = whole.position[-pre.position.shape[0]:]
    scale = np.abs(tail).max(axis=0)
    assert np.all(np.abs(pre.position - tail)[:, [0, 2, 4]] <= 1e-4 * scale[[0, 2, 4]])


def test_catenary_lines_follow_the_inextensible_closed_form():
    """With a very stiff line, MoorPy's fairlead tension H at a span X is the seabed
    catenary's root of X = L - s + (H/W) acosh(1 + h W / H), s = sqrt(h^2 + 2 h H / W)."""
    from moorpy.Catenary import catenary as moorpy_catenary
    from scipy.optimize import brentq
    lines = catenary.ChainLines(axial_stiffness_n=1e11)
    h = ENV.water_depth_m + PLATFORM.mooring.lines[0].fairlead_m[2]
    w = lines.weight_n_m

    def span_at(horizontal: float) -> float:
        a = horizontal / w
        return lines.length_m - math.sqrt(h * h + 2 * h * a) + a * math.acosh(1 + h / a)
    all_hanging = w * (lines.length_m ** 2 - h * h) / (2 * h)  # above it no chain would lie on the seabed
    for span in (760.0, 790.0, 800.0):
        ours = abs(moorpy_catenary(span, h, lines.length_m, lines.axial_stiffness_n, w, CB=0)[2])
        closed = brentq(lambda H, span=span: span_at(H) - span, 1e3, all_hanging)
        assert ours == pytest.approx(closed, rel=0.02)


def test_catenary_surge_curve_is_restoring_and_hardening():
    curve = np.asarray(catenary.surge_curve(PLATFORM, catenary.ChainLines()))
    x, extra = curve[:, 0], curve[:, 1]
    spring = np.array([cummins.mooring_wrench(PLATFORM, np.array([v, 0, 0, 0, 0, 0]))[0] for v in x])
    total = extra + spring - cummins.mooring_wrench(PLATFORM, np.zeros(6))[0]
    assert extra[x == 0.0][0] == pytest.approx(0.0, abs=1.0)
    stiffness = -np.gradient(total, x)
    assert np.all(stiffness > 0)
    assert stiffness[x == 30.0][0] > 3 * stiffness[x == 0.0][0]  # chain lifting off the seabed


def test_the_catenary_scenarios_stiffness_at_rest_is_within_the_catalogues_plausible_range():
    """The benchmark's chain lines are stiff at zero offset as the spring lines are (strength
    1) or 20 % more (strength 2), within mooring_stiffness's plausible scale, so that the
    right answer is reachable at plausible values; they harden with offset."""
    from fowt_hydro_sim.studies.diagnosis.benchmark import INDEPENDENT_INJECTIONS
    from fowt_hydro_sim.studies.diagnosis.effects import CATALOGUE
    low, high = next(p for p in CATALOGUE["mooring_stiffness"].parameters
                     if p.name == "line_stiffness_scale").plausible_range

    def stiffness(force, x: float) -> float:
        return -(force(x + 0.5) - force(x - 0.5))

    spring = stiffness(lambda x: cummins.mooring_wrench(PLATFORM, np.array([x, 0, 0, 0, 0, 0]))[0], 0.0)
    ratios = []
    for values in INDEPENDENT_INJECTIONS["catenary_mooring"].strengths:
        lines = catenary.ChainLines(values["anchor_distance_m"], values["length_m"], values["weight_n_m"])
        chain = lambda x, lines=lines: catenary.surge_force_n(PLATFORM, lines, x)  # noqa: E731
        ratios.append(stiffness(chain, 0.0) / spring)
        assert stiffness(chain, 5.0) > 1.2 * stiffness(chain, 0.0)
    assert ratios == pytest.approx([1.0, 1.2], abs=0.02) and all(low <= r <= high for r in ratios)


def test_the_catenary_scenarios_curves_have_the_mooring_candidates_form_at_plausible_values():
    """Over +-10 m the chain lines' surge restoring is K_11 x (1 + a x / d + h x^2 / d^2)
    (mooring_stiffness's form, d = 5 m) to 1 % of its force at 10 m, with the scale,
    asymmetry a and hardening h within their plausible ranges; without the asymmetric term
    the best symmetric curve misses it by over 10 %: the catenary is stiffer moving away
    from its single line's anchor (-x) than from the pair's."""
    from fowt_hydro_sim.studies.diagnosis.benchmark import INDEPENDENT_INJECTIONS
    from fowt_hydro_sim.studies.diagnosis.effects import CATALOGUE, base, mooring_stiffness
    plausible = {p.name: p.plausible_range for p in CATALOGUE["mooring_stiffness"].parameters}
    d = mooring_stiffness.REFERENCE_OFFSET_M
    k11 = base.linear_modes(PLATFORM)[1][0]
    x = np.linspace(-10.0, 10.0, 21)
    for values in INDEPENDENT_INJECTIONS["catenary_mooring"].strengths:
        lines = catenary.ChainLines(values["anchor_distance_m"], values["length_m"], values["weight_n_m"])
        restoring = -np.array([catenary.surge_force_n(PLATFORM, lines, v) for v in x])
        restoring -= -catenary.surge_force_n(PLATFORM, lines, 0.0)
        form = np.column_stack([x, x ** 2 / d, x ** 3 / d ** 2])
        (k, k2, k3), *_ = np.linalg.lstsq(form, restoring, rcond=None)
        fitted = {"line_stiffness_scale": k / k11, "asymmetry": k2 / k, "hardening": k3 / k}
        for name, value in fitted.items():
            assert plausible[name][0] <= value <= plausible[name][1], (name, value)
        assert np.abs(form @ (k, k2, k3) - restoring).max() < 0.01 * restoring[-1]
        symmetric = form[:, [0, 2]] @ np.linalg.lstsq(form[:, [0, 2]], restoring, rcond=None)[0]
        assert np.abs(symmetric - restoring).max() > 0.1 * restoring[-1]
        assert fitted["asymmetry"] > 0.05


def test_basin_runs_are_cached_and_keyed_by_what_makes_them(tmp_path):
    values = {"amplitude_n_m": 6e7, "frequency_hz": 0.12}
    first = basin.basin_run("a", "rotor_1p", values, 3, "lc5.1", PLATFORM, 120.0, cache=tmp_path)
    assert len(list(tmp_path.glob("*.npz"))) == 1
    again = basin.basin_run("a", "rotor_1p", values, 3, "lc5.1", PLATFORM, 120.0, cache=tmp_path)
    assert np.array_equal(first.motion, again.motion) and np.array_equal(first.elevation_m, again.elevation_m)
    basin.basin_run("a", "rotor_1p", {**values, "frequency_hz": 0.1}, 3, "lc5.1", PLATFORM, 120.0, cache=tmp_path)
    assert len(list(tmp_path.glob("*.npz"))) == 2


@pytest.mark.slow
def test_a_first_seed_gives_other_realisations_of_the_same_scenarios(tmp_path):
    """--seed moves every scenario to other sea realisations (to pool more nulls than one
    list holds) and leaves names and injections as they are; a negative seed is one line."""
    default, other = benchmark.independent_scenarios(nulls=3), benchmark.independent_scenarios(nulls=3, first_seed=5000)
    assert [(s.name, s.effect, s.values) for s in default] == [(s.name, s.effect, s.values) for s in other]
    assert [s.seed for s in default] == [2000 + 17 * i for i in range(len(default))]
    assert [s.seed for s in other] == [5000 + 17 * i for i in range(len(other))]
    runs = [basin.basin_run("null#1/lc5.1", None, {}, s.seed, "lc5.1", PLATFORM, 120.0) for s in (default[0], other[0])]
    assert np.std(runs[0].elevation_m) == pytest.approx(np.std(runs[1].elevation_m), rel=0.5)
    assert abs(np.corrcoef(runs[0].elevation_m, runs[1].elevation_m)[0, 1]) < 0.3  # another realisation
    result = fowt_sim("diagnose-benchmark", "--seed", "-1", "-o", str(tmp_path), timeout=120)
    assert result.returncode == 2 and result.stderr.strip().splitlines() == [
        "fowt-sim diagnose-benchmark: error: --seed: must be zero or more, got -1"], result.stderr



@pytest.mark.slow
@pytest.mark.dask
def test_diagnose_benchmark_independent_small(tmp_path):
    """``--source independent`` on the frequency-dependent drift and a null, 660 s records (60 s
    transient after the 600 s pre-roll), slow drift as the one candidate, two least-squares
    evaluations. Both sides have the hull's BEM slow drift (the model by default, the basin
    as its baseline drift). The injected drift leaves the model's low-frequency surge and
    offset below the measurement in every run; slow drift with a coefficient rising with
    frequency is named and explains those mismatches. The null's flagged cells are the two
    simulators' structural differences in the wave band (strip theory against the BEM: heave
    STD and frequency; their lags are judged only where they read a delay), linear in the
    waves, which slow drift does not close: set
    aside as the baseline's (consistent mismatches or differences of changing sign), so the
    verdict is a baseline mismatch with nothing named, a right answer for a null. Each
    scenario has its surge and pitch decays too."""
    out = tmp_path / "bench"
    result = fowt_sim("diagnose-benchmark", "--source", "independent", "--inject", "frequency_dependent_drift",
                      "--strengths", "1", "--nulls", "1", "--out-of-catalogue", "0", "--effects", "slow_drift",
                      "--max-evaluations", "2", "--duration", "660", "--transient", "60", "--workers", "2",
                      "-o", str(out), timeout=1200)
    assert result.returncode == 0, result.stderr
    data = json.loads((out / "benchmark.json").read_text())
    scores = {s["scenario"]: s for s in data["scenarios"]}
    drift, null = scores["frequency_dependent_drift#1"], scores["null#1"]
    assert (drift["verdict"] in ("explained", "baseline mismatch") and drift["named"] == "slow_drift"
            and drift["correct"]), drift
    assert drift["tuning_closure"] >= 0.5 and drift["blind_closure"] > 0.0, drift
    assert drift["footprint"][0] == ["surge", "std.low_frequency"] and drift["footprint_flagged"], drift
    report = json.loads((out / "reports" / "frequency_dependent_drift_1" / "diagnosis.json").read_text())
    explained = {(m["dof"], m["metric"]): m["explained_by"] for m in report["baseline_mismatches"]}
    assert explained[("surge", "std.low_frequency")] == "slow_drift", explained
    assert all(m["values"][k] < 0 for m in report["baseline_mismatches"] for k in range(3)
               if m["explained_by"] == "slow_drift" and not m["metric"].startswith("frequency"))  # the drift it lacks
    assert null["verdict"] == "baseline mismatch" and null["named"] is None and null["correct"], null
    report = json.loads((out / "reports" / "null_1" / "diagnosis.json").read_text())
    flagged = {(dof, metric) for _, dof, metric in report["flagged"]}
    assert ("heave", "std.wave") in flagged and ("surge", "offset") not in flagged, flagged
    aside = {(m["dof"], m["metric"]) for m in report["baseline_mismatches"]} | {tuple(c) for c in report["differences"]}
    assert ("heave", "std.wave") in aside and report["undriven"] == [], report["reason"]
    summary = data["summary"]  # the scores' figures: one injected scenario named, one null without an alarm
    assert (summary["injected_detected"], summary["top1_accuracy"], summary["footprint_flagged"]) == (1, 1.0, 1.0)
    assert (summary["null"], summary["false_alarm_rate"]) == (1, 0.0), summary
    assert summary["median_blind_closure"] == drift["blind_closure"], summary
    # both scenarios' runs in waves and free decays (surge, pitch), the drift's waves without it
    assert len(list((out / "runs").glob("*.npz"))) == 2 * (5 + 2) + 3
    result = fowt_sim("diagnose-benchmark", "--source", "independent", "--inject", "gremlins", "-o", str(out),
                      timeout=120)
    assert result.returncode == 2 and "unknown gremlins" in result.stderr
