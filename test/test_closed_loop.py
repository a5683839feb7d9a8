"""The closed loop over real DDS (loopback): the platform node and the turbine node with
NREL's ROSCO as child processes, recorded to one bag; and the faults: the turbine killed
mid-run, ROSCO refusing its input file."""
from __future__ import annotations

import inspect
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("rclpy")
pytest.importorskip("rosco")

from rosgraph_msgs.msg import Clock  # noqa: E402

from fowt_hydro_sim.ros import closed_loop  # noqa: E402
from fowt_hydro_sim.rosbag.reader import Bag  # noqa: E402
from fowt_hydro_sim.studies.simulate import read_run  # noqa: E402
from fowt_hydro_sim.testing import REPO, fowt_sim, rosco_oracle  # noqa: E402
from fowt_hydro_sim.testing.ros import Listener, finish, start  # noqa: E402
from fowt_hydro_sim.turbine.description import load_turbine, turbine_path  # noqa: E402
from msg_adapters import topics  # noqa: E402

pytestmark = pytest.mark.ros
PLATFORM_TOPICS = ("/clock", "/platform/odom", "/platform/pose", "/platform/external_wrench", "/platform/loads/total")


@pytest.mark.slow
def test_150_s_of_lc5_2_waves_and_13_m_s_wind_over_dds(tmp_path):
    """Both nodes over DDS in waves and wind: every message of both at 20 Hz, all finite, the
    rotor near rated. (The same loop offline is the same numbers,
    test_coupled.py::test_the_offline_loop_is_the_ros_closed_loop; its 600 s run is
    test_600_s_of_lc5_2_waves_and_13_m_s_wind_offline.)"""
    bag_path = tmp_path / "loop"
    result = closed_loop.run(bag_path, {"load_case": "lc5.2", "duration_s": 150.0, "real_time_factor": 0.0},
                             {"wind": "steady", "wind_speed_m_s": 13.0}, timeout_s=900.0)
    assert result.returncodes == {"node": 0, "turbine": 0, "record": 0}, result.logs
    assert result.simulated_s == pytest.approx(150.0)
    bag = Bag(bag_path)
    for topic in (*PLATFORM_TOPICS, *(t for t, _ in topics.TURBINE.values())):
        assert bag.topics[topic].message_count >= 3001, topic  # 20 Hz for 150 s, both nodes
    rated = load_turbine().rated_rotor_speed_rad_s
    speed = bag.scalar("/turbine/rotor_speed")
    assert speed.time_s[-1] >= 149.9
    assert np.all(np.abs(speed.values[:, 0] / rated - 1.0) < 0.10), (speed.values.min(), speed.values.max())
    for topic, _kind in topics.TURBINE.values():
        assert np.all(np.isfinite(bag.scalar(topic).values)), topic
    for topic in PLATFORM_TOPICS[1:]:
        assert np.all(np.isfinite(bag.series(topic).values)), topic


@pytest.mark.slow
def test_600_s_of_lc5_2_waves_and_13_m_s_wind_offline(tmp_path):
    """The closed loop's default system (the packaged platform, the 15 MW rotor, ROSCO) for
    600 s in LC5.2 and 13 m/s, offline: the rotor within 10 % of rated throughout, the
    platform pitched by the thrust, rated power on average."""
    out = tmp_path / "run"
    done = fowt_sim("simulate", "--turbine", "rosco", "--wind-speed", 13, "--load-case", "lc5.2",
                    "--duration", 600, "--transient", 0, "-o", out, timeout=900)
    assert done.returncode == 0, done.stderr
    run = read_run(out)
    rated = load_turbine().rated_rotor_speed_rad_s
    assert run["time_s"][-1] == pytest.approx(600.0)
    assert np.all(np.abs(run["rotor_speed_rad_s"] / rated - 1.0) < 0.10)
    assert 0.05 < run["pitch_rad"].mean() < 0.25  # pitched by the thrust (static offset about 0.13 rad)
    assert run["generator_power_w"].mean() == pytest.approx(15e6, rel=0.05)  # above rated: rated power on average


@pytest.mark.slow
@pytest.mark.reference
@pytest.mark.rosco
def test_held_fixed_the_turbine_node_gives_rosco_simulators_trajectories(tmp_path):
    """The platform held fixed (turbine parameter fixed_platform), a wind step 10 -> 14 m/s:
    the recorded rotor speed, pitch and generator torque against rosco.toolbox.sim.Sim."""
    dt, duration, step, rpm = 0.05, 90.0, 30.0, 7.0
    oracle = rosco_oracle.in_child_process(tmp_path, "iea15_umaine", dt, duration, step, 10.0, 14.0, rpm)
    bag_path = tmp_path / "fixed"
    result = closed_loop.run(bag_path, {"duration_s": duration, "real_time_factor": 0.0, "hs_m": 0.01, "tp_s": 10.0,
                                        "initial_state": [0.0] * 6},
                             {"wind": "step", "wind_speed_m_s": 10.0, "wind_end_m_s": 14.0, "wind_start_s": step,
                              "fixed_platform": True, "rotor_start": "given", "rotor_speed_rad_s": rpm * 2 * np.pi / 60,
                              "pitch_rad": 0.0}, timeout_s=900.0)
    assert result.returncodes == {"node": 0, "turbine": 0, "record": 0}, result.logs
    bag = Bag(bag_path)
    for topic, name in (("/turbine/rotor_speed", "rotor_speed_rad_s"), ("/turbine/blade_pitch", "pitch_rad"),
                        ("/turbine/generator_torque", "generator_torque_nm")):
        series = bag.scalar(topic)
        index = np.round(series.time_s / dt).astype(int)
        assert np.allclose(index * dt, series.time_s, atol=1e-6)
        ours, theirs = series.values[:, 0], oracle[name][index]
        assert len(index) > 0.95 * duration / dt
        rms = np.sqrt(np.mean((ours - theirs) ** 2)) / np.sqrt(np.mean(theirs ** 2))
        assert rms < 0.01, f"{topic}: RMS difference {100 * rms:.3f} %"


def clock_after(listener: Listener, time_s: float, timeout_s: float) -> bool:
    def reached() -> bool:
        clocks = listener.messages["/clock"]
        return bool(clocks) and clocks[-1].clock.sec >= time_s
    return listener.wait_for(reached, timeout_s)


@pytest.mark.slow
@pytest.mark.parametrize("lost", ["stop", "open_loop"])
def test_the_turbine_killed_mid_run_is_noticed_and_the_parameter_followed(tmp_path, lost):
    listener = Listener({"/clock": Clock})
    bag_path = tmp_path / "run"
    node = start("node", lockstep=True, duration_s=120.0 if lost == "open_loop" else 0.0, real_time_factor=0.0,
                 controller_lost=lost, lockstep_timeout_s=1.0, record=str(bag_path))
    turbine = start("turbine", wind_speed_m_s=12.0)
    try:
        assert clock_after(listener, 10.0, 180.0), finish(node, 5)
        turbine.send_signal(signal.SIGKILL)
        output = finish(node, 120.0)
    finally:
        finish(turbine, 5.0)
        finish(node, 5.0)
        listener.close()
    gone = re.findall(r"lockstep: the controller is gone at t = ([\d.]+) s \(([^)]*)\)", output)
    assert len(gone) == 1, output[-3000:]
    assert float(gone[0][0]) >= 10.0
    ended = float(re.search(r"stepping ended at t = ([\d.]+) s", output).group(1))
    if lost == "stop":
        assert "stepping stopped (controller_lost stop)" in output
        assert ended == pytest.approx(float(gone[0][0]))
    else:
        assert "going on open loop" in output and ended == pytest.approx(120.0)
    odom = Bag(bag_path).series("/platform/odom")  # the recording is complete and readable
    assert odom.time_s[-1] == pytest.approx(ended)
    assert np.all(np.isfinite(odom.values))


@pytest.mark.slow
def test_rosco_refusing_its_input_is_one_clear_line_and_the_bag_stays_readable(tmp_path):
    good = load_turbine()
    discon = tmp_path / "DISCON.IN"
    discon.write_text(good.discon_path.read_text().replace("! PC_MaxPit", "! PC_MaxPitX", 1)
                      .replace('"../IEA-15-240-RWT/', f'"{good.discon_path.parent.parent}/IEA-15-240-RWT/'))
    source = turbine_path("iea15_umaine").read_text()
    turbine_file = tmp_path / "broken.yaml"
    turbine_file.write_text(source.replace(f"discon: {good.discon}", f"discon: {discon}"))
    bag_path = tmp_path / "loop"
    result = closed_loop.run(bag_path, {"duration_s": 30.0, "real_time_factor": 0.0},
                             {"turbine": str(turbine_file)}, timeout_s=300.0)
    assert result.returncodes["turbine"] == 2
    errors = [line for line in result.logs["turbine"].splitlines() if "ERROR" in line]
    assert len(errors) == 1 and "ROSCO failed starting" in errors[0], result.logs["turbine"]
    assert "Traceback" not in result.logs["turbine"]
    Bag(bag_path)  # closed and readable


@pytest.mark.slow
def test_a_silent_controller_is_given_up_after_its_timeouts_in_a_row():
    """A controller connected both ways that never answers: after controller_timeouts
    timeouts in a row (not one timeout per step forever) the node says so once and stops."""
    from geometry_msgs.msg import WrenchStamped
    from nav_msgs.msg import Odometry

    listener = Listener({"/platform/odom": Odometry})
    listener.publisher(WrenchStamped, topics.EXTERNAL_WRENCH)  # connected, silent
    node = start("node", lockstep=True, real_time_factor=0.0, lockstep_timeout_s=0.5, controller_timeouts=3)
    try:
        output = finish(node, 120.0)
    finally:
        finish(node, 5.0)
        listener.close()
    assert node.returncode == 1  # cut short by the lost controller
    assert output.count("lockstep: no external wrench stamped") == 2, output[-3000:]
    gone = re.findall(r"the controller is gone at t = ([\d.]+) s \(3 lockstep timeouts in a row\)", output)
    assert len(gone) == 1 and float(gone[0]) == pytest.approx(0.1)  # two steps with the last wrench, then stop
    assert "stepping ended at t = 0.10 s" in output


@pytest.mark.parametrize("bad, named", [(["--wind-speed", "100"], "--wind-speed"), (["--duration", "0"], "--duration"),
                                        (["--turbine", "nope"], "turbine 'nope'"), (["--wind", "file"], "wind_file"),
                                        (["--params-file", "nope.yaml"], "--params-file nope.yaml: cannot be read")])
@pytest.mark.slow
def test_closed_loop_refuses_bad_input_in_one_line(tmp_path, bad, named):
    done = fowt_sim("closed-loop", "-o", str(tmp_path / "b"), *bad, timeout=120)
    assert done.returncode == 2
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and named in lines[0] and "Traceback" not in done.stderr
    assert not (tmp_path / "b").exists()  # nothing started


# ---------------------------------------------------------------------- the command as a user runs it
INITIAL = (0.0, 0.0, 0.0, 0.0, 0.1, 0.0)


@pytest.fixture(scope="module")
def loop_bag(tmp_path_factory):
    """``fowt-sim closed-loop`` for 3 s in still water from a given initial state, ROSCO's
    debug channels asked for; its bag and the command's result."""
    bag = tmp_path_factory.mktemp("cli") / "loop"
    done = fowt_sim("closed-loop", "-o", bag, "--duration", 3, "--initial", *INITIAL, "--still-water",
                    "--rosco-logging", 1, timeout=900)
    return bag, done


@pytest.mark.slow
def test_the_command_takes_the_initial_state_and_still_water(loop_bag):
    bag_path, done = loop_bag
    assert done.returncode == 0, done.stdout + done.stderr
    assert re.fullmatch(r"closed loop: 3\.0 s simulated in [\d.]+ s .*\n", done.stdout), done.stdout
    bag = Bag(bag_path)
    motion = bag.motion()
    assert motion.time_s[0] == 0.0 and np.allclose(motion.values[0], INITIAL, atol=1e-9)
    assert np.all(bag.series("/waves/elevation_used").values[:, 2] == 0.0)  # still water


@pytest.mark.slow
def test_the_bag_holds_one_sample_per_stamp_from_the_first(loop_bag):
    bag = Bag(loop_bag[0])
    odom = bag.series("/platform/odom").time_s  # sorted, repeated stamps dropped
    assert odom[0] == 0.0 and odom[-1] == pytest.approx(3.0)
    for topic in ("/platform/odom", "/platform/external_wrench", *(t for t, _ in topics.TURBINE.values())):
        assert np.array_equal(bag.series(topic).time_s, odom), topic
        assert bag.topics[topic].message_count == len(odom), topic  # no stamp twice


@pytest.mark.slow
def test_the_bag_reruns_the_loop_and_keeps_roscos_debug_channels(loop_bag, tmp_path):
    bag_path, done = loop_bag
    assert done.returncode == 0
    config = Bag(bag_path).config
    assert config["parameters"]["initial_state"] == list(INITIAL)
    assert config["parameters"]["wave_source"] == "none"
    assert config["turbine_parameters"]["wind_speed_m_s"] == 13.0
    params = tmp_path / "run.yaml"
    info = fowt_sim("info", bag_path, "--params-file", params, timeout=120)
    assert info.returncode == 0, info.stderr
    assert "closed-loop" in info.stderr and "--params-file" in info.stderr
    again = tmp_path / "again"
    rerun = fowt_sim("closed-loop", "-o", again, "--params-file", params, timeout=900)
    assert rerun.returncode == 0, rerun.stdout + rerun.stderr
    first, second = Bag(bag_path), Bag(again)
    assert np.array_equal(first.motion().values, second.motion().values)  # lockstep: the same run
    assert np.array_equal(first.scalar("/turbine/blade_pitch").values, second.scalar("/turbine/blade_pitch").values)
    debug = Path(f"{bag_path}.logs") / "rosco" / "rosco.RO.dbg"
    lines = debug.read_text().splitlines()
    header = lines[1].split()
    assert header[0] == "Time" and "FA_AccF" in header and "NacIMU_FA_AccF" in header
    rows = np.array([[float(v) for v in line.split()] for line in lines[3:]])
    assert len(rows) >= 3.0 / load_turbine().controller_dt_s - 1  # every controller step of the run
    rerun_debug = (Path(f"{again}.logs") / "rosco" / "rosco.RO.dbg").read_text().splitlines()
    assert rerun_debug[1:] == lines[1:]  # the rerun's own, beside its bag: the same channels, row for row


@pytest.mark.serial
@pytest.mark.slow
def test_ctrl_c_ends_the_command_with_a_summary_and_a_readable_bag(tmp_path):
    """Ctrl-C at a terminal: SIGINT to the command and its three processes (one process group)."""
    bag_path = tmp_path / "loop"
    listener = Listener({"/clock": Clock})
    command = subprocess.Popen([sys.executable, "-m", "fowt_hydro_sim.cli", "closed-loop", "-o", str(bag_path),
                                "--duration", "600"], cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                               text=True, start_new_session=True)
    try:
        assert clock_after(listener, 1.0, 600.0)
        os.killpg(command.pid, signal.SIGINT)
        out, err = command.communicate(timeout=120)
    finally:
        if command.poll() is None:
            os.killpg(command.pid, signal.SIGKILL)
        listener.close()
    assert command.returncode == 130, out + err
    assert "Traceback" not in out + err
    assert re.fullmatch(r"closed loop interrupted: [\d.]+ s simulated in [\d.]+ s .*\n", out), out
    assert Bag(bag_path).series("/platform/odom").time_s[-1] >= 1.0  # closed, readable


@pytest.mark.slow
def test_controller_lost_open_loop_goes_on_after_the_turbine_is_killed(tmp_path):
    bag_path = tmp_path / "loop"
    listener = Listener({"/clock": Clock})
    command = subprocess.Popen([sys.executable, "-m", "fowt_hydro_sim.cli", "closed-loop", "-o", str(bag_path),
                                "--duration", "12", "--controller-lost", "open_loop", "--lockstep-timeout", "1"],
                               cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert clock_after(listener, 2.0, 600.0)
        turbine = [pid for pid in child_pids(command.pid) if b"turbine" in Path(f"/proc/{pid}/cmdline").read_bytes()]
        assert len(turbine) == 1
        os.kill(turbine[0], signal.SIGKILL)
        out, err = command.communicate(timeout=600)
    finally:
        if command.poll() is None:
            command.kill()
        listener.close()
    assert "closed loop: 12.0 s simulated" in out, out + err
    node_log = (tmp_path / "loop.logs" / "node.log").read_text()
    assert "going on open loop" in node_log
    assert Bag(bag_path).series("/platform/odom").time_s[-1] == pytest.approx(12.0)


def child_pids(pid: int) -> list[int]:
    """The process ids whose parent is ``pid`` (from /proc)."""
    children = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if int(fields[1]) == pid:
            children.append(int(stat.parent.name))
    return children


def test_the_loop_has_no_wall_clock_limit():
    """A 3-hour closed loop at under 3x real time takes over an hour: the wrapper waits for
    the platform node, however long (a limit only when the caller gives one)."""
    assert inspect.signature(closed_loop.run).parameters["timeout_s"].default is None


@pytest.mark.slow
def test_one_wind_speed_default_everywhere():
    from fowt_hydro_sim.cli.turbine import parser
    from fowt_hydro_sim.ros.turbine_node import TurbineSettings
    from fowt_hydro_sim.turbine.wind import Wind

    args = parser().parse_args(["-o", "x"])
    assert args.wind_speed_m_s == TurbineSettings.wind_speed_m_s == Wind.speed_m_s == 13.0
    assert args.wind_end_m_s == TurbineSettings.wind_end_m_s == Wind.end_m_s == 13.0


@pytest.mark.slow
def test_the_turbine_answers_each_stamp_once(tmp_path):
    """An odometry sent again (same stamp): the wrench again, the turbine's state not twice."""
    from geometry_msgs.msg import Vector3Stamped, WrenchStamped
    from nav_msgs.msg import Odometry

    import msg_adapters as adapt

    listener = Listener({"/turbine/rotor_speed": Vector3Stamped, topics.EXTERNAL_WRENCH: WrenchStamped})
    odometry = listener.publisher(Odometry, topics.MOTION["odom"][0])
    turbine = start("turbine")
    try:
        assert listener.wait_for(lambda: odometry.get_subscription_count() == 1 and listener.node.count_publishers(
            "/turbine/rotor_speed") == 1, 120.0), finish(turbine, 5)
        time.sleep(0.5)
        zero = np.zeros(6)
        for t in (0.0, 0.0, 0.05):
            wrenches = len(listener.messages[topics.EXTERNAL_WRENCH]) + 1
            odometry.publish(adapt.odometry_msg(t, zero, zero))
            assert listener.wait_for(lambda n=wrenches: len(listener.messages[topics.EXTERNAL_WRENCH]) >= n, 60.0)
        time.sleep(0.5)
    finally:
        finish(turbine, 5)
        listener.close()
    stamps = [m.header.stamp.sec + 1e-9 * m.header.stamp.nanosec for m in listener.messages["/turbine/rotor_speed"]]
    assert stamps == pytest.approx([0.0, 0.05])
    wrench = [m.header.stamp.sec + 1e-9 * m.header.stamp.nanosec for m in listener.messages[topics.EXTERNAL_WRENCH]]
    assert wrench == pytest.approx([0.0, 0.0, 0.05])


@pytest.mark.serial
@pytest.mark.slow
def test_a_slow_controller_gets_each_odometry_once(tmp_path):
    """A controller answering 0.8 s after each odometry (a loaded machine): the node waits
    without sending the state again, and its bag holds one sample per stamp."""
    from geometry_msgs.msg import WrenchStamped
    from nav_msgs.msg import Odometry

    import msg_adapters as adapt

    listener = Listener({"/platform/odom": Odometry})
    wrench = listener.publisher(WrenchStamped, topics.EXTERNAL_WRENCH)
    bag_path = tmp_path / "run"
    node = start("node", lockstep=True, real_time_factor=0.0, duration_s=2.0, publish_rate_hz=2.0,
                 record=str(bag_path), hs_m=0.01, tp_s=10.0)
    answered: list[float] = []
    try:
        deadline = time.monotonic() + 300.0
        while node.poll() is None and time.monotonic() < deadline:
            stamps = [m.header.stamp.sec + 1e-9 * m.header.stamp.nanosec for m in listener.messages["/platform/odom"]]
            new = [t for t in stamps if t not in answered]
            if new:
                time.sleep(0.8)
                answered.append(new[0])
                wrench.publish(adapt.wrench_msg(new[0], np.zeros(6), "hub"))
            time.sleep(0.05)
        output = finish(node, 60.0)
    finally:
        finish(node, 5.0)
        listener.close()
    assert node.returncode == 0, output[-3000:]
    stamps = [m.header.stamp.sec + 1e-9 * m.header.stamp.nanosec for m in listener.messages["/platform/odom"]]
    assert stamps == pytest.approx([0.0, 0.5, 1.0, 1.5, 2.0])
    bag = Bag(bag_path)
    for topic in ("/platform/odom", "/platform/pose", "/clock"):
        assert bag.topics[topic].message_count == 5, topic
