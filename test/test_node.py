"""The simulator node over real DDS (loopback): the node and the controller run as child
processes (``fowt-sim node|controller``), the test's listener node records their topics.

Oracles: the offline model (same seed and dt: bit for bit), the static stiffness (mean
pitch under a thrust), the wall clock (pacing), and the node's own log for refused input.
"""
from __future__ import annotations

import math
import os
import re
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

pytest.importorskip("rclpy")

from geometry_msgs.msg import PointStamped, PoseStamped, WrenchStamped  # noqa: E402
from rclpy.serialization import deserialize_message  # noqa: E402
from rosgraph_msgs.msg import Clock  # noqa: E402

import msg_adapters as adapt  # noqa: E402
from fowt_hydro_sim.physics.config import HydroOptions, load_case, load_platform  # noqa: E402
from fowt_hydro_sim.physics.model import PlatformModel  # noqa: E402
from fowt_hydro_sim.physics.waves.components import repeat_period, synthesize  # noqa: E402
from fowt_hydro_sim.rosbag.reader import Bag  # noqa: E402
from fowt_hydro_sim.testing.ros import Listener, command_line, finish, start  # noqa: E402
from msg_adapters import topics  # noqa: E402


def poses(listener: Listener) -> tuple[np.ndarray, np.ndarray]:
    """Times and motions of the received poses, in time order, duplicates dropped."""
    rows = {}
    for msg in listener.messages["/platform/pose"]:
        t, motion = adapt.motion_from_pose(msg)
        rows[t] = motion
    times = np.array(sorted(rows))
    return times, np.array([rows[t] for t in times])


def run_node(duration_s: float, topics: dict | None = None, timeout_s: float = 120.0, **parameters):
    listener = Listener(topics or {"/platform/pose": PoseStamped, "/clock": Clock})
    parameters.setdefault("wait_for_subscribers", 1)  # the listener, before the first step
    node = start("node", duration_s=duration_s, **parameters)
    try:
        listener.wait_for(lambda: node.poll() is not None, timeout_s)
        output = finish(node, 10)
        time.sleep(0.3)
    finally:
        listener.close()
    return listener, output


@pytest.mark.slow
def test_internal_waves_match_the_offline_model_bit_for_bit():
    listener, output = run_node(30.0, real_time_factor=0.0, load_case="lc5.2", seed=3, drag_model="filtered")
    assert "duration 30 s reached" in output, output
    t, motion = poses(listener)
    assert len(t) >= 0.9 * 601 and t[-1] == pytest.approx(30.0)
    sea = load_case("lc5.2").sea_state
    sea = type(sea)(sea.hs_m, sea.tp_s, sea.gamma, seed=3)
    model = PlatformModel(load_platform(), synthesize(sea, repeat_period(sea, 30.0)), dt_s=0.05, drag_model="filtered")
    offline = model.run(30.0, output_interval_s=0.05)
    index = np.rint(t / 0.05).astype(int)
    assert np.abs(offline.time_s[index] - t).max() < 1e-9
    np.testing.assert_array_equal(motion[:, :3], offline.motion[index, :3])
    np.testing.assert_allclose(motion[:, 3:], offline.motion[index, 3:], rtol=0, atol=1e-12)  # via quaternions
    clock = [adapt.seconds(m.clock) for m in listener.messages["/clock"]]
    assert clock and max(clock) == pytest.approx(30.0)  # simulation time, not the wall clock


@pytest.mark.slow
def test_hydro_option_parameters_reach_the_model():
    """HydroDyn's hydro options as node parameters: the node's motion is the offline model's
    with the same options, bit for bit."""
    from fowt_hydro_sim.physics.config import EARLIER, HYDRODYN

    listener, output = run_node(20.0, real_time_factor=0.0, load_case="lc5.2", seed=3, drag_model="constant",
                                wetted_length="undisplaced", load_directions="fixed", hydrostatics="nonlinear",
                                slow_drift="none")
    assert "duration 20 s reached" in output, output
    t, motion = poses(listener)
    sea = load_case("lc5.2").sea_state
    sea = type(sea)(sea.hs_m, sea.tp_s, sea.gamma, seed=3)
    model = PlatformModel(load_platform(), synthesize(sea, repeat_period(sea, 20.0)), dt_s=0.05, options=HYDRODYN)
    offline = model.run(20.0, output_interval_s=0.05)
    index = np.rint(t / 0.05).astype(int)
    np.testing.assert_array_equal(motion[:, :3], offline.motion[index, :3])
    earlier = PlatformModel(load_platform(), synthesize(sea, repeat_period(sea, 20.0)), dt_s=0.05,
                            options=EARLIER).run(20.0, 0.05)
    assert np.abs(earlier.motion[index, 2] - motion[:, 2]).max() > 1e-6  # the options change the motion


def _controlled_run(duration_s: float, real_time_factor: float, damping: float, publish_rate_hz: float,
                    load_case: str = "lc5.0", **node_parameters) -> tuple[np.ndarray, np.ndarray, str]:
    listener = Listener({"/platform/pose": PoseStamped})
    controller = start("controller", mean_thrust_n=1.5e6, pitch_damping_n_s_rad=damping)
    node = start("node", duration_s=duration_s, real_time_factor=real_time_factor, lockstep=True,
                 publish_rate_hz=publish_rate_hz, load_case=load_case, drag_model="constant", **node_parameters)
    try:
        listener.wait_for(lambda: node.poll() is not None, 180.0)
        output = finish(node, 10)
        time.sleep(0.3)
    finally:
        controller.terminate()
        finish(controller, 10)
        listener.close()
    t, motion = poses(listener)
    return t, motion, output


@pytest.mark.slow
def test_controller_thrust_sets_the_static_mean_pitch():
    """A 1.5 MN hub thrust with pitch damping, in lockstep: the mean pitch and surge over the
    last 300 s of 600 s are K^-1 F, K the linear restoring matrix (hydrostatics, mooring).
    With linear hydrostatics: the nonlinear ones' stiffening at 7 deg makes K^-1 F 3.4 % large
    (the turbine tests check that against closed-form statics)."""
    t, motion, output = _controlled_run(600.0, 0.0, damping=2e7, publish_rate_hz=2.0, hydrostatics="linear")
    assert "duration 600 s reached" in output, output
    assert "lockstep: no external wrench" not in output, output
    model = PlatformModel(load_platform(), None, options=HydroOptions(hydrostatics="linear"))
    hub_z = load_platform().hub_point_m[2]
    static = np.linalg.solve(model.restoring_matrix(), np.array([1.5e6, 0, 0, 0, 1.5e6 * hub_z, 0]))
    late = t >= 300.0
    assert motion[late, 4].mean() == pytest.approx(static[4], rel=0.03)
    assert motion[late, 0].mean() == pytest.approx(static[0], rel=0.05)
    assert abs(static[4]) > math.radians(1.0)  # a visible tilt, not a rounding effect


@pytest.mark.slow
def test_lockstep_is_deterministic_at_any_speed():
    """The same closed loop at real-time factors 0 (as fast as possible) and 20: identical poses."""
    runs = [_controlled_run(60.0, factor, damping=5e7, publish_rate_hz=20.0, load_case="lc5.3",
                            wait_for_subscribers=1) for factor in (0.0, 20.0)]  # the listener hears the start
    (t0, fast, out0), (t1, paced, out1) = runs
    assert "lockstep: no external wrench" not in out0 + out1
    common, i0, i1 = np.intersect1d(t0, t1, return_indices=True)
    assert len(common) >= 0.95 * 1200 and common[-1] == pytest.approx(60.0)
    np.testing.assert_array_equal(fast[i0], paced[i1])
    assert np.ptp(fast[i0, 4]) > 1e-4  # the pitch moves: there is something to compare


@pytest.mark.serial
@pytest.mark.slow
@pytest.mark.parametrize("factor", [1.0, 10.0])
def test_pacing_follows_the_real_time_factor(factor: float):
    """Simulated time over wall time, from /clock as it arrives, over about 10 s: the slope of
    a straight line through (arrival, simulated time) within 2 % (a line, not the end points:
    one message delayed by a busy machine moves an end point, not the slope)."""
    listener = Listener({"/clock": Clock})
    node = start("node", real_time_factor=factor, drag_model="constant")
    try:
        listener.wait_for(lambda: len(listener.messages["/clock"]) > 20, 60.0)
        time.sleep(11.0)
        sim = np.array([adapt.seconds(m.clock) for m in listener.messages["/clock"]])
        arrivals = np.array(listener.arrival["/clock"][:len(sim)])  # the listener is still receiving
    finally:
        node.terminate()
        finish(node, 10)
        listener.close()
    keep = arrivals >= arrivals[0] + 1.0  # after the first second
    ratio = np.polyfit(arrivals[keep], sim[keep], 1)[0]
    assert arrivals[keep][-1] - arrivals[keep][0] > 9.0
    assert ratio == pytest.approx(factor, rel=0.02)


@pytest.mark.serial
@pytest.mark.slow
def test_wave_blocks_do_not_stall_the_paced_node():
    """Oracle: the wall clock. A node at 20x real time (2.5 ms between poses) on a 12-hour sea
    (duration_s sets the repeat period; a block costs about 1 s of synthesis on an idle
    core, whatever its length, and a 100 s block lasts 5 s of wall time) with 100 s blocks
    runs past 300 s: block boundaries at 100, 200 and 300 s. Every block the stepping took was
    made ahead by the worker (the node's report), and no pose interval at the subscriber
    exceeds 0.6 s. With each block made in the stepping thread (as the node once did) the
    poses stopped for the whole synthesis at every boundary: 1.46 s here. The 0.6 s bound
    leaves room for the scheduling of the node and of this test's own Python subscriber: a
    309 ms interval away from any boundary was seen once on an idle machine. How long the
    stepping still waits for a block made ahead depends on the machine's load (the worker
    shares the GIL with the stepping and publishing thread, which keeps one core busy at
    this rate: 0.13-0.62 s in all, seen on this 2-core machine); benchmarks/node.py reports it."""
    factor, period_s, block_s, bound_s = 20.0, 0.05, 100.0, 0.6
    listener = Listener({"/platform/pose": PoseStamped})
    node = start("node", real_time_factor=factor, drag_model="constant", duration_s=43200.0,
                 wave_block_s=block_s, wait_for_subscribers=1)
    try:
        listener.wait_for(lambda: node.poll() is not None or (
            bool(listener.messages["/platform/pose"])
            and adapt.seconds(listener.messages["/platform/pose"][-1].header.stamp) > 3 * block_s + 20.0), 180.0)
        sim = np.array([adapt.seconds(m.header.stamp) for m in listener.messages["/platform/pose"]])
        arrivals = np.array(listener.arrival["/platform/pose"][:len(sim)])
    finally:
        node.send_signal(signal.SIGINT)  # the node then reports its stepping
        output = finish(node, 20)
        listener.close()
    assert sim.size and sim[-1] > 3 * block_s + 20.0, output[-2000:]
    keep = sim >= 0.5 * block_s  # past the start
    intervals_s = np.diff(arrivals[keep])
    np.testing.assert_allclose(np.diff(sim[keep]), period_s, atol=1e-6)  # every pose, in order
    assert intervals_s.max() < bound_s, (f"longest pose interval {intervals_s.max() * 1e3:.0f} ms at t = "
                                         f"{sim[keep][1 + intervals_s.argmax()]:.2f} s")
    blocks = re.search(r"s waiting for wave blocks \((\d+) of (\d+) made ahead\)", output)
    assert blocks and int(blocks[2]) >= 3 and blocks[1] == blocks[2], output[-2000:]


def _log_after(output: str, needle: str) -> bool:
    return any(needle in line for line in output.splitlines())


@pytest.mark.slow
def test_bad_wrenches_are_refused_and_the_node_keeps_running():
    """NaN, absurd and unknown-frame wrenches: one log line each, the node keeps stepping on
    the last good wrench, and publishes no NaN."""
    listener = Listener({"/platform/pose": PoseStamped, "/platform/loads/external": WrenchStamped})
    node = start("node", real_time_factor=5.0, drag_model="constant", load_case="lc5.0")
    wrenches = listener.publisher(WrenchStamped, "/platform/external_wrench")
    try:
        listener.wait_for(lambda: len(listener.messages["/platform/pose"]) > 5, 60.0)
        time.sleep(0.5)
        good = adapt.wrench_msg(0.0, np.array([1e6, 0, 0, 0, 0, 0]), "hub")
        bad = [adapt.wrench_msg(0.0, np.array([np.nan, 0, 0, 0, 0, 0]), "hub"),
               adapt.wrench_msg(0.0, np.array([0, 0, 5e12, 0, 0, 0]), "world"),
               adapt.wrench_msg(0.0, np.array([1, 0, 0, 0, 0, 0]), "nacelle")]
        wrenches.publish(good)
        time.sleep(1.0)
        for msg in bad:
            wrenches.publish(msg)
            time.sleep(0.3)
        count = len(listener.messages["/platform/pose"])
        time.sleep(1.5)
        assert node.poll() is None and len(listener.messages["/platform/pose"]) > count  # still stepping
    finally:
        node.terminate()
        output = finish(node, 10)
        listener.close()
    assert _log_after(output, "external wrench: non-finite value"), output
    assert _log_after(output, "external wrench: absurd value"), output
    assert _log_after(output, "external wrench: unknown frame_id 'nacelle'"), output
    external = np.array([adapt.wrench_from_msg(m)[1] for m in listener.messages["/platform/loads/external"]])
    assert np.all(np.isfinite(external))
    assert np.abs(external[-1, 0] - 1e6) < 1e6 * 0.2  # the good hub thrust still acts (rotated by the pitch)
    for msg in listener.messages["/platform/pose"]:
        assert np.all(np.isfinite(adapt.motion_from_pose(msg)[1]))


@pytest.mark.slow
def test_a_diverging_state_stops_the_stepping():
    """A 0.9 GN thrust at the hub (accepted, under the absurd limit) overturns the platform:
    the node says the state diverged, stops stepping and publishes nothing beyond the bound."""
    listener = Listener({"/platform/pose": PoseStamped})
    # long enough that the wrench arrives mid-run (600 s take about a second as fast as possible)
    node = start("node", real_time_factor=0.0, drag_model="constant", lockstep=False, duration_s=36000.0)
    wrenches = listener.publisher(WrenchStamped, "/platform/external_wrench")
    try:
        listener.wait_for(lambda: len(listener.messages["/platform/pose"]) > 0, 60.0)
        wrenches.publish(adapt.wrench_msg(0.0, np.array([9e8, 0, 0, 0, 0, 0]), "hub"))
        listener.wait_for(lambda: node.poll() is not None, 60.0)
        output = finish(node, 10)
    finally:
        listener.close()
    assert _log_after(output, "the state diverged"), output
    assert node.returncode == 1 and _log_after(output, "the run is incomplete: the state diverged"), output
    motions = np.array([adapt.motion_from_pose(m)[1] for m in listener.messages["/platform/pose"]])
    assert np.all(np.isfinite(motions)) and np.abs(motions[:, 4]).max() < 1.2


@pytest.mark.slow
def test_batches_publish_every_stamp_in_order_and_record_them_all(tmp_path):
    """As fast as possible the node steps and publishes in batches (5 s of simulated time):
    over DDS every output topic delivers every publish time 0, 0.05, ..., 12 s once and in
    order (two full batches and a partial one), and the recording holds exactly the
    messages received, with their stamps as log times."""
    from fowt_hydro_sim.ros.node import MESSAGE_CLASSES, OUTPUTS
    from fowt_hydro_sim.rosbag.reader import Bag

    outputs = {topic: MESSAGE_CLASSES[kind] for topic, kind in OUTPUTS.values()}
    # the pose subscription last: the node waits for it, and DDS announces a participant's
    # subscriptions in the order they were made, so the others are matched by then
    outputs[topics.POSE] = outputs.pop(topics.POSE)
    bag = tmp_path / "run"
    listener, output = run_node(12.0, topics=outputs, real_time_factor=0.0, drag_model="constant",
                                record=str(bag), wait_for_subscribers=1)
    assert "duration 12 s reached" in output, output
    expected = [(n // 20, (n % 20) * 50_000_000) for n in range(241)]
    for topic, messages in listener.messages.items():
        stamps = [((m.clock if topic == "/clock" else m.header.stamp).sec,
                   (m.clock if topic == "/clock" else m.header.stamp).nanosec) for m in messages]
        assert stamps == expected, topic
    recorded = Bag(bag)
    assert {topic: recorded.topics[topic].message_count for topic in outputs} == dict.fromkeys(outputs, 241)
    for topic, kind in outputs.items():
        messages = list(recorded.messages([topic]))
        assert [log_time for _, log_time, _ in messages] == [sec * 10**9 + nanosec for sec, nanosec in expected]
        assert [deserialize_message(data, kind) for _, _, data in messages] == listener.messages[topic], topic
    pose_x = [m.pose.position.x for m in listener.messages["/platform/pose"]]
    assert np.ptp(pose_x) > 0.1  # the platform moves: the messages differ


@pytest.mark.parametrize("args, message", [
    ({"dt_s": -0.05}, "parameter dt_s: must be a positive number"),
    ({"drag_model": "smart"}, "parameter drag_model: must be one of constant, filtered"),
    ({"platform": "nowhere.yaml"}, "platform 'nowhere.yaml': no such file"),
    ({"publish_rate_hz": 7.0}, "parameter publish_rate_hz"),
    ({"load_case": "lc9.9"}, "load case 'lc9.9': unknown"),
    ({"hydrostatics": "exact"}, "parameter hydrostatics: must be one of linear, nonlinear"),
    ({"hydrostatics": "free_surface"}, "parameter hydrostatics: 'free_surface' is implemented for a prescribed "
                                       "motion only"),
    *[pytest.param(args, message, marks=pytest.mark.slow) for args, message in [
        ({"duraton_s": 600.0}, "parameter duraton_s: unknown to fowt_hydro_sim (did you mean duration_s?)"),
        ({"no_such_param": 1.0}, "parameter no_such_param: unknown to fowt_hydro_sim"),
        ({"hs_m": -3.0}, "parameter hs_m: must be 0 to 30, got -3"),
        ({"seed": 1.5}, "parameter seed: must be a whole number, got 1.5"),
        ({"lockstep": "maybe"}, "parameter lockstep: must be true or false, got 'maybe'"),
        ({"record": "/proc/foo"}, "parameter record: cannot create the bag directory /proc/foo: No such file or "
                                  "directory"),
    ]],
])
@pytest.mark.slow
def test_bad_parameters_end_with_one_line(args: dict, message: str):
    node = start("node", **args)
    output = finish(node, 60)
    assert node.returncode == 2 and message in output and "Traceback" not in output, output
    errors = [line for line in output.splitlines() if "ERROR" in line]
    assert len(errors) == 1 and "Invalid parameter" not in output, output


@pytest.mark.slow
def test_unknown_parameters_in_a_parameter_file_are_refused(tmp_path):
    """A misspelt name in a --params-file counts as on the command line: refused, not ignored."""
    params = tmp_path / "params.yaml"
    params.write_text("fowt_hydro_sim:\n  ros__parameters: {duration_s: 10.0, hs: 3.0}\n")
    node = subprocess.Popen([sys.executable, "-m", "fowt_hydro_sim.cli", "node", "--ros-args", "--params-file",
                             str(params)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    output = finish(node, 60)
    assert node.returncode == 2 and "parameter hs: unknown to fowt_hydro_sim (did you mean hs_m?)" in output, output


@pytest.mark.slow
@pytest.mark.parametrize("args, message", [
    ({"mean_thrust": 1e6}, "parameter mean_thrust: unknown to fowt_thrust_controller (did you mean mean_thrust_n?)"),
    ({"mean_thrust_n": "abc"}, "parameter mean_thrust_n: must be a number, got 'abc'"),
    ({"frame_id": "nacelle"}, "parameter frame_id: must be one of world, platform, hub, got 'nacelle'"),
])
def test_bad_controller_parameters_end_with_one_line(args: dict, message: str):
    controller = start("controller", **args)
    output = finish(controller, 60)
    assert controller.returncode == 2 and message in output and "Traceback" not in output, output


@pytest.mark.slow
@pytest.mark.parametrize("second_s", [0.1, 0.15, 0.2])
def test_a_second_ctrl_c_during_the_clean_up_does_not_cut_it(tmp_path, second_s: float):
    """Ctrl-C at a terminal reaches every process of the group, and a parent that stops its
    children (closed-loop) sends its own: a second SIGINT while the node closes its bag. The node
    still exits 0 with its bag closed and readable. Before, it could abort mid-clean-up (exit
    -6, or -2) about one time in four. The node waits for the listener before stepping: unpaced,
    its 600 s take under a second, less than discovery can take on a loaded machine."""
    listener = Listener({"/clock": Clock, "/platform/pose": PoseStamped})
    node = start("node", real_time_factor=0.0, duration_s=600.0, drag_model="constant", record=str(tmp_path / "bag"),
                 wait_for_subscribers=1)
    try:
        stepping = listener.wait_for(lambda: any(adapt.seconds(m.clock) > 1.0 for m in listener.messages["/clock"]),
                                     60.0)
        if stepping:
            node.send_signal(signal.SIGINT)
            time.sleep(second_s)
            if node.poll() is None:
                node.send_signal(signal.SIGINT)
    finally:
        output = finish(node, 60)
        listener.close()
    assert stepping, ("no clock past 1 s", output[-2000:])
    assert node.returncode == 0 and "stepping ended" in output, (node.returncode, output[-2000:])
    assert Bag(tmp_path / "bag").motion().time_s[-1] > 1.0


@pytest.mark.serial
@pytest.mark.slow
def test_the_controller_stops_on_sigterm():
    controller = start("controller")
    time.sleep(5.0)
    assert controller.poll() is None
    controller.terminate()
    started = time.monotonic()
    finish(controller, 20)
    assert controller.returncode == 0 and time.monotonic() - started < 5.0


def _tapered_record(duration_s: float = 600.0, dt_s: float = 0.1) -> tuple[np.ndarray, np.ndarray]:
    """LC5.2-like elevation at the origin: 100 s of calm, 60 s cosine ramps, calm at the end."""
    from fowt_hydro_sim.physics.config import SeaState
    t = np.arange(0.0, duration_s, dt_s)
    eta = synthesize(SeaState(6.19, 9.0, 4.9, seed=2), 3600.0).elevation(0.0, 0.0, t, 150.0, 9.80665)
    ramp = np.clip(np.minimum(t - 100.0, duration_s - 40.0 - t) / 60.0, 0.0, 1.0)
    return t, eta * np.sin(0.5 * np.pi * ramp) ** 2


@pytest.mark.slow
def test_wave_topic_gives_the_offline_models_motion():
    """An elevation record published on /waves/elevation (wave_source topic, streamed
    kinematics) against the offline model fed the same record by FFT decomposition: surge,
    heave and pitch agree within 1 % of their standard deviation over 150-500 s (measured: 0.16 %,
    0.07 %, 0.02 %)."""
    from fowt_hydro_sim.physics.waves.components import from_elevation_record
    t, eta = _tapered_record()
    listener = Listener({"/platform/pose": PoseStamped})
    publisher = listener.publisher(PointStamped, "/waves/elevation")
    node = start("node", wave_source="topic", real_time_factor=0.0, duration_s=500.0, drag_model="constant",
                 wave_timeout_s=60.0, wave_sample_dt_s=0.1)
    try:
        listener.wait_for(lambda: publisher.get_subscription_count() > 0, 60.0)
        time.sleep(1.0)
        for i, (ti, ei) in enumerate(zip(t, eta)):
            publisher.publish(adapt.elevation_msg(float(ti), 0.0, 0.0, float(ei)))
            if i % 200 == 199:
                time.sleep(0.02)
        listener.wait_for(lambda: node.poll() is not None, 240.0)
        output = finish(node, 10)
        time.sleep(0.3)
    finally:
        listener.close()
    assert "duration 500 s reached" in output and "still water" not in output and "gap" not in output, output
    times, motion = poses(listener)
    no_drift = HydroOptions(slow_drift="none")  # streamed kinematics carry no slow drift (README)
    offline = PlatformModel(load_platform(), from_elevation_record(t, eta), drag_model="constant",
                            options=no_drift).run(500.0, 0.05)
    index = np.rint(times / 0.05).astype(int)
    window = (times >= 150.0) & (times <= 500.0)
    assert window.sum() > 0.9 * 7000
    for dof in (0, 2, 4):
        reference = offline.motion[index[window], dof]
        error = motion[window, dof] - reference
        assert np.sqrt(np.mean(error**2)) < 0.01 * reference.std(), (dof, np.sqrt(np.mean(error**2)), reference.std())


@pytest.mark.slow
def test_bad_elevation_samples_and_a_silent_topic():
    """NaN, absurd (1e6 m), duplicated, out-of-order, far-future, misplaced and wrong-frame
    samples: one log line each and the sample is ignored; a burst of 400 bad samples of one kind
    gives a couple of lines with a count of the others, not 400 lines; when the topic stops,
    the node says so and goes on in still water; it keeps running and never publishes NaN."""
    listener = Listener({"/platform/pose": PoseStamped, "/waves/elevation_used": PointStamped})
    publisher = listener.publisher(PointStamped, "/waves/elevation")
    node = start("node", wave_source="topic", real_time_factor=50.0, wave_timeout_s=5.0, drag_model="constant",
                 wait_for_subscribers=1)  # the silence counts from the first step: after the listener is matched
    try:
        listener.wait_for(lambda: publisher.get_subscription_count() > 0, 60.0)
        time.sleep(0.5)
        for i in range(100):
            publisher.publish(adapt.elevation_msg(0.1 * i, 0.0, 0.0, 0.5 * math.sin(0.7 * i)))
        bad = [adapt.elevation_msg(10.0, 0.0, 0.0, float("nan")),
               adapt.elevation_msg(9.9, 0.0, 0.0, 0.1),
               adapt.elevation_msg(5.0, 0.0, 0.0, 0.1),
               adapt.elevation_msg(1e7, 0.0, 0.0, 0.1),
               adapt.elevation_msg(10.0, 50.0, 0.0, 0.1),
               adapt.elevation_msg(10.0, 0.0, 0.0, 0.1, "platform"),
               adapt.elevation_msg(10.0, 0.0, 0.0, 1e6)]
        for msg in bad:
            publisher.publish(msg)
            time.sleep(0.2)
        for i in range(400):  # a burst of one kind: out of order
            publisher.publish(adapt.elevation_msg(1.0 + 0.01 * i, 0.0, 0.0, 0.1))
        listener.wait_for(lambda: len(listener.messages["/platform/pose"]) > 200, 30.0)
        count = len(listener.messages["/platform/pose"])
        time.sleep(1.0)
        assert node.poll() is None and len(listener.messages["/platform/pose"]) > count
    finally:
        node.terminate()
        output = finish(node, 10)
        listener.close()
    for needle in ("wave elevation: non-finite sample", "wave elevation: duplicated sample at t = 9.900",
                   "wave elevation: out of order sample at t = 5.000", "ahead of the simulation",
                   "measured at (50, 0) m", "frame_id 'platform', expected 'world'",
                   "no wave elevation on /waves/elevation for", "1e+06 m at t = 10.000 s is beyond +-50 m"):
        assert _log_after(output, needle), (needle, output)
    burst = [line for line in output.splitlines() if "out of order sample" in line]
    shown = sum(1 for line in burst if "more refused like" not in line)
    counted = sum(int(a or b) for a, b in re.findall(r"and (\d+) more like it|(\d+) more refused like: wave", output))
    assert len(burst) <= 4 and shown + counted == 401, output  # the earlier t = 5 sample and the burst
    for msg in listener.messages["/platform/pose"]:
        assert np.all(np.isfinite(adapt.motion_from_pose(msg)[1]))
    assert all(math.isfinite(m.point.z) for m in listener.messages["/waves/elevation_used"])


@pytest.mark.slow
def test_integer_values_of_floating_point_parameters_are_taken():
    """``-p duration_s:=60`` as users type it (an INTEGER for a DOUBLE parameter)."""
    listener, output = run_node(8, real_time_factor=0, publish_rate_hz=10, dt_s=0.05)
    assert "duration 8 s reached" in output and "Traceback" not in output, output
    t, _ = poses(listener)
    assert t[-1] == pytest.approx(8.0) and len(t) >= 0.9 * 81


@pytest.mark.slow
def test_a_record_path_that_is_not_a_bag_is_said_so(tmp_path):
    (tmp_path / "notes.txt").write_text("mine")
    node = start("node", record=str(tmp_path))
    output = finish(node, 60)
    assert node.returncode == 2 and "is a directory that is not a bag (no metadata.yaml)" in output, output
    assert "Traceback" not in output and (tmp_path / "notes.txt").read_text() == "mine"


def test_a_parameter_file_that_does_not_parse(tmp_path):
    broken = tmp_path / "params.yaml"
    broken.write_text("fowt_hydro_sim:\n  ros__parameters: {dt_s: [0.05\n")
    done = subprocess.run([sys.executable, "-m", "fowt_hydro_sim.cli", "node", "--ros-args", "--params-file",
                           str(broken)], capture_output=True, text=True, timeout=60)
    output = done.stdout + done.stderr
    assert done.returncode == 2 and "fowt-sim node:" in output and "Traceback" not in output, output


def test_a_platform_file_that_does_not_parse(tmp_path):
    broken = tmp_path / "broken_platform.yaml"
    broken.write_text("name: broken\nmembers: [\n")
    node = start("node", platform=str(broken))
    output = finish(node, 60)
    assert node.returncode == 2 and "broken_platform.yaml:" in output and "not valid YAML" in output, output
    assert "Traceback" not in output


def test_a_users_own_domain_id():
    """Without ROS_DOMAIN_ID: the user's own id (1..101, different for different users),
    discovery on this host unless set; an explicit ROS_DOMAIN_ID is kept as it is."""
    from fowt_hydro_sim.ros.startup import domain_id_of, own_domain

    ids = [domain_id_of(uid) for uid in range(1000, 1101)]
    assert len(set(ids)) == 101 and min(ids) == 1 and max(ids) == 101 and domain_id_of(0) != domain_id_of(1000)
    environ: dict[str, str] = {}
    own_domain(environ)
    assert environ == {"ROS_DOMAIN_ID": str(domain_id_of(os.getuid())), "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST"}
    environ = {"ROS_AUTOMATIC_DISCOVERY_RANGE": "SUBNET"}
    own_domain(environ)
    assert environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] == "SUBNET" and environ["ROS_DOMAIN_ID"]
    environ = {"ROS_DOMAIN_ID": "7"}
    own_domain(environ)
    assert environ == {"ROS_DOMAIN_ID": "7"}


@pytest.mark.slow
def test_commands_without_a_domain_id_see_each_other(tmp_path):
    """fowt-sim record and fowt-sim node started without ROS_DOMAIN_ID: both pick the user's own
    domain, and the recording holds the node's poses. (The discovery range stays LOCALHOST: a
    test sends nothing off this host; its default is the unit test's.)"""
    from fowt_hydro_sim.ros.startup import domain_id_of
    from fowt_hydro_sim.rosbag.reader import Bag

    env = {k: v for k, v in os.environ.items() if k != "ROS_DOMAIN_ID"}
    bag = tmp_path / "run"
    record = subprocess.Popen([sys.executable, "-m", "fowt_hydro_sim.cli", "record", "-o", str(bag), "--topics",
                               topics.POSE], env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    node = subprocess.Popen(command_line("node", duration_s=5.0, real_time_factor=0.0, drag_model="constant",
                                         wait_for_subscribers=1), env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)
    try:
        node_output = finish(node, 120)
        time.sleep(1.0)
    finally:
        record.send_signal(signal.SIGINT)
        record_output = finish(record, 30)
    said = f"ROS_DOMAIN_ID not set: using {domain_id_of(os.getuid())}"
    assert said in node_output and said in record_output, node_output + record_output
    assert "duration 5 s reached" in node_output and node.returncode == 0, node_output
    assert Bag(bag).topics[topics.POSE].message_count == 101, record_output


@pytest.mark.slow
def test_a_lost_controller_cuts_the_run_short_with_exit_code_1(tmp_path):
    """Lockstep, controller_lost stop: the controller killed mid-run stops the stepping before
    duration_s; the node exits 1 and its bag is closed readable."""
    from fowt_hydro_sim.rosbag.reader import Bag

    listener = Listener({"/platform/pose": PoseStamped})
    controller = start("controller", mean_thrust_n=1.0e6)
    bag = tmp_path / "run"
    node = start("node", duration_s=600.0, real_time_factor=5.0, lockstep=True, drag_model="constant",
                 record=str(bag), lockstep_timeout_s=1.0)
    try:
        listener.wait_for(lambda: len(listener.messages["/platform/pose"]) > 100, 120.0)
        controller.kill()
        finish(controller, 10)
        listener.wait_for(lambda: node.poll() is not None, 60.0)
        output = finish(node, 10)
    finally:
        listener.close()
    assert _log_after(output, "lockstep: the controller is gone"), output
    assert node.returncode == 1 and _log_after(output, "the run is incomplete: the controller was lost"), output
    poses = Bag(bag).topics[topics.POSE].message_count
    assert 100 < poses < 0.5 * 12001, poses


def _play(bag, *args: str) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-m", "fowt_hydro_sim.cli", "play", str(bag), *args],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


def _wave_bag(path, duration_s: float):
    done = subprocess.run([sys.executable, "-m", "fowt_hydro_sim.cli", "waves", "--duration", str(duration_s),
                           "-o", str(path)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return path


def _elevation_used(bag) -> tuple[np.ndarray, np.ndarray]:
    from fowt_hydro_sim.rosbag.reader import Bag
    from msg_adapters import cdr

    times, values = cdr.decode_stamped(topics.POINT_STAMPED, [data for _, _, data in
                                                              Bag(bag).messages([topics.ELEVATION_USED[0]])])
    return times, values[:, 2]


@pytest.mark.slow
def test_a_wave_bag_played_as_fast_as_possible_drives_the_whole_run(tmp_path):
    """fowt-sim play --rate 0 of a 400 s wave bag into a node stepping 300 s as fast as possible
    on the topic's waves (needing samples up to 360 s: the kinematics lag them by 60 s): the
    player waits for the node (flow control) instead of losing samples, the node for the
    player; the elevation the node used is the sea's over the whole run, no still-water tail,
    and both exit 0."""
    waves = _wave_bag(tmp_path / "waves", 400.0)
    record = tmp_path / "run"
    player = _play(waves, "--rate", "0", "--wait-for-subscribers", "1")
    node = start("node", wave_source="topic", real_time_factor=0.0, duration_s=300.0, drag_model="constant",
                 record=str(record))
    node_output = finish(node, 600)
    player_output = finish(player, 120)
    assert node.returncode == 0 and "duration 300 s reached" in node_output, node_output
    assert "still water" not in node_output, node_output
    assert player.returncode == 0 and "dropped" not in player_output, player_output
    times, elevation = _elevation_used(record)
    assert times[-1] == pytest.approx(300.0) and len(times) == 6001
    for start_s in range(120, 300, 30):  # every 30 s past the stream's warm-up has its waves
        window = (times >= start_s) & (times < start_s + 30)
        assert elevation[window].std() > 0.5, (start_s, elevation[window].std())


@pytest.mark.slow
def test_a_wave_topic_silent_before_the_end_is_said_and_exits_1(tmp_path):
    """The player's 100 s of waves end long before the node's 300 s (as fast as possible): once
    the player has gone, the node says in one line that the topic went silent after samples up
    to 100 s, goes on in still water, and exits 1 (the run is incomplete)."""
    waves = _wave_bag(tmp_path / "waves", 100.0)
    player = _play(waves, "--rate", "0", "--wait-for-subscribers", "1")
    node = start("node", wave_source="topic", real_time_factor=0.0, duration_s=300.0, drag_model="constant")
    node_output = finish(node, 600)
    player_output = finish(player, 120)
    assert player.returncode == 0, player_output
    assert "went silent after samples up to t = 100.00 s" in node_output, node_output
    assert node.returncode == 1 and "duration 300 s reached" in node_output, node_output
    silent = [line for line in node_output.splitlines() if "no wave elevation on /waves/elevation" in line]
    assert len(silent) == 1 and "ERROR" in silent[0], node_output
