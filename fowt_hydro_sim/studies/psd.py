"""Power spectral densities and band standard deviations of motion records (the metric of
docs/load_cases.md: band STD = square root of the PSD integrated over the band)."""
from __future__ import annotations

import numpy as np

from fowt_hydro_sim.errors import InputError

# default bands of the paper's metric [Hz]: low-frequency (resonance) and wave-frequency
BANDS_HZ = {"low_frequency": (0.005, 0.05), "wave": (0.05, 0.25)}
SEGMENT_S = 2048.0  # longest Welch segment: 0.0005 Hz resolution, 10 bins below the 0.005 Hz band edge
MIN_SEGMENTS = 4  # a record holds at least this many segment lengths (7 averaged with the overlap)
# start-up left out of a run's statistics by default (fowt-sim simulate, analyze, load-cases, calibrate)
TRANSIENT_S = 600.0


def default_transient(record_s: float) -> float:
    """The start-up left out of a record of ``record_s`` seconds when none is given:
    ``TRANSIENT_S``, or nothing for a record not longer than that."""
    return TRANSIENT_S if record_s > TRANSIENT_S else 0.0


def psd(signal: np.ndarray, dt_s: float, segment_s: float = SEGMENT_S, window: str = "hann",
        overlap: float = 0.5) -> tuple[np.ndarray, np.ndarray]:
    """One-sided Welch PSD (mean removed): frequency [Hz], PSD [unit^2/Hz]. Segments of
    ``segment_s`` (shortened to a quarter of a shorter record), ``window`` (a scipy window
    name) and ``overlap`` (fraction of a segment)."""
    signal = np.asarray(signal, dtype=float)
    if signal.ndim != 1 or signal.size < 8 * MIN_SEGMENTS or not np.all(np.isfinite(signal)):
        raise InputError(f"psd: need a finite 1-D record of at least {8 * MIN_SEGMENTS} samples, "
                         f"got shape {signal.shape}")
    if not 0 <= overlap < 1:
        raise InputError(f"psd: overlap must be in [0, 1), got {overlap}")
    import scipy.signal  # here, not at the top: 0.6 s of start-up for commands that take no PSD

    n = segment_samples(signal.size, dt_s, segment_s)
    try:
        scipy.signal.get_window(window, n)
    except ValueError as exc:
        raise InputError(f"psd: window {window!r}: {exc}") from None
    return scipy.signal.welch(signal, fs=1.0 / dt_s, window=window, nperseg=n, noverlap=int(overlap * n),
                              detrend="constant")


def segment_samples(n_samples: int, dt_s: float, segment_s: float = SEGMENT_S) -> int:
    """Samples per Welch segment of ``psd``: ``segment_s``, at most a quarter of the record."""
    return min(n_samples // MIN_SEGMENTS, int(round(segment_s / dt_s)))


def welch_dof(n_samples: int, dt_s: float, segment_s: float = SEGMENT_S, window: str = "hann",
              overlap: float = 0.5) -> float:
    """Equivalent degrees of freedom of each bin of ``psd``'s estimate: nu = 2 K /
    (1 + 2 sum_j (1 - j/K) rho_j) over K averaged segments, rho_j the correlation of
    segments j apart for a Gaussian record with a smooth spectrum, from the window's overlap
    (Welch 1967; Percival and Walden, Spectral Analysis for Physical Applications, eq. 292b).
    nu PSD / chi2(nu) is the estimate's chi-square confidence band."""
    import scipy.signal

    n = segment_samples(n_samples, dt_s, segment_s)
    step = n - int(overlap * n)
    segments = (n_samples - n) // step + 1
    w = scipy.signal.get_window(window, n)
    power = float(np.sum(w**2))
    correlation = 0.0
    for j in range(1, segments):
        if j * step >= n:
            break
        rho = (float(np.sum(w[: n - j * step] * w[j * step:])) / power) ** 2
        correlation += (1 - j / segments) * rho
    return 2.0 * segments / (1.0 + 2.0 * correlation)


def psd_interval(density: np.ndarray, nu: float, confidence: float) -> tuple[np.ndarray, np.ndarray]:
    """The chi-square confidence band (low, high) at ``confidence`` of a PSD estimate whose
    bins have ``nu`` equivalent degrees of freedom: nu S / chi2(1 - a/2), nu S / chi2(a/2)."""
    import scipy.stats

    alpha = 1.0 - confidence
    return (nu * density / scipy.stats.chi2.ppf(1 - alpha / 2, nu),
            nu * density / scipy.stats.chi2.ppf(alpha / 2, nu))


def band_std(frequency_hz: np.ndarray, density: np.ndarray, band_hz: tuple[float, float]) -> float:
    """sqrt of the PSD integrated over [low, high) (rectangle rule on the Welch bins)."""
    low, high = band_hz
    if not 0 <= low < high:
        raise InputError(f"band {band_hz}: need 0 <= low < high")
    df = frequency_hz[1] - frequency_hz[0]
    inside = (frequency_hz >= low) & (frequency_hz < high)
    return float(np.sqrt(np.sum(density[inside]) * df))


def band_stds(signal: np.ndarray, dt_s: float, bands_hz: dict[str, tuple[float, float]] | None = None,
              segment_s: float = SEGMENT_S) -> dict[str, float]:
    """Band STDs of a record by band name (default: the paper's two bands)."""
    frequency, density = psd(signal, dt_s, segment_s)
    return {name: band_std(frequency, density, band) for name, band in (bands_hz or BANDS_HZ).items()}


def band_dof(frequency_hz: np.ndarray, density: np.ndarray, band_hz: tuple[float, float], record_s: float) -> float:
    """Equivalent degrees of freedom of a band variance from a record of ``record_s``
    (Satterthwaite: 2 T (sum S df)^2 / sum S^2 df, the bound a full-record estimate reaches;
    Bendat and Piersol, Random Data, sec. 8.5)."""
    df = frequency_hz[1] - frequency_hz[0]
    inside = (frequency_hz >= band_hz[0]) & (frequency_hz < band_hz[1])
    s = density[inside]
    if not np.any(s > 0):
        return float("nan")
    return float(2.0 * record_s * (np.sum(s) * df) ** 2 / (np.sum(s**2) * df))
