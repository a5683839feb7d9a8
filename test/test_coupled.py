"""The offline coupled run (platform model + turbine + ROSCO in one process, no ROS): the
same run as the two nodes in lockstep, the CLI's outputs, its start."""
from __future__ import annotations

import json

import numpy as np
import pytest

pytest.importorskip("rosco")

from fowt_hydro_sim.physics.config import HydroOptions, load_platform  # noqa: E402
from fowt_hydro_sim.physics.model import PlatformModel, RunResult  # noqa: E402
from fowt_hydro_sim.studies.simulate import read_run  # noqa: E402
from fowt_hydro_sim.testing import fowt_sim  # noqa: E402
from fowt_hydro_sim.turbine.coupled import (  # noqa: E402
    CHANNELS,
    restoring,
    run_coupled,
    static_offset,
    turbine_on_platform,
)
from fowt_hydro_sim.turbine.wind import Wind  # noqa: E402

pytestmark = pytest.mark.rosco

# the loop compared: VolturnUS-S in still water, its linear mooring, 11 m/s (just below rated: the torque and
# the pitch controller both act), a start 2 m and 0.02 rad away from the static offset so that the platform moves
PLATFORM, WIND_M_S, DURATION_S = "volturnus_s", 11.0, 30.0
KICK = np.array([2.0, 0.0, 0.0, 0.0, 0.02, 0.0])


def offline(platform_name: str, wind: Wind, duration_s: float, initial: np.ndarray | None = None,
            output_interval_s: float | None = None, mooring: str = "") -> tuple[RunResult, np.ndarray, np.ndarray]:
    """An offline coupled run: its platform time series, its turbine channels, its start."""
    platform = load_platform(platform_name)
    model = PlatformModel(platform, None, dt_s=0.05, options=HydroOptions(), mooring_model=mooring)
    rotor = turbine_on_platform("iea15_umaine", platform, wind)
    start = static_offset(model, rotor) if initial is None else initial
    model.reset(motion=start)
    try:
        parts = list(run_coupled(model, rotor, duration_s, output_interval_s))
    finally:
        rotor.close()
    return RunResult.joined([p.result for p in parts]), np.concatenate(
        [parts[0].turbine] + [p.turbine[1:] for p in parts[1:]]), start


def test_the_static_offset_balances_the_steady_thrust_with_the_restoring_matrix():
    """K x = F: the restoring matrix by central differences has the linear mooring's surge
    stiffness and every diagonal term positive (the potential-flow hydrostatics included);
    the offset is downwind and pitched back by the thrust."""
    platform = load_platform(PLATFORM)
    model = PlatformModel(platform, None)
    k = restoring(model)[1]
    np.testing.assert_allclose(k, model.restoring_matrix(), rtol=0, atol=1e-9 * np.abs(k).max())  # the model's own
    assert k[0, 0] == pytest.approx(platform.linear_mooring.stiffness[0][0], rel=1e-6)
    assert np.all(np.diag(k) > 0), np.diag(k)
    rotor = turbine_on_platform("iea15_umaine", platform, Wind(speed_m_s=WIND_M_S))
    offset = static_offset(model, rotor)
    rotor.close()
    assert 15.0 < offset[0] < 40.0 and 0.03 < offset[4] < 0.15, offset


def test_the_closed_loop_starts_volturnus_s_at_its_static_offset():
    """The ROS closed loop's start (the same restoring matrix): the platform's own restoring
    matrix left out the potential-flow hydrostatics and the linear mooring, so that it was
    singular for VolturnUS-S and the command failed before starting."""
    from fowt_hydro_sim.ros import closed_loop

    offset = closed_loop.static_offset({"platform": PLATFORM}, {"wind_speed_m_s": WIND_M_S})
    assert np.all(np.isfinite(offset)) and 15.0 < offset[0] < 40.0


@pytest.mark.slow
def test_two_turbines_in_one_process_keep_their_own_controller_state():
    """Each ROSCO loads its own copy of the library: a run repeated after another one in the
    same process is the same, number for number."""
    wind = Wind(speed_m_s=WIND_M_S)
    first, _, start = offline(PLATFORM, wind, 5.0)
    second, _, _ = offline(PLATFORM, wind, 5.0, start + KICK)
    third, _, _ = offline(PLATFORM, wind, 5.0)
    assert np.array_equal(first.motion, third.motion)
    assert not np.array_equal(first.motion, second.motion)


@pytest.mark.slow
def test_simulate_of_the_named_system_writes_the_turbine_channels(tmp_path):
    out = tmp_path / "run"
    done = fowt_sim("simulate", "--system", "iea15_volturnus_s", "--wind-speed", "11", "--still-water",
                    "--duration", "20", "--output-interval", "0.5", "-o", str(out), "--transient", "0")
    assert done.returncode == 0, done.stderr
    assert "rotor_speed_rad_s" in done.stdout
    assert "Running ROSCO" not in done.stdout + done.stderr  # its banner goes to the debug log, not the output
    run = read_run(out)
    assert len(run["time_s"]) == 41
    for name in CHANNELS:
        assert np.all(np.isfinite(run[name])), name
    summary = json.loads((out / "summary.json").read_text())
    assert summary["turbine"]["controller"] == "ROSCO"
    assert (summary["platform"], summary["mooring"], summary["turbine"]["name"]) == (
        "volturnus_s", "moorpy", "IEA-15-240-RWT-UMaineSemi")  # the named system's parts
    assert len([c for c in run if c.endswith("_fairlead_tension_n")]) == 3
    assert summary["turbine_statistics"]["wind_speed_m_s"]["mean"] == pytest.approx(11.0)
    assert summary["run"]["initial_state"][0] > 15.0  # the static offset
    assert summary["statistics"]["surge"]["mean"] == pytest.approx(summary["run"]["initial_state"][0], rel=0.1)


@pytest.mark.slow
def test_a_turbine_option_without_the_turbine_is_refused_in_one_line(tmp_path):
    done = fowt_sim("simulate", "--wind-speed", "11", "-o", str(tmp_path / "x"))
    assert done.returncode == 2
    assert done.stderr.strip().splitlines() == ["fowt-sim simulate: error: --wind-speed: a turbine option needs "
                                                "--turbine rosco"]


@pytest.mark.slow
@pytest.mark.ros
def test_the_offline_loop_is_the_ros_closed_loop(tmp_path):
    """The same run (VolturnUS-S in still water, 11 m/s, a start off the static offset)
    through the platform node in lockstep + the turbine node over DDS, and offline in one
    process: the exchange is the same in the same order (odometry at t -> the turbine to t
    -> its wrench at t -> the platform to t + 0.05 s) and the arithmetic the same, so the
    two are the same numbers. Tolerance: 1e-9 m and 1e-12 rad on the motion (the bag's pose
    goes through a quaternion and back: ~1e-16 rad), 1e-12 relative on the turbine's
    channels; a lockstep timeout (a wrench missed), a one-step lag or another thrust point
    is orders of magnitude above it. (The closed loop gave the turbine node the default
    platform's hub point, 131.7 m, instead of VolturnUS-S's 150 m: 2e-3 m/s of relative
    wind per 0.05 s of pitch motion, 0.3 m of surge after 30 s.)"""
    pytest.importorskip("rclpy")
    from fowt_hydro_sim.ros import closed_loop
    from fowt_hydro_sim.rosbag.reader import Bag
    from msg_adapters import topics

    wind = Wind(speed_m_s=WIND_M_S)
    ours, channels, start = offline(PLATFORM, wind, DURATION_S)
    initial = start + KICK
    ours, channels, _ = offline(PLATFORM, wind, DURATION_S, initial)
    result = closed_loop.run(tmp_path / "loop", {"platform": PLATFORM, "duration_s": DURATION_S,
                                                 "real_time_factor": 0.0, "drag_model": "constant",
                                                 "wave_source": "none", "initial_state": [float(v) for v in initial]},
                             {"wind": "steady", "wind_speed_m_s": WIND_M_S}, timeout_s=600.0)
    assert result.returncodes == {"node": 0, "turbine": 0, "record": 0}, result.logs
    assert "lockstep: no external wrench" not in result.logs["node"]
    bag = Bag(tmp_path / "loop")
    motion = bag.motion()
    assert motion.time_s.size == ours.time_s.size and np.allclose(motion.time_s, ours.time_s, atol=1e-9)
    assert np.ptp(ours.motion[:, 0]) > 0.5 and np.ptp(ours.motion[:, 4]) > 0.005  # the platform moved
    assert np.abs(motion.values[:, :3] - ours.motion[:, :3]).max() < 1e-9
    assert np.abs(motion.values[:, 3:] - ours.motion[:, 3:]).max() < 1e-12
    for name, topic in (("rotor_speed_rad_s", "rotor_speed"), ("blade_pitch_rad", "blade_pitch"),
                        ("generator_torque_nm", "generator_torque"),
                        ("relative_wind_speed_m_s", "relative_wind_speed")):
        series = bag.scalar(topics.TURBINE[topic][0])
        theirs = series.values[:, 0]
        ref = channels[:, CHANNELS.index(name)]
        assert series.time_s.size == ref.size, name
        assert np.abs(theirs - ref).max() <= 1e-12 * np.abs(ref).max(), name


def test_a_named_system_fills_the_settings_left_at_their_defaults(tmp_path):
    from fowt_hydro_sim.physics.config import RunConfig
    from fowt_hydro_sim.turbine.system import filled, load_system, system_values

    system = load_system("iea15_volturnus_s")
    assert (system.platform, system.turbine, system.mooring) == ("volturnus_s", "iea15_umaine", "moorpy")
    load_platform(system.platform)
    assert filled(RunConfig, {"system": "iea15_volturnus_s", "platform": "windmoor12"})["platform"] == "volturnus_s"
    with pytest.raises(ValueError, match="system iea15_volturnus_s sets platform 'volturnus_s'; platform 'mine.yaml'"):
        system_values("iea15_volturnus_s", {"platform": "mine.yaml"}, {"platform": "windmoor12"})
    assert system_values("iea15_volturnus_s", {"mooring": "moordyn"}, {"mooring": ""})["mooring"] == "moordyn"
    own = tmp_path / "mine.yaml"
    own.write_text("platform: volturnus_s\nturbine: iea15_umaine\nlines: 3\n")
    with pytest.raises(ValueError, match=r"mine.yaml: unknown field\(s\) lines"):
        load_system(str(own))


@pytest.mark.ros
def test_the_closed_loop_and_both_nodes_take_the_named_system():
    pytest.importorskip("rclpy")
    from fowt_hydro_sim.ros.closed_loop import with_systems
    from fowt_hydro_sim.ros.node import NodeSettings
    from fowt_hydro_sim.ros.turbine_node import TurbineSettings
    from fowt_hydro_sim.turbine.system import with_system

    node, turbine = with_systems({"system": "iea15_volturnus_s", "duration_s": 10.0}, {"wind_speed_m_s": 9.0})
    assert (node["platform"], node["mooring"], turbine["platform"], turbine["turbine"]) == (
        "volturnus_s", "moorpy", "volturnus_s", "iea15_umaine")
    settings = with_system(NodeSettings(system="iea15_volturnus_s"))
    assert (settings.platform, settings.mooring) == ("volturnus_s", "moorpy")
    assert with_system(TurbineSettings(system="iea15_volturnus_s")).platform == "volturnus_s"


def test_the_turbine_settings_wind_topic_is_the_contracts():
    from fowt_hydro_sim.turbine.settings import WIND_TOPIC
    from msg_adapters import topics

    assert WIND_TOPIC == topics.TURBINE["wind_speed"][0]
