"""The independent second-order mean drift reference (studies/diagnosis/independent/drift.py):
Maruo's far-field formula against the near-field pressure integral of the MacCamy-Fuchs
field of a bottom-mounted cylinder, capytaine's Kochin function against that closed form,
and the stored windmoor12 table's symmetry, energy balance and limits."""
from __future__ import annotations

import math

import numpy as np
import pytest

from fowt_hydro_sim.studies.diagnosis.independent import cummins, drift

pytestmark = pytest.mark.reference  # against another code's output

RHO, G = 1025.0, 9.80665


@pytest.mark.parametrize("depth_m", [20.0, 200.0])
@pytest.mark.parametrize("ka", [0.3, 1.0, 3.0])
def test_maruo_equals_the_near_field_integral_for_a_bottom_mounted_cylinder(depth_m, ka):
    radius = 5.0
    k = ka / radius
    f = drift.cylinder_far_field(ka, drift.theta_grid(720))
    far = drift.maruo_drift(f, k, depth_m, RHO, G)
    near = drift.cylinder_drift_near_field(radius, k, depth_m, RHO, G)
    assert far[0] == pytest.approx(near, rel=1e-9)
    assert abs(far[1]) < 1e-9 * far[0]
    radiated, extinct = drift.energy_balance(f)
    assert radiated == pytest.approx(extinct, rel=1e-9)  # optical theorem


def test_short_waves_on_a_large_cylinder_tend_to_total_reflection():
    """Geometrical optics: the front half reflects, F = (2/3) rho g A^2 a in deep water."""
    radius, ka = 5.0, 25.0
    f = drift.cylinder_far_field(ka, drift.theta_grid(2048), terms=120)
    force = drift.maruo_drift(f, ka / radius, math.inf, RHO, G)[0]
    assert force == pytest.approx(2.0 / 3.0 * RHO * G * radius, rel=0.03)


@pytest.mark.slow
def test_capytaine_kochin_drift_of_a_bottom_mounted_cylinder():
    cpt = pytest.importorskip("capytaine")
    import logging

    from capytaine.post_pro.kochin import compute_kochin
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    radius, depth = 5.0, 20.0
    mesh = cpt.mesh_vertical_cylinder(length=depth + 2.0, radius=radius, center=(0.0, 0.0, -depth / 2 + 1.0),
                                      resolution=(0, 40, 22)).immersed_part(water_depth=depth)
    body = cpt.FloatingBody(mesh=mesh, name="cylinder")
    solver = cpt.BEMSolver()
    theta = drift.theta_grid(360)
    for ka in (1.0, 2.0):
        k = ka / radius
        omega = math.sqrt(G * k * math.tanh(k * depth))
        result = solver.solve(cpt.DiffractionProblem(body=body, wave_direction=0.0, omega=omega, water_depth=depth,
                                                     rho=RHO, g=G), method="indirect")
        f = drift.far_field_amplitude(compute_kochin(result, theta), omega, result.wavenumber, depth, G)
        closed = drift.cylinder_far_field(ka, theta)
        assert np.max(np.abs(f - closed)) < 0.05 * np.max(np.abs(closed))
        bem_force = drift.maruo_drift(f, k, depth, RHO, G)[0]
        assert bem_force == pytest.approx(drift.cylinder_drift_near_field(radius, k, depth, RHO, G), rel=0.03)
        radiated, extinct = drift.energy_balance(f)
        assert radiated == pytest.approx(extinct, rel=0.01)


def test_stored_windmoor12_table():
    table = drift.load_table()
    peak = table.fixed_n_m2.max()
    assert 3e4 < peak < 3e5  # a 15 m column semi's order (Newman's ~1e5 N/m^2 per column pair)
    # head seas on a hull symmetric about y = 0: no sway drift
    assert np.max(np.abs(table.fixed_sway_n_m2)) < 1e-9 * peak
    assert np.max(np.abs(table.free_sway_n_m2)) < 1e-9 * peak
    # the fixed hull absorbs nothing: extinct = radiated within the mesh's error
    assert np.max(np.abs(table.energy_error_fixed_n_m2)) < 0.01 * peak
    assert np.all(table.fixed_n_m2 > -np.abs(table.energy_error_fixed_n_m2))
    # short waves: the hull hardly moves, floating = fixed; long waves: it rides them, little drift
    short = table.omega_rad_s > 1.25
    assert np.allclose(table.free_radiated_n_m2[short], table.fixed_n_m2[short], rtol=0.1)
    long = table.omega_rad_s < 0.35
    assert np.all(table.free_radiated_n_m2[long] < 0.2 * table.fixed_n_m2[long])
    assert np.all(table.free_radiated_n_m2 >= 0.0)  # (E n / k) int |f|^2 (1 - cos)


def test_spectral_mean_drift_and_newman_spectrum_against_time_series():
    """2 int S D dw and int S_F dmu against the mean and the slow-drift-band variance of the
    Newman force series the independent simulator applies (cummins.Effects), averaged over
    8 random-phase realisations of one JONSWAP sea (one record's band variance scatters by
    +-40 %; the midpoint D^2 of the spectrum and the series' D_j D_k differ by a few %)."""
    table = drift.load_table()
    pairs = tuple((float(w), float(d)) for w, d in zip(table.omega_rad_s, table.free_radiated_n_m2))
    coefficient = lambda w: table.coefficient_n_m2(w)
    time_s = np.arange(0.0, 1800.0, 0.25)
    band_rad_s = 0.1
    omega = 2 * np.pi * np.fft.rfftfreq(time_s.size, 0.25)
    in_band = (omega > 0) & (omega <= band_rad_s)
    spectral, measured = [], []
    for seed in range(8):
        waves = cummins.jonswap_waves(6.19, 9.0, 3.3, 1800.0, seed=seed)
        series = cummins.Effects(drift_coefficient_n_m2=pairs).drift_force_n(waves, time_s)
        assert series.mean() == pytest.approx(drift.spectral_mean_drift_n(waves, coefficient), rel=1e-6)
        fourier = np.fft.rfft(series - series.mean()) / series.size
        measured.append(2 * np.sum(np.abs(fourier[in_band]) ** 2))
        mu = np.linspace(0.0, band_rad_s, 200)
        spectral.append(np.trapezoid(drift.newman_force_spectrum(waves, coefficient, mu), mu))
    assert np.mean(spectral) == pytest.approx(np.mean(measured), rel=0.2)
