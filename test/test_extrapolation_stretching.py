"""Extrapolation stretching (SeaState's WaveStMod 2): above z = 0 the kinematics are those at
z = 0 plus z times their vertical gradient there. Checked against the closed form of one Airy
component (C'(0)/C(0) = k tanh kh for the horizontal channels and the pressure, S'(0)/S(0) =
k coth kh for the vertical ones) and, end to end, against vertical stretching where the
surface is below z = 0 (the two then agree) and above it (they differ by the extrapolated
part)."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from fowt_hydro_sim.physics.config import HYDRODYN, ConfigError, load_platform
from fowt_hydro_sim.physics.loads import ROW
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import WaveComponents, wavenumber
from fowt_hydro_sim.physics.waves.kinematics import extrapolated_kinematics, moving_point_kinematics

RHO, G, DEPTH = 1025.0, 9.80665, 60.0
WAVE = WaveComponents(np.array([0.1]), np.array([2.0]), np.array([0.4]), np.array([math.radians(30.0)]), 10.0)


def test_extrapolated_kinematics_follow_the_airy_gradient_at_the_surface():
    k = float(wavenumber(2 * np.pi * WAVE.frequency_hz, DEPTH, G)[0])
    horizontal, vertical = k * math.tanh(k * DEPTH), k / math.tanh(k * DEPTH)
    t = np.linspace(0.0, 10.0, 7)
    for height in (0.5, 1.7):
        points = np.tile([3.0, -2.0, height], (t.size, 1))
        surface = moving_point_kinematics(WAVE, points * [1, 1, 0], t, DEPTH, G, RHO)
        got = extrapolated_kinematics(WAVE, points, t, DEPTH, G, RHO)
        factor = 1.0 + height * np.array([horizontal, horizontal, vertical, horizontal, horizontal, vertical,
                                          horizontal])
        assert np.allclose(got, surface * factor, rtol=1e-5, atol=1e-5 * np.abs(surface).max(axis=0))
    below = np.tile([3.0, -2.0, -4.0], (t.size, 1))
    assert np.array_equal(extrapolated_kinematics(WAVE, below, t, DEPTH, G, RHO),
                          moving_point_kinematics(WAVE, below, t, DEPTH, G, RHO))


@pytest.mark.slow
def test_extrapolation_equals_vertical_stretching_under_a_trough_and_adds_under_a_crest():
    """windmoor12's first column alone at rest, kinematics summed at each time for both (the
    displaced points, at rest the undisplaced ones): the Morison loads with extrapolation and
    with vertical stretching are equal when the surface over it is below z = 0 (within 1e-4: the
    strips above z = 0 keep their own points for the extrapolation, which moves the point of the
    strip through z = 0) and differ above."""
    platform = load_platform("windmoor12")
    platform = dataclasses.replace(platform, members=platform.members[:1])
    t = np.arange(0.0, 10.0, 0.5)
    rest = np.zeros((t.size, 6))
    loads = {mode: PlatformModel(platform, WAVE, options=dataclasses.replace(
        HYDRODYN, stretching=mode, kinematics="displaced"))
             .prescribed_motion_loads(t, rest, rest, rest)[:, ROW["inertia"]] for mode in ("vertical", "extrapolation")}
    centre = np.array(platform.members[0].end_a_m[:2])
    eta = WAVE.elevation(centre[0], centre[1], t, platform.environment.water_depth_m, G)
    trough, crest = eta < -0.05, eta > 0.05
    assert trough.any() and crest.any()
    scale = np.abs(loads["vertical"][:, 0:2]).max()
    for part in (slice(0, 3), slice(3, 6)):  # forces, moments
        part_scale = np.abs(loads["vertical"][:, part]).max()
        assert np.allclose(loads["extrapolation"][trough, part], loads["vertical"][trough, part], rtol=0,
                           atol=1e-4 * part_scale)
    assert np.all(np.abs(loads["extrapolation"][crest, 0:2] - loads["vertical"][crest, 0:2]).max(axis=1) > 1e-6 * scale)


def test_extrapolation_stretching_is_refused_for_time_stepping():
    with pytest.raises(ConfigError, match="stretching"):
        PlatformModel(load_platform("windmoor12"), WAVE, options=dataclasses.replace(HYDRODYN,
                                                                                        stretching="extrapolation")).run(1.0)
