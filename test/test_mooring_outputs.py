"""Mooring tensions as outputs: rainflow counting and the damage-equivalent load against closed
forms, and the tensions ``fowt-sim simulate`` writes and ``fowt-sim analyze`` reports."""
from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest
import yaml

from fowt_hydro_sim.physics.config import load_platform, platform_document
from fowt_hydro_sim.studies.simulate import read_run
from fowt_hydro_sim.studies.tensions import damage_equivalent_load, rainflow
from fowt_hydro_sim.testing import fowt_sim

VOLTURNUS_LINES = (Path(__file__).parents[1] / "fowt_hydro_sim" / "physics" / "data" / "platforms" / "volturnus_s"
                   / "IEA-15-240-RWT-UMaineSemi_MoorDyn.dat")


def test_rainflow_counts_the_astm_e1049_example():
    """ASTM E1049-85 (2017), 5.4.4 and its Fig. 6: the reversals -2 1 -3 5 -1 3 -4 4 -2 count as
    ranges 3 (half), 4 (one and a half), 6 (half), 8 (one) and 9 (half)."""
    counted: dict[float, float] = {}
    for size, count in rainflow(np.array([-2, 1, -3, 5, -1, 3, -4, 4, -2.0])):
        counted[size] = counted.get(size, 0.0) + count
    assert counted == {3.0: 0.5, 4.0: 1.5, 6.0: 0.5, 8.0: 1.0, 9.0: 0.5}


def test_the_del_of_a_sine_is_its_range_scaled_by_its_cycles():
    """A cosine of amplitude A and frequency f over T, trough to trough: f T cycles of range 2 A,
    so with 1 Hz equivalent cycles DEL = 2 A f^(1/m), for any slope m."""
    t = np.arange(0.0, 600.0 + 0.025, 0.05)
    x = 2e6 - 3e5 * np.cos(2 * np.pi * 0.1 * t)
    for slope in (3.0, 5.0):
        assert damage_equivalent_load(x, 600.0, slope) == pytest.approx(2 * 3e5 * 0.1 ** (1 / slope), rel=1e-9)


@pytest.fixture(scope="module")
def catenary_platform(tmp_path_factory) -> Path:
    """windmoor12's hull on the VolturnUS-S lines (moorpy; its springs as the other choice) in
    200 m of water, as a YAML file."""
    folder = tmp_path_factory.mktemp("platform")
    document = platform_document(load_platform("windmoor12"))
    document["environment"]["water_depth_m"] = 200.0
    document["mooring"].update(model="moorpy", file=str(VOLTURNUS_LINES))  # its springs kept: a run may choose them
    (folder / "catenary.yaml").write_text(yaml.safe_dump(document))
    return folder / "catenary.yaml"


@pytest.mark.slow
def test_simulate_writes_and_analyze_reports_each_lines_tensions(tmp_path, catenary_platform):
    out = tmp_path / "run"
    done = fowt_sim("simulate", "--platform", str(catenary_platform), "--load-case", "lc5.3", "--duration", "120",
                    "-o", str(out))
    assert done.returncode == 0, done.stderr
    columns = read_run(out)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["mooring"] == "moorpy"
    for line in (1, 2, 3):
        fairlead = columns[f"line{line}_fairlead_tension_n"]
        assert 1.5e6 < fairlead.mean() < 3.5e6 and np.all(columns[f"line{line}_anchor_tension_n"] < fairlead)
        assert summary["mooring_tensions"][f"line{line}_fairlead"]["max"] == pytest.approx(fairlead.max())
    report = fowt_sim("analyze", str(out), "--transient", "0", "-o", str(tmp_path / "report"))
    assert report.returncode == 0, report.stderr
    assert "mooring tensions" in report.stdout and "S-N slope m = 3" in report.stdout
    rows = (tmp_path / "report" / "tensions.csv").read_text().splitlines()
    assert rows[0].startswith("run,tension,mean_n,std_n,max_n,del_n,sn_slope") and len(rows) == 7
    refused = fowt_sim("simulate", "--mooring", "moorpy", "--still-water", "--duration", "10", "-o",
                       str(tmp_path / "none"))
    assert refused.returncode == 2
    assert refused.stderr.strip().splitlines()[-1].endswith("mooring moorpy: the platform has no MoorDyn input file "
                                                            "(mooring.file)")
    assert "Traceback" not in refused.stderr


def test_a_sweep_row_holds_the_worst_lines_fairlead_tension_statistics():
    """Two lines, cosines of 0.1 Hz around 2 MN (amplitudes 0.3 and 0.5 MN), 600 s after a
    100 s transient: the row's columns are the second line's, its DEL the closed form."""
    from fowt_hydro_sim.studies.sweep import TENSION_METRICS, metric_names, tension_metrics
    t = np.arange(0.0, 700.0 + 0.025, 0.05)
    tensions = np.zeros((t.size, 2, 2))
    tensions[:, 0, 0] = 2e6 - 3e5 * np.cos(2 * np.pi * 0.1 * t)
    tensions[:, 1, 0] = 2e6 - 5e5 * np.cos(2 * np.pi * 0.1 * t)
    row = tension_metrics(t, tensions, 100.0)
    assert set(TENSION_METRICS) <= set(metric_names())
    assert row["fairlead_tension_max_n"] == pytest.approx(2.5e6)
    assert row["fairlead_tension_std_n"] == pytest.approx(5e5 / np.sqrt(2), rel=1e-3)
    assert row["fairlead_tension_del_n"] == pytest.approx(2 * 5e5 * 0.1 ** (1 / 3), rel=1e-9)


@pytest.mark.slow
def test_loads_writes_each_lines_tensions_along_a_prescribed_motion(tmp_path):
    """``fowt-sim loads``' study with the moorpy lines: the tension columns are the model's
    tensions at the prescribed positions; the moordyn lines are refused (they need the time loop)."""
    from fowt_hydro_sim.errors import InputError
    from fowt_hydro_sim.physics.config import ConfigError, HydroOptions, load_platform
    from fowt_hydro_sim.studies.prescribed_motion import PrescribedMotion, prescribed_run, write_loads_csv
    platform = load_platform("windmoor12")
    platform = dataclasses.replace(platform, environment=dataclasses.replace(platform.environment, water_depth_m=200.0),
                                   mooring=dataclasses.replace(platform.mooring, file=str(VOLTURNUS_LINES)))
    t = np.arange(0.0, 10.0, 0.5)
    motion = np.zeros((t.size, 6))
    motion[:, 0] = 10 * np.sin(0.3 * t)
    prescribed = PrescribedMotion(t, motion, np.zeros_like(motion), np.zeros_like(motion))
    loads, tensions = prescribed_run(platform, None, prescribed, HydroOptions(), mooring_model="moorpy")
    path = write_loads_csv(tmp_path / "loads.csv", t, loads, tensions)
    table = np.genfromtxt(path, delimiter=",", names=True)
    assert np.allclose(table["line1_fairlead_tension_n"], tensions[:, 0, 0], rtol=1e-8)
    assert np.all(np.diff(table["line1_fairlead_tension_n"][:6]) > 0)  # line 1's anchor at -x: tightens as x grows
    with pytest.raises((ConfigError, InputError), match="prescribed motion: the moordyn mooring needs the time loop"):
        prescribed_run(platform, None, prescribed, HydroOptions(), mooring_model="moordyn")


@pytest.mark.slow
def test_analyze_marks_a_moordyn_platforms_natural_frequencies_from_its_static_lines():
    """MoorDyn's lines hold no stiffness to linearise in the model: the natural frequencies
    ``analyze`` marks take them as their quasi-static catenaries, so a moordyn platform has its
    surge, sway and yaw modes, those of the same lines as moorpy."""
    from fowt_hydro_sim.studies.analysis import natural_frequencies_hz
    platform = load_platform("windmoor12")
    platform = dataclasses.replace(platform, environment=dataclasses.replace(platform.environment, water_depth_m=200.0),
                                   mooring=dataclasses.replace(platform.mooring, file=str(VOLTURNUS_LINES)))
    moordyn = natural_frequencies_hz(dataclasses.replace(platform, mooring=platform.mooring.chosen("moordyn")))
    assert moordyn == natural_frequencies_hz(dataclasses.replace(platform, mooring=platform.mooring.chosen("moorpy")))
    assert {"surge", "sway", "yaw"} <= set(moordyn)


def test_a_run_file_chooses_the_mooring(tmp_path):
    from fowt_hydro_sim.physics.config import ConfigError, load_run_file
    (tmp_path / "run.yaml").write_text("platform: windmoor12\nrun: {duration_s: 60, mooring: moorpy}\n")
    assert load_run_file(tmp_path / "run.yaml").run.mooring == "moorpy"
    (tmp_path / "bad.yaml").write_text("platform: windmoor12\nrun: {mooring: chain}\n")
    with pytest.raises(ConfigError, match="bad.yaml: run.mooring: must be one of spring, linear, moorpy, moordyn"):
        load_run_file(tmp_path / "bad.yaml")


@pytest.mark.slow
@pytest.mark.dask
def test_a_sweep_row_and_bag_carry_the_tensions_simulate_gives_for_the_same_run(tmp_path):
    """A sweep of two runs of VolturnUS-S on its catenary lines (moorpy), bags on: the row of
    seed 1 holds the worst line's fairlead tension mean, STD, maximum and DEL that ``simulate``
    of the same settings writes (its time series analysed as ``analyze`` does), and the run's
    bag each line's tensions on its ``/platform/mooring/lineN/tension`` topic, as the node
    records them."""
    from fowt_hydro_sim.physics.config import RunConfig, load_case
    from fowt_hydro_sim.rosbag.reader import Bag
    from fowt_hydro_sim.studies import simulate
    from fowt_hydro_sim.studies.sweep import RUNS_FILE, TENSION_METRICS, Sweep, Variant, read_rows, run_sweep
    from fowt_hydro_sim.studies.tensions import tension_rows
    from msg_adapters import topics

    run = RunConfig(duration_s=40.0, mooring="moorpy")
    sweep = Sweep(("lc5.3",), (1, 2), ("constant",), (Variant("lines", platform="volturnus_s"),), run,
                  transient_s=10.0)
    run_sweep(sweep, tmp_path / "sweep", workers=1, bags=True)
    rows = {int(r["seed"]): r for r in read_rows(tmp_path / "sweep" / RUNS_FILE)}
    assert set(rows) == {1, 2}

    sea = dataclasses.replace(load_case("lc5.3").sea_state, seed=1)
    single = dataclasses.replace(run, platform="volturnus_s")
    simulate.simulate(single, *simulate.sea_state_waves(sea, 40.0, "lc5.3"), tmp_path / "single", transient_s=10.0)
    columns = read_run(tmp_path / "single")
    lines = {f"line{i}": columns[f"line{i}_fairlead_tension_n"] for i in (1, 2, 3)}
    analysed = tension_rows("single", columns["time_s"], lines, 10.0)
    for metric, key in zip(TENSION_METRICS, ("mean_n", "std_n", "max_n", "del_n")):
        # (the CSV's significant digits move the rainflow ranges by parts in 1e8)
        assert float(rows[1][metric]) == pytest.approx(max(r[key] for r in analysed), rel=1e-6), metric

    bag = Bag(tmp_path / "sweep" / "bags" / "lc5.3_seed1_constant_lines")
    for i in (1, 2, 3):
        series = bag.series(topics.tension_topic(i))  # (the CSV holds tensions to 0.01 N)
        assert np.allclose(series.time_s, columns["time_s"])
        assert np.allclose(series.values[:, 0], columns[f"line{i}_fairlead_tension_n"], rtol=0, atol=0.01)
        assert np.allclose(series.values[:, 1], columns[f"line{i}_anchor_tension_n"], rtol=0, atol=0.01)
