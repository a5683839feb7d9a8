"""The wave kinematics synthesised in blocks (waves.kinematics.BlockSynthesis, the model's ring
of two blocks): the same rows as the one-shot table, and block boundaries invisible in a run."""
from __future__ import annotations

import numpy as np
import pytest
import scipy.fft

from fowt_hydro_sim.physics.config import RunConfig, SeaState, load_platform
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.strips import discretise
from fowt_hydro_sim.physics.waves.components import synthesize
from fowt_hydro_sim.physics.waves.kinematics import (
    BlockSynthesis,
    KinematicsTable,
    complex_amplitudes,
    point_kinematics,
    table_step,
)
from fowt_hydro_sim.studies.simulate import read_run, run_model, sea_state_waves, simulate, statistics

G, RHO, DEPTH = 9.80665, 1025.0, 150.0


@pytest.fixture(scope="module")
def sea():
    """An irregular oblique sea repeating every 1200 s and four points (one above the water)."""
    waves = synthesize(SeaState(6.19, 9.0, 4.9, heading_deg=25.0, seed=12), 1200.0)
    points = np.array([[0.0, 0.0, -0.5], [-35.2, 0.0, -15.5], [17.6, 30.5, -7.0], [5.0, -5.0, 3.0]])
    return waves, points, table_step(waves)


def one_shot_float64(waves, points, step, depth_m: float = DEPTH) -> np.ndarray:
    """The one-shot table's inverse FFT, kept in float64: (N, points, 7)."""
    n = int(round(waves.period_s / step))
    out = np.empty((n, len(points), 7))
    for i, point in enumerate(points):
        spectrum = np.zeros((7, n // 2 + 1), dtype=complex)
        spectrum[:, waves.harmonic] = complex_amplitudes(waves, point, depth_m, G, RHO)[0] * (n / 2.0)
        out[:, i, :] = scipy.fft.irfft(spectrum, n, axis=1).T
    return out


def test_block_rows_equal_the_component_sum(sea) -> None:
    """Oracle: direct summation (point_kinematics) at the rows' times and the one-shot inverse
    FFT in float64, within 1e-12 of each channel's peak, for blocks anywhere: across the end
    of the repeat period, past it, before t = 0; and blocks longer than the period."""
    waves, points, step = sea
    full = one_shot_float64(waves, points, step)
    n = full.shape[0]
    scale = np.abs(full).max(axis=0)
    for block_rows in (97, 700, n + 37):
        synthesis = BlockSynthesis(waves, points, step, block_rows, DEPTH, G, RHO)
        for first in (0, 3 * block_rows + 5, n - 40, 2 * n + 11, -block_rows):
            got = synthesis.rows(first)
            rows = (first + np.arange(block_rows)) % n
            assert np.all(np.abs(got - full[rows]) <= 1e-12 * scale), (block_rows, first)
        rows = np.arange(300, 300 + block_rows)
        exact = point_kinematics(waves, points, rows * step, DEPTH, G, RHO)
        assert np.all(np.abs(synthesis.rows(300) - exact) <= 1e-12 * scale)


def test_block_rows_round_to_the_one_shot_table(sea) -> None:
    """Oracle: KinematicsTable.build (float32): the blocks rounded to float32 are within one
    float32 step of it (the two float64 sums differ by round-off, which changes the float32
    rounding of a rare value); the model's ring holds them in float64."""
    waves, points, step = sea
    table = KinematicsTable.build(waves, points, step, DEPTH, G, RHO).values
    synthesis = BlockSynthesis(waves, points, step, 500, DEPTH, G, RHO)
    got = np.concatenate([synthesis.rows(first) for first in range(0, table.shape[0], 500)])[:table.shape[0]]
    np.testing.assert_array_max_ulp(got.astype(np.float32), table, maxulp=1)
    assert np.mean(got.astype(np.float32) == table) > 0.999


def relative_difference(a: np.ndarray, b: np.ndarray) -> float:
    """Largest |a - b| over time, relative to b's largest force (or moment) of the same load row
    (or over the translations / rotations of a motion)."""
    peak = np.abs(b).max(axis=0)
    force, moment = peak[..., :3].max(axis=-1, keepdims=True), peak[..., 3:].max(axis=-1, keepdims=True)
    scale = np.concatenate([np.repeat(force, 3, -1), np.repeat(moment, 3, -1)], axis=-1)
    return float((np.abs(a - b) / np.where(scale > 0, scale, 1.0)).max())


@pytest.fixture(scope="module")
def runs():
    """windmoor12, filtered drag, an LC-like sea repeating every hour: 1000 s with blocks of
    150 s and 370 s (each run crosses several block boundaries, and blocks end mid-step) and
    with the one-shot table (its inverse FFT kept in float64, as the blocks are)."""
    platform = load_platform("windmoor12")
    waves = synthesize(SeaState(6.19, 12.0, 1.23, heading_deg=20.0, seed=3), 3600.0)
    env = platform.environment
    models = {f"blocks {b:g} s": PlatformModel(platform, waves, drag_model="filtered", wave_block_s=b)
              for b in (150.0, 370.0)}
    step = models["blocks 150 s"].wave_table_step_s
    points = discretise(platform).points_m
    table = KinematicsTable(one_shot_float64(waves, points, step, env.water_depth_m), step, points)
    models["one-shot"] = PlatformModel(platform, waves, drag_model="filtered", kinematics=table)
    return models, {name: model.run(1000.0, output_interval_s=0.1) for name, model in models.items()}


@pytest.mark.slow
@pytest.mark.parametrize("name", ["blocks 370 s", "one-shot"])
def test_block_boundaries_invisible_in_the_loads(runs, name: str) -> None:
    """Oracle: the same run with another block length and with the one-shot table: every load
    row, the motion and the velocity within 1e-12 relative."""
    _, results = runs
    reference, other = results["blocks 150 s"], results[name]
    np.testing.assert_array_equal(other.time_s, reference.time_s)
    assert np.abs(reference.loads).max() > 1e5  # a real sea
    assert relative_difference(other.loads, reference.loads) <= 1e-12
    assert relative_difference(other.motion, reference.motion) <= 1e-12
    assert relative_difference(other.velocity, reference.velocity) <= 1e-12


def test_blocked_model_holds_two_blocks(runs) -> None:
    """The ring is two blocks long, whatever the repeat period."""
    models, _ = runs
    model = models["blocks 150 s"]
    rows = int(np.ceil(150.0 / model.wave_table_step_s))
    assert model._data.waves.values.shape[0] == 2 * rows


def test_prescribed_motion_across_blocks_equals_one_shot(runs) -> None:
    """Oracle: the one-shot table's model; prescribed-motion loads over 400 s, which the blocked
    model takes in parts of the ring (constant drag: no filter states)."""
    models, _ = runs
    platform, waves = models["one-shot"].platform, models["one-shot"].waves
    step, points = models["one-shot"].wave_table_step_s, models["one-shot"].geometry.points_m
    table = KinematicsTable(one_shot_float64(waves, points, step), step, points)
    table_model = PlatformModel(platform, waves, kinematics=table)
    blocked = PlatformModel(platform, waves, wave_block_s=60.0)
    t = np.arange(0.0, 400.0, 0.1)
    motion = np.zeros((t.size, 6))
    motion[:, 0], motion[:, 4] = 2.0 * np.sin(0.05 * t), 0.03 * np.sin(0.2 * t)
    velocity = np.gradient(motion, t, axis=0)
    acceleration = np.gradient(velocity, t, axis=0)
    expected = table_model.prescribed_motion_loads(t, motion, velocity, acceleration)
    got = blocked.prescribed_motion_loads(t, motion, velocity, acceleration)
    assert relative_difference(got, expected) <= 1e-12


@pytest.mark.slow
def test_simulate_streams_the_same_run_as_one_call(tmp_path) -> None:
    """Oracle: ``run_model`` (the whole run in memory, as ``fowt-sim sweep`` runs it): the time
    series ``simulate`` writes part by part has its rows and the summary its statistics,
    exactly."""
    run = RunConfig(platform="windmoor12", drag_model="filtered", duration_s=1500.0, output_interval_s=0.5)
    waves, info = sea_state_waves(SeaState(6.19, 12.0, 1.23, seed=3), run.duration_s)
    summary = simulate(run, waves, info, tmp_path, transient_s=100.0)
    result, _, _ = run_model(load_platform("windmoor12"), run, waves)
    assert summary["statistics"] == statistics(result, 100.0)
    written = read_run(tmp_path)
    np.testing.assert_array_equal(written["time_s"], result.time_s)
    np.testing.assert_allclose(written["heave_m"], result.motion[:, 2], rtol=1e-8, atol=1e-12)
    np.testing.assert_allclose(written["mooring_fx_n"], result.load("mooring")[:, 0], rtol=1e-8)


@pytest.mark.slow
def test_blocks_made_ahead_give_the_same_run(runs) -> None:
    """Oracle: the same model with every block made in the stepping thread (blocks_ahead
    False). A run in one call (1000 s of 150 s blocks: six boundaries) and a run stepped one
    step at a time, as a node steps, give identical arrays, bit for bit; the blocks after
    the first two came from the worker thread."""
    models, results = runs
    ahead = models["blocks 150 s"]
    assert ahead._blocks.made_ahead >= 5
    inline = PlatformModel(ahead.platform, ahead.waves, drag_model="filtered", wave_block_s=150.0, blocks_ahead=False)
    got = inline.run(1000.0, output_interval_s=0.1)
    assert inline._blocks.made_ahead == 0
    for name in ("time_s", "motion", "velocity", "acceleration", "loads", "wave_elevation_m"):
        np.testing.assert_array_equal(getattr(got, name), getattr(results["blocks 150 s"], name), err_msg=name)
    stepped = PlatformModel(ahead.platform, ahead.waves, drag_model="filtered", wave_block_s=150.0)
    inline.reset()
    expected = inline.run(500.0)
    motion, loads = [], []
    for _ in range(10_000):
        stepped.step()
        motion.append(stepped.motion)
        loads.append(stepped.loads)
    assert stepped._blocks.made_ahead >= 2
    np.testing.assert_array_equal(np.array(motion), expected.motion[1:])
    np.testing.assert_array_equal(np.array(loads), expected.loads[1:])
