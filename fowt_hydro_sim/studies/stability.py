"""The platform's surge and pitch modes with the rotor and its controller (``fowt-sim
stability``): natural frequency and damping ratio of each, so that a user sees a poorly
or negatively damped mode before a long run.

Two estimates, for any platform, turbine and controller:

- **free decay of the coupled loop** (``decay_modes``): the offline loop (platform model +
  rotor + ROSCO, ``turbine.coupled``) in still water and steady wind, started a small
  surge and pitch step away from its static offset; the modes identified from the
  response by the eigensystem realisation algorithm (ERA: a Hankel matrix of the surge
  and pitch responses, its SVD, the realised state matrix's eigenvalues); the same for
  the platform alone and with the rotor's controls held (open loop: blade pitch and
  generator torque fixed at the operating point, as OpenFAST's linearisation holds its
  inputs);
- **quasi-steady aerodynamic damping** (``aerodynamic_damping``): dT/dU at the operating
  point, with the controls held and with the controller's quasi-steady response (above
  rated the pitch that holds the aerodynamic torque at rated; below rated the rotor speed
  that holds the optimal tip-speed ratio), as a damping ratio of each mode
  (c / (2 m omega), c = dT/dU and dT/dU h^2 about the platform's reference point).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fowt_hydro_sim.physics.config import ConfigError, load_platform
from fowt_hydro_sim.physics.model import PlatformModel, RunResult
from fowt_hydro_sim.turbine.coupled import restoring, run_coupled, static_offset, turbine_on_platform
from fowt_hydro_sim.turbine.description import TurbineDescription
from fowt_hydro_sim.turbine.performance import RotorCoefficients
from fowt_hydro_sim.turbine.rotor import aero_loads, steady_operating_point
from fowt_hydro_sim.turbine.wind import Wind

SURGE, HEAVE, PITCH = 0, 2, 4
# the platform's rigid-body modes: a frequency band [Hz] and the DOF each moves most
MODES = {"surge": ((0.003, 0.03), SURGE), "pitch": ((0.015, 0.1), PITCH)}
HANKEL_ROWS = 60  # block rows of the Hankel matrix (60 x 0.5 s: longer than a pitch period)
KICK = np.array([0.5, 0.0, 0.0, 0.0, 0.005, 0.0])  # the decays' start: small, so that the drag stays near linear
SAMPLE_S = 0.5  # the responses' step for the identification
ERA_ORDER = 12  # states of the realisation: the modes below ~1 Hz, the offset and some room for noise


@dataclass(frozen=True)
class Mode:
    """A platform mode: its frequency and damping ratio (fraction of critical; negative:
    growing)."""

    frequency_hz: float
    damping_ratio: float

    @property
    def period_s(self) -> float:
        return 1.0 / self.frequency_hz


def era_modes(time_s: np.ndarray, response: np.ndarray,
              order: int = ERA_ORDER) -> list[tuple[float, float, np.ndarray]]:
    """The oscillating modes of a free response (n samples, k channels at a constant step)
    by the eigensystem realisation algorithm: (frequency [Hz], damping ratio, |mode shape|
    over the channels, each channel scaled to unit range); a constant offset is a pole at
    z = 1 and is left out."""
    dt = float(time_s[1] - time_s[0])
    y = response - response.mean(axis=0)
    y = y / np.maximum(np.abs(y).max(axis=0), 1e-30)
    n, k = y.shape
    rows = max(order, min(n // 4, HANKEL_ROWS))
    cols = n - rows - 1
    if cols < 2 * order:
        raise ConfigError(f"decay of {time_s[-1] - time_s[0]:g} s: too short to identify the modes")
    h0 = np.array([y[j:j + rows].ravel() for j in range(cols)]).T  # block Hankel matrix (rows k, cols)
    h1 = np.array([y[j + 1:j + 1 + rows].ravel() for j in range(cols)]).T  # shifted one step
    u, s, vt = np.linalg.svd(h0, full_matrices=False)
    u, s, vt = u[:, :order], s[:order], vt[:order]
    root = np.diag(1 / np.sqrt(s))
    a = root @ u.T @ h1 @ vt.T @ root
    c = (u @ np.diag(np.sqrt(s)))[:k]  # the output matrix: the first block row
    values, vectors = np.linalg.eig(a)
    out = []
    for z, vector in zip(values.astype(complex), vectors.T):
        pole = np.log(z) / dt
        if pole.imag > 1e-6:
            out.append((abs(pole.imag) / (2 * math.pi), -pole.real / abs(pole), np.abs(c @ vector)))
    return out


def pick(modes: list[tuple[float, float, np.ndarray]], band_hz: tuple[float, float], channel: int) -> Mode | None:
    """The mode in a frequency band that moves ``channel`` most against the other channels
    (the platform's surge or pitch mode; a heave mode or noise moves others), or None."""
    inside = [m for m in modes if band_hz[0] <= m[0] <= band_hz[1] and abs(m[1]) < 0.9]
    if not inside:
        return None
    best = max(inside, key=lambda m: m[2][channel] / max(m[2].sum(), 1e-30) * min(1.0, m[2][channel] / 1e-3))
    return Mode(best[0], best[1])


def identified(result: RunResult) -> dict[str, Mode | None]:
    """The surge and pitch modes of a decay (its surge, heave and pitch x 100 m, resampled)."""
    step = max(1, int(round(SAMPLE_S / float(result.time_s[1] - result.time_s[0]))))
    channels = [SURGE, HEAVE, PITCH]
    response = result.motion[::step][:, channels] * np.array([1.0, 1.0, 100.0])
    modes = era_modes(result.time_s[::step], response)
    return {name: pick(modes, band, channels.index(dof)) for name, (band, dof) in MODES.items()}


def platform_decay(platform: str, mooring: str = "", duration_s: float = 600.0) -> dict[str, Mode | None]:
    """The platform's surge and pitch modes alone (no turbine) in still water."""
    model = PlatformModel(load_platform(platform), None, dt_s=0.05, mooring_model=mooring)
    at_rest, stiffness = restoring(model)
    model.reset(motion=np.linalg.solve(stiffness, at_rest) + KICK)
    return identified(model.run(duration_s, output_interval_s=SAMPLE_S))


def coupled_decay(platform: str, turbine: str, wind_m_s: float, mooring: str = "", duration_s: float = 600.0,
                  held: bool = False, discon_changes: str = "") -> dict[str, Mode | None]:
    """The surge and pitch modes of the platform with the rotor and ROSCO (``held``: the
    blade pitch and generator torque held at the operating point; ``discon_changes``: entries
    of its DISCON.IN replaced) in steady wind."""
    chosen = load_platform(platform)
    model = PlatformModel(chosen, None, dt_s=0.05, mooring_model=mooring)
    rotor = turbine_on_platform(turbine, chosen, Wind(speed_m_s=wind_m_s), held=held, discon_changes=discon_changes)
    try:
        model.reset(motion=static_offset(model, rotor) + KICK)
        parts = list(run_coupled(model, rotor, duration_s, SAMPLE_S))
    finally:
        rotor.close()
    return identified(RunResult.joined([p.result for p in parts]))


@dataclass(frozen=True)
class AeroDamping:
    """dT/dU at the operating point [N s/m]: controls held and with the controller's
    quasi-steady response; the damping ratios they give the surge and pitch modes."""

    thrust_n: float
    held_n_s_m: float
    controlled_n_s_m: float
    surge_held: float
    surge_controlled: float
    pitch_held: float
    pitch_controlled: float


def aerodynamic_damping(turbine: TurbineDescription, coefficients: RotorCoefficients, wind_m_s: float,
                        thrust_height_m: float, mass: np.ndarray, stiffness: np.ndarray) -> AeroDamping:
    """The quasi-steady aerodynamic damping of the surge and pitch modes (``mass``,
    ``stiffness``: the platform's 6x6 at rest; each mode taken as its own DOF, c / (2 sqrt(k m)))."""
    speed, pitch, _ = steady_operating_point(turbine, coefficients, wind_m_s)
    du = 0.01 * wind_m_s

    def loads(u: float, omega: float, beta: float) -> tuple[float, float]:
        return aero_loads(turbine, coefficients, u, omega, beta)

    thrust = loads(wind_m_s, speed, pitch)[0]
    held = (loads(wind_m_s + du, speed, pitch)[0] - loads(wind_m_s - du, speed, pitch)[0]) / (2 * du)
    # the controller's quasi-steady answer to U + du: the steady operating point there
    plus, minus = (steady_operating_point(turbine, coefficients, wind_m_s + s * du) for s in (1, -1))
    controlled = (loads(wind_m_s + du, plus[0], plus[1])[0] - loads(wind_m_s - du, minus[0], minus[1])[0]) / (2 * du)
    ratios = []
    for c in (held, controlled):
        for dof, arm in ((SURGE, 1.0), (PITCH, thrust_height_m)):
            ratios.append(c * arm ** 2 / (2 * math.sqrt(stiffness[dof, dof] * mass[dof, dof])))
    return AeroDamping(thrust, held, controlled, ratios[0], ratios[2], ratios[1], ratios[3])


@dataclass(frozen=True)
class Stability:
    """The surge and pitch modes at one wind speed: the platform alone, with the rotor's
    controls held, with its controller; and the quasi-steady aerodynamic damping."""

    wind_m_s: float
    alone: dict[str, Mode | None]
    held: dict[str, Mode | None]
    controlled: dict[str, Mode | None]
    aero: AeroDamping


def stability(platform: str, turbine: str, wind_m_s: float, mooring: str = "",
              duration_s: float = 600.0, discon_changes: str = "") -> Stability:
    """The surge and pitch modes of ``platform`` with ``turbine`` and its ROSCO at
    ``wind_m_s`` (see the module's description; ``discon_changes``: entries of ROSCO's
    DISCON.IN replaced, ``TurbineDescription.discon_changes``)."""
    from fowt_hydro_sim.turbine.coupled import restoring
    from fowt_hydro_sim.turbine.description import load_turbine
    from fowt_hydro_sim.turbine.performance import read_table

    chosen = load_platform(platform)
    model = PlatformModel(chosen, None, dt_s=0.05, mooring_model=mooring)
    description = load_turbine(turbine, discon_changes=discon_changes)
    coefficients = RotorCoefficients(read_table(description.performance_path))
    aero = aerodynamic_damping(description, coefficients, wind_m_s, float(chosen.hub_point_m[2]),
                               model.mass_matrix(), restoring(model)[1])
    return Stability(wind_m_s, platform_decay(platform, mooring, duration_s),
                     coupled_decay(platform, turbine, wind_m_s, mooring, duration_s, held=True),
                     coupled_decay(platform, turbine, wind_m_s, mooring, duration_s, discon_changes=discon_changes),
                     aero)


def _mode_text(mode: Mode | None) -> str:
    return "not found" if mode is None else f"{mode.period_s:6.1f} s {100 * mode.damping_ratio:+7.2f} %"


def stability_text(result: Stability, title: str) -> str:
    """The modes as ``fowt-sim stability`` prints them."""
    a = result.aero
    lines = [f"{title}, {result.wind_m_s:g} m/s (thrust {a.thrust_n / 1e6:.2f} MN; dT/dU "
             f"{a.held_n_s_m / 1e3:.0f} kN s/m controls held, {a.controlled_n_s_m / 1e3:.0f} kN s/m with the "
             "controller's quasi-steady response):",
             f"{'mode':7s}{'platform alone':>20s}{'rotor, controls held':>22s}{'rotor + ROSCO':>20s}"
             f"{'quasi-steady aero (held / controller)':>40s}"]
    for name, held, controlled in (("surge", a.surge_held, a.surge_controlled), ("pitch", a.pitch_held,
                                                                                 a.pitch_controlled)):
        lines.append(f"{name:7s}{_mode_text(result.alone[name]):>20s}{_mode_text(result.held[name]):>22s}"
                     f"{_mode_text(result.controlled[name]):>20s}{100 * held:+17.2f} % / {100 * controlled:+.2f} %")
    for name in ("surge", "pitch"):
        mode = result.controlled[name]
        if mode is not None and mode.damping_ratio < 0:
            lines.append(f"the {name} mode is negatively damped with the controller ({100 * mode.damping_ratio:+.2f} % "
                         f"of critical): its swing grows (docs: guide/coupled.md, a negatively damped mode)")
            lines.append(f"it needs more than {-100 * mode.damping_ratio:.2f} % of critical more {name} damping: "
                         "from the lines, a damper or the controller's tuning")
    return "\n".join(lines)
