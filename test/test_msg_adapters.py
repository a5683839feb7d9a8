"""msg_adapters: ROS message conversions and the Euler/quaternion pair in rigid_body.

Oracles: Hamilton products written here, scipy's Rotation, integer nanosecond arithmetic
and exact Fraction rounding for stamps, and a hand-worked yawed-body odometry case.
"""
from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import msg_adapters as ma
from fowt_hydro_sim.frames import euler_from_quaternion, quaternion_from_euler, rotation_matrix

RNG = np.random.default_rng(20240611)


def random_motion() -> np.ndarray:
    return np.concatenate([RNG.uniform(-30.0, 30.0, 3), RNG.uniform(-3.1, 3.1, 1),
                           RNG.uniform(-1.4, 1.4, 1), RNG.uniform(-3.1, 3.1, 1)])


def hamilton(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Quaternion product, (x, y, z, w) storage."""
    (ax, ay, az, aw), (bx, by, bz, bw) = a, b
    return np.array([aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz])


@pytest.mark.parametrize("trial", range(50))
def test_quaternion_rotates_like_rotation_matrix_and_matches_scipy(trial):
    roll, pitch, yaw = random_motion()[3:]
    q = quaternion_from_euler(roll, pitch, yaw)
    assert q[3] >= 0.0 and np.linalg.norm(q) == pytest.approx(1.0, abs=1e-15)
    v = RNG.normal(size=3)
    rotated = hamilton(hamilton(q, np.append(v, 0.0)), q * [-1, -1, -1, 1])
    np.testing.assert_allclose(rotated[:3], rotation_matrix(roll, pitch, yaw) @ v, atol=1e-13)
    ref = Rotation.from_euler("ZYX", [yaw, pitch, roll]).as_quat()
    np.testing.assert_allclose(q * np.sign(q @ ref), ref, atol=1e-14)
    np.testing.assert_allclose(euler_from_quaternion(-3.7 * q), [roll, pitch, yaw], atol=1e-12)


@pytest.mark.parametrize("bad, problem", [([0, 0, 0, 0], "zero"), ([np.nan, 0, 0, 1], "non-finite"),
                                          ([0, 0, np.inf, 1], "non-finite"), ([0, 0, 1], "shape")])
def test_euler_from_bad_quaternion_raises(bad, problem):
    with pytest.raises(ValueError, match=problem):
        euler_from_quaternion(bad)


@pytest.mark.parametrize("t", [0.0, 0.05 * 10**7, 0.05 * (10**7 + 7), 1e9 + 0.123456789, 12.3456789012])
@pytest.mark.ros
def test_stamp_is_nearest_nanosecond_and_round_trips(t):
    ns = round(Fraction(t) * 10**9)
    msg = ma.stamp(t)
    assert (msg.sec, msg.nanosec) == (ns // 10**9, ns % 10**9)
    back = ma.seconds(msg)
    assert abs(Fraction(back) - Fraction(ns, 10**9)) <= Fraction(1, 2 * 10**9)
    assert ma.stamp(back) == msg
    assert ma.clock_msg(t).clock == msg


@pytest.mark.ros
def test_stamps_of_fixed_steps_at_large_step_counts():
    for n in range(10**7, 10**7 + 2000):
        msg = ma.stamp(0.05 * n)
        assert (msg.sec, msg.nanosec) == (n // 20, (n % 20) * 50_000_000)
    assert ma.seconds(ma.stamp(1e9 + 0.123456789)) == 1e9 + 0.123456789


@pytest.mark.parametrize("t", [-1e-12, -0.05, float("nan")])
@pytest.mark.ros
def test_negative_or_nan_time_raises(t):
    with pytest.raises(ValueError, match="time"):
        ma.stamp(t)


def test_stamps_of_a_batch_are_each_times_own():
    """The vectorised stamps (a batch's messages) against the one-message rounding, at fixed
    steps, large, random and near-tie times, and against exact Fraction rounding at the
    fixed steps; bad times raise."""
    from msg_adapters import cdr
    from msg_adapters.sim_time import nanoseconds, nanoseconds_array

    steps = 0.05 * np.arange(10**7, 10**7 + 500)
    times = np.concatenate([steps, [0.0, 1e9 + 0.123456789, 12.3456789012], RNG.uniform(0, 1e6, 500),
                            np.arange(40) * 1e-9 + 0.5e-9])
    expected = [nanoseconds(t) for t in times.tolist()]
    assert nanoseconds_array(times).tolist() == expected
    assert expected[:len(steps)] == [round(Fraction(t) * 10**9) for t in steps.tolist()]
    raw = cdr.stamps(times).copy().view([("sec", "<i4"), ("nanosec", "<u4")])[:, 0]
    assert raw["sec"].tolist() == [ns // 10**9 for ns in expected]
    assert raw["nanosec"].tolist() == [ns % 10**9 for ns in expected]
    for bad in (-0.05, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="time"):
            nanoseconds_array(np.array([1.0, bad]))


@pytest.mark.parametrize("trial", range(20))
@pytest.mark.ros
def test_round_trips(trial):
    t = RNG.uniform(0.0, 1e4)
    motion, velocity, acc, wrench = random_motion(), RNG.normal(size=6), RNG.normal(size=6), 1e6 * RNG.normal(size=6)
    pose = ma.pose_msg(t, motion)
    t_back, m_back = ma.motion_from_pose(pose)
    assert abs(t_back - t) <= 5e-10 and pose.header.frame_id == "world"
    np.testing.assert_allclose(m_back, motion, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(ma.velocity_from_twist(ma.twist_msg(t, velocity))[1], velocity)
    np.testing.assert_array_equal(ma.acceleration_from_accel(ma.accel_msg(t, acc))[1], acc)
    t_w, w_back, frame = ma.wrench_from_msg(ma.wrench_msg(t, wrench, frame_id="platform"))
    np.testing.assert_array_equal(w_back, wrench)
    assert frame == "platform" and t_w == ma.seconds(ma.stamp(t))
    t_o, m_o, v_o = ma.state_from_odometry(ma.odometry_msg(t, motion, velocity))
    np.testing.assert_allclose(m_o, motion, rtol=0, atol=1e-12)
    np.testing.assert_allclose(v_o, velocity, rtol=0, atol=1e-12)
    x, y, eta = RNG.normal(size=3)
    assert ma.elevation_from_msg(ma.elevation_msg(t, x, y, eta, "sea")) == (t_o, x, y, eta, "sea")


@pytest.mark.ros
def test_odometry_twist_is_in_body_axes():
    # Body x axis points along world +y after +90 deg yaw; world +x is then body -y.
    motion = np.array([1.0, 2.0, -3.0, 0.0, 0.0, np.pi / 2])
    msg = ma.odometry_msg(5.0, motion, [2.0, 0.0, 0.0, 0.0, 0.0, 0.3], child_frame_id="hull")
    assert msg.child_frame_id == "hull"
    lin, ang = msg.twist.twist.linear, msg.twist.twist.angular
    np.testing.assert_allclose([lin.x, lin.y, lin.z], [0.0, -2.0, 0.0], atol=1e-15)
    np.testing.assert_allclose([ang.x, ang.y, ang.z], [0.0, 0.0, 0.3], atol=1e-15)
    # Pitched by p: world +z in body axes is the third row of Ry(p), (-sin p, 0, cos p).
    pitch = 0.5
    msg = ma.odometry_msg(5.0, [0, 0, 0, 0, pitch, 0], [0, 0, 1.0, 0, 0, 0])
    lin = msg.twist.twist.linear
    np.testing.assert_allclose([lin.x, lin.y, lin.z], [-np.sin(pitch), 0.0, np.cos(pitch)], atol=1e-15)
    assert (msg.header.frame_id, msg.child_frame_id) == ("world", "platform")
    assert not msg.pose.covariance.any() and not msg.twist.covariance.any()
    o = msg.pose.pose.orientation
    np.testing.assert_allclose([o.x, o.y, o.z, o.w], [0, np.sin(pitch / 2), 0, np.cos(pitch / 2)], atol=1e-15)


@pytest.mark.ros
@pytest.mark.parametrize("call, name", [
    (lambda: ma.pose_msg(0.0, np.zeros(5)), r"motion must have shape \(6,\)"),
    (lambda: ma.twist_msg(0.0, np.zeros((6, 1))), r"velocity must have shape \(6,\)"),
    (lambda: ma.accel_msg(0.0, np.zeros(7)), r"acceleration must have shape \(6,\)"),
    (lambda: ma.wrench_msg(0.0, [1.0, 2.0]), r"wrench must have shape \(6,\)"),
    (lambda: ma.odometry_msg(0.0, np.zeros(6), np.zeros(3)), r"velocity must have shape \(6,\)"),
    (lambda: ma.odometry_msg(0.0, np.zeros(3), np.zeros(6)), r"motion must have shape \(6,\)"),
])
def test_wrong_shapes_raise_naming_the_argument(call, name):
    with pytest.raises(ValueError, match=name):
        call()


@pytest.mark.ros
def test_non_finite_values_pass_through():
    _, w = ma.velocity_from_twist(ma.twist_msg(1.0, [np.nan, np.inf, 0, 0, 0, 0]))
    assert np.isnan(w[0]) and np.isinf(w[1])


# --------------------------------------------------------------------------- CDR bytes
@pytest.mark.ros
def test_cdr_bytes_are_rclpys_serialisation():
    """Oracle: rclpy's own (de)serialisation. Our bytes deserialise to the message the adapters
    build, and have the length of serialize_message's output (which differs only in the
    padding bytes, left uninitialised there), for random states, times and frame ids of
    several lengths (alignment)."""
    from geometry_msgs.msg import AccelStamped, PointStamped, PoseStamped, TwistStamped, WrenchStamped
    from nav_msgs.msg import Odometry
    from rclpy.serialization import deserialize_message, serialize_message
    from rosgraph_msgs.msg import Clock

    from msg_adapters import cdr

    rng = np.random.default_rng(7)
    for frame, child in (("world", "platform"), ("w", "p1"), ("a_longer_world_frame", "hub")):
        t = float(rng.uniform(0, 1e5))
        motion = np.concatenate([rng.normal(0, 5, 3), rng.uniform(-1.2, 1.2, 3)])
        velocity, values = rng.normal(0, 1, 6), rng.normal(0, 1e6, 6)
        cases = [(cdr.clock(t), ma.clock_msg(t), Clock),
                 (cdr.pose(t, motion, frame), ma.pose_msg(t, motion, frame), PoseStamped),
                 (cdr.six(t, velocity, frame), ma.twist_msg(t, velocity, frame), TwistStamped),
                 (cdr.six(t, values, frame), ma.accel_msg(t, values, frame), AccelStamped),
                 (cdr.six(t, values, frame), ma.wrench_msg(t, values, frame), WrenchStamped),
                 (cdr.point(t, 1.5, -2.0, 0.3, frame), ma.elevation_msg(t, 1.5, -2.0, 0.3, frame), PointStamped),
                 (cdr.odometry(t, motion, velocity, frame, child),
                  ma.odometry_msg(t, motion, velocity, frame, child), Odometry)]
        for data, message, kind in cases:
            assert deserialize_message(data, kind) == message, kind
            assert len(data) == len(serialize_message(message)), kind


def test_a_batch_of_outputs_is_each_messages_own_serialisation():
    """cdr.outputs (vectorised over a batch) against the one-message functions, topic by
    topic in the contract's order, one load topic per published component."""
    from fowt_hydro_sim.physics.loads import PUBLISHED
    from msg_adapters import cdr, topics

    rng = np.random.default_rng(3)
    n = 5
    time_s = np.sort(rng.uniform(0, 1e4, n))
    motion = np.hstack([rng.normal(0, 5, (n, 3)), rng.uniform(-1.2, 1.2, (n, 3))])
    velocity, acceleration = rng.normal(0, 1, (n, 6)), rng.normal(0, 1, (n, 6))
    loads, total, eta = rng.normal(0, 1e6, (n, len(PUBLISHED), 6)), rng.normal(0, 1e6, (n, 6)), rng.normal(0, 2, n)
    for frame, child in (("world", "platform"), ("w", "p1"), ("a_longer_world_frame", "hub")):  # alignments
        batch = cdr.outputs(time_s, motion, velocity, acceleration, loads, total, eta, frame, child)
        assert [len(row) for row in batch] == [len(topics.outputs(PUBLISHED))] * n
        for i, row in enumerate(batch):
            t = float(time_s[i])
            expected = [cdr.clock(t), cdr.odometry(t, motion[i], velocity[i], frame, child),
                        cdr.pose(t, motion[i], frame), cdr.six(t, velocity[i], frame),
                        cdr.six(t, acceleration[i], frame), cdr.six(t, total[i], frame),
                        *(cdr.six(t, loads[i, k], frame) for k in range(len(PUBLISHED))),
                        cdr.point(t, 0.0, 0.0, eta[i], frame)]
            assert row == expected
