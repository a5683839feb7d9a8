"""Linear (Airy) wave kinematics in finite depth at fixed points, and their time table.

Per component of complex elevation amplitude A at the point (A = a exp(i(phase - k s))):
  u_h = Re[A w  C(z) e^{iwt}],   w = Re[A i w S(z) e^{iwt}],
  a_h = Re[A i w^2 C(z) e^{iwt}], a_z = Re[-A w^2 S(z) e^{iwt}],  p = Re[A rho g P(z) e^{iwt}]
with C = cosh k(z+h)/sinh kh, S = sinh k(z+h)/sinh kh, P = cosh k(z+h)/cosh kh, written in
exponentials so that they stay finite in deep water. Points above the still water line take
the kinematics at z = 0 (no stretching, as HydroDyn with WaveStMod = 0).

``KinematicsTable`` precomputes the seven channels (u_x, u_y, u_z, a_x, a_y, a_z, p) at the
undisplaced strip points (HydroDyn's WaveDisp = 0) over one repeat period by inverse FFT,
and is read with 4-point (cubic) Lagrange interpolation in time. ``BlockSynthesis`` gives
the same table's rows a block at a time (a chirp-z transform of the component sum), so that
a run holds one or two blocks instead of the whole period; ``BlocksAhead`` makes the next
block in a worker thread while a run uses the current ones.
"""
from __future__ import annotations

import math
import time
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numba import njit

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.waves.components import WaveComponents, wavenumber
from fowt_hydro_sim.physics.waves.maccamy_fuchs import point_groups, scaled_waves

CHANNELS = ("u_x", "u_y", "u_z", "a_x", "a_y", "a_z", "p_dyn")
N_CHANNELS = len(CHANNELS)
# 4-point Lagrange interpolation error of a sinusoid is at most 0.0234 (w h)^4: keep it
# below 1e-3 at the highest wave frequency
_MAX_OMEGA_STEP = 0.45


def depth_factors(k: np.ndarray, z_m: np.ndarray, depth_m: float) -> tuple[np.ndarray, ...]:
    """C, S, P of the module docstring for wavenumbers k (..., n_freq) at depths z (..., 1)."""
    z = np.minimum(z_m, 0.0)
    decay_up = np.exp(k * z)  # e^{kz}
    decay_down = np.exp(-k * (z + 2.0 * depth_m))  # e^{-k(z+2h)}
    two_h = np.exp(-2.0 * k * depth_m)
    c = (decay_up + decay_down) / (1.0 - two_h)
    s = (decay_up - decay_down) / (1.0 - two_h)
    p = (decay_up + decay_down) / (1.0 + two_h)
    return c, s, p


class _Components(NamedTuple):
    """The per-component quantities of the kinematics that do not depend on the point."""

    amplitude_m: np.ndarray
    phase_rad: np.ndarray
    omega: np.ndarray
    k: np.ndarray
    cos_b: np.ndarray
    sin_b: np.ndarray

    @classmethod
    def of(cls, waves: WaveComponents, depth_m: float, gravity_m_s2: float) -> _Components:
        omega = 2 * np.pi * waves.frequency_hz
        return cls(waves.amplitude_m, waves.phase_rad, omega, wavenumber(omega, depth_m, gravity_m_s2),
                   np.cos(waves.direction_rad), np.sin(waves.direction_rad))


def complex_amplitudes(waves: WaveComponents, points_m: np.ndarray, depth_m: float,
                       gravity_m_s2: float, density_kg_m3: float) -> np.ndarray:
    """Complex amplitudes (n_points, 7 channels, n_components) of the kinematics."""
    return _channel_amplitudes(_Components.of(waves, depth_m, gravity_m_s2), np.atleast_2d(points_m), depth_m,
                               gravity_m_s2, density_kg_m3)


def _channel_amplitudes(comp: _Components, points: np.ndarray, depth_m: float, gravity_m_s2: float,
                        density_kg_m3: float) -> np.ndarray:
    omega, k, cos_b, sin_b = comp.omega, comp.k, comp.cos_b, comp.sin_b
    s = points[:, :1] * cos_b + points[:, 1:2] * sin_b
    amp = comp.amplitude_m * np.exp(1j * (comp.phase_rad - k * s))  # (n_points, n_freq)
    c, sh, p = depth_factors(k, points[:, 2:3], depth_m)
    out = np.empty((points.shape[0], N_CHANNELS, omega.size), dtype=complex)
    u_h, acc_h = amp * omega * c, amp * 1j * omega**2 * c
    out[:, 0], out[:, 1] = u_h * cos_b, u_h * sin_b
    out[:, 2] = amp * 1j * omega * sh
    out[:, 3], out[:, 4] = acc_h * cos_b, acc_h * sin_b
    out[:, 5] = -amp * omega**2 * sh
    out[:, 6] = amp * density_kg_m3 * gravity_m_s2 * p
    return out


def point_kinematics(waves: WaveComponents, points_m: np.ndarray, t_s: np.ndarray, depth_m: float,
                     gravity_m_s2: float, density_kg_m3: float) -> np.ndarray:
    """Kinematics (n_times, n_points, 7) by direct summation: exact, for short records."""
    amp = complex_amplitudes(waves, points_m, depth_m, gravity_m_s2, density_kg_m3)
    phasor = np.exp(1j * np.outer(np.atleast_1d(t_s), 2 * np.pi * waves.frequency_hz))
    return np.einsum("pcf,tf->tpc", amp, phasor).real


def moving_point_kinematics(waves: WaveComponents, points_m: np.ndarray, t_s: np.ndarray, depth_m: float,
                            gravity_m_s2: float, density_kg_m3: float) -> np.ndarray:
    """Kinematics (n, 7) at n points each at its own time (a point moving with the body), by
    direct summation over the components (compiled): exact, cost n x components."""
    points = np.ascontiguousarray(np.atleast_2d(points_m), dtype=float)
    omega = 2 * np.pi * waves.frequency_hz
    k = wavenumber(omega, depth_m, gravity_m_s2)
    out = np.zeros((points.shape[0], N_CHANNELS))
    _sum_components(points, np.ascontiguousarray(t_s, dtype=float), omega, k, waves.amplitude_m, waves.phase_rad,
                    np.cos(waves.direction_rad), np.sin(waves.direction_rad), depth_m,
                    density_kg_m3 * gravity_m_s2, out)
    return out


def extrapolated_kinematics(waves: WaveComponents, points_m: np.ndarray, t_s: np.ndarray, depth_m: float,
                            gravity_m_s2: float, density_kg_m3: float, step_m: float = 0.01) -> np.ndarray:
    """Kinematics (n, 7) at n points each at its own time, those above z = 0 extrapolated
    linearly from z = 0: value(0) + z d(value)/dz(0) (SeaState's extrapolation stretching,
    WaveStMod 2). The gradient is the one-sided second-order difference over 0, -step, -2 step
    (error (k step)^2 / 3 of it, 3e-6 for a 0.1 rad/m wave)."""
    points = np.atleast_2d(np.asarray(points_m, dtype=float))
    t = np.asarray(t_s, dtype=float)
    height = np.maximum(points[:, 2], 0.0)
    below = points.copy()
    below[:, 2] = np.minimum(points[:, 2], 0.0)
    args = (depth_m, gravity_m_s2, density_kg_m3)
    out = moving_point_kinematics(waves, below, t, *args)
    above = height > 0.0
    if np.any(above):
        surface = below[above]
        values = [out[above]] + [moving_point_kinematics(waves, surface - [0.0, 0.0, j * step_m], t[above], *args)
                                 for j in (1, 2)]
        gradient = (3.0 * values[0] - 4.0 * values[1] + values[2]) / (2.0 * step_m)
        out[above] += height[above, None] * gradient
    return out


@njit(cache=True, fastmath=True)
def _sum_components(points, t, omega, k, amplitude, phase, cos_b, sin_b, depth, rho_g, out):
    """complex_amplitudes times e^{i omega t}, real part, summed, point by point."""
    for i in range(points.shape[0]):
        x, y, z = points[i, 0], points[i, 1], min(points[i, 2], 0.0)
        for f in range(omega.size):
            w, kf = omega[f], k[f]
            theta = w * t[i] + phase[f] - kf * (x * cos_b[f] + y * sin_b[f])
            cos_t, sin_t = math.cos(theta), math.sin(theta)
            up, down, two_h = math.exp(kf * z), math.exp(-kf * (z + 2.0 * depth)), math.exp(-2.0 * kf * depth)
            c, sh, pr = (up + down) / (1.0 - two_h), (up - down) / (1.0 - two_h), (up + down) / (1.0 + two_h)
            a = amplitude[f]
            u_h, acc_h = a * w * c * cos_t, -a * w * w * c * sin_t
            out[i, 0] += u_h * cos_b[f]
            out[i, 1] += u_h * sin_b[f]
            out[i, 2] += -a * w * sh * sin_t
            out[i, 3] += acc_h * cos_b[f]
            out[i, 4] += acc_h * sin_b[f]
            out[i, 5] += -a * w * w * sh * cos_t
            out[i, 6] += a * rho_g * pr * cos_t


def table_step(waves: WaveComponents) -> float:
    """The longest step that divides the repeat period and keeps the interpolation error below
    1e-3 at the highest wave frequency (it need not be a multiple of the model's dt)."""
    f_max = float(np.max(waves.frequency_hz, initial=0.0))
    if f_max <= 0:
        return waves.period_s
    return waves.period_s / np.ceil(waves.period_s * 2 * np.pi * f_max / _MAX_OMEGA_STEP)


_CHUNK_BYTES = 32e6


def period_table(waves: WaveComponents, points: np.ndarray, n_samples: int, depth_m: float, gravity_m_s2: float,
                 density_kg_m3: float, dtype: type, maccamy_fuchs_diameter_m: np.ndarray | None = None) -> np.ndarray:
    """The kinematics at ``points`` over one repeat period in ``n_samples`` rows (n_samples,
    n_points, 7), by inverse FFT; the points with a ``maccamy_fuchs_diameter_m`` > 0 get the
    MacCamy-Fuchs acceleration for it (waves/maccamy_fuchs.py)."""
    harmonic = waves.harmonic
    values = np.zeros((n_samples, points.shape[0], N_CHANNELS), dtype=dtype)
    if harmonic.size == 0:
        return values
    # points in chunks: one transform per chunk (few calls), the spectrum bounded to ~32 MB
    chunk = max(1, int(_CHUNK_BYTES // (16 * N_CHANNELS * (n_samples // 2 + 1))))
    unique = np.unique(harmonic).size == harmonic.size
    for start in range(0, points.shape[0], chunk):
        part = points[start:start + chunk]
        amp = complex_amplitudes(waves, part, depth_m, gravity_m_s2, density_kg_m3)  # (p, 7, f)
        spectrum = np.zeros((n_samples // 2 + 1, part.shape[0] * N_CHANNELS), dtype=complex)
        terms = amp.reshape(-1, harmonic.size).T * (n_samples / 2.0)
        if unique:
            spectrum[harmonic] = terms
        else:  # components sharing a frequency add up
            np.add.at(spectrum, harmonic, terms)
        signal = np.fft.irfft(spectrum, n_samples, axis=0)  # numpy's: no scipy import at start-up
        values[:, start:start + part.shape[0], :] = signal.reshape(n_samples, part.shape[0], N_CHANNELS)
    for diameter, index in point_groups(maccamy_fuchs_diameter_m):
        scaled = scaled_waves(waves, diameter, depth_m, gravity_m_s2)
        values[:, index, 3:6] = period_table(scaled, points[index], n_samples, depth_m, gravity_m_s2, density_kg_m3,
                                             dtype)[:, :, 3:6]
    return values


@dataclass
class KinematicsTable:
    """Kinematics at fixed points over one repeat period, sampled every ``step_s``.

    ``values`` has shape (n_samples, n_points, 7), float32 to halve the memory of long runs
    (relative rounding 6e-8, far below the 1e-3 of the time interpolation).
    """

    values: np.ndarray
    step_s: float
    points_m: np.ndarray

    @classmethod
    def build(cls, waves: WaveComponents, points_m: np.ndarray, step_s: float, depth_m: float,
              gravity_m_s2: float, density_kg_m3: float) -> KinematicsTable:
        points = np.atleast_2d(np.asarray(points_m, dtype=float))
        n_samples = int(round(waves.period_s / step_s))
        if abs(n_samples * step_s - waves.period_s) > 1e-6 * waves.period_s:
            raise InputError(f"wave table step {step_s:g} s does not divide the repeat period "
                             f"{waves.period_s:g} s")
        harmonic = waves.harmonic
        if harmonic.size and harmonic.max() >= n_samples // 2:
            raise InputError(f"wave table step {step_s:g} s is too coarse for the highest wave "
                             f"frequency {waves.frequency_hz.max():g} Hz")
        return cls(period_table(waves, points, n_samples, depth_m, gravity_m_s2, density_kg_m3, np.float32),
                   step_s, points)

    @property
    def period_s(self) -> float:
        return self.values.shape[0] * self.step_s


class BlockSynthesis:
    """Rows of the kinematics table of ``KinematicsTable.build`` (same points, step and time
    grid), ``block_rows`` consecutive rows at a time, for any first row (row r is time r step,
    past the repeat period too): a run holds one block at a time, not the whole period.

    Each block is the component sum evaluated exactly, as a chirp-z transform (Bluestein's
    algorithm): with the components on harmonics k0 + j of 1/T (j < K) and rows n0 + m
    (m < M) of the N-row period,

        sum_j X_j e^{2 pi i (k0+j)(n0+m)/N}
            = e^{i pi (2 k0 (n0+m) + m^2)/N} sum_j [X_j e^{i pi (2 j n0 + j^2)/N}] e^{-i pi (m-j)^2/N},

    a linear convolution done by FFT of length L >= K + M - 1, O(L log L) per point and
    channel; every phase is reduced modulo 2N in integers first, so the long chirps keep
    full precision. A long-crested sea (one direction) takes five transforms per point, not
    seven: the horizontal velocity and acceleration along the heading, split after. A block
    costs about (K + M) / M times a row of the one-shot inverse FFT: the cost per simulated
    second grows with the repeat period (K is proportional to it), the memory does not.
    """

    def __init__(self, waves: WaveComponents, points_m: np.ndarray, step_s: float, block_rows: int,
                 depth_m: float, gravity_m_s2: float, density_kg_m3: float,
                 maccamy_fuchs_diameter_m: np.ndarray | None = None):
        self.points_m = np.atleast_2d(np.asarray(points_m, dtype=float))
        # the points whose accelerations are MacCamy-Fuchs scaled: from a synthesis of their own
        self._scaled = [(index, BlockSynthesis(scaled_waves(waves, diameter, depth_m, gravity_m_s2),
                                               self.points_m[index], step_s, block_rows, depth_m, gravity_m_s2,
                                               density_kg_m3))
                        for diameter, index in point_groups(maccamy_fuchs_diameter_m)]
        self.n_samples = int(round(waves.period_s / step_s))
        if abs(self.n_samples * step_s - waves.period_s) > 1e-6 * waves.period_s:
            raise InputError(f"wave table step {step_s:g} s does not divide the repeat period "
                             f"{waves.period_s:g} s")
        if block_rows < 1 or waves.harmonic.size == 0:
            raise ValueError("block synthesis: needs wave components and at least one row per block")
        self.step_s, self.block_rows = float(step_s), int(block_rows)
        self._depth = (depth_m, gravity_m_s2, density_kg_m3)
        self._components = _Components.of(waves, depth_m, gravity_m_s2)
        self._first_harmonic = int(waves.harmonic.min())
        self._offsets = waves.harmonic - self._first_harmonic  # j of each component
        self._unique = np.unique(self._offsets).size == self._offsets.size
        self._dense = np.array_equal(self._offsets, np.arange(self._offsets.size))  # every harmonic once, in order
        heading = waves.direction_rad[0]
        self._heading = (np.cos(heading), np.sin(heading)) if np.all(waves.direction_rad == heading) else None
        n_harmonics = int(self._offsets.max()) + 1
        import scipy.fft  # here, not at start-up: only blocked runs need it
        # a 5-smooth length (2, 3, 5 only): the complex lengths scipy would choose may have 7 and 11
        # as factors, which made the 3-hour LC5.3 block's transforms 25 % slower (7,546 = 2 x 7^3 x 11)
        self._fft_rows = scipy.fft.next_fast_len(n_harmonics + self.block_rows - 1, real=True)
        lag = np.arange(self._fft_rows, dtype=np.int64)  # lags 0..M-1, then -(L-M)..-1
        lag[lag >= self.block_rows] -= self._fft_rows
        self._chirp_spectrum = scipy.fft.fft(self._phase(-(lag * lag)))
        self._harmonics = np.arange(n_harmonics, dtype=np.int64)
        self._rows = np.arange(self.block_rows, dtype=np.int64)

    def _phase(self, numerator: np.ndarray) -> np.ndarray:
        """e^{i pi numerator / N} for integer numerators, reduced modulo 2N first."""
        return np.exp(1j * np.pi * (numerator % (2 * self.n_samples)) / self.n_samples)

    def rows(self, first_row: int, out: np.ndarray | None = None) -> np.ndarray:
        """Rows first_row .. first_row + block_rows - 1: (block_rows, n_points, 7), float64,
        written into ``out`` if given (an array of that shape)."""
        import scipy.fft
        n = self.n_samples
        start = int(first_row) % n
        j, m = self._harmonics, self._rows
        into = self._phase(2 * j * start + j * j)[self._offsets]  # per component
        out_phase = self._phase(2 * self._first_harmonic * ((start + m) % n) + m * m)
        if out is None:
            out = np.empty((self.block_rows, self.points_m.shape[0], N_CHANNELS))
        n_transforms = N_CHANNELS if self._heading is None else N_CHANNELS - 2
        n_harmonics = self._offsets.size
        spectrum = np.zeros((n_transforms, self._fft_rows), dtype=complex)  # the rest stays zero when dense
        if self._heading is not None:  # u_x, u_y = cos, sin u_h (a_x, a_y likewise)
            split, scale = [0, 0, 1, 2, 2, 3, 4], np.array([*self._heading, 1.0, *self._heading, 1.0, 1.0])
        for i, point in enumerate(self.points_m):  # one point at a time bounds the temporaries
            amp = self._spectra(point, into)
            if self._dense:
                spectrum[:, :n_harmonics] = amp
            else:
                spectrum[:] = 0.0
                if self._unique:
                    spectrum[:, self._offsets] = amp
                else:
                    np.add.at(spectrum, (slice(None), self._offsets), amp)
            convolved = scipy.fft.ifft(scipy.fft.fft(spectrum, axis=1) * self._chirp_spectrum, axis=1,
                                       overwrite_x=True)
            values = (convolved[:, :self.block_rows] * out_phase).real.T
            out[:, i, :] = values if self._heading is None else values[:, split] * scale
        for index, synthesis in self._scaled:
            out[:, index, 3:6] = synthesis.rows(first_row)[:, :, 3:6]
        return out

    def _spectra(self, point: np.ndarray, into: np.ndarray) -> np.ndarray:
        """The point's transforms' spectra times ``into`` (n_transforms, n_components): the
        seven channels', or for a long-crested sea five: the velocity and acceleration along
        the heading (split into x and y after the transform), vertical, and the pressure."""
        if self._heading is None:
            return _channel_amplitudes(self._components, point[None], *self._depth)[0] * into
        comp = self._components
        depth_m, gravity_m_s2, density_kg_m3 = self._depth
        s = point[0] * comp.cos_b + point[1] * comp.sin_b
        base = comp.amplitude_m * np.exp(1j * (comp.phase_rad - comp.k * s)) * into
        c, sh, p = depth_factors(comp.k, np.array([point[2]]), depth_m)
        u_h, u_z = base * (comp.omega * c), base * (1j * comp.omega * sh)  # as _channel_amplitudes
        return np.stack([u_h, u_z, u_h * (1j * comp.omega), u_z * (1j * comp.omega),
                         base * (density_kg_m3 * gravity_m_s2 * p)])


class BlocksAhead:
    """The blocks of a ``BlockSynthesis`` for a run that moves forward: ``prepare(b)`` starts
    making block b in a worker thread (into one spare block; numpy's and scipy's transforms
    release the GIL) while the run uses the blocks before it; ``take(b, out)`` writes block
    b into ``out``: the worker's rows if b was prepared (waiting for them only if the run
    has caught up with the worker), else made now in the calling thread. The same rows
    either way, bit for bit. ``ahead`` False makes every block in ``take``."""

    def __init__(self, synthesis: BlockSynthesis, ahead: bool = True):
        self.synthesis = synthesis
        self.block_rows = synthesis.block_rows
        self.ahead = ahead
        self.waited_s = 0.0  # wall seconds ``take`` spent: waiting for the worker or making a block
        self.taken = 0  # blocks taken
        self.made_ahead = 0  # of which from the worker
        self._worker: ThreadPoolExecutor | None = None
        self._spare: np.ndarray | None = None
        self._pending: tuple[int, Future] | None = None  # the block being made ahead

    def prepare(self, block: int) -> None:
        """Start making ``block`` in the worker (a block prepared before and not taken is
        dropped)."""
        if not self.ahead or (self._pending is not None and self._pending[0] == block):
            return
        if self._pending is not None:
            self._pending[1].cancel()  # if it runs already, it ends before the next one starts
        if self._worker is None:
            self._worker = ThreadPoolExecutor(max_workers=1, thread_name_prefix="wave_blocks")
            self._spare = np.empty((self.block_rows, self.synthesis.points_m.shape[0], N_CHANNELS))
        self._pending = (block, self._worker.submit(self.synthesis.rows, block * self.block_rows, self._spare))

    def take(self, block: int, out: np.ndarray) -> None:
        """Block ``block``'s rows into ``out`` (block_rows, n_points, 7)."""
        start = time.perf_counter()
        self.taken += 1
        if self._pending is not None and self._pending[0] == block:
            self._pending[1].result()  # the worker is done with the spare (one job at a time)
            self._pending = None
            out[:] = self._spare
            self.made_ahead += 1
        else:
            self.synthesis.rows(block * self.block_rows, out)
        self.waited_s += time.perf_counter() - start
