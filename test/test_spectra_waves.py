"""Wave spectra, dispersion, random-phase synthesis, .Comp files and FFT decomposition.

Oracles: closed-form spectral moments (scipy.integrate.quad), DNV-RP-C205's JONSWAP written
in angular frequency, scipy.signal.welch, scipy.optimize.brentq on the dispersion relation,
numpy's default_rng, the orthogonality of harmonics over one period, and the OpenFAST
reference component table in test/data/openfast_hydrodyn/cyl_fixed.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.signal import welch

from fowt_hydro_sim.physics.config import ConfigError, SeaState
from fowt_hydro_sim.physics.waves.components import (
    WaveComponents,
    from_elevation_record,
    read_comp_file,
    repeat_period,
    synthesize,
    wavenumber,
    write_comp_file,
)
from fowt_hydro_sim.physics.waves.spectra import jonswap, pierson_moskowitz, spectrum
from fowt_hydro_sim.testing.references import hydrodyn_case

G = 9.80665
CYL_FIXED = hydrodyn_case("cyl_fixed")


# --------------------------------------------------------------------------- helpers
def k_brentq(omega: np.ndarray, depth: float, g: float = G) -> np.ndarray:
    """Wavenumbers by bracketing root finding of w^2 = g k tanh(k h) (independent of the library)."""
    out = []
    for w in np.atleast_1d(omega):
        lo = w**2 / g  # k >= w^2/g since tanh < 1
        hi = max(w / np.sqrt(g * depth), lo) * 2.0 + 1e-12
        out.append(brentq(lambda k, w=w: g * k * np.tanh(k * depth) - w**2, lo * 0.999, hi, xtol=1e-300,
                          rtol=1e-15))
    return np.array(out)


def direct_elevation(f: np.ndarray, a: np.ndarray, phase: np.ndarray, beta: np.ndarray, x: float, y: float,
                     t: np.ndarray, depth: float, g: float = G) -> np.ndarray:
    """eta = sum a cos(w t - k (x cos b + y sin b) + phase), written out in the test."""
    w = 2 * np.pi * f
    k = k_brentq(w, depth, g)
    s = x * np.cos(beta) + y * np.sin(beta)
    return np.sum(a * np.cos(w * t[:, None] - k * s + phase), axis=1)


def jonswap_dnv_omega(omega: np.ndarray, hs: float, tp: float, gamma: float) -> np.ndarray:
    """DNV-RP-C205 eq. 3.5.5 in angular frequency, S(w) in m^2 s / rad."""
    wp = 2 * np.pi / tp
    s_pm = 5.0 / 16.0 * hs**2 * wp**4 * omega**-5 * np.exp(-1.25 * (omega / wp) ** -4)
    sigma = np.where(omega <= wp, 0.07, 0.09)
    return (1 - 0.287 * np.log(gamma)) * s_pm * gamma ** np.exp(-0.5 * ((omega - wp) / (sigma * wp)) ** 2)


def m0_quad(fun, fp: float) -> float:
    """Zeroth moment of a one-sided spectrum by adaptive quadrature, split at the peak."""
    g = lambda x: float(fun(np.array([x]))[0])  # noqa: E731
    return quad(g, 0.0, fp, limit=200)[0] + quad(g, fp, np.inf, limit=200)[0]


# --------------------------------------------------------------------------- spectra
@pytest.mark.parametrize("hs, tp", [(2.0, 7.0), (11.0, 12.0), (14.97, 14.0)])
def test_pm_zeroth_moment_is_hs2_over_16(hs: float, tp: float) -> None:
    """Oracle: closed form m0 = Hs^2/16 of the PM Hs-Tp form, integrated with scipy quad."""
    m0 = m0_quad(lambda f: pierson_moskowitz(f, hs, tp), 1 / tp)
    assert m0 == pytest.approx(hs**2 / 16, rel=1e-6)


@pytest.mark.parametrize("gamma, tol", [(1.0, 0.005), (1.5, 0.005), (2.0, 0.005), (3.3, 0.005),
                                        (4.9, 0.005), (5.0, 0.005), (7.0, 0.018)])
def test_jonswap_zeroth_moment_within_documented_tolerance(gamma: float, tol: float) -> None:
    """Oracle: Hs^2/16 with the DNV normalisation's documented error (0.5 % for gamma<=5, 1.8 % at 7)."""
    hs, tp = 11.0, 12.0
    m0 = m0_quad(lambda f: jonswap(f, hs, tp, gamma), 1 / tp)
    assert abs(m0 / (hs**2 / 16) - 1) < tol


@pytest.mark.parametrize("gamma", [1.0, 1.49, 3.3, 4.9])
def test_jonswap_matches_dnv_formula_in_omega(gamma: float) -> None:
    """Oracle: DNV-RP-C205 JONSWAP in rad/s, converted with S(f) = 2 pi S(w)."""
    hs, tp = 6.19, 9.0
    f = np.linspace(0.02, 0.6, 500)
    expected = 2 * np.pi * jonswap_dnv_omega(2 * np.pi * f, hs, tp, gamma)
    np.testing.assert_allclose(jonswap(f, hs, tp, gamma), expected, rtol=1e-12, atol=1e-300)
    np.testing.assert_allclose(spectrum("jonswap", f, hs, tp, gamma), expected, rtol=1e-12, atol=1e-300)


def test_jonswap_gamma_one_is_pierson_moskowitz() -> None:
    """Oracle: JONSWAP's definition reduces to PM at gamma = 1 (normalisation 1, peak factor 1)."""
    f = np.linspace(0.0, 1.0, 1001)
    np.testing.assert_allclose(jonswap(f, 3.74, 12.0, 1.0), pierson_moskowitz(f, 3.74, 12.0), rtol=1e-14)
    np.testing.assert_allclose(spectrum("pierson_moskowitz", f, 3.74, 12.0),
                               pierson_moskowitz(f, 3.74, 12.0), rtol=0)
    assert pierson_moskowitz(np.array([0.0]), 3.74, 12.0)[0] == 0.0
    with pytest.raises(ValueError, match="unknown spectrum"):
        spectrum("bretschneider", f, 3.74, 12.0)


@pytest.mark.parametrize("name, gamma", [("pierson_moskowitz", 1.0), ("jonswap", 1.0), ("jonswap", 3.3),
                                         ("jonswap", 7.0)])
def test_spectrum_peaks_at_peak_frequency(name: str, gamma: float) -> None:
    """Oracle: dS/df = 0 at fp = 1/Tp (PM shape maximum, and the JONSWAP factor peaks there too)."""
    tp = 9.0
    f = np.linspace(0.5 / tp, 3 / tp, 200001)
    s = spectrum(name, f, 5.0, tp, gamma)
    assert f[np.argmax(s)] == pytest.approx(1 / tp, abs=2 * (f[1] - f[0]))


# --------------------------------------------------------------------------- dispersion
@pytest.mark.parametrize("depth", [0.5, 5.0, 30.0, 150.0, 1000.0, 5000.0])
def test_wavenumber_satisfies_dispersion(depth: float) -> None:
    """Oracle: residual of w^2 = g k tanh(k h) over 5 decades of frequency, and scipy brentq."""
    w = np.logspace(-3, 2, 300)
    k = wavenumber(w, depth, G)
    assert np.all(np.isfinite(k)) and np.all(k > 0)
    np.testing.assert_allclose(G * k * np.tanh(k * depth), w**2, rtol=1e-12)
    sub = slice(None, None, 30)
    np.testing.assert_allclose(k[sub], k_brentq(w[sub], depth), rtol=1e-12)
    assert wavenumber(np.array([0.0]), depth, G)[0] == 0.0


def test_wavenumber_deep_and_shallow_limits() -> None:
    """Oracle: k = w^2/g for kh >> 1 and k = w/sqrt(g h) (1 + O((kh)^2)) for kh << 1."""
    w = np.array([0.5, 1.0, 2.0, 5.0])
    np.testing.assert_allclose(wavenumber(w, 5000.0, G), w**2 / G, rtol=1e-12)
    h = 2.0
    w_shallow = np.array([1e-4, 1e-3, 1e-2])
    k = wavenumber(w_shallow, h, G)
    k0 = w_shallow / np.sqrt(G * h)
    # tanh(x) = x - x^3/3: k = k0 (1 + (k0 h)^2 / 6 + ...)
    np.testing.assert_allclose(k, k0 * (1 + (k0 * h) ** 2 / 6), rtol=1e-10)
    assert np.max(np.abs(k / k0 - 1)) < 1e-5


# --------------------------------------------------------------------------- synthesis
SEAS = [SeaState(11.0, 12.0, 4.9, seed=7), SeaState(3.74, 9.0, 1.49, seed=3),
        SeaState(2.0, 7.0, 1.0, spectrum="pierson_moskowitz", seed=11)]


def one_period_record(waves: WaveComponents, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """The elevation at the origin over exactly one repeat period, by direct summation in the test."""
    t = np.arange(0.0, waves.period_s, dt)
    return t, direct_elevation(waves.frequency_hz, waves.amplitude_m, waves.phase_rad,
                               waves.direction_rad, 0.0, 0.0, t, 150.0)


@pytest.mark.parametrize("sea", SEAS)
def test_synthesis_grid_band_and_hs(sea: SeaState) -> None:
    """Oracle: f = i/T, every harmonic strictly inside (0.5 fp, 5 fp) present and none outside
    [0.5 fp, 5 fp] (a harmonic lying exactly on a band edge may go either way in floating point);
    record variance over one period = sum a^2/2 = Hs^2/16."""
    period = 600.0
    waves = synthesize(sea, period)
    lo, hi = 0.5 / sea.tp_s * period, 5.0 / sea.tp_s * period
    h = waves.harmonic
    np.testing.assert_allclose(waves.frequency_hz, h / period, rtol=1e-14)
    np.testing.assert_array_equal(np.diff(h), 1)
    assert lo - 1e-9 <= h[0] <= lo + 1 + 1e-9 and hi - 1 - 1e-9 <= h[-1] <= hi + 1e-9
    assert waves.period_s == period
    np.testing.assert_allclose(waves.direction_rad, np.deg2rad(sea.heading_deg))
    _, eta = one_period_record(waves, dt=0.25)
    assert np.mean(eta) == pytest.approx(0.0, abs=1e-10)
    assert np.var(eta) == pytest.approx(np.sum(waves.amplitude_m**2) / 2, rel=1e-10)
    assert 4 * np.sqrt(np.var(eta)) == pytest.approx(sea.hs_m, rel=1e-10)
    assert waves.hs_m == pytest.approx(sea.hs_m, rel=1e-12)


@pytest.mark.parametrize("sea", SEAS)
def test_welch_psd_of_one_period_returns_input_spectrum(sea: SeaState) -> None:
    """Oracle: scipy.signal.welch (boxcar, one segment = one period, bins = components) equals
    S(f) times the documented Hs scale^2, scale = Hs / (4 sqrt(sum S df)) within 1 % of 1."""
    period, dt = 600.0, 0.25
    waves = synthesize(sea, period)
    t, eta = one_period_record(waves, dt)
    f_w, pxx = welch(eta, fs=1 / dt, window="boxcar", nperseg=t.size, detrend=False, scaling="density")
    s_in = spectrum(sea.spectrum, waves.frequency_hz, sea.hs_m, sea.tp_s, sea.gamma)
    scale = sea.hs_m / (4 * np.sqrt(np.sum(s_in) / period))
    assert abs(scale - 1) < 0.01
    bins = np.searchsorted(f_w, waves.frequency_hz - 1e-9)
    np.testing.assert_allclose(f_w[bins], waves.frequency_hz, rtol=1e-12)
    significant = s_in > 1e-3 * s_in.max()
    np.testing.assert_allclose(pxx[bins][significant], scale**2 * s_in[significant], rtol=1e-6)
    # no energy outside the band
    outside = np.ones(f_w.size, bool)
    outside[bins] = False
    assert np.sum(pxx[outside]) * (f_w[1] - f_w[0]) < 1e-12 * sea.hs_m**2
    # band-integrated energy around the peak against the continuous spectrum (quad)
    fp = 1 / sea.tp_s
    df = f_w[1] - f_w[0]
    for lo, hi in [(0.6 * fp, 0.9 * fp), (0.9 * fp, 1.1 * fp), (1.1 * fp, 1.5 * fp), (1.5 * fp, 2.5 * fp)]:
        sel = (f_w >= lo) & (f_w < hi)
        e_psd = np.sum(pxx[sel]) * df
        e_ref = quad(lambda x: spectrum(sea.spectrum, np.array([x]), sea.hs_m, sea.tp_s, sea.gamma)[0],
                     f_w[sel][0] - df / 2, f_w[sel][-1] + df / 2, limit=200)[0]
        assert e_psd == pytest.approx(e_ref, rel=0.03)


def test_record_repeats_after_period_but_not_half() -> None:
    """Oracle: all frequencies are multiples of 1/T, so eta(t + T) = eta(t); eta(t + T/2) is a different record."""
    waves = synthesize(SeaState(6.19, 9.0, 4.9, seed=5), 400.0)
    t = np.linspace(0.0, 400.0, 801)
    eta = waves.elevation(3.0, -2.0, t, 150.0, G)
    eta_t = waves.elevation(3.0, -2.0, t + 400.0, 150.0, G)
    eta_half = waves.elevation(3.0, -2.0, t + 200.0, 150.0, G)
    scale = np.std(eta)
    assert np.max(np.abs(eta_t - eta)) < 1e-9 * scale
    assert np.sqrt(np.mean((eta_half - eta) ** 2)) > 0.5 * scale


def test_phases_from_seed() -> None:
    """Oracle: phases are numpy default_rng(seed).uniform(0, 2 pi, n): same seed same, other seed different."""
    a = synthesize(SeaState(3.74, 7.0, 4.9, seed=42), 900.0)
    b = synthesize(SeaState(3.74, 7.0, 4.9, seed=42), 900.0)
    c = synthesize(SeaState(3.74, 7.0, 4.9, seed=43), 900.0)
    np.testing.assert_array_equal(a.phase_rad, b.phase_rad)
    np.testing.assert_allclose(a.phase_rad, np.random.default_rng(42).uniform(0, 2 * np.pi, a.phase_rad.size))
    assert np.mean(np.abs(np.exp(1j * a.phase_rad) - np.exp(1j * c.phase_rad))) > 0.5
    np.testing.assert_array_equal(a.amplitude_m, c.amplitude_m)


def test_repeat_period_rule() -> None:
    """Oracle: the documented rule: explicit repeat period, else ceil(duration) but at least 3600 s."""
    assert repeat_period(SeaState(2.0, 7.0), 600.0) == 3600.0
    assert repeat_period(SeaState(2.0, 7.0), 12000.2) == 12001.0
    assert repeat_period(SeaState(2.0, 7.0, repeat_period_s=1800.0), 12000.0) == 1800.0


def test_empty_band_raises_config_error() -> None:
    """Oracle: a band narrower than 1/T holds no harmonic, which the docs say is a ConfigError."""
    with pytest.raises(ConfigError, match="no wave frequency"):
        synthesize(SeaState(2.0, 7.0, f_min_hz=0.1001, f_max_hz=0.1009), 600.0)


def test_delayed_is_time_shift() -> None:
    """Oracle: the delayed sea at t equals the original at t - delay."""
    waves = synthesize(SeaState(3.74, 9.0, 1.49), 600.0)
    t = np.linspace(0, 100, 51)
    np.testing.assert_allclose(waves.delayed(12.3).elevation(5.0, 1.0, t, 150.0, G),
                               waves.elevation(5.0, 1.0, t - 12.3, 150.0, G), atol=1e-10)


# --------------------------------------------------------------------------- .Comp files
@pytest.mark.reference
def test_read_comp_matches_reference_csv() -> None:
    """Oracle: the reference .csv (f, omega, a, phase, k) written beside the OpenFAST .Comp deck."""
    waves = read_comp_file(CYL_FIXED / "waves_jonswap_Hs11_Tp12_g4.9.Comp")
    rows = [ln for ln in (CYL_FIXED / "waves_jonswap_Hs11_Tp12_g4.9.csv").read_text().splitlines()
            if ln.strip() and not ln.startswith("#")]
    columns = rows[0].split(",")
    values = np.array([[float(v) for v in ln.split(",")] for ln in rows[1:]])
    csv = {name: values[:, j] for j, name in enumerate(columns)}
    assert waves.frequency_hz.size == values.shape[0] == 169
    np.testing.assert_allclose(waves.amplitude_m, csv["amp_m"], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(waves.frequency_hz, csv["f_Hz"], rtol=1e-11)
    np.testing.assert_allclose(np.exp(1j * waves.phase_rad), np.exp(1j * csv["phase_rad"]), atol=1e-9)
    np.testing.assert_allclose(waves.direction_rad, 0.0)
    assert waves.period_s == pytest.approx(600.0, rel=1e-9)
    np.testing.assert_array_equal(waves.harmonic, np.arange(12, 181))
    assert waves.hs_m == pytest.approx(11.0, rel=1e-6)
    # the reference's k (finite depth 150 m) against our dispersion solver
    np.testing.assert_allclose(wavenumber(2 * np.pi * csv["f_Hz"], 150.0, G), csv["k_1_per_m"], rtol=1e-11)


def test_comp_round_trip(tmp_path: Path) -> None:
    """Oracle: write then read gives the same components (OpenFAST .Comp text precision)."""
    rng = np.random.default_rng(0)
    h = np.arange(5, 60)
    waves = WaveComponents(h / 256.0, rng.uniform(0, 2, h.size), rng.uniform(-np.pi, np.pi, h.size),
                           np.deg2rad(rng.uniform(-90, 90, h.size)), 256.0)
    path = tmp_path / "sea.Comp"
    write_comp_file(path, waves, header="round trip\nsecond header line")
    back = read_comp_file(path)
    np.testing.assert_allclose(back.frequency_hz, waves.frequency_hz, rtol=1e-11)
    np.testing.assert_allclose(back.amplitude_m, waves.amplitude_m, rtol=1e-9)
    np.testing.assert_allclose(np.exp(1j * back.phase_rad), np.exp(1j * waves.phase_rad), atol=1e-9)
    np.testing.assert_allclose(back.direction_rad, waves.direction_rad, atol=1e-7)
    assert back.period_s == pytest.approx(256.0, rel=1e-9)
    np.testing.assert_array_equal(back.harmonic, h)
    # written H is 2a and omega in rad/s, as OpenFAST reads it
    first = [ln for ln in path.read_text().splitlines() if not ln.startswith("!")][0].split()
    assert float(first[0]) == pytest.approx(2 * np.pi * 5 / 256.0, rel=1e-11)
    assert float(first[1]) == pytest.approx(2 * waves.amplitude_m[0], rel=1e-9)


def test_read_comp_rejects_bad_rows(tmp_path: Path) -> None:
    """Oracle: the .Comp format has 4 columns; anything else is a ConfigError naming the line."""
    path = tmp_path / "bad.Comp"
    path.write_text("! header\n0.5 1.0 0.0 10.0\n0.6 1.0 0.0\n")
    with pytest.raises(ConfigError, match=r"bad\.Comp:3: expected 4 columns"):
        read_comp_file(path)


# --------------------------------------------------------------------------- FFT decomposition
def test_from_elevation_record_recovers_components() -> None:
    """Oracle: a record built by direct summation at (20, 5) from known harmonics of the record
    length; the decomposition predicts the elevation elsewhere as the direct sum does."""
    depth, heading = 60.0, 30.0
    n, dt, t0 = 1024, 0.5, 37.25
    period = n * dt
    rng = np.random.default_rng(1)
    h = np.arange(8, 300)
    f = h / period
    a = rng.uniform(0.0, 0.5, h.size) * np.exp(-((f - 0.1) / 0.08) ** 2)
    phase = rng.uniform(0, 2 * np.pi, h.size)
    beta = np.full(h.size, np.deg2rad(heading))
    t = t0 + dt * np.arange(n)
    eta = direct_elevation(f, a, phase, beta, 20.0, 5.0, t, depth) + 0.3  # mean level is removed
    waves = from_elevation_record(t, eta, 20.0, 5.0, heading, depth, G)
    assert waves.period_s == pytest.approx(period)
    np.testing.assert_allclose(waves.direction_rad, np.deg2rad(heading))
    t_new = np.linspace(-50.0, 900.0, 400)
    for x, y in [(0.0, 0.0), (-40.0, 60.0), (20.0, 5.0)]:
        expected = direct_elevation(f, a, phase, beta, x, y, t_new, depth)
        np.testing.assert_allclose(waves.elevation(x, y, t_new, depth, G), expected, rtol=0, atol=1e-9)
    # only the harmonics below f_max are kept when asked
    cut = from_elevation_record(t, eta, 20.0, 5.0, heading, depth, G, f_max_hz=0.2)
    assert cut.frequency_hz.max() <= 0.2 and cut.frequency_hz.max() > 0.2 - 1 / period


def test_from_elevation_record_rejects_bad_records() -> None:
    """Oracle: the documented input contract (finite, uniform, matching arrays) -> ConfigError."""
    t = np.arange(64) * 0.5
    eta = np.sin(t)
    bad = eta.copy()
    bad[10] = np.nan
    with pytest.raises(ConfigError, match="NaN"):
        from_elevation_record(t, bad)
    t_bad = t.copy()
    t_bad[20] += 0.1
    with pytest.raises(ConfigError, match="uniformly"):
        from_elevation_record(t_bad, eta)
    with pytest.raises(ConfigError, match="matching"):
        from_elevation_record(t, eta[:-1])
