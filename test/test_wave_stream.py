"""Streamed kinematics from a point elevation measurement (fowt_hydro_sim.wave_stream).

Oracles: ``kinematics.point_kinematics`` (direct summation of Airy components) for a regular
wave and for the true components of an irregular sea, the offline route
``waves.from_elevation_record`` + ``point_kinematics`` on the same record, the DTFT of the
designed taps, and group velocities by a finite difference of brentq wavenumbers.
"""
from __future__ import annotations

import logging
import re

import numpy as np
import pytest
from scipy.optimize import brentq

from fowt_hydro_sim.physics.config import SeaState
from fowt_hydro_sim.physics.waves.components import WaveComponents, from_elevation_record, synthesize
from fowt_hydro_sim.physics.waves.kinematics import CHANNELS, point_kinematics
from fowt_hydro_sim.physics.waves.stream import (
    DEFAULT_BAND_HZ,
    DEFAULT_TAPER_HZ,
    ElevationStream,
    design_taps,
    transfer_functions,
    tukey_window,
)

log = logging.getLogger(__name__)

G, RHO, DEPTH = 9.80665, 1025.0, 150.0
# windmoor12-like points: column keel and waterline up- and downstream, a pontoon, one above water
POINTS = np.array([[-35.2184, 0.0, -15.5], [-35.2184, 0.0, 0.0], [17.6092, 30.5, 0.0],
                   [17.6092, -30.5, -13.5], [0.0, 0.0, -5.0], [17.6092, 30.5, 3.0]])
PREVIEW_S = 60.0


def stream_record(stream: ElevationStream, eta_m: np.ndarray) -> tuple[np.ndarray, int]:
    """Push a record; the outputs (n_out, n_points, 7) and the index of the first sample that
    gave one (all the earlier ones must give None)."""
    outputs = [stream.push(e) for e in eta_m]
    first = stream.n_taps - 1
    assert all(o is None for o in outputs[:first]) and outputs[first] is not None
    return np.array(outputs[first:]), first


def relative_rms(got: np.ndarray, want: np.ndarray) -> np.ndarray:
    """RMS error over time / RMS of the reference, per (point, channel)."""
    return np.sqrt(np.mean((got - want) ** 2, axis=0) / np.mean(want**2, axis=0))


@pytest.mark.parametrize("n", [1, 2, 3, 10, 11, 257])
@pytest.mark.parametrize("alpha", [0.0, 0.1, 0.5, 1.0])
def test_the_tukey_window_is_scipys(n: int, alpha: float):
    """Oracle: scipy.signal.windows.tukey (symmetric), which the model does not import."""
    from scipy.signal.windows import tukey
    np.testing.assert_allclose(tukey_window(n, alpha), tukey(n, alpha), rtol=0.0, atol=1e-14)


def test_regular_wave_matches_airy_kinematics_delayed():
    """A regular wave in the middle of the band: every channel at points up- and downstream of
    the probe, at depth, at and above z = 0, equals the direct Airy kinematics at t - D."""
    heading, probe = 20.0, (5.0, -3.0)
    wave = WaveComponents(np.array([0.125]), np.array([1.5]), np.array([0.7]),
                          np.array([np.deg2rad(heading)]), 8.0)
    dt = 0.1
    stream = ElevationStream(POINTS, probe, heading, DEPTH, G, RHO, dt, PREVIEW_S,
                             elevation_points_xy_m=[(0.0, 0.0), (-30.0, 10.0)])
    distance = (POINTS[:, 0] - probe[0]) * np.cos(np.deg2rad(heading)) + \
        (POINTS[:, 1] - probe[1]) * np.sin(np.deg2rad(heading))
    assert distance.min() < -30 and distance.max() > 20  # both sides of the probe
    t = np.arange(0.0, 300.0, dt)
    got, first = stream_record(stream, wave.elevation(*probe, t, DEPTH, G))
    want = point_kinematics(wave, POINTS, t[first:] - stream.delay_s, DEPTH, G, RHO)
    error = np.max(np.abs(got - want), axis=0) / np.max(np.abs(want), axis=0)
    log.info("regular wave: max relative error per channel %s", dict(zip(CHANNELS, error.max(0))))
    assert error.max() < 1e-3
    np.testing.assert_array_equal(got[:, 5], got[:, 2])  # z > 0 is taken at z = 0
    # the extra elevation outputs, for the last sample's time
    t_last = t[-1] - stream.delay_s
    eta_want = [wave.elevation(x, y, t_last, DEPTH, G)[0] for x, y in [(0.0, 0.0), (-30.0, 10.0)]]
    np.testing.assert_allclose(stream.elevation_m, eta_want, rtol=0, atol=1e-3 * wave.amplitude_m[0])


def test_taps_reproduce_the_delayed_transfer_function_in_band_and_zero_outside():
    """The DTFT of the designed taps is H exp(-i w D) in the flat band and ~0 outside the band."""
    dt, n_taps = 0.2, 600
    probe = (0.0, 0.0)
    points = POINTS[:3]
    taps = design_taps(points, probe, 0.0, DEPTH, G, RHO, dt, PREVIEW_S, DEFAULT_BAND_HZ, DEFAULT_TAPER_HZ,
                       n_taps)
    (f_low, f_high), (taper_low, taper_high) = DEFAULT_BAND_HZ, DEFAULT_TAPER_HZ
    f_in = np.linspace(f_low + taper_low, f_high - taper_high, 200)
    dtft = np.exp(-2j * np.pi * np.outer(np.arange(n_taps) * dt, f_in))
    got = np.einsum("pcn,nf->fpc", taps, dtft)
    want = transfer_functions(f_in, points, probe, 0.0, DEPTH, G, RHO) * \
        np.exp(-2j * np.pi * f_in * PREVIEW_S)[:, None, None]
    peak = np.abs(want).max(axis=0)  # per point and channel; 0 for u_y, a_y at heading 0
    significant = np.abs(want) > 1e-2 * peak  # leaves out the e^{kz}-decayed deep high frequencies
    relative = np.abs(got - want)[significant] / np.abs(want)[significant]
    log.info("taps: largest relative error in the flat band %.1e", relative.max())
    assert relative.max() < 1e-2  # 6e-3, at the flat band's lower edge; 1e-4 in the middle
    f_out = np.array([0.0, 0.9, 1.2, 2.0])
    gain = np.abs(np.einsum("pcn,nf->fpc", taps,
                            np.exp(-2j * np.pi * np.outer(np.arange(n_taps) * dt, f_out))))
    stop = gain[:, peak > 0] / peak[peak > 0]
    log.info("taps: largest stop-band gain / in-band peak %.1e", stop.max())
    assert stop.max() < 1e-3 and np.all(gain[:, peak == 0] == 0)
    assert np.all(gain[0] < 1e-12 * peak.max())  # no mean level (sensor offset, tide) at all


def test_irregular_sea_against_offline_decomposition_and_truth():
    """JONSWAP record at the probe, 1200 s at 0.1 s: the streamed kinematics against the
    offline route (FFT decomposition of the same record, kinematics by direct summation) and
    against the true components.

    Measured (relative RMS over 1080 s after the warm-up, worst point), velocities /
    accelerations / pressure: stream vs truth 1.4e-4 / 5e-5 / 3.3e-4; stream vs offline
    3.4e-3 / 1.4e-2 / 6e-4, the same as offline vs truth: the offline route's own error. It
    treats the 1200 s record as periodic, and the jump at its wrap rings, through the sharp
    cut at f_max (the stream's upper band edge), into the free-surface points' accelerations
    (w^2); without f_max that leakage up to the 5 Hz Nyquist makes them wrong by ~100 %. The
    bounds are two to three times the measured values.
    """
    heading, dt = 30.0, 0.1
    waves = synthesize(SeaState(hs_m=6.19, tp_s=9.0, gamma=4.9, seed=2, heading_deg=heading), 3600.0)
    t = np.arange(0.0, 1200.0, dt)
    eta = waves.elevation(0.0, 0.0, t, DEPTH, G)
    points = POINTS[:5]
    stream = ElevationStream(points, (0.0, 0.0), heading, DEPTH, G, RHO, dt, PREVIEW_S)
    got, first = stream_record(stream, eta)
    every = slice(None, None, 10)  # 1 s apart: enough for the statistics, cheap oracles
    t_out = t[first:][every] - stream.delay_s
    got = got[every]
    offline = from_elevation_record(t, eta, 0.0, 0.0, heading, DEPTH, G, f_max_hz=DEFAULT_BAND_HZ[1])
    want_offline = point_kinematics(offline, points, t_out, DEPTH, G, RHO)
    want_true = point_kinematics(waves, points, t_out, DEPTH, G, RHO)
    vs_offline = relative_rms(got, want_offline).max(axis=0)
    vs_truth = relative_rms(got, want_true).max(axis=0)
    log.info("irregular sea, relative RMS per channel: vs offline %s, vs truth %s, offline vs truth %s",
             dict(zip(CHANNELS, vs_offline)), dict(zip(CHANNELS, vs_truth)),
             dict(zip(CHANNELS, relative_rms(want_offline, want_true).max(axis=0))))
    assert np.all(vs_offline < [7e-3, 7e-3, 7e-3, 3e-2, 3e-2, 3e-2, 1.5e-3])
    assert np.all(vs_truth < 1e-3)


def test_memory_is_bounded_and_bad_samples_are_rejected():
    dt = 0.25
    stream = ElevationStream(POINTS, (0.0, 0.0), 0.0, DEPTH, G, RHO, dt, PREVIEW_S)
    twin = ElevationStream(POINTS, (0.0, 0.0), 0.0, DEPTH, G, RHO, dt, PREVIEW_S)
    eta = np.random.default_rng(3).normal(size=11 * stream.n_taps)

    def array_sizes() -> dict[str, int]:
        return {k: v.size for k, v in vars(stream).items() if isinstance(v, np.ndarray)}

    for e in eta[:stream.n_taps]:
        stream.push(e)
        twin.push(e)
    sizes = array_sizes()
    assert sum(sizes.values()) == stream.n_taps * (7 * len(POINTS) + 2)  # taps + doubled ring
    for bad in (np.nan, np.inf):
        with pytest.raises(ValueError, match="elevation sample (nan|inf) is not finite"):
            stream.push(bad)
    for e in eta[stream.n_taps:]:
        out = stream.push(e)
        np.testing.assert_array_equal(out, twin.push(e))  # the rejected samples left no trace
    assert array_sizes() == sizes
    assert np.all(np.isfinite(out))


def group_velocity_brentq(f_hz: float, depth_m: float) -> float:
    """dw/dk by a central difference of brentq wavenumbers (independent of the library)."""
    def k_of(omega: float) -> float:
        return brentq(lambda k: G * k * np.tanh(k * depth_m) - omega**2, 1e-9, 10 * omega**2 / G + 1.0,
                      xtol=1e-15, rtol=1e-15)
    omega, step = 2 * np.pi * f_hz, 1e-4 * 2 * np.pi * f_hz
    return 2 * step / (k_of(omega + step) - k_of(omega - step))


def test_too_short_preview_or_kernel_names_the_minimum():
    """Rule: for each band edge, upstream distance / c_g(edge) + 1 / taper width; the larger."""
    upstream = 35.2184  # heading 0, probe at the origin: the x = -35.2 column
    (f_low, f_high), (taper_low, taper_high) = DEFAULT_BAND_HZ, DEFAULT_TAPER_HZ
    need = max(upstream / group_velocity_brentq(f_high, DEPTH) + 1 / taper_high,
               upstream / group_velocity_brentq(f_low + taper_low, DEPTH) + 1 / taper_low)
    assert 45.0 < need < 47.0  # the windmoor12 figure of the module docstring
    with pytest.raises(ValueError, match=r"preview_s 0 s is too short") as error:
        ElevationStream(POINTS, (0.0, 0.0), 0.0, DEPTH, G, RHO, 0.25, 0.0, kernel_s=120.0)
    named = float(re.search(r"at least ([0-9.]+) s", str(error.value)).group(1))
    assert named == pytest.approx(need, abs=0.06)
    ElevationStream(POINTS, (0.0, 0.0), 0.0, DEPTH, G, RHO, 0.25, need + 0.1, kernel_s=120.0)
    with pytest.raises(ValueError, match="kernel_s 70 s is too short"):  # causal side 10 s
        ElevationStream(POINTS, (0.0, 0.0), 0.0, DEPTH, G, RHO, 0.25, PREVIEW_S, kernel_s=70.0)
