"""The filtered (frequency-dependent) drag model of the seed paper.

Oracles: scipy.signal's analog Butterworth designs (freqs_zpk) and the paper's band-pass
formula (eq. 4); the energy balance of a quadratic drag over one cycle (effective Cd); the
constant-Cd model (one all-pass band); rotation invariance; a body spinning at constant
rate, whose member-frame relative velocity is steady.

To drive the filters with a pure sinusoid in the real time loop, the column stands on a body
of 1e30 kg held up by an external force equal to its weight: it does not move, so each
strip's relative velocity is the regular wave's velocity.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import scipy.signal

from fowt_hydro_sim.frames import rotation_matrix
from fowt_hydro_sim.physics.config import (
    ConfigError,
    DragBand,
    DragCoefficients,
    HydroOptions,
    MassProperties,
    Platform,
    SeaState,
    Zone,
    load_case,
    load_platform,
)
from fowt_hydro_sim.physics.drag_filters import (
    band_zpk,
    bank_state_space,
    effective_drag_coefficient,
    frequency_response,
)
from fowt_hydro_sim.physics.loads import ROW
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.platform_edits import scaled_cd, with_cds
from fowt_hydro_sim.physics.waves.components import WaveComponents, synthesize
from fowt_hydro_sim.studies.psd import band_stds

DRAG = ROW["drag"]
PAPER_BANDS = (DragBand("low_frequency", "lowpass", 5, cutoff_hz=0.05), DragBand("wave", "highpass", 1, cutoff_hz=0.05))
TEST_BANDS = PAPER_BANDS + (DragBand("resonance", "bandpass", 1, centre_hz=0.02, q=0.7),
                            DragBand("lp2", "lowpass", 2, cutoff_hz=0.1),
                            DragBand("hp3", "highpass", 3, cutoff_hz=0.02))
HEAVY_KG = 1e30
HEAVY = MassProperties(HEAVY_KG, (0.0, 0.0, 0.0), ((HEAVY_KG, 0, 0), (0, HEAVY_KG, 0), (0, 0, HEAVY_KG)))


def analog_response(band: DragBand, frequency_hz: np.ndarray) -> np.ndarray:
    z, p, k = scipy.signal.butter(band.order, 2 * np.pi * band.cutoff_hz,
                                  "low" if band.kind == "lowpass" else "high", analog=True, output="zpk") \
        if band.kind in ("lowpass", "highpass") else band_zpk(band)
    return scipy.signal.freqs_zpk(z, p, k, 2 * np.pi * np.asarray(frequency_hz))[1]


def paper_bandpass(band: DragBand, frequency_hz: np.ndarray) -> np.ndarray:
    """Eq. 4 of the paper: H(s) = (wc/Q) s / (s^2 + (wc/Q) s + wc^2)."""
    wc, s = 2 * np.pi * band.centre_hz, 2j * np.pi * np.asarray(frequency_hz)
    return (wc / band.q) * s / (s**2 + (wc / band.q) * s + wc**2)


def fixed_column(bands: tuple[DragBand, ...], cd: DragCoefficients) -> Platform:
    """A 2 m vertical column from z = -20 to -10 m (no end plate) on an immovable body."""
    p = load_platform("windmoor12")
    zone = Zone("all", math.inf, (1.0, 1.0), (cd, cd))
    column = dataclasses.replace(p.members[0], end_a_m=(0.0, 0.0, -20.0), end_b_m=(0.0, 0.0, -10.0), width_m=2.0,
                                 height_m=2.0, zones=(zone,), end_a_plate=None, strip_length_m=1.0)
    return dataclasses.replace(p, members=(column,), mass=HEAVY, drag_bands=bands)


def regular_wave(frequency_hz: float, n_periods: int = 1) -> WaveComponents:
    return WaveComponents(np.array([frequency_hz]), np.array([1.0]), np.array([0.3]), np.array([0.0]),
                          n_periods / frequency_hz)


def held_model(platform: Platform, waves: WaveComponents, drag_model: str = "filtered") -> PlatformModel:
    model = PlatformModel(platform, waves, drag_model=drag_model)
    model.set_external_wrench(np.array([0.0, 0.0, HEAVY_KG * platform.environment.gravity_m_s2, 0, 0, 0]))
    return model


def amplitude(x: np.ndarray, t: np.ndarray, frequency_hz: float) -> complex:
    """Complex amplitude at one frequency of samples over whole periods (first sample left out)."""
    return 2.0 * np.mean(x * np.exp(-2j * np.pi * frequency_hz * t))


# --------------------------------------------------------------------------- design
def test_realisation_equals_scipy_and_the_papers_bandpass():
    """The cascaded state-space bank has scipy's analog Butterworth response, and the band-pass
    band is the paper's eq. 4, at 200 frequencies from 1e-4 to 2 Hz."""
    f = np.logspace(-4, np.log10(2.0), 200)
    response = frequency_response(bank_state_space(TEST_BANDS), f)
    for b, band in enumerate(TEST_BANDS):
        np.testing.assert_allclose(response[:, b], analog_response(band, f), rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(response[:, 2], paper_bandpass(TEST_BANDS[2], f), rtol=1e-9, atol=1e-12)
    assert np.all(np.real(np.linalg.eigvals(bank_state_space(TEST_BANDS).a)) < 0)


# --------------------------------------------------------------------------- in the time loop
@pytest.mark.parametrize("frequency_hz", [0.005, 0.02, 0.05, 0.1, 0.25])
def test_band_responses_in_the_time_loop_match_scipy(frequency_hz: float):
    """Drive every band with a sinusoidal relative velocity through model.step() (dt 0.05 s,
    ABM4 with the body) and measure gain and phase over two periods from t = 0: within 1 % of
    scipy's analog design, with |H(fc)| = 1/sqrt(2) at the 0.05 Hz cutoff. The filters start
    in steady state, so there is no transient to wait for."""
    cd = DragCoefficients(1.0, (1.0,) * len(TEST_BANDS))
    model = held_model(fixed_column(TEST_BANDS, cd), regular_wave(frequency_hz))
    n = int(round(2 / frequency_hz / model.dt_s))
    t, v_in, v_out = np.empty(n), np.empty(n), np.empty((n, len(TEST_BANDS)))
    for i in range(n):
        model.step()
        v_rel, v_band = model.strip_velocities()
        t[i], v_in[i], v_out[i] = model.time_s, v_rel[0, 0], v_band[0, :, 0]
    assert np.abs(model.motion).max() < 1e-9  # the body is held still
    measured = np.array([amplitude(v_out[:, b], t, frequency_hz) for b in range(len(TEST_BANDS))])
    measured /= amplitude(v_in, t, frequency_hz)
    expected = np.array([analog_response(b, [frequency_hz])[0] for b in TEST_BANDS])
    assert np.abs(measured / expected - 1.0).max() < 0.01, (measured, expected)
    if frequency_hz == 0.05:
        assert abs(measured[0]) == pytest.approx(1 / math.sqrt(2), rel=0.01)
        assert abs(measured[1]) == pytest.approx(1 / math.sqrt(2), rel=0.01)


@pytest.mark.parametrize("frequency_hz", [0.005, 0.0103, 0.02, 0.037, 0.05, 0.1, 0.2])
def test_effective_drag_coefficient_of_the_papers_bank(frequency_hz: float):
    """A single-frequency oscillation through the whole drag path: the energy the filtered drag
    takes from the flow per cycle, over that of a Cd = 1 constant model, is
    sum_b Cd_b |H_b|^2 cos(arg H_b) (the band filters do not sum to one)."""
    band_cd = (0.4, 1.0)
    wave = regular_wave(frequency_hz)
    work = {}
    for drag_model, cd in (("filtered", DragCoefficients(1.0, band_cd)), ("constant", DragCoefficients(1.0))):
        model = held_model(fixed_column(PAPER_BANDS, cd), wave, drag_model)
        result = model.run(1 / frequency_hz)
        u = np.cos(2 * np.pi * frequency_hz * result.time_s + 0.3)  # the wave velocity's phase at x = 0
        work[drag_model] = np.mean((result.loads[:, DRAG, 0] * u)[1:])
    measured = work["filtered"] / work["constant"]
    predicted = effective_drag_coefficient(band_cd,
                                           frequency_response(bank_state_space(PAPER_BANDS), [frequency_hz]))[0]
    assert measured == pytest.approx(predicted, abs=0.005), (measured, predicted)


def test_one_all_pass_band_equals_the_constant_model_exactly():
    """windmoor12 in LC5.3 for 300 s: the filtered model with one all-pass band whose Cd is each
    direction's constant Cd gives the constant model's numbers, bit for bit."""
    p = load_platform("windmoor12")

    def all_pass(cd: DragCoefficients) -> DragCoefficients:
        return DragCoefficients(cd.constant, (cd.constant,))

    single = with_cds(p, all_pass, drag_bands=(DragBand("all", "allpass", 0),))
    waves = synthesize(SeaState(11.0, 12.0, 4.9, seed=3), 3600.0)
    constant = PlatformModel(p, waves, drag_model="constant").run(300.0)
    filtered = PlatformModel(single, waves, drag_model="filtered").run(300.0)
    np.testing.assert_array_equal(filtered.motion, constant.motion)
    np.testing.assert_array_equal(filtered.loads, constant.loads)
    assert np.abs(constant.loads[:, DRAG]).max() > 1e5  # drag does act


# --------------------------------------------------------------------------- frames
def _rz(angle: float) -> np.ndarray:
    return rotation_matrix(0.0, 0.0, angle)


def test_rotated_platform_and_flow_give_the_same_band_forces():
    """The platform and its waves turned by 37 degrees about z: the same band speeds on every
    strip and the drag wrench turned with them (filtering in each member's frame). The body is
    held still, so that the float32 rounding of the two kinematics tables is not amplified by
    the motion over the 100 s compared."""
    angle = math.radians(37.0)
    rz = _rz(angle)
    p = dataclasses.replace(load_platform("windmoor12"), mass=HEAVY)

    def turn(v):
        return tuple(rz @ np.array(v))

    turned = dataclasses.replace(
        p, members=tuple(dataclasses.replace(m, end_a_m=turn(m.end_a_m), end_b_m=turn(m.end_b_m)) for m in p.members),
        mooring=dataclasses.replace(p.mooring, lines=tuple(
            dataclasses.replace(line, fairlead_m=turn(line.fairlead_m), anchor_m=turn(line.anchor_m))
            for line in p.mooring.lines)))
    waves = synthesize(SeaState(11.0, 12.0, 4.9, seed=5), 3600.0)
    turned_waves = dataclasses.replace(waves, direction_rad=waves.direction_rad + angle)
    a = held_model(p, waves)
    b = held_model(turned, turned_waves)
    for _ in range(4):
        a.step(500)
        b.step(500)
        speeds_a = np.linalg.norm(a.strip_velocities()[1], axis=2)
        speeds_b = np.linalg.norm(b.strip_velocities()[1], axis=2)
        np.testing.assert_allclose(speeds_b, speeds_a, rtol=1e-5, atol=1e-6 * np.nanmax(speeds_a))  # NaN: dry at rest
        rotate6 = np.kron(np.eye(2), rz)
        drag_a, drag_b = a.loads[DRAG], b.loads[DRAG]
        np.testing.assert_allclose(drag_b, rotate6 @ drag_a, rtol=0, atol=1e-5 * np.abs(drag_a).max())


def test_spinning_body_filters_in_the_member_frame():
    """A body spinning at a constant yaw rate of 2 pi 0.05 rad/s in still water: in each member's
    frame the relative velocity is steady, so the low-pass band passes it whole and the
    high-pass band nothing, and the drag equals a constant model with the low-frequency Cds.
    (A world-frame filter would see a 0.05 Hz rotation and lose about half of it.) Load
    directions rotating with the body: the fixed ones (the default, HydroDyn's small-angle
    choice) keep the undisplaced member frames, which a full turn makes meaningless."""
    p = load_platform("windmoor12")
    rotating = HydroOptions(load_directions="rotating")

    def low_frequency_only(cd: DragCoefficients) -> DragCoefficients:
        return cd if cd.bands is None else DragCoefficients(cd.bands[0])

    yaw_rate = 2 * np.pi * 0.05
    drag = {}
    for name, platform in (("filtered", dataclasses.replace(p, mass=HEAVY)),
                           ("constant", with_cds(p, low_frequency_only, mass=HEAVY))):
        model = PlatformModel(platform, None, drag_model=name, options=rotating)
        model.set_external_wrench(np.array([0.0, 0.0, HEAVY_KG * p.environment.gravity_m_s2, 0, 0, 0]))
        model.reset(velocity=np.array([0, 0, 0, 0, 0, yaw_rate]))
        drag[name] = model.run(40.0).loads[:, DRAG]
    assert np.abs(drag["constant"][:, 5]).max() > 1e6
    np.testing.assert_allclose(drag["filtered"], drag["constant"], rtol=0, atol=1e-4 * np.abs(drag["constant"]).max())


def test_filtered_model_needs_drag_bands_and_the_time_loop():
    p = load_platform("windmoor12")
    with pytest.raises(ConfigError, match="has no drag_bands"):
        PlatformModel(dataclasses.replace(p, drag_bands=()), None, drag_model="filtered")
    with pytest.raises(ConfigError, match="must be one of constant, filtered"):
        PlatformModel(p, None, drag_model="smart")
    model = PlatformModel(p, None, drag_model="filtered")
    with pytest.raises(ConfigError, match="filter states need the time loop"):
        model.prescribed_motion_loads(np.zeros(1), np.zeros((1, 6)), np.zeros((1, 6)), np.zeros((1, 6)))


# --------------------------------------------------------------------------- the paper's mechanism
@pytest.mark.slow
def test_band_cds_act_on_their_bands_in_lc53():
    """LC5.3 (Hs 11 m, Tp 12 s), filtered model, 3600 s after 300 s of start-up, band STDs
    (0.005-0.05 and 0.05-0.25 Hz) with each band's Cd doubled in turn, same waves:

    * doubling the low-frequency Cd cuts the surge resonance response by more than 10 % and
      leaves the wave-frequency surge, heave and pitch within 0.3 %;
    * doubling the wave-band Cd moves the wave-frequency surge at least 5 times more than
      doubling the low-frequency Cd does. That move is small (under 3 %), because the
      wave-frequency response is inertia-dominated. The wave-band Cd also damps the surge
      resonance: |v_wave| multiplies the small part of the resonance velocity that the
      first-order high-pass lets through. So the converse of the first point holds only for
      the wave band's share of the wave-frequency response, not as 'leaves the resonance
      unchanged'. The test bounds that cross effect below the low-frequency Cd's own effect.
    """
    p = load_platform("windmoor12")

    waves = synthesize(SeaState(11.0, 12.0, 4.9, seed=1), 3900.0)
    stds = {}
    for name, platform in (("base", p), ("low_frequency", with_cds(p, lambda c: scaled_cd(c, 2.0, band=0))),
                           ("wave", with_cds(p, lambda c: scaled_cd(c, 2.0, band=1)))):
        result = PlatformModel(platform, waves, drag_model="filtered").run(3900.0, output_interval_s=0.25)
        keep = result.time_s >= 300.0
        stds[name] = {dof: band_stds(result.motion[keep, j], 0.25)
                      for dof, j in (("surge", 0), ("heave", 2), ("pitch", 4))}

    def change(case: str, dof: str, band: str) -> float:
        return stds[case][dof][band] / stds["base"][dof][band] - 1.0

    assert change("low_frequency", "surge", "low_frequency") < -0.10
    for dof in ("surge", "heave", "pitch"):
        assert abs(change("low_frequency", dof, "wave")) < 0.003
    assert abs(change("wave", "surge", "wave")) > 5 * abs(change("low_frequency", "surge", "wave"))
    assert abs(change("wave", "surge", "wave")) < 0.03
    assert abs(change("wave", "surge", "low_frequency")) < abs(change("low_frequency", "surge", "low_frequency"))


@pytest.mark.slow
def test_no_filter_state_becomes_subnormal_in_an_hour():
    """An hour of windmoor12 in LC5.3 with the filtered drag leaves no filter state subnormal
    (nonzero but below the smallest normal double): products with subnormal numbers are many
    times slower, and filters left at zero input decay into them (those of strips dry at rest
    did, until such strips, which never load, lost their filter states)."""
    model = PlatformModel(load_platform("windmoor12"), synthesize(load_case("lc5.3").sea_state, 3600.0),
                          drag_model="filtered")
    model.run(3600.0, output_interval_s=10.0)
    states = np.abs(model._state[12:])  # noqa: SLF001 (the integrator's state)
    assert states.size > 1000
    assert not np.any((states > 0.0) & (states < np.finfo(float).tiny))
