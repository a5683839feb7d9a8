"""The MacCamy-Fuchs diffraction correction of the fluid acceleration, as OpenFAST's SeaState
applies it (``Waves.f90``, MCFD): each wave component's acceleration is scaled by

    C(ka) = 4 / (pi (ka)^2 |H1'(ka)|),   |H1'(x)| = sqrt(J1'(x)^2 + Y1'(x)^2),   a = D / 2,

and HydroDyn's transverse fluid inertia of a member flagged MCF (its Cp given as ``MCF``) is
rho (pi D^2 / 4) times that acceleration, in place of rho (Ca + Cp) (pi D^2 / 4) times the
incident one (``Morison.f90``); its added mass (Ca on the body acceleration), axial terms and
drag keep the incident kinematics. As ka -> 0, C -> 2: Ca = Cp = 1. C is real: SeaState scales
the amplitude only; the textbook MacCamy-Fuchs force also leads the incident acceleration by
delta = atan(J1'(ka) / Y1'(ka)), which SeaState leaves out (so does this module).

A vertical cylinder from the seabed through the surface in a regular wave of height H then
carries the textbook MacCamy-Fuchs force amplitude, |F| = 4 rho g (H/2) tanh(kh) / (k^2 |H1'(ka)|)
(checked in ``test/test_maccamy_fuchs.py``).
"""
from __future__ import annotations

import numpy as np

from fowt_hydro_sim.physics.waves.components import WaveComponents, wavenumber


def inertia_factor(omega_rad_s: np.ndarray, diameter_m: float, depth_m: float, gravity_m_s2: float) -> np.ndarray:
    """SeaState's scaling C(ka) of each component's acceleration (2 in the slender limit)."""
    from scipy.special import jvp, yvp  # here, not at start-up: only MacCamy-Fuchs members need it
    ka = wavenumber(np.asarray(omega_rad_s, dtype=float), depth_m, gravity_m_s2) * diameter_m / 2.0
    out = np.full(ka.shape, 2.0)
    positive = ka > 0
    x = ka[positive]
    out[positive] = 4.0 / (np.pi * x * x * np.hypot(jvp(1, x), yvp(1, x)))
    return out


def scaled_waves(waves: WaveComponents, diameter_m: float, depth_m: float, gravity_m_s2: float) -> WaveComponents:
    """The components with each amplitude times C(ka): their accelerations are SeaState's
    MacCamy-Fuchs accelerations (only the accelerations are meant to be taken from them)."""
    factor = inertia_factor(2 * np.pi * waves.frequency_hz, diameter_m, depth_m, gravity_m_s2)
    return WaveComponents(waves.frequency_hz, waves.amplitude_m * factor, waves.phase_rad, waves.direction_rad,
                          waves.period_s)


def point_groups(diameter_m: np.ndarray | None) -> list[tuple[float, np.ndarray]]:
    """(diameter, indices) of the kinematics points whose acceleration is MacCamy-Fuchs
    scaled, one group per diameter (``diameter_m`` per point, 0: not scaled)."""
    if diameter_m is None:
        return []
    d = np.asarray(diameter_m, dtype=float)
    return [(float(value), np.flatnonzero(d == value)) for value in np.unique(d[d > 0])]
