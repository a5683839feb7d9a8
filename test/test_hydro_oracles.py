"""Closed-form oracles for the moving-body hydro options and the slow-drift component:
a pitched column's inertia loads in a regular wave (rotating vs fixed directions), the mean
surge force the displaced wetted length adds to a heaving column in a regular wave, and
Newman's slow drift from the platform's drift table."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from fowt_hydro_sim.physics.config import HydroOptions, load_platform
from fowt_hydro_sim.physics.loads import ROW, drift
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.platform_edits import uniform_drag
from fowt_hydro_sim.physics.waves.components import WaveComponents, wavenumber

RHO = 1025.0
DRAFT_M, RADIUS_M = 15.5, 7.5
AMPLITUDE_M, PERIOD_S = 1.0, 10.0


def _column():
    """windmoor12's first column moved to the origin, no drag, no keel plate (Ca 1)."""
    p = load_platform("windmoor12")
    column = dataclasses.replace(uniform_drag(p.members[0], 0.0, 0.0), end_a_m=(0.0, 0.0, -DRAFT_M),
                                 end_b_m=(0.0, 0.0, 15.0), end_a_plate=None)
    return dataclasses.replace(p, members=(column,))


def _regular_wave() -> WaveComponents:
    return WaveComponents(np.array([1.0 / PERIOD_S]), np.array([AMPLITUDE_M]), np.zeros(1), np.zeros(1), PERIOD_S)


def _depth_integrals(t_s, depth_m: float, g: float):
    """int_{-d}^{0} (a_x, a_z) dz, analytically."""
    omega = 2 * math.pi / PERIOD_S
    k = float(wavenumber(np.array([omega]), depth_m, g)[0])
    scale = AMPLITUDE_M * omega**2 / math.sinh(k * depth_m) / k
    ix = -scale * (math.sinh(k * depth_m) - math.sinh(k * (depth_m - DRAFT_M))) * np.sin(omega * t_s)
    iz = -scale * (math.cosh(k * depth_m) - math.cosh(k * (depth_m - DRAFT_M))) * np.cos(omega * t_s)
    return ix, iz


@pytest.mark.slow
@pytest.mark.parametrize("directions", ["rotating", "fixed"])
def test_pitched_column_inertia_in_a_regular_wave_is_the_rotated_normal_projection(directions):
    """A column pitched by th about its water-line centre, kinematics and wetted length
    undisplaced: each strip's inertia force is rho (1 + Ca) A times the fluid acceleration's
    part normal to the axis e = (sin th, 0, cos th) with rotating directions, normal to the
    undisplaced (vertical) axis with fixed ones; summed over the draft,
    F = rho (1 + Ca) A (I - e e^T) int a dz."""
    platform = _column()
    env = platform.environment
    pitch = 0.2
    t = np.linspace(0.0, PERIOD_S, 9)[:-1]
    pose = np.zeros((t.size, 6))
    pose[:, 4] = pitch
    still = np.zeros((t.size, 6))
    options = HydroOptions(wetted_length="undisplaced", load_directions=directions, hydrostatics="linear",
                           slow_drift="none")
    model = PlatformModel(platform, _regular_wave(), options=options)
    loads = model.prescribed_motion_loads(t, pose, still, still)[:, ROW["inertia"], :3]
    ix, iz = _depth_integrals(t, env.water_depth_m, env.gravity_m_s2)
    integral = np.stack([ix, np.zeros_like(ix), iz], axis=1)
    axis = np.array([math.sin(pitch), 0.0, math.cos(pitch)]) if directions == "rotating" else np.array([0.0, 0.0, 1.0])
    expected = RHO * 2.0 * math.pi * RADIUS_M**2 * (integral - np.outer(integral @ axis, axis))
    scale = np.max(np.abs(expected))
    assert np.max(np.abs(loads - expected)) < 2e-3 * scale
    if directions == "rotating":  # the rotation is visible: a vertical force of order th F_x
        assert np.max(np.abs(expected[:, 2])) > 0.1 * scale


def test_displaced_wetted_length_adds_a_mean_surge_force_in_a_regular_wave():
    """A column lifted by z(t) = z0 + Z cos(w t + b) (0 < z < the top strip) in a regular wave,
    no surge, displaced wetted length, fixed directions: only the top strip's wetted length
    changes, by -z, so the mean surge force is -rho (1 + Ca) A <z(t) a_x(z_c, t)>
    = -rho (1 + Ca) A Z A w^2 cosh k(z_c + h) / sinh kh sin(b) / 2 at its centre z_c."""
    platform = _column()
    env = platform.environment
    omega = 2 * math.pi / PERIOD_S
    lift, heave, phase = 0.45, 0.3, 1.1
    t = np.arange(0.0, 4 * PERIOD_S, PERIOD_S / 64)
    motion, velocity, acceleration = (np.zeros((t.size, 6)) for _ in range(3))
    motion[:, 2] = lift + heave * np.cos(omega * t + phase)
    velocity[:, 2] = -heave * omega * np.sin(omega * t + phase)
    acceleration[:, 2] = -heave * omega**2 * np.cos(omega * t + phase)
    means = {}
    for wetted in ("displaced", "undisplaced"):
        model = PlatformModel(platform, _regular_wave(), options=HydroOptions(
            wetted_length=wetted, load_directions="fixed", hydrostatics="linear", slow_drift="none"))
        loads = model.prescribed_motion_loads(t, motion, velocity, acceleration)
        means[wetted] = loads[:, ROW["inertia"], 0].mean()
    strips = model.geometry.strips
    top = int(np.argmax(np.where(strips.centre_m[:, 2] < 0, strips.centre_m[:, 2], -np.inf)))  # highest submerged
    z_c = float(strips.centre_m[top, 2])
    assert 0 < lift + heave < strips.length_m[top] and z_c < 0
    k = float(wavenumber(np.array([omega]), env.water_depth_m, env.gravity_m_s2)[0])
    a_x_amplitude = AMPLITUDE_M * omega**2 * math.cosh(k * (z_c + env.water_depth_m)) / math.sinh(k * env.water_depth_m)
    expected = -RHO * 2.0 * math.pi * RADIUS_M**2 * heave * a_x_amplitude * math.sin(phase) / 2
    assert means["displaced"] == pytest.approx(expected, rel=0.01)
    assert abs(means["undisplaced"]) < 1e-3 * abs(expected)


def test_newman_force_of_a_bichromatic_sea():
    """F(t) = a1^2 D1 + a2^2 D2 + 2 a1 a2 sqrt(D1 D2) cos((w2 - w1) t + p2 - p1)."""
    table = ((0.5, 1.0e4), (1.0, 9.0e4))
    period = 200.0
    waves = WaveComponents(np.array([20 / period, 28 / period]), np.array([1.5, 0.8]), np.array([0.3, 2.0]),
                           np.zeros(2), period)
    samples, step = drift.newman_force(waves, table)
    t = np.arange(samples.shape[0]) * step
    w = 2 * np.pi * waves.frequency_hz
    d = np.interp(w, [0.0, 0.5, 1.0], [0.0, 1.0e4, 9.0e4])
    a = waves.amplitude_m
    expected = (a[0]**2 * d[0] + a[1]**2 * d[1]
                + 2 * a[0] * a[1] * np.sqrt(d[0] * d[1]) * np.cos((w[1] - w[0]) * t + 2.0 - 0.3))
    assert np.allclose(samples[:, 0], expected, rtol=1e-9, atol=1e-9 * expected.max())
    assert np.allclose(samples[:, 1], 0.0, atol=1e-9 * expected.max())


def test_slow_drift_component_gives_the_mean_drift_of_a_regular_wave():
    """The model's drift row in a regular wave is the constant a^2 D(w) of the platform's table
    (along the heading), and nothing with ``slow_drift: none``."""
    platform = load_platform("windmoor12")
    heading = math.radians(30.0)
    waves = dataclasses.replace(_regular_wave(), direction_rad=np.array([heading]))
    t = np.linspace(0.0, PERIOD_S, 7)
    still = np.zeros((t.size, 6))
    d = drift.coefficients(platform.drift_coefficients_n_m2, np.array([2 * math.pi / PERIOD_S]))[0]
    assert d > 0
    for slow_drift, expected in (("newman", AMPLITUDE_M**2 * d), ("none", 0.0)):
        options = HydroOptions(wetted_length="undisplaced", load_directions="fixed", hydrostatics="linear",
                               slow_drift=slow_drift)
        loads = PlatformModel(platform, waves, options=options).prescribed_motion_loads(t, still, still, still)
        row = loads[:, ROW["drift"]]
        assert np.allclose(row[:, 0], expected * math.cos(heading), rtol=1e-9, atol=1e-6)
        assert np.allclose(row[:, 1], expected * math.sin(heading), rtol=1e-9, atol=1e-6)
        assert np.allclose(row[:, 2:], 0.0)


def _rotation(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """Rz Ry Rx, written here with numpy (not the kernel's)."""
    cx, sx, cy, sy, cz, sz = (math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch), math.cos(yaw),
                              math.sin(yaw))
    return (np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]]) @ np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
            @ np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]]))


@pytest.mark.parametrize("angles", [(0.0, 0.0, 0.0), (0.05, -0.12, 0.3), (-0.2, 0.15, -1.1)])
def test_deep_strips_added_mass_from_moments_is_the_sum_of_each_strips_rigid_transfer(angles):
    """Fixed directions: the deep strips' 6x6 added mass about the reference point, made from
    precomputed moments at any attitude, equals sum L J^T A J with J = [I, -skew(R c)] built
    strip by strip with numpy."""
    from fowt_hydro_sim.physics.morison import added_mass_moments, added_mass_tensors, deep_added_mass_about
    from fowt_hydro_sim.physics.strips import discretise
    geometry = discretise(load_platform("windmoor12"))
    s = geometry.strips
    mass_3x3, _ = added_mass_tensors(geometry)
    deep = s.centre_m[:, 2] + 0.5 * s.length_m * np.abs(s.axis[:, 2]) < 0.0
    rotation = _rotation(*angles)
    expected = np.zeros((6, 6))
    for centre, a, length in zip(s.centre_m[deep], mass_3x3[deep], s.length_m[deep]):
        r = rotation @ centre
        jacobian = np.hstack([np.eye(3), -np.array([[0, -r[2], r[1]], [r[2], 0, -r[0]], [-r[1], r[0], 0]])])
        expected += length * jacobian.T @ a @ jacobian
    got = deep_added_mass_about(rotation, added_mass_moments(s.centre_m, mass_3x3, s.length_m * deep))
    assert deep.sum() > 100
    assert np.allclose(got, expected, rtol=0, atol=1e-12 * np.abs(expected).max())


@pytest.mark.parametrize("angles", [(0.0, 0.0, 0.0), (0.05, -0.12, 0.3), (-0.2, 0.15, -1.1)])
def test_centripetal_added_mass_wrench_from_moments_is_the_sum_over_strips(angles):
    """The centripetal added-mass wrench of strips wetted as at rest, made from the same
    moments as their 6x6 added mass, equals -sum L A w x (w x r) and its moment r x f about
    the reference point, summed strip by strip with numpy at lever arms r = R c (fixed
    directions) for an angular velocity with all three components."""
    from fowt_hydro_sim.physics.morison import (
        added_mass_moments,
        added_mass_tensors,
        centripetal_from_moments,
        rotated_moments,
        wetted_fractions,
    )
    from fowt_hydro_sim.physics.strips import discretise
    geometry = discretise(load_platform("windmoor12"))
    s = geometry.strips
    mass_3x3, _ = added_mass_tensors(geometry)
    wet = np.empty(len(s.length_m))
    wetted_fractions(np.eye(3), 0.0, s.centre_m, s.axis, s.length_m, np.zeros(wet.size), wet)
    rotation, omega = _rotation(*angles), np.array([0.03, -0.05, 0.02])
    expected = np.zeros(6)
    for centre, a, wet_length in zip(s.centre_m, mass_3x3, s.length_m * wet):
        r = rotation @ centre
        force = -wet_length * a @ np.cross(omega, np.cross(omega, r))
        expected += np.concatenate([force, np.cross(r, force)])
    first, half, second, got = np.empty((3, 3, 3)), np.empty((3, 3, 3, 3)), np.empty((3, 3, 3, 3)), np.empty(6)
    rotated_moments(rotation, added_mass_moments(s.centre_m, mass_3x3, s.length_m * wet), first, half, second)
    centripetal_from_moments(first, second, tuple(omega), got)
    assert np.allclose(got, expected, rtol=0, atol=1e-12 * np.abs(expected).max())


@pytest.mark.parametrize("pitch_rad, heave_m", [(0.1, 0.0), (-0.25, 2.0), (0.35, -3.0)])
def test_nonlinear_hydrostatics_of_an_obliquely_cut_column_is_the_closed_form(pitch_rad, heave_m):
    """A column pitched about the origin, the water plane through its side wall only: the
    submerged volume is the section area times the axis's submerged length, and the centroid
    (body frame) is on the axis at half that length plus tan^2(pitch) r^2 / (4 h) along the
    axis and tan(pitch) r^2 / (4 h) across it, toward the side the pitch lowers (the wedge's
    shift). The member-wise rule
    (whole members, coarse lines for a side-wall cut) gives them to round-off, as does the
    fine quadrature."""
    from fowt_hydro_sim.physics.loads.hydrostatic import member_records, members_submerged_volume
    platform = _column()
    rotation = _rotation(0.0, pitch_rad, 0.0)
    records, lines = member_records(platform)
    volume, moment = members_submerged_volume(rotation, heave_m, records, lines)
    # the axis from (0, 0, -draft): world z = heave + cos(pitch) (s - draft); wet below 0
    wet_length = DRAFT_M - heave_m / math.cos(pitch_rad)
    area = math.pi * RADIUS_M**2
    tan = math.tan(pitch_rad)
    centre_z = -DRAFT_M + wet_length / 2 + tan**2 * RADIUS_M**2 / (8 * wet_length)
    centre_x = tan * RADIUS_M**2 / (4 * wet_length)  # positive pitch lowers +x (R = Ry)
    assert volume == pytest.approx(area * wet_length, rel=1e-12)
    assert moment / volume == pytest.approx([centre_x, 0.0, centre_z], rel=1e-10, abs=1e-10)
