"""Offline analysis: band STDs and their confidence intervals checked by Monte Carlo on
Gaussian records of a known spectrum (coverage, false-alarm rate of "significant"), errors
against a reference, and ``fowt-sim analyze`` on real bags."""
from __future__ import annotations

import json

import numpy as np
import pytest

from fowt_hydro_sim.physics.waves.spectra import jonswap
from fowt_hydro_sim.rosbag.writer import BagWriter
from fowt_hydro_sim.studies.analysis import AnalysisSettings, analyse, compare, pass_rate
from fowt_hydro_sim.testing import fowt_sim
from msg_adapters import cdr, topics
from msg_adapters.sim_time import nanoseconds

DT_S = 0.5
BANDS = {"low_frequency": (0.005, 0.05), "wave": (0.05, 0.25)}


def spectrum(f_hz: np.ndarray) -> np.ndarray:
    """A two-peaked motion spectrum: a resonance at 0.01 Hz and a wave peak at 0.08 Hz."""
    resonance = 400.0 / (1 + ((f_hz - 0.01) / 0.002) ** 2)
    return resonance + jonswap(f_hz, 4.0, 12.5, 3.3)


def gaussian_record(rng: np.random.Generator, duration_s: float) -> np.ndarray:
    """A Gaussian random process with one-sided PSD ``spectrum`` (complex normal Fourier
    coefficients, so amplitudes are Rayleigh: a true random sea, not fixed amplitudes)."""
    n = int(duration_s / DT_S)
    f = np.fft.rfftfreq(n, DT_S)
    df = f[1]
    variance = spectrum(f) * df  # per bin
    coefficients = (rng.normal(size=f.size) + 1j * rng.normal(size=f.size)) * np.sqrt(variance / 4)  # E|c|^2 = S df / 2
    coefficients[0] = 0
    return np.fft.irfft(coefficients * n, n)


def true_band_std(band: tuple[float, float]) -> float:
    f = np.linspace(band[0], band[1], 20001)
    return float(np.sqrt(np.trapezoid(spectrum(f), f)))


def as_motion(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    motion = np.zeros((x.size, 6))
    motion[:, 0] = x
    return np.arange(x.size) * DT_S, motion


SETTINGS = AnalysisSettings(transient_s=0.0, dofs=("surge",), confidence=0.9)


def test_band_std_intervals_cover_the_true_value_and_errors_rarely_look_significant():
    """90 % intervals from 3-hour records: coverage of the spectrum's band STD near 90 %, and
    between two independent records of one process, "significant" about 10 % of the time."""
    rng = np.random.default_rng(11)
    runs = [analyse(f"r{i}", *as_motion(gaussian_record(rng, 10800.0)), SETTINGS) for i in range(120)]
    for band in BANDS:
        truth = true_band_std(BANDS[band])
        low = np.array([r.std_interval["surge"][band][0] for r in runs])
        high = np.array([r.std_interval["surge"][band][1] for r in runs])
        coverage = np.mean((low <= truth) & (truth <= high))
        assert 0.8 <= coverage <= 0.99, (band, coverage)
        assert abs(np.mean([r.std["surge"][band] for r in runs]) / truth - 1) < 0.03  # unbiased
    alarms = [row["significant"] for a, b in zip(runs[::2], runs[1::2]) for row in compare(a, b, SETTINGS)]
    assert 0.02 <= np.mean(alarms) <= 0.2, np.mean(alarms)


def test_an_error_is_measured_passed_or_failed_and_flagged_when_real():
    x = gaussian_record(np.random.default_rng(2), 10800.0)
    reference = analyse("ref", *as_motion(x), SETTINGS)
    same = compare(analyse("same", *as_motion(x), SETTINGS), reference, SETTINGS)
    assert all(r["error_percent"] == 0 and r["passes"] and not r["significant"] for r in same)
    larger = compare(analyse("x1.3", *as_motion(1.3 * x), SETTINGS), reference, SETTINGS)
    assert all(abs(r["error_percent"] - 30.0) < 1e-9 and not r["passes"] and r["significant"] for r in larger)
    slightly = compare(analyse("x1.1", *as_motion(1.1 * x), SETTINGS), reference, SETTINGS)
    assert all(r["passes"] for r in slightly) and pass_rate(larger + slightly) == 0.5


def test_welch_settings_set_the_resolution_and_the_transient_is_dropped():
    x = gaussian_record(np.random.default_rng(5), 7200.0)
    short = analyse("a", *as_motion(x), AnalysisSettings(transient_s=1200.0, segment_s=512.0, window="hamming",
                                                           overlap=0.25, dofs=("surge",)))
    assert abs(short.frequency_hz[1] - 1 / 512.0) < 1e-12 and abs(short.analysed_s - 6000.0) < 1.0
    with pytest.raises(ValueError, match="nothing left after"):
        analyse("b", *as_motion(x[:1000]), AnalysisSettings(transient_s=600.0, dofs=("surge",)))


def write_pose_bag(path, x: np.ndarray, pitch_rad: np.ndarray) -> None:
    with BagWriter(path) as bag:
        channel = bag.add_topic(topics.POSE, topics.POSE_STAMPED)
        for i, (surge, pitch) in enumerate(zip(x, pitch_rad)):
            t = i * DT_S
            bag.write(channel, nanoseconds(t), cdr.pose(t, [surge, 0.0, 0.0, 0.0, pitch, 0.0]))


@pytest.mark.slow
def test_fowt_sim_analyze_writes_the_tables_and_figures(tmp_path):
    rng = np.random.default_rng(8)
    x, y = gaussian_record(rng, 7200.0), gaussian_record(rng, 7200.0)
    write_pose_bag(tmp_path / "measured", x, 0.01 * y)
    write_pose_bag(tmp_path / "model", 1.25 * x, 0.01 * y)  # surge 25 % too large, pitch right
    result = fowt_sim("analyze", str(tmp_path / "model"), "--ref", str(tmp_path / "measured"), "--dofs", "surge",
                      "pitch", "--transient", "100", "--band", "pitch.wave=0.05:0.3", "-o", str(tmp_path / "report"),
                      timeout=120)
    assert result.returncode == 0, result.stderr
    assert "pass rate: 50 % of 4 band metrics" in result.stdout
    report = json.loads((tmp_path / "report" / "analysis.json").read_text())
    errors = {(r["dof"], r["band"]): r for r in report["errors"]}
    assert abs(errors[("surge", "wave")]["error_percent"] - 25.0) < 1e-6
    assert abs(errors[("pitch", "wave")]["error_percent"]) < 1e-6 and report["settings"]["bands_hz"]["pitch"]["wave"] \
        == [0.05, 0.3]
    for name in ("band_stds.csv", "errors.csv", "table.txt", "psd_model.png", "band_stds_model.png"):
        assert (tmp_path / "report" / name).stat().st_size > 100, name


@pytest.mark.slow
def test_analyze_without_a_reference_draws_the_band_stds_and_the_psd_confidence_band(tmp_path):
    """One run, no --ref: the band-STD figure (with its intervals) and the PSD figure, whose
    legend names the confidence band's level."""
    rng = np.random.default_rng(9)
    write_pose_bag(tmp_path / "alone", gaussian_record(rng, 3600.0), 0.01 * gaussian_record(rng, 3600.0))
    result = fowt_sim("analyze", str(tmp_path / "alone"), "--dofs", "surge", "pitch", "--transient", "0",
                      "--confidence", "0.8", "-o", str(tmp_path / "report"), timeout=120)
    assert result.returncode == 0, result.stderr
    for name in ("psd_alone.png", "band_stds_alone.png"):
        assert (tmp_path / "report" / name).stat().st_size > 1000, name
    assert "80 % interval" in result.stdout
    from fowt_hydro_sim.studies.analysis import psd_labels
    run = analyse("alone", *as_motion(gaussian_record(rng, 3600.0)), SETTINGS)
    assert psd_labels(run, None, ("surge",), 0.8)["band"].startswith("run's 80 % confidence band (chi-square, ")


def test_the_psd_confidence_band_covers_the_true_spectrum():
    """Oracle: Monte Carlo on Gaussian records of a known spectrum. The 90 % chi-square band
    of the Welch estimate (its equivalent degrees of freedom from the window's overlap)
    holds the true PSD in about 90 % of the bins between 0.03 and 0.2 Hz."""
    from fowt_hydro_sim.studies.psd import psd_interval
    rng = np.random.default_rng(21)
    inside = []
    for _ in range(40):
        run = analyse("r", *as_motion(gaussian_record(rng, 10800.0)), SETTINGS)
        f = run.frequency_hz
        low, high = psd_interval(run.psd["surge"], run.psd_nu, 0.9)
        bins = (f > 0.03) & (f < 0.2)
        inside.append((low[bins] <= spectrum(f[bins])) & (spectrum(f[bins]) <= high[bins]))
    coverage = float(np.mean(inside))
    assert 0.86 < coverage < 0.94, coverage
    assert 10 < run.psd_nu < 20  # about 10 Hann segments at 50 % overlap in 3 hours


@pytest.mark.parametrize("args, message", [
    (["--dofs", "surge", "swim"], "--dofs: unknown swim"),
    (["--band", "low=0.1"], "expected [DOF.]NAME=LOW:HIGH"),
    (["--band", "wave=0.3:0.1"], "need 0 <= low < high"),
])
def test_analyze_refuses_bad_options_in_one_line(tmp_path, args, message):
    write_pose_bag(tmp_path / "run", np.zeros(400), np.zeros(400))
    result = fowt_sim("analyze", str(tmp_path / "run"), *args, "-o", str(tmp_path / "out"), timeout=60)
    assert result.returncode == 2 and message in result.stderr and "Traceback" not in result.stderr


@pytest.mark.slow
def test_analyze_reads_what_simulate_writes_into_a_default_report_folder(tmp_path):
    """An offline run is analysed like a recorded one; without -o the report goes beside it."""
    run = tmp_path / "run1"
    done = fowt_sim("simulate", "--load-case", "lc5.2", "--duration", "900", "-o", str(run), timeout=300)
    assert done.returncode == 0, done.stderr
    done = fowt_sim("analyze", str(run), "--transient", "100", timeout=300)
    assert done.returncode == 0, done.stderr
    report = json.loads((tmp_path / "run1_report" / "analysis.json").read_text())
    from fowt_hydro_sim.studies.psd import band_std, psd
    from fowt_hydro_sim.studies.simulate import read_run
    columns = read_run(run)
    keep = columns["time_s"] >= 100.0
    f, s = psd(columns["heave_m"][keep], 0.25, 2048.0)
    heave = {r["band"]: r["std"] for r in report["band_stds"] if r["dof"] == "heave"}
    assert heave["wave"] == pytest.approx(band_std(f, s, BANDS["wave"]), rel=1e-9)
    assert (tmp_path / "run1_report" / "psd_run1.png").stat().st_size > 1000


def _printed_band_stds(simulate_out: str, analyze_out: str) -> tuple[dict, dict]:
    """(DOF, band) -> STD as ``simulate`` prints them (its table's last two columns) and as
    ``analyze`` prints them (one line per run, DOF and band)."""
    simulated, analysed = {}, {}
    for line in simulate_out.splitlines():
        words = line.split()
        if len(words) == 8 and words[0] in ("surge", "heave", "pitch"):
            simulated[(words[0], "low_frequency")], simulated[(words[0], "wave")] = float(words[6]), float(words[7])
    for line in analyze_out.splitlines():
        words = line.split()
        if len(words) >= 4 and words[1] in ("surge", "heave", "pitch") and words[2] in BANDS:
            analysed[(words[1], words[2])] = float(words[3])
    return simulated, analysed


@pytest.mark.slow
def test_simulate_and_analyze_drop_the_same_transient_and_print_the_same_band_stds(tmp_path):
    """Both commands' defaults drop the same start-up, both say so, and the band STDs
    simulate prints are those analyze prints of the same output folder."""
    from fowt_hydro_sim.studies.psd import TRANSIENT_S
    run = tmp_path / "run"
    simulated = fowt_sim("simulate", "--load-case", "lc5.2", "--duration", "900", "-o", str(run), timeout=300)
    assert simulated.returncode == 0, simulated.stderr
    analysed = fowt_sim("analyze", str(run), timeout=300)
    assert analysed.returncode == 0, analysed.stderr
    assert f"statistics from t = {TRANSIENT_S:g} s (the first {TRANSIENT_S:g} s dropped" in simulated.stdout
    assert f"each run analysed after its first {TRANSIENT_S:g} s" in analysed.stdout
    from_simulate, from_analyze = _printed_band_stds(simulated.stdout, analysed.stdout)
    assert len(from_simulate) == len(from_analyze) == 6, (simulated.stdout, analysed.stdout)
    for key, value in from_simulate.items():
        assert from_analyze[key] == pytest.approx(value, abs=1.5e-3, rel=1e-3), key


def test_the_psd_figure_says_the_sea_the_drag_the_record_and_whether_resonance_is_resolved():
    from fowt_hydro_sim.physics.config import load_platform
    from fowt_hydro_sim.physics.model import PlatformModel
    from fowt_hydro_sim.studies.analysis import RunContext, natural_frequencies_hz, psd_labels
    platform = load_platform()
    natural = natural_frequencies_hz(platform)
    model = PlatformModel(platform, None)
    assert sorted(natural.values()) == pytest.approx(sorted(set(np.round(1 / model.natural_periods_s(), 9))),
                                                     rel=1e-6)
    heave_hz = np.sqrt(model.restoring_matrix()[2, 2] / model.mass_matrix()[2, 2]) / (2 * np.pi)
    assert natural["heave"] == pytest.approx(heave_hz, rel=1e-6)  # heave is uncoupled: its own mode
    assert 0.009 < natural["surge"] < 0.012  # the 97 s surge resonance
    context = RunContext(11.0, 12.0, 4.9, "filtered", natural)
    rng = np.random.default_rng(3)
    settings = AnalysisSettings(transient_s=0.0, dofs=("surge", "pitch"))
    short = analyse("model", *as_motion(gaussian_record(rng, 1200.0)), settings, context)
    long = analyse("model", *as_motion(gaussian_record(rng, 3 * 3600.0)), settings, context)
    reference = analyse("model", *as_motion(gaussian_record(rng, 1200.0)), settings)
    labels = psd_labels(short, reference, settings.dofs)
    assert labels["title"][0] == "PSD: model vs reference model"
    assert labels["title"][1] == "Hs 11 m, Tp 12 s, gamma 4.9, drag filtered, 1200 s analysed, df 0.0033 Hz"
    assert labels["title"][2].startswith("resonance NOT RESOLVED (surge 0.0103 Hz")
    assert (labels["run"], labels["reference"]) == ("run: model", "reference: model")
    assert set(labels["marks"]) == {"surge 97 s", f"pitch {1 / natural['pitch']:.0f} s", "Tp 12 s"}
    long_labels = psd_labels(long, None, settings.dofs)
    assert len(long_labels["title"]) == 2 and "10800 s analysed, df 0.0005 Hz" in long_labels["title"][1]
