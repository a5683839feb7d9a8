"""Streamed linear wave kinematics at fixed points from a point elevation measurement.

The elevation eta(t) is measured at one point (x_m, y_m) and arrives as a stream of samples
every ``sample_dt_s``. For a long-crested sea travelling toward heading b, linear (Airy)
theory makes each kinematics channel c (``kinematics.CHANNELS``) at each point p a linear
filter of eta with frequency response

    H_pc(w) = T_c(w, z_p) exp(-i k(w) d_p),   d_p = (x_p - x_m) cos b + (y_p - y_m) sin b,

T_c the channel's transfer function of ``kinematics`` (u_h = w C, u_z = i w S, ...) and d_p the
along-wave distance from the measurement point (positive downstream: the wave arrives later).
H is not causal: an upstream point (d_p < 0) sees a wave group |d_p| / c_g(w) seconds before
the probe does, and the velocity's factor w (a Hilbert-transform-like operation) and the band
limitation below spread every kernel both ways in time. The stream therefore runs with a
preview delay D (``preview_s``): after the sample of time t it outputs the kinematics of time
t - D, by a FIR filter kin(t - D) = sum_n h[n] eta(t - n dt), n = 0 .. N - 1.

Design (frequency sampling): the desired response H_pc(w) B(f) exp(-i w D), with B = 1 inside
[f_low + taper_low, f_high - taper_high], raised-cosine tapers down to 0 at f_low and f_high
and 0 outside [f_low, f_high] (no mean level, drift or sensor noise in the kinematics; the
accelerations' w^2 does not amplify high-frequency noise), is sampled on a grid of M >= 4 N
frequencies, inverse FFT'd, and the first N = kernel_s / dt taps are kept under a Tukey
window (flat over 1 - TUKEY_ALPHA of the kernel, cosine tapers at both ends), less the
Blackman pulse that makes the gain at f = 0 exactly zero (the truncation would otherwise leak
~5e-3 of the in-band gain there: a sensor offset or the tide into u and p). Dispersion puts
each frequency's part of the kernel at its own group delay D + d_p / c_g(w), anywhere in the
kernel: a flat-top window leaves all of them untouched and only smooths the truncation of the
tails, where a window peaked at the kernel's middle would attenuate the off-centre groups of
upstream and downstream points (a group 20 s off the centre of a 120 s kernel keeps 65 % of
its amplitude under a Kaiser(8) window, 75 % under a Hann window).

What D must cover (``required_support_s``): the travel time of the wave groups from the
farthest upstream point to the probe, plus the non-causal half of the band-limited pulse. A
raised-cosine edge of width df rings for about 1 / df seconds (decaying as t^-3) at the edge's
frequencies, which travel at that edge's group velocity; so, taking the larger over the two
edges, D >= upstream distance / c_g(edge) + 1 / taper(edge), with c_g at f_high for the upper
edge (the slowest passed groups) and at f_low + taper_low for the lower one. The kernel's
causal side, kernel_s - D, must cover the same with the farthest downstream distance. At this
minimum the relative error of the filter's response is 1e-3 to 2e-3 in the middle of the flat
band and up to 5e-2 at its edges; it grows steeply below it (order 1 at the flat band's edges
at 0.75 of it) and falls fast above it (15 s more: 2e-4 mid-band, 6e-3 at worst, at the lower
edge of the flat band). For windmoor12 (probe at the platform centre, strip points up to
35.2 m from it; default band 0.01-0.8 Hz with tapers 0.03 / 0.1 Hz, flat over 0.04-0.7 Hz,
which holds 0.5-5 f_p of the load cases with Tp 7.1-12.5 s) the minimum is at most
36 + 10 = 46 s; preview_s = 60 s and kernel_s = 2 preview_s = 120 s give ~1e-4 relative RMS
error against the exact kinematics of an irregular sea inside the flat band
(test/test_wave_stream.py).

Cost: one (7 n_points + n_elevation_points, N) @ (N,) float64 product per sample, read from a
doubled ring buffer of 2 N samples (the N newest samples are always contiguous); memory is
fixed. For windmoor12's 194 points and a 120 s kernel on the development machine (2 cores,
OpenBLAS): 0.1 ms per sample at dt = 0.25 s, 0.11-0.27 ms at 0.1 s (2 / 1 BLAS threads),
0.33-0.71 ms at 0.05 s. A 20 Hz probe can push every other sample with sample_dt_s = 0.1:
only content within 0.8 Hz of 10 Hz (or its multiples) would alias into the band, and ocean
waves have none there.
"""
from __future__ import annotations

import logging

import numpy as np
import scipy.fft

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.waves.components import wavenumber
from fowt_hydro_sim.physics.waves.kinematics import CHANNELS, N_CHANNELS, depth_factors

log = logging.getLogger(__name__)

DEFAULT_BAND_HZ = (0.01, 0.8)
DEFAULT_TAPER_HZ = (0.03, 0.1)
TUKEY_ALPHA = 0.25  # fraction of the kernel under the window's cosine tapers
_GRID_FACTOR = 4  # design grid length M >= 4 N: the ideal kernel's wrap-around is negligible
_P_DYN = CHANNELS.index("p_dyn")


def along_wave_distance_m(points_xy_m: np.ndarray, measurement_xy_m: np.ndarray,
                          heading_deg: float) -> np.ndarray:
    """d = (x - x_m) cos b + (y - y_m) sin b of each point (n, >= 2): positive downstream."""
    points = np.atleast_2d(np.asarray(points_xy_m, dtype=float))
    b = np.deg2rad(heading_deg)
    rel = points[:, :2] - np.asarray(measurement_xy_m, dtype=float)
    return rel[:, 0] * np.cos(b) + rel[:, 1] * np.sin(b)


def group_velocity_m_s(frequency_hz: np.ndarray, depth_m: float, gravity_m_s2: float) -> np.ndarray:
    """c_g = (w / k) (1 + 2kh / sinh 2kh) / 2, finite in deep water (frequency > 0)."""
    omega = 2 * np.pi * np.asarray(frequency_hz, dtype=float)
    k = wavenumber(omega, depth_m, gravity_m_s2)
    two_kh = 2.0 * k * depth_m
    ratio = 2.0 * two_kh * np.exp(-two_kh) / (1.0 - np.exp(-2.0 * two_kh))  # 2kh / sinh 2kh
    return 0.5 * omega / k * (1.0 + ratio)


def transfer_functions(frequency_hz: np.ndarray, points_m: np.ndarray, measurement_xy_m: np.ndarray,
                       heading_deg: float, depth_m: float, gravity_m_s2: float,
                       density_kg_m3: float) -> np.ndarray:
    """H (n_freq, n_points, 7) from the elevation at the measurement point to the kinematics
    channels at the points (z > 0 taken at z = 0), for frequencies > 0."""
    points = np.atleast_2d(np.asarray(points_m, dtype=float))
    omega = 2 * np.pi * np.asarray(frequency_hz, dtype=float)[:, None]
    k = wavenumber(omega[:, 0], depth_m, gravity_m_s2)[:, None]
    b = np.deg2rad(heading_deg)
    shift = np.exp(-1j * k * along_wave_distance_m(points, measurement_xy_m, heading_deg))
    c, s, p = depth_factors(k, points[:, 2], depth_m)
    out = np.empty((omega.size, points.shape[0], N_CHANNELS), dtype=complex)
    u_h, acc_h = omega * c * shift, 1j * omega**2 * c * shift
    out[..., 0], out[..., 1] = u_h * np.cos(b), u_h * np.sin(b)
    out[..., 2] = 1j * omega * s * shift
    out[..., 3], out[..., 4] = acc_h * np.cos(b), acc_h * np.sin(b)
    out[..., 5] = -omega**2 * s * shift
    out[..., 6] = density_kg_m3 * gravity_m_s2 * p * shift
    return out


def band_weights(frequency_hz: np.ndarray, band_hz: tuple[float, float],
                 taper_hz: tuple[float, float]) -> np.ndarray:
    """B(f): 0 outside the band, raised-cosine tapers of the given widths inside its edges, 1
    between them."""
    f = np.asarray(frequency_hz, dtype=float)
    (f_low, f_high), (taper_low, taper_high) = band_hz, taper_hz
    rise = np.clip((f - f_low) / taper_low, 0.0, 1.0)
    fall = np.clip((f_high - f) / taper_high, 0.0, 1.0)
    return 0.25 * (1.0 - np.cos(np.pi * rise)) * (1.0 - np.cos(np.pi * fall))


def required_support_s(points_m: np.ndarray, measurement_xy_m: np.ndarray, heading_deg: float,
                       depth_m: float, gravity_m_s2: float, band_hz: tuple[float, float],
                       taper_hz: tuple[float, float]) -> tuple[float, float]:
    """The minimum (preview_s, kernel_s - preview_s): for each band edge, the farthest upstream
    (downstream) point's group travel time at the edge's slowest frequency plus the edge's
    ringing time 1 / taper width; the larger of the two edges."""
    d = along_wave_distance_m(points_m, measurement_xy_m, heading_deg)
    edge_hz = np.array([band_hz[0] + taper_hz[0], band_hz[1]])
    slowness_s_m = 1.0 / group_velocity_m_s(edge_hz, depth_m, gravity_m_s2)
    ringing_s = 1.0 / np.asarray(taper_hz, dtype=float)
    return (float(np.max(max(0.0, -d.min()) * slowness_s_m + ringing_s)),
            float(np.max(max(0.0, d.max()) * slowness_s_m + ringing_s)))


def tukey_window(n: int, alpha: float) -> np.ndarray:
    """The symmetric Tukey (tapered cosine) window of ``n`` points: cosine tapers over a fraction
    ``alpha`` of its length, flat between (``scipy.signal.windows.tukey``'s definition)."""
    if n < 2 or alpha <= 0.0:
        return np.ones(n)
    x = np.arange(n) / (n - 1)
    taper = np.minimum(x, 1.0 - x) / (alpha / 2.0)  # < 1 inside the tapers
    return np.where(taper < 1.0, 0.5 * (1.0 - np.cos(np.pi * np.minimum(taper, 1.0))), 1.0)


def design_taps(points_m: np.ndarray, measurement_xy_m: np.ndarray, heading_deg: float,
                depth_m: float, gravity_m_s2: float, density_kg_m3: float, sample_dt_s: float,
                preview_s: float, band_hz: tuple[float, float], taper_hz: tuple[float, float],
                n_taps: int) -> np.ndarray:
    """FIR taps h (n_points, 7, n_taps), kin(t - preview) = sum_n h[n] eta(t - n dt), by
    frequency sampling of the band-limited, delayed response, a Tukey window and a zero gain
    at f = 0."""
    points = np.atleast_2d(np.asarray(points_m, dtype=float))
    n_grid = 1 << int(np.ceil(np.log2(_GRID_FACTOR * n_taps)))
    f = scipy.fft.rfftfreq(n_grid, sample_dt_s)
    weight = band_weights(f, band_hz, taper_hz)
    inside = weight > 0
    factor = weight[inside] * np.exp(-2j * np.pi * f[inside] * preview_s)
    window = tukey_window(n_taps, TUKEY_ALPHA)
    taps = np.empty((points.shape[0], N_CHANNELS, n_taps))
    response = np.zeros((f.size, N_CHANNELS), dtype=complex)
    for i, point in enumerate(points):  # one point at a time bounds the temporaries
        response[inside] = factor[:, None] * transfer_functions(
            f[inside], point, measurement_xy_m, heading_deg, depth_m, gravity_m_s2, density_kg_m3)[:, 0]
        taps[i] = (scipy.fft.irfft(response, n_grid, axis=0)[:n_taps] * window[:, None]).T
    # the truncation leaks ~5e-3 of the in-band gain to f = 0 (a sensor offset, the tide): null it
    # with a Blackman pulse, whose spectrum is below 1.3e-3 of its peak beyond 3 / kernel_s
    pulse = np.blackman(n_taps)
    return taps - taps.sum(axis=-1, keepdims=True) * (pulse / pulse.sum())


class ElevationStream:
    """Causal FIR kinematics (n_points, 7) at fixed points, delayed by ``preview_s``, from a
    stream of elevation samples measured at ``measurement_xy_m``; optionally also the elevation
    at ``elevation_points_xy_m`` (e.g. the origin) through the same filters.

    ``push`` returns None until ``n_taps`` samples are in (no output from a partial history),
    then the kinematics at (time of the pushed sample - preview_s) for every sample.
    """

    def __init__(self, points_m: np.ndarray, measurement_xy_m: tuple[float, float], heading_deg: float,
                 depth_m: float, gravity_m_s2: float, density_kg_m3: float, sample_dt_s: float,
                 preview_s: float, band_hz: tuple[float, float] = DEFAULT_BAND_HZ,
                 kernel_s: float | None = None, taper_hz: tuple[float, float] = DEFAULT_TAPER_HZ,
                 elevation_points_xy_m: np.ndarray | None = None):
        points = np.atleast_2d(np.asarray(points_m, dtype=float))
        elevation_xy = np.zeros((0, 2)) if elevation_points_xy_m is None else \
            np.atleast_2d(np.asarray(elevation_points_xy_m, dtype=float))
        if points.ndim != 2 or points.shape[1] != 3 or elevation_xy.shape[1] != 2:
            raise ValueError("wave stream: points_m must be (n, 3) and elevation_points_xy_m (n, 2)")
        if not sample_dt_s > 0:
            raise InputError(f"wave stream: sample_dt_s must be positive, got {sample_dt_s}")
        f_low, f_high = band_hz
        nyquist_hz = 0.5 / sample_dt_s
        if not 0.0 <= f_low < f_high < nyquist_hz:
            raise InputError(f"wave stream: band_hz {band_hz} must satisfy 0 <= low < high < the "
                             f"Nyquist frequency {nyquist_hz:g} Hz")
        if not (min(taper_hz) > 0 and sum(taper_hz) <= f_high - f_low):
            raise InputError(f"wave stream: taper_hz {taper_hz} must be positive and fit in the band {band_hz}")
        kernel_s = 2.0 * preview_s if kernel_s is None else kernel_s
        all_points = np.vstack([points, np.column_stack([elevation_xy, np.zeros(len(elevation_xy))])])
        need_preview, need_causal = required_support_s(all_points, measurement_xy_m, heading_deg, depth_m,
                                                       gravity_m_s2, band_hz, taper_hz)
        if not preview_s >= need_preview:  # NaN too
            raise InputError(f"wave stream: preview_s {preview_s:g} s is too short; it must be at least "
                             f"{need_preview:.1f} s (the wave groups' travel time from the farthest upstream "
                             f"point plus the band edges' ringing 1 / taper_hz: see required_support_s)")
        if not kernel_s - preview_s >= need_causal:
            raise InputError(f"wave stream: kernel_s {kernel_s:g} s is too short; it must be at least "
                             f"preview_s + {need_causal:.1f} s = {preview_s + need_causal:.1f} s")
        self._preview_s = float(preview_s)
        self._n_points = points.shape[0]
        n_taps = int(round(kernel_s / sample_dt_s))
        taps = design_taps(all_points, measurement_xy_m, heading_deg, depth_m, gravity_m_s2, density_kg_m3,
                           sample_dt_s, preview_s, band_hz, taper_hz, n_taps)
        rows = [taps[:self._n_points].reshape(-1, n_taps),
                taps[self._n_points:, _P_DYN] / (density_kg_m3 * gravity_m_s2)]  # p(z=0) = rho g eta
        # columns from the oldest sample to the newest, as the ring buffer's window
        self._taps = np.ascontiguousarray(np.vstack(rows)[:, ::-1])
        self._buffer = np.zeros(2 * n_taps)  # each sample twice: the window is always contiguous
        self._count = 0
        self._elevation_m: np.ndarray | None = None
        log.info("wave stream: %d points, %d elevation points, %d taps of %g s, preview %g s, band %g-%g Hz",
                 self._n_points, len(elevation_xy), n_taps, sample_dt_s, preview_s, f_low, f_high)

    @property
    def delay_s(self) -> float:
        """The output's delay behind the newest sample (= preview_s)."""
        return self._preview_s

    @property
    def n_taps(self) -> int:
        return self._taps.shape[1]

    @property
    def elevation_m(self) -> np.ndarray | None:
        """Elevation at the elevation points at the time of the last returned kinematics."""
        return None if self._elevation_m is None else self._elevation_m.copy()

    def push(self, elevation_m: float) -> np.ndarray | None:
        """Append the next sample; the kinematics (n_points, 7) at its time - delay_s, or None
        while fewer than n_taps samples are in."""
        value = float(elevation_m)
        if not np.isfinite(value):
            raise InputError(f"wave stream: elevation sample {elevation_m!r} is not finite")
        n = self.n_taps
        slot = self._count % n
        self._buffer[slot] = self._buffer[slot + n] = value
        self._count += 1
        if self._count < n:
            return None
        out = self._taps @ self._buffer[slot + 1:slot + 1 + n]
        self._elevation_m = out[self._n_points * N_CHANNELS:]
        return out[:self._n_points * N_CHANNELS].reshape(self._n_points, N_CHANNELS)
