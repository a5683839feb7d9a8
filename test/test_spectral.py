"""Band STDs of the paper's metric. Oracles: Parseval (a sinusoid of amplitude A has variance
A^2/2, all of it in the band holding its frequency) and white noise's variance."""
from __future__ import annotations

import numpy as np
import pytest

from fowt_hydro_sim.studies.psd import BANDS_HZ, band_std, band_stds, psd


@pytest.mark.parametrize("frequency_hz, band", [(0.012, "low_frequency"), (0.1, "wave")])
def test_sinusoid_lands_in_its_band(frequency_hz: float, band: str):
    dt = 0.25
    t = np.arange(0, 12000, dt)
    stds = band_stds(2.0 * np.sin(2 * np.pi * frequency_hz * t + 0.4) + 5.0, dt)
    assert stds[band] == pytest.approx(2.0 / np.sqrt(2), rel=0.01)
    other = next(b for b in BANDS_HZ if b != band)
    assert stds[other] < 0.02


def test_white_noise_variance_is_the_psd_integral():
    dt = 0.5
    x = np.random.default_rng(4).normal(0.0, 3.0, 40000)
    f, s = psd(x, dt)
    assert band_std(f, s, (0.0, f[-1] + 1.0)) == pytest.approx(3.0, rel=0.02)


@pytest.mark.parametrize("bad", [np.zeros(3), np.full(100, np.nan), np.zeros((10, 2))])
def test_bad_records_are_refused(bad):
    with pytest.raises(ValueError, match="psd: need a finite 1-D record"):
        psd(bad, 0.1)
    with pytest.raises(ValueError, match="need 0 <= low < high"):
        band_std(np.arange(5.0), np.ones(5), (0.2, 0.1))
