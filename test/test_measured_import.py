"""``fowt-sim measured import``: basin files in, measured bags out.

Every model-scale file here is written by the test with its own arithmetic (Froude factors,
units, signs, offsets, the motion point's rotation, the waves' travel between probes), not
with the importer's functions, from a full-scale run the test defines; importing it back
must give the full-scale run to round-off.
"""
from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest
import scipy.io
import yaml

from fowt_hydro_sim.cli import main
from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.io.basin import load_column_map
from fowt_hydro_sim.io.scaling import froude_factor, to_full_scale
from fowt_hydro_sim.rosbag.reader import Bag
from fowt_hydro_sim.studies.basin_import import import_files
from fowt_hydro_sim.studies.diagnosis.decay import half_cycles
from fowt_hydro_sim.studies.replay import measured_run

LAMBDA = 50.0
RHO_RATIO = 1025.0 / 1000.0
G = 9.80665
PROBE_2_M = (2.0, 0.0)  # model scale, 2 m down-wave of the first probe (100 m full scale)
MOTION_POINT_M = (0.3, -0.1, 0.4)  # model scale, platform axes: where the basin tracked the model
WAVES = ((0.06, 0.8, 0.3), (0.09, 0.5, 1.7), (0.12, 0.3, 4.0))  # full scale: frequency [Hz], amplitude [m], phase


def _rotation(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """Rz(yaw) Ry(pitch) Rx(roll), written out here."""
    rx = np.array([[1, 0, 0], [0, math.cos(roll), -math.sin(roll)], [0, math.sin(roll), math.cos(roll)]])
    ry = np.array([[math.cos(pitch), 0, math.sin(pitch)], [0, 1, 0], [-math.sin(pitch), 0, math.cos(pitch)]])
    rz = np.array([[math.cos(yaw), -math.sin(yaw), 0], [math.sin(yaw), math.cos(yaw), 0], [0, 0, 1]])
    return rz @ ry @ rx


def full_scale_run(duration_s: float = 240.0, step_s: float = 0.2) -> dict[str, np.ndarray]:
    """A full-scale run: elevation at two probes (deep-water waves travelling +x), the
    platform's motion at its reference point, a line tension."""
    t = np.arange(0.0, duration_s, step_s)
    eta1, eta2 = np.zeros_like(t), np.zeros_like(t)
    for f, a, phase in WAVES:
        w = 2 * math.pi * f
        k = w * w / G
        eta1 += a * np.cos(w * t + phase)
        eta2 += a * np.cos(w * t + phase - k * PROBE_2_M[0] * LAMBDA)
    motion = np.column_stack([3.0 + 1.5 * np.sin(2 * math.pi * t / 90.0), 0.2 * np.sin(t / 20.0),
                              0.4 * np.cos(2 * math.pi * t / 17.0), 0.01 * np.sin(t / 11.0),
                              0.04 * np.sin(2 * math.pi * t / 30.0) + 0.02, 0.005 * np.cos(t / 40.0)])
    tension = 1.2e6 + 2.0e5 * np.sin(2 * math.pi * t / 90.0)
    return {"time": t, "eta1": eta1, "eta2": eta2, "motion": motion, "tension": tension}


def model_scale_channels(run: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The basin's channels for a full-scale run: time [s], probes [mm], motion of the
    tracked point [mm] (heave positive down, surge with its zero reading 12 mm), angles
    [deg], tension [N]."""
    root = math.sqrt(LAMBDA)
    point = np.array(MOTION_POINT_M) * LAMBDA
    tracked = np.array([m[:3] + _rotation(*m[3:]) @ point for m in run["motion"]])
    return {"Time": run["time"] / root, "WP1": run["eta1"] / LAMBDA * 1000, "WP2": run["eta2"] / LAMBDA * 1000,
            "SurgeMM": tracked[:, 0] / LAMBDA * 1000 + 12.0, "SwayMM": tracked[:, 1] / LAMBDA * 1000,
            "HeaveDownMM": -tracked[:, 2] / LAMBDA * 1000, "RollDeg": np.degrees(run["motion"][:, 3]),
            "PitchDeg": np.degrees(run["motion"][:, 4]), "YawDeg": np.degrees(run["motion"][:, 5]),
            "FairleadN": run["tension"] / (LAMBDA**3 * RHO_RATIO)}


def column_map_data(**extra) -> dict:
    return {"scale": LAMBDA, "density_ratio": RHO_RATIO, "time": {"channel": "Time", "unit": "s"},
            "motion_point_m": list(MOTION_POINT_M), "sea_state": {"hs_m": 2.4, "tp_s": 11.0, "heading_deg": 0.0},
            "channels": {"WP1": {"quantity": "elevation", "unit": "mm", "position_m": [0.0, 0.0]},
                         "WP2": {"quantity": "elevation", "unit": "mm", "position_m": list(PROBE_2_M)},
                         "SurgeMM": {"quantity": "surge", "unit": "mm", "offset": 12.0},
                         "SwayMM": {"quantity": "sway", "unit": "mm"},
                         "HeaveDownMM": {"quantity": "heave", "unit": "mm", "sign": -1},
                         "RollDeg": {"quantity": "roll", "unit": "deg"},
                         "PitchDeg": {"quantity": "pitch", "unit": "deg"},
                         "YawDeg": {"quantity": "yaw", "unit": "deg"},
                         "FairleadN": {"quantity": "tension", "unit": "N", "line": "line1"}}, **extra}


def write_csv(path: Path, channels: dict[str, np.ndarray], delimiter: str = ",") -> Path:
    with open(path, "w", newline="") as stream:
        writer = csv.writer(stream, delimiter=delimiter)
        writer.writerow(list(channels))
        for row in zip(*channels.values()):
            writer.writerow(["" if math.isnan(v) else repr(float(v)) for v in row])
    return path


def write_map(path: Path, data: dict) -> Path:
    path.write_text(yaml.safe_dump(data))
    return path


def assert_bag_is_the_run(bag_path: Path, run: dict[str, np.ndarray], rtol: float = 1e-9) -> None:
    bag = Bag(bag_path)
    elevation, probe_2, pose = bag.elevation(), bag.series("/waves/elevation/WP2"), bag.motion()
    np.testing.assert_allclose(elevation.time_s, run["time"], atol=2e-9)
    np.testing.assert_allclose(elevation.values[:, 2], run["eta1"], atol=rtol * 1.6)
    np.testing.assert_allclose(probe_2.values[:, 2], run["eta2"], atol=rtol * 1.6)
    assert tuple(probe_2.values[0, :2]) == (PROBE_2_M[0] * LAMBDA, 0.0)
    np.testing.assert_allclose(pose.values, run["motion"], atol=rtol * 5)
    tension = bag.scalar("/mooring/tension/line1")
    np.testing.assert_allclose(tension.values[:, 0], run["tension"], rtol=rtol)
    measured = bag.config["measured"]
    assert measured["scale"] == LAMBDA and measured["checks"] == [] and measured["column_map"]["scale"] == LAMBDA
    assert bag.config["sea_state"]["hs_m"] == 2.4


def test_a_full_scale_run_written_at_model_scale_imports_back_to_round_off(tmp_path: Path):
    run = full_scale_run()
    source = write_csv(tmp_path / "basin_run.csv", model_scale_channels(run))
    mapping = load_column_map(write_map(tmp_path / "map.yaml", column_map_data()))
    [(bag_path, imported)] = import_files([source], mapping, tmp_path / "bags")
    assert imported.notes == []
    assert_bag_is_the_run(bag_path, run)


def test_froude_scaling_of_a_free_decay_period_and_a_force_by_hand(tmp_path: Path):
    # a model heaving freely with a 3.5 s period at 1:50 is a platform with a 3.5 sqrt(50) = 24.75 s period
    assert froude_factor("time", 50.0) == pytest.approx(7.0710678118654755, rel=1e-15)
    assert to_full_scale(3.5, "time", 50.0) == pytest.approx(24.748737341529164, rel=1e-15)
    # 10 N in fresh water at 1:50 is 10 x 50^3 x 1.025 = 1,281,250 N at sea; 2 N m is 2 x 50^4 x 1.025
    assert to_full_scale(10.0, "force", 50.0, 1.025) == pytest.approx(1_281_250.0, rel=1e-15)
    assert to_full_scale(2.0, "moment", 50.0, 1.025) == pytest.approx(12_812_500.0, rel=1e-15)
    # the same through the importer: a model's free pitch decay in calm water (3.5 s, log
    # decrement 0.04 pi per half-cycle), mapped without a probe, and a constant 10 N
    t = np.arange(0.0, 40.0, 0.02)
    wd = 2 * math.pi / 3.5
    pitch_deg = 3.0 * np.exp(-0.04 * wd * t) * np.cos(wd * t)
    channels = {"Time": t, "PitchDeg": pitch_deg, "SurgeMM": 0.0 * t, "FairleadN": 10.0 + 0.0 * t}
    data = {"scale": 50.0, "density_ratio": 1.025, "time": {"channel": "Time"}, "free_decay": "pitch",
            "channels": {"PitchDeg": {"quantity": "pitch", "unit": "deg"},
                         "SurgeMM": {"quantity": "surge", "unit": "mm"},
                         "FairleadN": {"quantity": "tension", "unit": "N", "line": "fairlead"}}}
    source = write_csv(tmp_path / "decay.csv", channels)
    [(bag_path, _)] = import_files([source], load_column_map(write_map(tmp_path / "m.yaml", data)), tmp_path / "b")
    bag = Bag(bag_path)
    assert "/waves/elevation" not in bag.topics and bag.config["measured"]["free_decay"] == "pitch"
    pose = bag.motion()
    pitch = pose.values[:, 4]
    up = np.flatnonzero((pitch[:-1] < 0) & (pitch[1:] >= 0))
    crossings = pose.time_s[up] - pitch[up] * (pose.time_s[up + 1] - pose.time_s[up]) / (pitch[up + 1] - pitch[up])
    assert np.mean(np.diff(crossings)) == pytest.approx(3.5 * math.sqrt(50.0), rel=1e-4)
    assert np.max(np.abs(pitch)) == pytest.approx(math.radians(3.0), rel=1e-12)  # angles are not scaled
    np.testing.assert_allclose(bag.scalar("/mooring/tension/fairlead").values[:, 0], 1_281_250.0, rtol=1e-12)
    # the diagnosis's decay analysis of the bag: half-periods and damping ratios of the closed form
    run = measured_run(bag_path, decay_dof="pitch")
    half_periods, ratios = half_cycles(run.motion_time_s, run.motion[:, 4])
    assert half_periods.size >= 10
    np.testing.assert_allclose(half_periods, 3.5 * math.sqrt(50.0) / 2, rtol=1e-3)
    np.testing.assert_allclose(ratios, 0.04, atol=1e-3)


def test_a_bag_imported_as_a_free_decay_is_read_only_as_one_in_its_dof(tmp_path: Path):
    t = np.arange(0.0, 20.0, 0.05)
    channels = {"Time": t, "SurgeMM": 30.0 * np.exp(-0.02 * t) * np.cos(t)}
    data = {"scale": 40.0, "time": {"channel": "Time"}, "free_decay": "surge",
            "channels": {"SurgeMM": {"quantity": "surge", "unit": "mm"}}}
    source = write_csv(tmp_path / "surge_decay.csv", channels)
    [(bag_path, _)] = import_files([source], load_column_map(write_map(tmp_path / "m.yaml", data)), tmp_path / "b")
    assert measured_run(bag_path, decay_dof="surge").decay_dof == "surge"
    with pytest.raises(InputError, match="a free decay in surge .*not a wave run: give it as a free decay"):
        measured_run(bag_path)
    with pytest.raises(InputError, match="a free decay in surge .*given as one in pitch"):
        measured_run(bag_path, decay_dof="pitch")


def test_one_file_with_many_runs_hdf5_and_a_run_column_and_a_matlab_v73_file(tmp_path: Path):
    h5py = pytest.importorskip("h5py", reason="not installed: pip install '.[basin]'")
    runs = [full_scale_run(120.0), full_scale_run(100.0)]
    runs[1]["motion"] = runs[1]["motion"] * 0.5
    source = tmp_path / "campaign.h5"
    with h5py.File(source, "w") as stream:
        for name, run in zip(("irregular_01", "irregular_02"), runs):
            group = stream.create_group(f"tests/{name}")
            for channel, values in model_scale_channels(run).items():
                group.create_dataset(channel, data=values)
    mapping = load_column_map(write_map(tmp_path / "map.yaml", column_map_data()))
    written = import_files([source], mapping, tmp_path / "bags")
    assert [p.name for p, _ in written] == ["campaign_tests_irregular_01", "campaign_tests_irregular_02"]
    for (bag_path, _), run in zip(written, runs):
        assert_bag_is_the_run(bag_path, run)
    # a MATLAB v7.3 file (HDF5 after a 512-byte MATLAB header; MATLAB stores vectors as 1 x n)
    source = tmp_path / "campaign73.mat"
    with h5py.File(source, "w", userblock_size=512) as stream:
        for channel, values in model_scale_channels(runs[0]).items():
            stream.create_dataset(f"test_03/{channel}", data=values.reshape(1, -1))
    header = b"MATLAB 7.3 MAT-file, Platform: GLNXA64, HDF5 schema 1.00 .".ljust(116) + bytes(8) + b"\x00\x02IM"
    with open(source, "r+b") as stream:
        stream.write(header.ljust(512, b"\x00"))
    [(bag_path, _)] = import_files([source], mapping, tmp_path / "v73")
    assert bag_path.name == "campaign73"
    assert_bag_is_the_run(bag_path, runs[0])
    # two runs in one table, told apart by a run column
    table = {**{k: np.concatenate([model_scale_channels(r)[k] for r in runs]) for k in model_scale_channels(runs[0])},
             "Run": np.concatenate([np.full(r["time"].size, i + 1.0) for i, r in enumerate(runs)])}
    source = write_csv(tmp_path / "campaign.tsv", table, delimiter="\t")
    mapping = load_column_map(write_map(tmp_path / "map2.yaml", column_map_data(run_channel="Run")))
    written = import_files([source], mapping, tmp_path / "tsv")
    assert [p.name for p, _ in written] == ["campaign_1.0", "campaign_2.0"]
    for (bag_path, _), run in zip(written, runs):
        assert_bag_is_the_run(bag_path, run)


def test_gaps_dropouts_clock_steps_back_and_a_probe_clock_offset_are_reported_and_handled(tmp_path: Path):
    run = full_scale_run()
    channels = model_scale_channels(run)
    late = 0.6  # full scale: probe 2's clock runs late
    w = [2 * math.pi * f for f, _, _ in WAVES]
    channels["WP2"] = sum(a * np.cos(wi * (channels["Time"] * math.sqrt(LAMBDA) - late) + phase
                                     - wi * wi / G * PROBE_2_M[0] * LAMBDA)
                          for wi, (_, a, phase) in zip(w, WAVES)) / LAMBDA * 1000
    keep = np.ones(channels["Time"].size, bool)
    keep[300:303] = False  # a gap of 3 samples (0.6 s full scale)
    channels["PitchDeg"] = channels["PitchDeg"].copy()
    channels["PitchDeg"][500:502] = np.nan  # a dropout of 2 samples
    rows = {k: v[keep] for k, v in channels.items()}
    order = np.arange(rows["Time"].size)
    order[[700, 701]] = order[[701, 700]]  # two samples swapped
    rows = {k: np.insert(v[order], 900, v[order][899]) for k, v in rows.items()}  # a sample repeated
    source = write_csv(tmp_path / "rough.csv", rows)
    mapping = load_column_map(write_map(tmp_path / "map.yaml", column_map_data()))
    [(bag_path, imported)] = import_files([source], mapping, tmp_path / "bags")
    notes = imported.notes
    assert len([n for n in notes if "clock not monotonic: 2 samples out of order (sorted), 1 repeated" in n]) == 1, \
        notes
    assert len([n for n in notes if "1 clock gap(s), the longest" in n and "interpolated" in n]) == 1, notes
    assert len([n for n in notes if "channel PitchDeg: 1 dropout(s)" in n]) == 1, notes
    offset = [n for n in notes if "probe WP2: clock" in n]
    assert len(offset) == 1 and "corrected" in offset[0], notes
    bag = Bag(bag_path)
    pose = bag.motion()
    assert pose.time_s.size == run["time"].size  # the swapped pair sorted, the repeat dropped, the gap refilled
    assert np.allclose(np.diff(pose.time_s), 0.2, atol=1e-6)
    shift = bag.config["measured"]["probe_clock_shifts_s"]["WP2"]
    assert shift == pytest.approx(-late, abs=0.02)
    # refilled samples lie on the run (linear interpolation across 0.8 s of slow motion)
    np.testing.assert_allclose(np.interp(run["time"], pose.time_s, pose.values[:, 4]), run["motion"][:, 4],
                               atol=2e-4)


def test_a_long_gap_is_refused_in_one_line_and_nothing_is_written(tmp_path: Path, capsys):
    run = full_scale_run(120.0)
    channels = model_scale_channels(run)
    keep = np.ones(channels["Time"].size, bool)
    keep[200:220] = False  # 4 s full scale
    source = write_csv(tmp_path / "long_gap.csv", {k: v[keep] for k, v in channels.items()})
    column_map = write_map(tmp_path / "map.yaml", column_map_data())
    command = ["measured", "import", str(source), "--map", str(column_map), "-o", str(tmp_path / "bags")]
    assert main(command) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and "clock gap of" in lines[0] and "refused" in lines[0], lines
    assert not (tmp_path / "bags").exists()
    assert main([*command, "--max-gap", "5"]) == 0
    assert "wrote" in capsys.readouterr().out
    assert main([*command, "--max-gap", "5"]) == 2  # the bag is there
    assert "exists (pass --overwrite to replace it)" in capsys.readouterr().err


@pytest.mark.parametrize("edit, message", [
    ({"channels": {"WP1": {"quantity": "elevation", "unit": "furlong", "position_m": [0, 0]}}}, "unit: must be one"),
    ({"channels": {"X": {"quantity": "surge", "unit": "m"}}}, "no wave probe"),
    ({"free_decay": "bob"}, "free_decay: must be one of surge"),
    ({"channels": {"X": {"quantity": "surge", "unit": "m"}}, "free_decay": "pitch"},
     "free_decay: pitch is not a channel's quantity"),
    ({"density_ratio": None}, "density_ratio: needed"),
    ({"time": {}}, "give either channel"),
    ({"scael": 50}, "unknown field(s) scael"),
])
def test_a_bad_column_map_is_one_line_naming_the_field(tmp_path: Path, capsys, edit: dict, message: str):
    column_map = write_map(tmp_path / "map.yaml", {**column_map_data(), **edit})
    source = write_csv(tmp_path / "r.csv", model_scale_channels(full_scale_run(20.0)))
    assert main(["measured", "import", str(source), "--map", str(column_map), "-o", str(tmp_path / "bags")]) == 2
    error = capsys.readouterr().err
    assert message in error and len(error.strip().splitlines()) == 1, error


@pytest.mark.slow
def test_independent_csv_and_mat_files_import_to_bags_calibrate_and_diagnose_read(tmp_path: Path):
    """Bags from a CSV and a .mat file made here are read by ``measured_run`` (calibrate's and
    diagnose's reader) and replayed by the model, whose gap to them the diagnosis measures."""
    from fowt_hydro_sim.physics.config import load_platform
    from fowt_hydro_sim.studies.diagnosis.gap import GapSettings, gap
    from fowt_hydro_sim.studies.replay import Variant, measured_run, replay
    run = full_scale_run(300.0)
    channels = model_scale_channels(run)
    csv_source = write_csv(tmp_path / "basin_csv.csv", channels)
    mat_source = tmp_path / "basin_mat.mat"
    scipy.io.savemat(mat_source, {"test_07": {k: v.reshape(-1, 1) for k, v in channels.items()}})
    mapping = load_column_map(write_map(tmp_path / "map.yaml", column_map_data()))
    written = import_files([csv_source, mat_source], mapping, tmp_path / "bags")
    assert [p.name for p, _ in written] == ["basin_csv", "basin_mat"]
    platform = load_platform()
    settings = GapSettings(transient_s=60.0)
    for bag_path, _ in written:
        assert_bag_is_the_run(bag_path, run)
        measured = measured_run(bag_path)
        assert measured.point_xy_m == (0.0, 0.0) and measured.elevation_step_s == pytest.approx(0.2)
        model = replay(Variant(platform), measured, dt_s=0.1, preroll_s=60.0)
        cells = gap(measured.name, (measured.motion_time_s, measured.motion), model, settings)
        assert np.isfinite(cells.value).any()
