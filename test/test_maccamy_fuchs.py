"""The MacCamy-Fuchs correction (``physics/waves/maccamy_fuchs.py``, SeaState's MCFD with
HydroDyn's Cp MCF) against closed forms: the textbook MacCamy-Fuchs force amplitude on a
vertical cylinder standing on the seabed in a regular wave, |F| = 4 rho g (H/2) tanh(kh) /
(k^2 |H1'(ka)|), and Morison's Cm = 2 in the slender limit; the kinematics paths (the period
table, its blocks, the moving points of displaced kinematics) agree with each other."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.special import jvp, yvp

from fowt_hydro_sim.physics.config import (
    HYDRODYN,
    ConfigError,
    EndPlate,
    load_platform,
    platform_document,
    platform_from_dict,
)
from fowt_hydro_sim.physics.loads import ROW
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.strips import discretise
from fowt_hydro_sim.physics.waves.components import WaveComponents, wavenumber
from fowt_hydro_sim.physics.waves.kinematics import BlockSynthesis, period_table
from fowt_hydro_sim.physics.waves.maccamy_fuchs import inertia_factor

RHO, G, DEPTH, H, PERIOD = 1025.0, 9.80665, 50.0, 4.0, 8.0


def column(diameter_m: float, maccamy_fuchs: bool = True):
    """A vertical cylinder from the seabed (50 m) to 10 m above the water, Ca = Cp = 1, no drag."""
    p = load_platform("windmoor12")
    zone = dataclasses.replace(p.members[0].zones[0], below_z_m=math.inf, ca=(1.0, 1.0), cp=1.0)
    zone = dataclasses.replace(zone, cd=tuple(dataclasses.replace(c, constant=0.0) for c in zone.cd))
    member = dataclasses.replace(p.members[0], end_a_m=(0.0, 0.0, -DEPTH), end_b_m=(0.0, 0.0, 10.0),
                                 width_m=diameter_m, height_m=diameter_m, diameter_b_m=None,
                                 taper_axial=EndPlate(0.0, 1.0, 0.0), zones=(zone,), strip_length_m=0.25,
                                 end_a_plate=None, end_b_plate=None, maccamy_fuchs=maccamy_fuchs)
    env = dataclasses.replace(p.environment, water_depth_m=DEPTH, water_density_kg_m3=RHO, gravity_m_s2=G)
    return dataclasses.replace(p, members=(member,), environment=env)


def regular_wave() -> WaveComponents:
    return WaveComponents(np.array([1 / PERIOD]), np.array([H / 2]), np.zeros(1), np.zeros(1), PERIOD)


def inertia_fx(platform, kinematics: str = "undisplaced") -> tuple[np.ndarray, np.ndarray]:
    """The inertia load's Fx over one period at rest (20 samples)."""
    t = np.arange(20) * PERIOD / 20
    rest = np.zeros((t.size, 6))
    model = PlatformModel(platform, regular_wave(), options=dataclasses.replace(HYDRODYN, kinematics=kinematics),
                          wave_table_dt_s=PERIOD / 40)
    return t, model.prescribed_motion_loads(t, rest, rest, rest)[:, ROW["inertia"], 0]


def maccamy_fuchs_amplitude(diameter_m: float) -> float:
    k = float(wavenumber(np.array([2 * np.pi / PERIOD]), DEPTH, G)[0])
    ka = k * diameter_m / 2
    return 4 * RHO * G * (H / 2) * math.tanh(k * DEPTH) / (k * k * math.hypot(jvp(1, ka), yvp(1, ka)))


@pytest.mark.parametrize("kinematics", ["undisplaced", "displaced"])
def test_column_carries_the_maccamy_fuchs_force_amplitude(kinematics):
    """D = 20 m (ka = 0.65, C = 1.55): the inertia force's amplitude is the textbook
    MacCamy-Fuchs amplitude within 1e-4 (the strips' midpoint rule), and, as SeaState takes
    the correction's magnitude only, it stays in phase with the incident acceleration at the
    axis, -sin(w t) for a crest at t = 0 (the textbook force leads it by atan(J1'/Y1'))."""
    t, fx = inertia_fx(column(20.0), kinematics)
    amplitude = maccamy_fuchs_amplitude(20.0)
    expected = -amplitude * np.sin(2 * np.pi * t / PERIOD)
    assert np.max(np.abs(fx - expected)) < 1e-4 * amplitude, np.max(np.abs(fx - expected)) / amplitude


def test_slender_column_is_morison_with_cm_2():
    """D = 0.5 m (ka = 0.016): the correction is 2 within 1e-3 (its departure goes as
    (ka)^2 ln ka), and the flagged column carries Morison's inertia with Ca = Cp = 1 times
    C / 2, to round-off."""
    factor = inertia_factor(np.array([2 * np.pi / PERIOD]), 0.5, DEPTH, G)[0]
    assert factor == pytest.approx(2.0, rel=1e-3)
    _, with_mcf = inertia_fx(column(0.5))
    _, morison = inertia_fx(column(0.5, maccamy_fuchs=False))
    assert np.max(np.abs(with_mcf - morison * factor / 2)) < 1e-9 * np.max(np.abs(morison))


def test_blocks_give_the_period_tables_scaled_accelerations():
    """The blocked synthesis scales the same points' accelerations as the period table."""
    geometry = discretise(column(20.0))
    scaled = geometry.maccamy_fuchs_diameter_m
    assert np.count_nonzero(scaled) and set(scaled[scaled > 0]) == {20.0}
    waves = regular_wave()
    rows = 16
    table = period_table(waves, geometry.points_m, rows, DEPTH, G, RHO, np.float64, scaled)
    blocks = BlockSynthesis(waves, geometry.points_m, PERIOD / rows, rows, DEPTH, G, RHO, scaled).rows(0)
    assert np.allclose(blocks, table, rtol=0, atol=1e-9 * np.max(np.abs(table)))
    plain = period_table(waves, geometry.points_m, rows, DEPTH, G, RHO, np.float64)
    assert np.array_equal(table[..., [0, 1, 2, 6]], plain[..., [0, 1, 2, 6]])  # only accelerations change


def test_flag_round_trips_and_is_refused_where_it_has_no_meaning():
    platform = column(20.0)
    document = platform_document(platform)
    assert document["members"][0]["maccamy_fuchs"] is True
    assert platform_from_dict(document, "round trip").members == platform.members
    document["members"][0]["diameter_b_m"] = 18.0
    with pytest.raises(ConfigError, match="maccamy_fuchs: for untapered circular members"):
        platform_from_dict(document, "tapered")
