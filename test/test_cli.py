"""``fowt-sim simulate`` as a user runs it: a real subprocess, real files."""
from __future__ import annotations

import csv
import json
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from fowt_hydro_sim.studies.simulate import read_run
from fowt_hydro_sim.testing import REPO, fowt_sim
from fowt_hydro_sim.testing.references import hydrodyn_case


@pytest.mark.slow
def test_simulate_writes_time_series_and_summary(tmp_path: Path):
    out = tmp_path / "run"
    done = fowt_sim("simulate", "--load-case", "lc5.2", "--duration", "120", "--seed", "2", "-o", str(out))
    assert done.returncode == 0, done.stderr
    columns = read_run(out)
    summary = json.loads((out / "summary.json").read_text())
    assert columns["time_s"][-1] == 120.0 and np.allclose(np.diff(columns["time_s"]), 0.25)
    assert summary["waves"]["hs_m"] == 6.19 and summary["waves"]["seed"] == 2
    assert summary["waves"]["repeat_period_s"] == 3600.0
    assert np.isclose(summary["statistics"]["heave"]["std"], np.std(columns["heave_m"]), rtol=1e-6)
    assert "surge [m]" in done.stdout
    again = fowt_sim("simulate", "--load-case", "lc5.2", "--duration", "120", "--seed", "2", "-o", str(out))
    assert again.returncode == 2 and "--overwrite" in again.stderr  # never overwrites silently


def test_simulate_reuses_an_openfast_comp_file(tmp_path: Path):
    comp = hydrodyn_case("cyl_fixed") / "waves_jonswap_Hs11_Tp12_g4.9.Comp"
    done = fowt_sim("simulate", "--waves-comp", str(comp), "--duration", "60", "-o", str(tmp_path))
    assert done.returncode == 0, done.stderr
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["run"]["n_wave_components"] == 169


def test_bad_input_is_one_clear_line(tmp_path: Path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: x\nmass: {mass_kg: -3}\n")
    for args, expected in ((["--platform", str(bad)], "mass.mass_kg"),
                           (["--load-case", "lc9.9"], "load case"),
                           (["--platform", "no_such_platform"], "no_such_platform"),
                           (["--hs", "3"], "--tp")):
        done = fowt_sim("simulate", *args, "-o", str(tmp_path / "o"))
        assert done.returncode == 2
        assert expected in done.stderr and "Traceback" not in done.stderr


@pytest.mark.parametrize("args, message", [
    (("--hs", "-3", "--tp", "10"), "--hs: must be 0 to 30, got -3"),
    (("--hs", "4", "--tp", "10", "--dt", "0"), "--dt: must be a positive number, got 0"),
    (("--duration", "-5"), "--duration: must be a positive number, got -5"),
    (("--hs", "4", "--tp", "-10"), "--tp: must be a positive number, got -10"),
    (("--load-case", "5.3", "--seed", "-1"), "--seed: must be zero or more, got -1"),
])
def test_out_of_range_options_are_named_with_their_range(tmp_path: Path, args: tuple, message: str):
    """Each value outside its setting's range ends the run with one line naming the option
    and what is allowed, before anything is written."""
    out = tmp_path / "o"
    done = fowt_sim("simulate", *args, "-o", str(out))
    assert done.returncode == 2, done.stdout
    assert done.stderr.strip().splitlines() == [f"fowt-sim simulate: error: {message}"]
    assert not (out / "summary.json").exists()


def test_a_load_case_given_by_its_number_is_recorded_by_its_name(tmp_path: Path):
    done = fowt_sim("simulate", "--load-case", "5.3", "--duration", "5", "-o", str(tmp_path))
    assert done.returncode == 0, done.stderr
    waves = json.loads((tmp_path / "summary.json").read_text())["waves"]
    assert (waves["load_case"], waves["hs_m"], waves["tp_s"], waves["gamma"]) == ("lc5.3", 11.0, 12.0, 4.9)


def test_help_lists_every_command_and_every_option_says_its_default():
    import argparse

    from fowt_hydro_sim.cli import command_parsers
    done = fowt_sim("--help")
    listed = {line.split()[0] for line in done.stdout.splitlines() if line.startswith("    ") and line.split()}
    assert {"simulate", "load-cases", "waves", "recover", "info", "analyze", "calibrate", "diagnose",
            "node", "controller", "play", "record"} <= listed, done.stdout
    commands = command_parsers()
    for name, command in commands.items():
        for action in command._actions:
            if action.option_strings and not isinstance(action, argparse._HelpAction):
                assert re.search(r"default|required", action.help or ""), (name, action.option_strings)
    simulate_help = fowt_sim("simulate", "--help").stdout
    assert "(default: none" in simulate_help and "(default off)" in simulate_help


def test_top_level_help_imports_no_command_module_and_lists_every_command():
    """``fowt-sim --help`` in a fresh interpreter imports neither numba, scipy, dask nor the
    model (the command table is static) and lists every command with its module's own help."""
    from fowt_hydro_sim.cli import COMMAND_HELP, COMMAND_MODULES, ROS_COMMANDS
    probe = ("import contextlib, io, json, sys\n"
             "from fowt_hydro_sim.cli import main\n"
             "out = io.StringIO()\n"
             "with contextlib.redirect_stdout(out), contextlib.suppress(SystemExit):\n"
             "    main(['--help'])\n"
             "heavy = sorted(m for m in sys.modules if m.split('.')[0] in ('numba', 'scipy', 'dask', 'distributed')\n"
             "               or m.startswith(('fowt_hydro_sim.physics', 'fowt_hydro_sim.studies')))\n"
             "print(json.dumps({'help': out.getvalue(), 'heavy': heavy}))\n")
    done = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=120,
                          cwd=Path(__file__).resolve().parents[1])
    assert done.returncode == 0, done.stderr
    result = json.loads(done.stdout)
    assert result["heavy"] == []
    listed = {line.split()[0]: " ".join(line.split()[1:]) for line in result["help"].splitlines()
              if line.startswith("    ") and line.split()}
    assert set(COMMAND_MODULES) | set(ROS_COMMANDS) <= set(listed), result["help"]
    assert set(COMMAND_HELP) == set(COMMAND_MODULES)
    # the static table says what each command's module says
    import argparse

    from fowt_hydro_sim.cli import _define
    sub = argparse.ArgumentParser().add_subparsers()
    for module in set(COMMAND_MODULES.values()):
        _define(sub, module)
    assert {a.dest: a.help for a in sub._choices_actions} == COMMAND_HELP


@pytest.mark.slow
def test_list_defaults_are_printed_as_the_option_takes_them():
    """``sweep --help`` says ``(default lc5.3)``, not a Python list; ``load-cases --help``
    names the study's cases."""
    from fowt_hydro_sim.cli.simulate import STUDY_CASES
    from fowt_hydro_sim.studies.load_case_study import STUDY_CASES as STUDY
    assert STUDY_CASES == STUDY
    for command in ("sweep", "analyze", "load-cases", "calibrate"):
        done = fowt_sim(command, "--help")
        assert done.returncode == 0, done.stderr
        assert "['" not in done.stdout and "[1" not in done.stdout, done.stdout
    text = " ".join(fowt_sim("sweep", "--help").stdout.split())
    assert "(default lc5.3)" in text and "(default surge heave pitch)" not in text
    assert "(default 1)" in text and "(default constant)" in text
    text = " ".join(fowt_sim("load-cases", "--help").stdout.split())
    assert " ".join(STUDY) in text
    assert "(default: surge heave pitch)" in " ".join(fowt_sim("analyze", "--help").stdout.split())
    for command in ("stability", "simulate"):  # an empty default is said, not left blank
        text = " ".join(fowt_sim(command, "--help").stdout.split())
        assert "(default )" not in text and "(default: empty)" in text, text


@pytest.mark.slow
def test_simulate_from_a_run_file(tmp_path: Path):
    """Platform, sea state and run from one YAML file; a bad field is named."""
    run_file = tmp_path / "run.yaml"
    run_file.write_text("platform: windmoor12\nsea_state: {hs_m: 4.0, tp_s: 10.0, gamma: 2.0, seed: 7}\n"
                        "run: {dt_s: 0.05, duration_s: 30, output_interval_s: 0.5}\n")
    done = fowt_sim("simulate", "--config", str(run_file), "-o", str(tmp_path / "out"))
    assert done.returncode == 0, done.stderr
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert (summary["waves"]["hs_m"], summary["waves"]["seed"], summary["run"]["output_interval_s"]) == (4.0, 7, 0.5)
    assert read_run(tmp_path / "out")["time_s"][-1] == 30.0
    run_file = tmp_path / "bad.yaml"
    run_file.write_text("run: {dt_s: -1}\n")
    done = fowt_sim("simulate", "--config", str(run_file), "-o", str(tmp_path / "bad"))
    assert done.returncode == 2 and "bad.yaml: run.dt_s: must be a positive number" in done.stderr


@pytest.mark.slow
def test_filtered_simulate_and_the_load_case_study_agree(tmp_path: Path):
    """``simulate --drag filtered`` and ``load-cases`` on the same sea (seed, duration,
    start-up) report the same band STDs; the study writes its CSV, Markdown table and a PNG
    per load case, and the band STDs in the summary are those of the written time series."""
    from fowt_hydro_sim.studies.psd import band_stds

    sim = tmp_path / "sim"
    done = fowt_sim("simulate", "--load-case", "lc5.0", "--drag", "filtered", "--duration", "700",
                    "--transient", "100", "--seed", "4", "-o", str(sim))
    assert done.returncode == 0, done.stderr
    summary = json.loads((sim / "summary.json").read_text())
    assert summary["drag_model"] == "filtered" and summary["statistics"]["analysed_from_s"] == 100.0
    columns = read_run(sim)
    keep = columns["time_s"] >= 100.0
    assert summary["statistics"]["heave"]["band_std"] == pytest.approx(band_stds(columns["heave_m"][keep], 0.25),
                                                                       rel=1e-6)

    study = tmp_path / "study"
    done = fowt_sim("load-cases", "--cases", "lc5.0", "--duration", "600", "--transient", "100", "--seed", "4",
                    "-o", str(study))
    assert done.returncode == 0, done.stderr
    assert (study / "psd_lc5.0.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    rows = list(csv.DictReader(open(study / "band_stds.csv")))
    assert [r["dof"] for r in rows] == ["surge", "heave", "pitch"]
    for row in rows:
        expected = summary["statistics"][row["dof"]]["band_std"]
        for band in ("low_frequency", "wave"):
            assert float(row[f"{band}_case2"]) == pytest.approx(expected[band], rel=1e-6)
            change = 100 * (float(row[f"{band}_case2"]) / float(row[f"{band}_case1"]) - 1)
            assert float(row[f"{band}_change_percent"]) == pytest.approx(change)
    assert "| lc5.0 | surge [m] |" in (study / "band_stds.md").read_text()
    assert "2/2 runs |" in done.stderr and "left" in done.stderr  # the progress bar, with the time left
    assert done.stdout.count("fowt-sim") == 0 and "x real time" not in done.stderr  # no line per run


@pytest.mark.slow
def test_an_interrupted_load_case_study_keeps_the_table_of_the_cases_done(tmp_path: Path):
    """Ctrl-C during a study: exit 130, one line, the tables of the cases done. The study gets
    SIGINT's default disposition, as a process started from a terminal has: a test run
    started in the background by a shell without job control ignores SIGINT, and so would
    the study, which would then run to its end."""
    study = tmp_path / "study"
    process = subprocess.Popen([sys.executable, "-m", "fowt_hydro_sim.cli", "load-cases", "--cases", "lc5.0",
                                "lc5.1", "lc5.2", "lc5.3", "--duration", "1500", "--transient", "60", "-o",
                                str(study)], cwd=Path(__file__).resolve().parents[1], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True,
                               preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        deadline = time.monotonic() + 240
        while not (study / "psd_lc5.0.png").exists() and process.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)
        process.send_signal(signal.SIGINT)
        _, stderr = process.communicate(timeout=120)
    finally:
        if process.poll() is None:
            process.kill()
            process.communicate()
    assert process.returncode == 130 and "interrupted" in stderr and "Traceback" not in stderr, stderr
    rows = list(csv.DictReader(open(study / "band_stds.csv")))
    done = list(dict.fromkeys(r["load_case"] for r in rows))
    assert done and done == ["lc5.0", "lc5.1", "lc5.2"][:len(done)]
    assert f"(partial: {len(done)} of 4 load cases)" in (study / "band_stds.md").read_text()


def test_load_case_figures_have_a_log_frequency_axis_the_sea_state_and_the_marks():
    from fowt_hydro_sim.physics.config import load_platform
    from fowt_hydro_sim.studies.analysis import natural_frequencies_hz
    from fowt_hydro_sim.studies.load_case_study import CaseRun, case_labels, plot_case
    frequency = np.fft.rfftfreq(8192, 0.25)
    runs = [CaseRun("lc5.3", drag, frequency, {d: 1 / (1e-3 + frequency) for d in ("surge", "heave", "pitch")},
                    {}, 100.0) for drag in ("constant", "filtered")]
    natural = natural_frequencies_hz(load_platform())
    labels = case_labels("windmoor12", "lc5.3", runs, 12000.0, natural)
    assert labels["title"].startswith("windmoor12, lc5.3: Hs 11 m, Tp 12 s, gamma 4.9\n")
    assert "12000 s analysed, df 0.0005 Hz" in labels["title"]
    assert labels["marks"]["Tp 12 s"] == pytest.approx(1 / 12) and "surge 97 s" in labels["marks"]
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    shown = []
    original = plt.Figure.savefig

    def keep(fig, *args, **kwargs):
        shown.append([(ax.get_xscale(), ax.get_xlim()) for ax in fig.axes])
        return original(fig, *args, **kwargs)

    plt.Figure.savefig = keep
    try:
        plot_case("lc5.3", runs, Path("/dev/null"), labels)
    finally:
        plt.Figure.savefig = original
    assert all(scale == "log" and lim[0] < 0.005 < 0.25 < lim[1] for scale, lim in shown[0])


@pytest.mark.slow
@pytest.mark.parametrize("dof, j, offset", [("surge", 0, 8.0), ("heave", 2, 2.0), ("pitch", 4, 0.05)])
def test_a_free_decay_run_reports_its_fitted_period_and_damping(tmp_path: Path, dof: str, j: int, offset: float):
    """Still water and an initial offset: the fitted period is the linearised model's natural
    period (within 1 %), and the damping ratio agrees with the log decrement of the record's
    peaks over the same first cycles (within 10 %)."""
    import scipy.signal

    from fowt_hydro_sim.physics.config import load_platform
    from fowt_hydro_sim.physics.model import PlatformModel
    from fowt_hydro_sim.studies.simulate import DECAY_CYCLES
    initial = ["0"] * 6
    initial[j] = str(offset)
    done = fowt_sim("simulate", "--still-water", "--initial", *initial, "--duration", "600", "--output-interval",
                    "0.05", "-o", str(tmp_path))
    assert done.returncode == 0, done.stderr
    fits = json.loads((tmp_path / "summary.json").read_text())["free_decay"]
    assert list(fits) == [dof] and f"free decay {dof}: period" in done.stdout
    fit = fits[dof]
    natural = PlatformModel(load_platform(), None).natural_periods_s()
    assert np.min(np.abs(natural - fit["natural_period_s"])) < 0.01 * fit["natural_period_s"], (natural, fit)
    columns = read_run(tmp_path)
    x = columns[("surge_m", "sway_m", "heave_m", "roll_rad", "pitch_rad", "yaw_rad")[j]]
    peaks, _ = scipy.signal.find_peaks(x)
    peaks = peaks[x[peaks] > 0]
    n = min(DECAY_CYCLES, len(peaks) - 1)
    assert fit["cycles"] == pytest.approx(n, abs=1.0)
    decrement = np.log(x[peaks[0]] / x[peaks[n]]) / n
    zeta = decrement / np.sqrt(4 * np.pi**2 + decrement**2)
    period = np.diff(columns["time_s"][peaks[:n + 1]]).mean()
    assert fit["damping_ratio"] == pytest.approx(zeta, rel=0.10), (fit, zeta)
    assert fit["period_s"] == pytest.approx(period, rel=0.01)


def test_node_help_lists_every_parameter_with_its_default():
    pytest.importorskip("rclpy")
    from fowt_hydro_sim.ros.node import NodeSettings
    from fowt_hydro_sim.settings import described
    done = fowt_sim("node", "--help")
    assert done.returncode == 0, done.stderr
    listed = {line.split()[0]: line for line in done.stdout.splitlines() if line.startswith("  ")}
    assert set(listed) == set(described(NodeSettings))
    assert "(default 'stop'; one of stop, continue)" in listed["record_failure"]
    assert all("(default " in line for line in listed.values())


WITHOUT = """
import sys

class Absent:
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in sys.argv[1].split(","):
            raise ModuleNotFoundError(f"No module named {name!r}")

sys.meta_path.insert(0, Absent())
from fowt_hydro_sim.cli import main
sys.exit(main(sys.argv[2:]))
"""


def fowt_sim_without(packages: str, *args: object) -> subprocess.CompletedProcess:
    """``fowt-sim ARGS`` in a child process where ``packages`` (comma-separated) cannot be imported."""
    return subprocess.run([sys.executable, "-c", WITHOUT, packages, *map(str, args)], cwd=REPO,
                          capture_output=True, text=True, timeout=300)


@pytest.mark.slow
def test_without_matplotlib_analyze_writes_its_tables_and_says_the_figures_are_not_drawn(tmp_path: Path):
    run = tmp_path / "run"
    assert fowt_sim("simulate", "--load-case", "lc5.2", "--duration", "200", "-o", run).returncode == 0
    done = fowt_sim_without("matplotlib", "analyze", run, "--transient", "0", "-o", tmp_path / "report")
    assert done.returncode == 0, done.stderr
    said = [line for line in done.stderr.splitlines() if "not installed" in line]
    assert len(said) == 1 and "figures not drawn: matplotlib" in said[0] and "[plots]" in said[0], done.stderr
    assert "Traceback" not in done.stderr and "surge" in done.stdout
    assert (tmp_path / "report" / "table.txt").exists() and not list((tmp_path / "report").glob("*.png"))


def test_without_dask_a_sweep_is_refused_in_one_line_naming_the_extra(tmp_path: Path):
    done = fowt_sim_without("dask,distributed", "sweep", "--duration", "60", "--seeds", "1", "-o", tmp_path / "s")
    assert done.returncode == 2 and "Traceback" not in done.stderr, done.stderr
    assert [line for line in done.stderr.splitlines() if "error" in line] == [
        "fowt-sim sweep: error: this command runs on a Dask cluster, and Dask is not installed: "
        "pip install 'fowt_hydro_sim[cluster]'"], done.stderr


@pytest.mark.slow
@pytest.mark.ros
@pytest.mark.parametrize("command, module, settings", [("turbine", "turbine_node", "TurbineSettings"),
                                                       ("controller", "thrust_controller", "ControllerSettings")])
def test_the_other_nodes_help_lists_their_parameters(command, module, settings):
    pytest.importorskip("rclpy")
    import importlib

    from fowt_hydro_sim.settings import described
    done = fowt_sim(command, "--help")
    assert done.returncode == 0, done.stderr
    listed = {line.split()[0] for line in done.stdout.splitlines() if line.startswith("  ")}
    assert listed == set(described(getattr(importlib.import_module(f"fowt_hydro_sim.ros.{module}"), settings)))
