"""``fowt-sim sweep``: a real Dask LocalCluster, real runs, real files. Each row must be what a
single ``simulate`` run of the same settings gives; an interrupted sweep resumes without
redoing its finished runs; the intervals over seeds are Student t's, log-normal (positive) for
STDs."""
from __future__ import annotations

import csv
import json
import os
import re
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest
import scipy.stats
import yaml

from fowt_hydro_sim.physics.config import RunConfig, SeaState, load_platform, platform_document
from fowt_hydro_sim.physics.platform_edits import scaled_drag
from fowt_hydro_sim.rosbag.reader import Bag
from fowt_hydro_sim.studies import simulate
from fowt_hydro_sim.studies.sweep import (
    RUNS_FILE,
    SUMMARY_FILE,
    Sweep,
    Variant,
    confidence_interval,
    is_positive,
    metric_names,
    run_sweep,
)
from fowt_hydro_sim.testing import REPO, fowt_sim

DOFS = (("surge", "m"), ("sway", "m"), ("heave", "m"), ("roll", "deg"), ("pitch", "deg"), ("yaw", "deg"))



def read_table(path: Path) -> list[dict]:
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def dask_noise(stderr: str) -> list[str]:
    """The lines of a command's stderr that are neither its progress bar, its own INFO log
    nor its one-line error or interruption: Dask's warnings, tracebacks."""
    lines = [line.strip() for line in stderr.replace("\r", "\n").splitlines()]
    own = ("sweep:", "measured runs:", "INFO fowt_hydro_sim", "fowt-sim sweep: ", "fowt-sim diagnose-benchmark: ")
    return [line for line in lines if line and not line.startswith(own)]


def expected_row(summary: dict) -> dict:
    """A runs.csv row's statistics as ``simulate``'s summary.json gives them."""
    out = {}
    for name, unit in DOFS:
        s = summary["statistics"][name]
        out.update({f"{name}_{k}_{unit}": s[k] for k in ("mean", "std", "min", "max")})
        out.update({f"{name}_std_{b}_{unit}": v for b, v in s["band_std"].items()})
    out["wave_hs_4std_m"] = summary["statistics"]["wave_elevation"]["hs_4std"]
    return out


def cox_interval(values: np.ndarray, level: float) -> tuple[float, float]:
    """Cox's log-normal interval of the mean with Student's t, written out here."""
    y = np.log(values)
    n, s2 = y.size, y.var(ddof=1)
    half = scipy.stats.t.ppf(0.5 + level / 2, n - 1) * np.sqrt(s2 / n + s2**2 / (2 * (n - 1)))
    return float(np.exp(y.mean() + s2 / 2 - half)), float(np.exp(y.mean() + s2 / 2 + half))


def test_an_std_interval_over_two_seeds_is_wide_but_positive():
    """The two seeds whose Student-t interval was [-1.71, 3.78] around an STD of 1.034:
    the log-normal interval holds the mean and stays above zero."""
    values = np.array([0.818, 1.250])
    mean, _, low, high = confidence_interval(values, 0.95, positive=True)
    assert mean == pytest.approx(1.034) and 0 < low < min(values) and high > 5 * mean
    assert (low, high) == pytest.approx(cox_interval(values, 0.95), rel=1e-12)
    assert confidence_interval(values, 0.95)[2] < 0  # (Student's t: below zero)
    assert confidence_interval(np.array([0.0, 0.0]), 0.95, positive=True)[2:] == (0.0, 0.0)  # an unexcited DOF
    assert is_positive("surge_std_low_frequency_m") and is_positive("wave_hs_4std_m")
    assert not is_positive("surge_mean_m") and not is_positive("pitch_min_deg")


def test_std_intervals_cover_the_mean_of_seed_to_seed_stds():
    """Oracle: Monte Carlo. STDs of 20-sample Gaussian records (true mean of the sample STD
    c4(20) = 0.98693), two and five seeds: 90 % intervals cover it about 90 % of the time,
    and never go below zero."""
    rng = np.random.default_rng(5)
    c4 = 0.9869313
    for n in (2, 5):
        draws = [confidence_interval(rng.normal(size=(n, 20)).std(axis=1, ddof=1), 0.9, positive=True)
                 for _ in range(3000)]
        coverage = np.mean([low <= c4 <= high for _, _, low, high in draws])
        assert 0.87 < coverage < 0.93, (n, coverage)
        assert min(low for _, _, low, _ in draws) > 0


@pytest.mark.slow
@pytest.mark.dask
def test_sweep_rows_are_single_simulate_runs_and_intervals_are_student_t(tmp_path: Path):
    """2 seeds x 2 drag models x 2 variants on a 2-worker LocalCluster, bags on; each row
    against ``simulate`` of the same settings (the Cd-scaled variant as a platform file),
    the summary's 90 % intervals against scipy.stats.t.interval (Cox's log-normal interval
    for the STDs)."""
    run = RunConfig(duration_s=150.0)
    sweep = Sweep(("lc5.3",), (1, 2, 3), ("constant", "filtered"), (Variant("base"), Variant("cd120", cd_scale=1.2)),
                  run, transient_s=20.0)
    outcome = run_sweep(sweep, tmp_path / "sweep", workers=2, bags=True, level=0.9)
    assert outcome["runs"] == outcome["new"] == 12
    rows = read_table(tmp_path / "sweep" / RUNS_FILE)
    assert len(rows) == 12 and len({(r["seed"], r["drag_model"], r["variant"]) for r in rows}) == 12

    scaled = tmp_path / "windmoor12_cd120.yaml"
    scaled.write_text(yaml.safe_dump(platform_document(scaled_drag(load_platform("windmoor12"), 1.2))))
    platforms = {"base": "windmoor12", "cd120": str(scaled)}
    for row in rows:
        if row["seed"] == "3":
            continue  # (two seeds against simulate are enough)
        single = RunConfig(platform=platforms[row["variant"]], drag_model=row["drag_model"], duration_s=150.0)
        sea = SeaState(float(row["hs_m"]), float(row["tp_s"]), float(row["gamma"]), seed=int(row["seed"]))
        out = tmp_path / f"single_{row['seed']}_{row['drag_model']}_{row['variant']}"
        summary = simulate.simulate(single, *simulate.sea_state_waves(sea, 150.0, "lc5.3"), out, transient_s=20.0)
        for column, value in expected_row(summary).items():
            assert float(row[column]) == pytest.approx(value, rel=1e-12, abs=1e-15), (row["variant"], column)
        if row["seed"] == "1" and row["variant"] == "cd120":
            bag = Bag(tmp_path / "sweep" / "bags" / f"lc5.3_seed1_{row['drag_model']}_cd120")
            pose = bag.motion()
            columns = simulate.read_run(out)
            assert np.allclose(pose.time_s, columns["time_s"]) and np.allclose(pose.values[:, 0], columns["surge_m"],
                                                                                atol=1e-6)

    summary_rows = read_table(tmp_path / "sweep" / SUMMARY_FILE)
    assert len(summary_rows) == 4 * len(metric_names())
    for s in summary_rows:
        values = np.array([float(r[s["statistic"]]) for r in rows
                           if (r["drag_model"], r["variant"]) == (s["drag_model"], s["variant"])])
        assert int(s["n_seeds"]) == values.size == 3
        if np.ptp(values) == 0:
            continue  # (e.g. a band with no bin in a short record: no spread, no interval)
        if is_positive(s["statistic"]) and np.all(values > 0):
            low, high = cox_interval(values, 0.9)
            assert s["interval"] == "lognormal_cox" and float(s["ci_low"]) > 0
        else:
            low, high = scipy.stats.t.interval(0.9, values.size - 1, loc=values.mean(),
                                               scale=scipy.stats.sem(values))
            low = max(low, 0.0) if is_positive(s["statistic"]) else low
        assert float(s["mean"]) == pytest.approx(values.mean(), rel=1e-12)
        assert (float(s["ci_low"]), float(s["ci_high"])) == pytest.approx((low, high), rel=1e-9, abs=1e-14)


@pytest.mark.slow
@pytest.mark.dask
def test_an_interrupted_sweep_resumes_without_redoing_finished_runs(tmp_path: Path):
    """Kill the command (and its cluster) once some rows are written, cut its last line as a
    kill during a write would, and run it again: finished rows stay as they were."""
    out = tmp_path / "sweep"
    args = ("sweep", "--load-cases", "lc5.2", "lc5.3", "--seeds", "1", "2", "3", "4", "--duration", "400",
            "--workers", "1", "-o", str(out))
    process = subprocess.Popen([sys.executable, "-m", "fowt_hydro_sim.cli", *args], cwd=REPO,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    runs = out / RUNS_FILE
    try:
        deadline = time.monotonic() + 400
        while time.monotonic() < deadline and process.poll() is None:
            if runs.exists() and runs.read_text().count("\n") >= 3:  # header and two rows
                break
            time.sleep(0.05)
    finally:
        os.killpg(process.pid, signal.SIGKILL)
        process.wait(timeout=30)
    lines = runs.read_text().splitlines(keepends=True)
    finished = len(lines) - 1
    assert 2 <= finished < 8, f"{finished} runs finished before the kill: the test needs it mid-way"
    with open(runs, "a") as f:
        f.write(lines[-1][:40])  # a row cut short

    again = fowt_sim(*args)
    assert again.returncode == 0, again.stderr
    assert f"8 runs ({8 - finished} new)" in again.stdout
    after = runs.read_text().splitlines(keepends=True)
    assert after[: len(lines)] == lines  # finished rows (their wall times too) untouched
    keys = [tuple(row[:2]) for row in csv.reader(after[1:])]
    assert len(after) == 9 and len(set(keys)) == 8


@pytest.mark.slow
@pytest.mark.dask
def test_sweep_from_a_file_and_bad_input_in_one_line(tmp_path: Path):
    """A sweep YAML (seeds as a count, a variant by coefficient path); bad entries named."""
    spec = {"load_cases": ["lc5.2"], "seeds": 2, "variants": [{"name": "stiff", "mooring_stiffness_scale": 1.5,
                                                               "coefficients": {"column*.submerged.cd.constant": 0.9}}],
            "run": {"duration_s": 60}}
    path = tmp_path / "sweep.yaml"
    path.write_text(yaml.safe_dump(spec))
    done = fowt_sim("sweep", "--config", str(path), "--workers", "1", "-o", str(tmp_path / "a"))
    assert done.returncode == 0, done.stderr
    assert dask_noise(done.stderr) == [], done.stderr  # the cluster shut down cleanly and quietly
    rows = read_table(tmp_path / "a" / RUNS_FILE)
    assert sorted(r["seed"] for r in rows) == ["1", "2"] and {r["variant"] for r in rows} == {"stiff"}
    settings = json.loads((tmp_path / "a" / "sweep.json").read_text())
    assert settings["variants"]["stiff"]["mooring_stiffness_scale"] == 1.5

    changed = fowt_sim("sweep", "--load-cases", "lc5.2", "--duration", "90", "-o", str(tmp_path / "a"))
    assert changed.returncode == 2 and "other run settings" in changed.stderr
    spec["variants"][0]["coefficients"] = {"nothing*.submerged.cd.constant": 1.0}
    path.write_text(yaml.safe_dump(spec))
    for args, expected in ((["--load-cases", "lc9.9"], "lc9.9"),
                           (["--config", str(path)], "nothing*"),
                           (["--cd-scales", "-1"], "cd_scale"),
                           (["--seeds", "1", "1"], "duplicates")):
        bad = fowt_sim("sweep", *args, "-o", str(tmp_path / "b"))
        assert bad.returncode == 2, bad.stderr
        assert expected in bad.stderr and "Traceback" not in bad.stderr and len(bad.stderr.strip().splitlines()) == 1


@pytest.mark.serial
@pytest.mark.slow
@pytest.mark.dask
@pytest.mark.parametrize("command, under_way", [
    (["sweep", "--seeds", "1", "2", "--duration", "20000"], r"sweep: +0%"),
    (["diagnose-benchmark", "--strengths", "0", "--nulls", "0", "--out-of-catalogue", "1", "--duration", "1200"],
     r"diagnosis: \d+/\d+ model runs"),  # (its fewest measured runs before a diagnosis)
], ids=["sweep", "diagnose-benchmark"])
def test_ctrl_c_ends_a_cluster_command_with_one_line_and_no_process_left(tmp_path: Path, command: list[str],
                                                                         under_way: str):
    """Ctrl-C (SIGINT to the terminal's process group: the command and its workers) while
    runs are under way: "interrupted", exit 130, no Dask warning, CancelledError or worker's
    traceback, and every process of the group gone. (A worker busy in Python code when the
    signal comes, as a diagnosis's often is, printed its event loop's KeyboardInterrupt.)"""
    process = subprocess.Popen([sys.executable, "-m", "fowt_hydro_sim.cli", *command, "--workers", "2",
                                "-o", str(tmp_path / "s")], cwd=REPO,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    stderr: list[str] = []
    reader = threading.Thread(target=lambda: stderr.extend(iter(lambda: process.stderr.read(1), "")), daemon=True)
    reader.start()
    try:
        deadline = time.monotonic() + 180
        while not re.search(under_way, "".join(stderr)) and time.monotonic() < deadline and process.poll() is None:
            time.sleep(0.2)  # a progress line: the cluster is up, the runs under way
        assert process.poll() is None, "".join(stderr)
        time.sleep(3.0)
        os.killpg(process.pid, signal.SIGINT)
        assert process.wait(timeout=90) == 130
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
    reader.join(timeout=10)
    text = "".join(stderr)
    assert dask_noise(text) == [] and "CancelledError" not in text and "Traceback" not in text, text
    assert [line for line in text.splitlines() if line.startswith("fowt-sim")] == [
        f"fowt-sim {command[0]}: interrupted"]
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline:
        try:
            os.killpg(process.pid, 0)  # any worker still alive?
        except ProcessLookupError:
            break
        time.sleep(0.2)
    else:
        pytest.fail("worker processes outlived the interrupted sweep")


@pytest.mark.slow
@pytest.mark.dask
def test_a_cluster_that_loses_a_run_ends_the_sweep_in_one_line(tmp_path: Path):
    """A sweep on an existing scheduler whose worker process is killed mid-run (the
    scheduler allowed no failure): exit 1 and one line naming the lost run, no traceback or
    Dask warning."""
    import dask
    from dask.distributed import Client, LocalCluster
    with dask.config.set({"distributed.scheduler.allowed-failures": 0}), \
            LocalCluster(n_workers=1, threads_per_worker=1, processes=True, host="127.0.0.1",
                         scheduler_kwargs={"dashboard": False, "dashboard_address": "127.0.0.1:0"}) as cluster, \
            Client(cluster) as client:
        process = subprocess.Popen([sys.executable, "-m", "fowt_hydro_sim.cli", "sweep", "--seeds", "1",
                                    "--duration", "20000", "--scheduler", cluster.scheduler_address,
                                    "-o", str(tmp_path / "s")], cwd=REPO, stdout=subprocess.DEVNULL,
                                   stderr=subprocess.PIPE, text=True, start_new_session=True)
        try:
            deadline = time.monotonic() + 180
            while not any(client.processing().values()):  # asked of the scheduler, not a cached view
                assert time.monotonic() < deadline and process.poll() is None, process.stderr.read()
                time.sleep(0.2)  # the run is on the worker
            (worker_pid,) = client.run(os.getpid).values()
            os.kill(worker_pid, signal.SIGKILL)
            _, stderr = process.communicate(timeout=120)
        finally:
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGKILL)
    assert process.returncode == 1, stderr
    assert dask_noise(stderr) == [] and "Traceback" not in stderr, stderr
    (line,) = [line for line in stderr.splitlines() if line.startswith("fowt-sim")]
    assert line.startswith("fowt-sim sweep: error: the Dask cluster lost runs under way (") and "resumes" in line
