"""The seed paper's band split on a potential-flow hull's AddBQuad (loads/added_quadratic_bands):
one all-pass band is the plain AddBQuad; two complementary bands with equal matrices dissipate
the plain AddBQuad's energy times sum_b |H_b|^2 cos(arg H_b) (drag_filters.effective_drag_
coefficient), which for a first-order low-/high-pass pair is (1 + x^3) / (1 + x^2)^(3/2), x = w/wc:
0.707 at the cutoff, within 1.4 % of the plain matrix a decade or more from it."""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from fowt_hydro_sim.physics.config import ConfigError, DragBand, load_platform, platform_document, platform_from_dict
from fowt_hydro_sim.physics.drag_filters import bank_state_space, effective_drag_coefficient, frequency_response
from fowt_hydro_sim.physics.loads import ComponentInputs
from fowt_hydro_sim.physics.loads import added_matrices as plain_load
from fowt_hydro_sim.physics.loads import added_quadratic_bands as bands_load
from fowt_hydro_sim.physics.model import PlatformModel

CUTOFF_HZ = 0.05
PAIR = (DragBand("low", "lowpass", 1, cutoff_hz=CUTOFF_HZ), DragBand("high", "highpass", 1, cutoff_hz=CUTOFF_HZ))
ALL = (DragBand("all", "allpass", 0),)


@pytest.fixture(scope="module")
def volturnus():
    return load_platform("volturnus_s")


def banded(platform, bands, matrices, plain=False):
    """The platform with ``bands`` as its drag bands and ``matrices`` as their AddBQuad (the plain
    AddBQuad zeroed unless ``plain``)."""
    flow = platform.potential_flow
    flow = replace(flow, added_quadratic_damping_bands=tuple(tuple(map(tuple, np.asarray(m, float))) for m in matrices),
                   added_quadratic_damping=flow.added_quadratic_damping if plain else ((0.0,) * 6,) * 6)
    return replace(platform, drag_bands=bands, potential_flow=flow)


def wrenches(platform, drag_model: str, time_s: np.ndarray, velocity: np.ndarray) -> np.ndarray:
    """The band-split and the plain component's wrenches summed, evaluated at each time (y's
    velocity part set), as the kernel calls them."""
    inputs = ComponentInputs(platform, None, None, None, None, None, 0.05, drag_model)
    loads = [(m, *m.parameters(inputs)) for m in (bands_load, plain_load)]
    out = np.zeros((time_s.size, 6))
    for n, t in enumerate(time_s):
        y = np.zeros(12)
        y[6:] = velocity[n]
        for module, params, table in loads:
            module.wrench(float(t), y, np.eye(3), params, table, out[n], np.zeros((6, 6)))
    return out


def test_one_allpass_band_is_the_plain_addbquad(volturnus):
    """With the filtered drag model, one all-pass band carrying the deck's AddBQuad gives the plain
    component's AddBQuad loads to round-off, for a velocity in every DOF; with the constant drag
    model the band matrices are not used (the plain AddBQuad acts)."""
    deck = np.array(volturnus.potential_flow.added_quadratic_damping)
    rng = np.random.default_rng(1)
    time_s = np.arange(40) * 0.05
    velocity = rng.normal(0.0, 0.5, (40, 6)) * np.array([1, 1, 1, 0.02, 0.02, 0.02])
    plain = wrenches(volturnus, "filtered", time_s, velocity)
    split = wrenches(banded(volturnus, ALL, [deck]), "filtered", time_s, velocity)
    np.testing.assert_allclose(split, plain, rtol=1e-13, atol=1e-9 * np.abs(plain).max())
    assert np.abs(plain).max() > 1e5
    constant = wrenches(banded(volturnus, ALL, [2 * deck], plain=True), "constant", time_s, velocity)
    np.testing.assert_allclose(constant, plain, rtol=1e-13, atol=1e-9 * np.abs(plain).max())


@pytest.mark.parametrize("ratio", [0.1, 1.0, 10.0])
def test_two_bands_with_equal_matrices_dissipate_the_plain_energy_times_the_filters_factor(volturnus, ratio):
    """A surge velocity cos(w t) at w = ratio * wc: the energy the low- and high-pass bands take per
    cycle, with the deck's AddBQuad in both, is the plain AddBQuad's times sum_b |H_b|^2 cos(arg H_b)
    (closed form (1 + x^3) / (1 + x^2)^(3/2), x = ratio) within 1 % (the Tustin filters on the
    model's 0.05 s step); a decade from the cutoff that is within 1.4 % of the plain matrix's."""
    deck = np.array(volturnus.potential_flow.added_quadratic_damping)
    omega = ratio * 2 * np.pi * CUTOFF_HZ
    period = 2 * np.pi / omega
    cycles = 6 if ratio < 1 else 12
    time_s = np.arange(0.0, cycles * period, 0.05)
    velocity = np.zeros((time_s.size, 6))
    velocity[:, 0] = 0.3 * np.cos(omega * time_s)
    last = time_s >= time_s[-1] - 2 * period
    energy = {}
    for name, platform in (("plain", volturnus), ("bands", banded(volturnus, PAIR, [deck, deck]))):
        force = wrenches(platform, "filtered", time_s, velocity)[:, 0]
        energy[name] = -np.trapezoid((force * velocity[:, 0])[last], time_s[last])
    factor = energy["bands"] / energy["plain"]
    response = frequency_response(bank_state_space(PAIR), np.array([omega / (2 * np.pi)]))
    expected = float(effective_drag_coefficient(np.ones(2), response)[0])
    assert expected == pytest.approx((1 + ratio**3) / (1 + ratio**2) ** 1.5, rel=1e-9)
    assert factor == pytest.approx(expected, rel=0.01)
    if ratio != 1.0:
        assert factor == pytest.approx(1.0, abs=0.014)


@pytest.mark.slow
def test_a_free_decay_with_one_allpass_band_is_the_plain_addbquads(volturnus):
    """The time loop: volturnus_s released from 3 deg pitch and 4 m surge for 40 s, the deck's
    AddBQuad as the plain matrix (constant drag model) and as one all-pass band (filtered drag
    model): the same motion to 1e-9 of its range (the two sum the loads in different rows)."""
    deck = np.array(volturnus.potential_flow.added_quadratic_damping)
    start = np.array([4.0, 0.0, 0.0, 0.0, np.radians(3.0), 0.0])
    runs = []
    for platform, drag_model in ((volturnus, "constant"), (banded(volturnus, ALL, [deck]), "filtered")):
        model = PlatformModel(platform, None, dt_s=0.05, drag_model=drag_model)
        model.reset(motion=start)
        runs.append(model.run(40.0).motion)
    span = np.ptp(runs[0], axis=0)
    assert span[0] > 1.0 and span[4] > 0.02
    np.testing.assert_allclose(runs[1], runs[0], rtol=0, atol=1e-9 * span.max())


def test_the_band_matrices_are_read_written_and_checked(volturnus):
    """The YAML field ``potential_flow.added_quadratic_damping_bands`` (a 6x6 per drag band, by
    band name) reads back from the platform document; a band set other than the platform's is
    refused in one line naming the field."""
    deck = np.array(volturnus.potential_flow.added_quadratic_damping)
    platform = banded(volturnus, PAIR, [deck, 2 * deck])
    document = platform_document(platform)
    assert set(document["potential_flow"]["added_quadratic_damping_bands"]) == {"low", "high"}
    again = platform_from_dict(document, "round trip")
    assert again.potential_flow.added_quadratic_damping_bands == platform.potential_flow.added_quadratic_damping_bands
    del document["potential_flow"]["added_quadratic_damping_bands"]["high"]
    with pytest.raises(ConfigError, match="added_quadratic_damping_bands") as refused:
        platform_from_dict(document, "one band missing")
    assert len(str(refused.value).splitlines()) == 1
