"""Linear wave components: synthesis from a spectrum, OpenFAST ``.Comp`` files, and the FFT
decomposition of a measured elevation record.

Convention (OpenFAST SeaState's): eta(x, y, t) = sum_i a_i cos(w_i t - k_i s_i + phase_i),
s_i = x cos(beta_i) + y sin(beta_i), beta the direction the component travels to (0 = +x,
90 deg = +y); phase 0 is a crest at the origin at t = 0; k from w^2 = g k tanh(k h).

All frequencies are integer multiples of 1 / ``period_s``: the sea repeats every
``period_s`` seconds, and its kinematics can be computed by an inverse FFT. Components on no
common frequency grid (a ``.Comp`` file's frequencies as printed) have ``period_s`` 0: they
do not repeat, and are summed directly, component by component, at every point and time
(``fowt-sim loads`` only).
"""
from __future__ import annotations

import logging
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.config import ConfigError, SeaState
from fowt_hydro_sim.physics.waves.spectra import spectrum

log = logging.getLogger(__name__)

MIN_REPEAT_PERIOD_S = 3600.0


def wavenumber(omega_rad_s: np.ndarray, depth_m: float, gravity_m_s2: float) -> np.ndarray:
    """Solve the finite-depth dispersion relation w^2 = g k tanh(k h) (Newton, vectorised)."""
    w = np.atleast_1d(np.asarray(omega_rad_s, dtype=float))
    k = np.maximum(w**2 / gravity_m_s2, 1e-12)  # deep-water start
    shallow = w / np.sqrt(gravity_m_s2 * depth_m)
    k = np.where(shallow > k, shallow, k)
    for _ in range(50):
        th = np.tanh(k * depth_m)
        f = gravity_m_s2 * k * th - w**2
        df = gravity_m_s2 * (th + k * depth_m * (1.0 - th**2))
        step = f / df
        k = k - step
        if np.all(np.abs(step) <= 1e-14 * np.abs(k)):
            break
    return np.where(w > 0, k, 0.0)


@dataclass(frozen=True)
class WaveComponents:
    """Long-crested or directional linear wave components (``period_s`` 0: on no common
    frequency grid, summed directly)."""

    frequency_hz: np.ndarray
    amplitude_m: np.ndarray
    phase_rad: np.ndarray
    direction_rad: np.ndarray
    period_s: float

    def __post_init__(self):
        n = len(self.frequency_hz)
        for name in ("amplitude_m", "phase_rad", "direction_rad"):
            if len(getattr(self, name)) != n:
                raise ValueError(f"wave components: {name} has {len(getattr(self, name))} values, expected {n}")
        harmonics = self.frequency_hz * self.period_s
        if self.period_s and n and np.max(np.abs(harmonics - np.round(harmonics))) > 1e-6:
            raise ValueError(f"wave components: frequencies are not multiples of 1/{self.period_s:g} s")

    @property
    def periodic(self) -> bool:
        """Whether the components are harmonics of 1 / period_s (else summed directly)."""
        return self.period_s > 0

    @property
    def harmonic(self) -> np.ndarray:
        """Each component's frequency as an integer multiple of 1 / period_s."""
        return np.round(self.frequency_hz * self.period_s).astype(np.int64)

    @property
    def hs_m(self) -> float:
        return 4.0 * float(np.sqrt(np.sum(self.amplitude_m**2) / 2.0))

    def elevation(self, x_m: float, y_m: float, t_s: np.ndarray, depth_m: float,
                  gravity_m_s2: float) -> np.ndarray:
        """Elevation at one point, by direct summation (use for short records and tests)."""
        omega = 2 * np.pi * self.frequency_hz
        k = wavenumber(omega, depth_m, gravity_m_s2)
        s = x_m * np.cos(self.direction_rad) + y_m * np.sin(self.direction_rad)
        theta = np.outer(np.atleast_1d(t_s), omega) - k * s + self.phase_rad
        return np.cos(theta) @ self.amplitude_m

    def elevation_at(self, xy_m: np.ndarray, t_s: float, depth_m: float, gravity_m_s2: float) -> np.ndarray:
        """Elevation at time ``t_s`` at the points ``xy_m`` (p, 2), by direct summation."""
        omega = 2 * np.pi * self.frequency_hz
        k = wavenumber(omega, depth_m, gravity_m_s2)
        s = np.outer(xy_m[:, 0], np.cos(self.direction_rad)) + np.outer(xy_m[:, 1], np.sin(self.direction_rad))
        return np.cos(omega * t_s - k * s + self.phase_rad) @ self.amplitude_m

    def elevation_series(self, x_m: float, y_m: float, step_s: float, depth_m: float,
                         gravity_m_s2: float) -> np.ndarray:
        """Elevation at one point every ``step_s`` over one repeat period, by inverse FFT."""
        n = int(round(self.period_s / step_s))
        k = wavenumber(2 * np.pi * self.frequency_hz, depth_m, gravity_m_s2)
        s = x_m * np.cos(self.direction_rad) + y_m * np.sin(self.direction_rad)
        spectrum = np.zeros(n // 2 + 1, dtype=complex)
        np.add.at(spectrum, self.harmonic, self.amplitude_m * np.exp(1j * (self.phase_rad - k * s)) * n / 2.0)
        return np.fft.irfft(spectrum, n)

    def delayed(self, delay_s: float) -> WaveComponents:
        """The same sea, arriving ``delay_s`` later (a phase shift of -w delay)."""
        return WaveComponents(self.frequency_hz, self.amplitude_m,
                              self.phase_rad - 2 * np.pi * self.frequency_hz * delay_s,
                              self.direction_rad, self.period_s)


def repeat_period(sea: SeaState, duration_s: float) -> float:
    """The sea state's repeat period: as set, or the run's duration, at least one hour."""
    return sea.repeat_period_s or max(MIN_REPEAT_PERIOD_S, float(np.ceil(duration_s)))


def synthesize(sea: SeaState, period_s: float) -> WaveComponents:
    """Random-phase components at f = i / period_s inside the sea state's band.

    Amplitudes a_i = sqrt(2 S(f_i) df), phases uniform from ``numpy.random.default_rng(seed)``,
    then scaled so that the record's Hs = 4 sqrt(sum a^2 / 2) is the requested Hs exactly
    (the band cut-off and the spectrum's normalisation leave it a fraction of a percent off).
    """
    f_lo, f_hi = sea.band_hz
    first, last = int(np.ceil(f_lo * period_s - 1e-9)), int(np.floor(f_hi * period_s + 1e-9))
    if last < first:
        raise ConfigError(f"sea state: no wave frequency in [{f_lo:g}, {f_hi:g}] Hz at a "
                          f"repeat period of {period_s:g} s")
    harmonic = np.arange(first, last + 1)
    f = harmonic / period_s
    amplitude = np.sqrt(2.0 * spectrum(sea.spectrum, f, sea.hs_m, sea.tp_s, sea.gamma) / period_s)
    phase = np.random.default_rng(sea.seed).uniform(0.0, 2 * np.pi, f.size)
    band_hs = 4.0 * np.sqrt(np.sum(amplitude**2) / 2.0)
    if band_hs > 0:
        log.debug("sea state: amplitude scale %.6f (band Hs %.4f m -> %.4f m)",
                  sea.hs_m / band_hs, band_hs, sea.hs_m)
        amplitude *= sea.hs_m / band_hs
    direction = np.full(f.size, np.deg2rad(sea.heading_deg))
    return WaveComponents(f, amplitude, phase, direction, period_s)


def read_comp_file(path: str | Path, direct_sum: bool = False) -> WaveComponents:
    """Components from an OpenFAST SeaState ``.Comp`` file (WaveMod = 7).

    Lines holding a non-numeric word are headers; data lines are omega (rad/s), wave height
    H = 2a (m), direction (deg), phase (deg), separated by blanks or commas. Frequencies on no
    common grid (multiples of one step, to 1e-6 of a step) are refused, or with ``direct_sum``
    kept as written with ``period_s`` 0 (summed directly: each point and time costs one cosine
    per component instead of an interpolation in a table).
    """
    path = Path(path)
    rows = []
    try:
        lines = path.read_text().splitlines()
    except (OSError, UnicodeDecodeError) as exc:
        raise ConfigError(f"{path}: cannot be read ({getattr(exc, 'strerror', None) or exc})") from None
    for number, line in enumerate(lines, 1):
        words = line.replace(",", " ").split()
        try:
            values = [float(w) for w in words]
        except ValueError:
            continue  # a header line
        if not values:
            continue
        if len(values) != 4:
            raise ConfigError(f"{path}:{number}: expected 4 columns (omega, H, direction, phase), got {len(values)}")
        rows.append(values)
    if not rows:
        raise ConfigError(f"{path}: no wave components found")
    data = np.array(rows)
    if not np.all(np.isfinite(data)) or np.any(data[:, 0] <= 0) or np.any(data[:, 1] < 0):
        raise ConfigError(f"{path}: frequencies must be positive and heights non-negative and finite")
    f = data[:, 0] / (2 * np.pi)
    period = _common_period(f)
    if period is None:
        if not direct_sum:
            raise ConfigError(f"{path}: wave frequencies are not on a common grid (multiples of one frequency "
                              "step): the time loop's kinematics tables need one (fowt-sim loads sums such "
                              "components directly)")
        log.info("%s: %d wave frequencies on no common grid: summed directly", path, f.size)
        period = 0.0
    return WaveComponents(f, data[:, 1] / 2.0, np.deg2rad(data[:, 3]), np.deg2rad(data[:, 2]), period)


def write_comp_file(path: str | Path, waves: WaveComponents, header: str = "") -> None:
    lines = [f"! {line}" for line in header.splitlines()]
    lines.append("! columns: omega(rad/s)  H=2a(m)  dir(deg)  phase(deg)")
    for f, a, p, d in zip(waves.frequency_hz, waves.amplitude_m, waves.phase_rad, waves.direction_rad):
        lines.append(f"{2 * np.pi * f:.12f} {2 * a:.10e} {np.rad2deg(d):.6f} {np.rad2deg(p) % 360:.10f}")
    Path(path).write_text("\n".join(lines) + "\n")


def _common_period(f_hz: np.ndarray) -> float | None:
    """The longest period of which every frequency is a harmonic (1 / the frequencies' GCD),
    or None if they are on no common grid."""
    gaps = np.diff(np.unique(np.concatenate([[0.0], f_hz])))
    df = np.min(gaps)
    harmonics = f_hz / df
    if np.max(np.abs(harmonics - np.round(harmonics))) > 1e-6 * max(1.0, harmonics.max()):
        return None
    return float(1.0 / df)


def from_elevation_record(t_s: np.ndarray, eta_m: np.ndarray, x_m: float = 0.0, y_m: float = 0.0,
                          heading_deg: float = 0.0, depth_m: float = 150.0,
                          gravity_m_s2: float = 9.80665, f_max_hz: float | None = None) -> WaveComponents:
    """Decompose a uniformly sampled elevation record measured at (x, y) into long-crested
    components travelling toward ``heading_deg``, by FFT. The record is taken as one period
    of a periodic sea (period = N dt); its mean is removed."""
    t = np.asarray(t_s, dtype=float)
    eta = np.asarray(eta_m, dtype=float)
    if t.ndim != 1 or t.shape != eta.shape or t.size < 8:
        raise ConfigError("elevation record: need matching 1-D time and elevation arrays of at least 8 samples")
    if not np.all(np.isfinite(eta)) or not np.all(np.isfinite(t)):
        raise ConfigError("elevation record: contains NaN or infinite values")
    dt = np.diff(t)
    if np.any(dt <= 0) or np.max(np.abs(dt - dt.mean())) > 1e-6 * dt.mean():
        raise ConfigError("elevation record: samples must be uniformly spaced in increasing time")
    n, step = t.size, float(dt.mean())
    period = n * step
    spectrum_c = np.fft.rfft(eta - eta.mean())
    harmonic = np.arange(1, spectrum_c.size)
    if n % 2 == 0:
        harmonic = harmonic[:-1]  # the Nyquist bin has no phase: leave it out
    if f_max_hz is not None:
        harmonic = harmonic[harmonic / period <= f_max_hz]
    c = spectrum_c[harmonic]
    f = harmonic / period
    amplitude = 2.0 * np.abs(c) / n
    heading = np.deg2rad(heading_deg)
    k = wavenumber(2 * np.pi * f, depth_m, gravity_m_s2)
    # the record starts at t[0]: shift phases to t = 0, and from (x, y) to the origin
    phase = np.angle(c) - 2 * np.pi * f * t[0] + k * (x_m * np.cos(heading) + y_m * np.sin(heading))
    return WaveComponents(f, amplitude, phase, np.full(f.size, heading), period)
