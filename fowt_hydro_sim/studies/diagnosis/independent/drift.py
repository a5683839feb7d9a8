"""The hull's second-order mean wave drift from potential flow (capytaine), independent of the
model: Maruo's far-field formula on the Kochin function of the diffracted and radiated waves.

With incident waves eta_I = A e^{i(k x - w t)} (capytaine's e^{-i w t}) the far field of the
body's waves is eta_s = A f(theta) e^{i k r} / sqrt(k r), and the mean horizontal force is

    F = (E n / k) [ -int |f|^2 (cos th, sin th) dth - 2 sqrt(2 pi) Re(f(0) e^{i pi/4}) (1, 0) ],

E = rho g A^2 / 2, n = Cg / C (momentum balance on a control cylinder; the second term is the
incident wave's momentum lost by interference). Energy conservation (no damping but the
radiation's) gives the optical theorem int |f|^2 dth = -2 sqrt(2 pi) Re(f(0) e^{i pi/4}).
Both are checked on the closed form of a bottom-mounted cylinder (MacCamy-Fuchs), whose mean
drift is also integrated in the near field (waterline term and quadratic velocity pressure).

For the hull, f is capytaine's Kochin function H(theta) of the diffraction problem plus, for
the freely floating hull, those of the six radiation problems times the body velocities
-i w xi from the RAO (rigid-body mass, BEM A and B, hydrostatics, the spring lines' linear
stiffness), with the finite-depth far field of capytaine's Green function:
f = 2 sqrt(2 pi) (w / g) 2 k cosh^2(kh) / (2 kh + sinh 2kh) e^{-i pi/4} H."""
from __future__ import annotations

import csv
import logging
import math
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.config import Platform
from fowt_hydro_sim.studies.diagnosis.independent import bem, cummins

LOG = logging.getLogger(__name__)

DRIFT_TABLE = bem.DATA / "windmoor12_drift.csv"
DRIFT_PERIODS_S = np.round(np.geomspace(4.0, 25.0, 32), 3)
THETA_POINTS = 360
# viscous damping added to heave, roll and pitch for the floating hull's RAO: with radiation
# damping alone the heave resonance (16.5 s) radiates an unbounded wave and drift
DAMPING_RATIO = 0.05
DAMPED_DOFS = np.array([0.0, 0.0, 1.0, 1.0, 1.0, 0.0])
DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")


# --------------------------------------------------------------------------- far field
def theta_grid(points: int = THETA_POINTS) -> np.ndarray:
    """Uniform periodic grid 0 .. 2 pi (endpoint excluded): the trapezoidal rule is spectral."""
    return 2.0 * math.pi * np.arange(points) / points


def group_ratio(k: float, depth_m: float) -> float:
    """n = Cg / C = (1 + 2 k h / sinh 2 k h) / 2 (1/2 in deep water)."""
    kh = k * depth_m
    return 0.5 if not math.isfinite(kh) or kh > 20.0 else 0.5 * (1.0 + 2.0 * kh / math.sinh(2.0 * kh))


def far_field_amplitude(kochin: np.ndarray, omega_rad_s: float, k: float, depth_m: float, g: float) -> np.ndarray:
    """f(theta) per unit wave amplitude from capytaine's Kochin function (its normalisation:
    (1/4 pi) int sigma cosh k(z+h)/cosh kh e^{-ik(x cos th + y sin th)} dS)."""
    kh = k * depth_m
    depth_factor = (k if not math.isfinite(kh) or kh > 20.0
                    else 2.0 * k * math.cosh(kh) ** 2 / (2.0 * kh + math.sinh(2.0 * kh)))
    return 2.0 * math.sqrt(2.0 * math.pi) * omega_rad_s / g * depth_factor * np.exp(-0.25j * math.pi) * kochin


def maruo_drift(f: np.ndarray, k: float, depth_m: float, rho: float, g: float) -> tuple[float, float]:
    """Mean drift force (x, y) per unit wave amplitude squared [N/m^2], waves travelling
    along +x, f on :func:`theta_grid`."""
    d_theta = 2.0 * math.pi / f.size
    theta = theta_grid(f.size)
    scale = 0.5 * rho * g * group_ratio(k, depth_m) / k
    power = np.abs(f) ** 2
    interference = -2.0 * math.sqrt(2.0 * math.pi) * float(np.real(f[0] * np.exp(0.25j * math.pi)))
    fx = scale * (-np.sum(power * np.cos(theta)) * d_theta + interference)
    fy = scale * (-np.sum(power * np.sin(theta)) * d_theta)
    return float(fx), float(fy)


def energy_balance(f: np.ndarray) -> tuple[float, float]:
    """(radiated: int |f|^2 dth, extinct: -2 sqrt(2 pi) Re(f(0) e^{i pi/4})): equal when
    nothing but the waves takes energy out."""
    radiated = float(np.sum(np.abs(f) ** 2) * 2.0 * math.pi / f.size)
    return radiated, -2.0 * math.sqrt(2.0 * math.pi) * float(np.real(f[0] * np.exp(0.25j * math.pi)))


# --------------------------------------------------------------------------- closed form
def _bessel_terms(ka: float, terms: int):
    from scipy.special import h1vp, jvp
    m = np.arange(terms)
    return m, np.where(m == 0, 1.0, 2.0), jvp(m, ka), h1vp(m, ka)


def cylinder_far_field(ka: float, theta: np.ndarray, terms: int = 60) -> np.ndarray:
    """f(theta) of a bottom-mounted vertical cylinder (MacCamy-Fuchs; any depth):
    -sqrt(2/pi) e^{-i pi/4} sum eps_m J'_m(ka)/H'_m(ka) cos m th."""
    m, eps, jp, hp = _bessel_terms(ka, terms)
    return -math.sqrt(2.0 / math.pi) * np.exp(-0.25j * math.pi) * ((eps * jp / hp) @ np.cos(np.outer(m, theta)))


def cylinder_drift_near_field(radius_m: float, k: float, depth_m: float, rho: float, g: float,
                              points: int = 720, terms: int = 60) -> float:
    """Mean surge drift [N/m^2] of a bottom-mounted cylinder by direct pressure integration of
    the MacCamy-Fuchs field: -rho g/4 oint |eta|^2 n_x dl + rho/4 int |grad phi|^2 n_x dS,
    with eta(a, th) = sum eps_m i^m 2i/(pi ka H'_m(ka)) cos m th and the depth profile
    cosh k(z+h)/cosh kh."""
    omega = math.sqrt(g * k * math.tanh(k * depth_m))
    theta = theta_grid(points)
    m, eps, _, hp = _bessel_terms(k * radius_m, terms)
    coefficient = eps * (1j ** m) * 2j / (math.pi * k * radius_m * hp)
    eta = coefficient @ np.cos(np.outer(m, theta))
    d_eta = (coefficient * -m) @ np.sin(np.outer(m, theta))
    kh = k * depth_m
    cosh2 = math.sinh(2.0 * kh) / (4.0 * k) + depth_m / 2.0  # int cosh^2 k(z+h) dz over the depth
    sinh2 = math.sinh(2.0 * kh) / (4.0 * k) - depth_m / 2.0
    potential = (g / omega / math.cosh(kh)) ** 2
    velocity2 = potential * (np.abs(d_eta / radius_m) ** 2 * cosh2 + k ** 2 * np.abs(eta) ** 2 * sinh2)
    arc = radius_m * 2.0 * math.pi / points
    waterline = -0.25 * rho * g * np.sum(np.abs(eta) ** 2 * np.cos(theta)) * arc
    return float(waterline + 0.25 * rho * np.sum(velocity2 * np.cos(theta)) * arc)


# --------------------------------------------------------------------------- the hull
@dataclass(frozen=True)
class DriftTable:
    """Head-sea (heading 0) mean surge drift per unit amplitude squared of the fixed and the
    freely floating moored hull, with the energy check and the RAO it used."""

    omega_rad_s: np.ndarray
    fixed_n_m2: np.ndarray
    fixed_sway_n_m2: np.ndarray
    energy_error_fixed_n_m2: np.ndarray  # (E n / k)(radiated - extinct): the energy imbalance as a drift
    free_n_m2: np.ndarray  # moored, heave/roll/pitch with extra viscous damping (DAMPING_RATIO)
    free_sway_n_m2: np.ndarray
    energy_error_free_n_m2: np.ndarray  # the body's viscous damping absorbs: not zero by design
    free_potential_n_m2: np.ndarray  # moored, radiation damping only (heave resonance unbounded)
    energy_error_free_potential_n_m2: np.ndarray
    surge_rao_m_m: np.ndarray  # |xi| of the damped RAO
    heave_rao_m_m: np.ndarray
    pitch_rao_rad_m: np.ndarray

    COLUMNS = ("omega_rad_s", "fixed_n_m2", "fixed_sway_n_m2", "energy_error_fixed_n_m2", "free_n_m2",
               "free_sway_n_m2", "energy_error_free_n_m2", "free_potential_n_m2",
               "energy_error_free_potential_n_m2", "surge_rao_m_m", "heave_rao_m_m", "pitch_rao_rad_m")

    @property
    def free_radiated_n_m2(self) -> np.ndarray:
        """The floating hull's drift from the momentum of its outgoing waves alone,
        (E n / k) int |f|^2 (1 - cos th) dth (>= 0): Maruo's drift without the momentum of the
        energy its viscous damping takes out (which a damper fixed to the ground would feel,
        heave plates shedding vortices into the water need not)."""
        return self.free_n_m2 + self.energy_error_free_n_m2

    def coefficient_n_m2(self, omega_rad_s, floating: bool = True) -> np.ndarray:
        """D(w) (floating: :attr:`free_radiated_n_m2`), linear between the table's frequencies
        and zero below the first (long waves drift nothing); held at the last value above."""
        values = self.free_radiated_n_m2 if floating else self.fixed_n_m2
        omega = np.concatenate([[0.0], self.omega_rad_s])
        return np.interp(omega_rad_s, omega, np.concatenate([[0.0], values]))


def save_table(table: DriftTable, path: str | Path = DRIFT_TABLE) -> None:
    with open(path, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(DriftTable.COLUMNS)
        for row in zip(*(getattr(table, name) for name in DriftTable.COLUMNS)):
            writer.writerow([f"{value:.6g}" for value in row])


def load_table(path: str | Path = DRIFT_TABLE) -> DriftTable:
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return DriftTable(*(data[:, i] for i in range(len(DriftTable.COLUMNS))))


def mooring_stiffness(platform: Platform, step: float = 1e-4) -> np.ndarray:
    """The spring lines' 6x6 linear stiffness at rest, -dF/dx by central differences."""
    stiffness = np.zeros((6, 6))
    for j in range(6):
        dx = np.zeros(6)
        dx[j] = step
        stiffness[:, j] = -(cummins.mooring_wrench(platform, dx) - cummins.mooring_wrench(platform, -dx)) / (2 * step)
    return stiffness


def rao(omega_rad_s: float, mass: np.ndarray, damping: np.ndarray, restoring: np.ndarray,
        excitation: np.ndarray, damping_ratio: float) -> np.ndarray:
    """xi (6,) per unit amplitude, capytaine's e^{-i w t}: (-w^2 M - i w (B + B_v) + C) xi = X,
    B_v = ``damping_ratio`` of critical in heave, roll and pitch (diagonal)."""
    viscous = 2.0 * damping_ratio * np.sqrt(np.abs(np.diag(mass) * np.diag(restoring))) * DAMPED_DOFS
    impedance = -omega_rad_s ** 2 * mass - 1j * omega_rad_s * (damping + np.diag(viscous)) + restoring
    return np.linalg.solve(impedance, excitation)


def _drift_and_imbalance(f: np.ndarray, k: float, depth_m: float, rho: float, g: float) -> tuple[float, float, float]:
    """(D_x, D_y, the energy imbalance expressed as a drift (E n / k)(radiated - extinct))."""
    imbalance = 0.5 * rho * g * group_ratio(k, depth_m) / k * float(np.subtract(*energy_balance(f)))
    return (*maruo_drift(f, k, depth_m, rho, g), imbalance)


def hull_drift(platform: Platform, omegas_rad_s: np.ndarray, panel_size_m: float = bem.PANEL_SIZE_M,
               points: int = THETA_POINTS, damping_ratio: float = DAMPING_RATIO) -> DriftTable:
    """Solve diffraction (heading 0) and radiation (6 DOF) at each frequency with sources kept,
    the RAO, and Maruo's drift of the fixed and the freely floating hull (with and without
    ``damping_ratio`` of critical added in heave, roll and pitch)."""
    import capytaine as cpt
    from capytaine.bem.airy_waves import froude_krylov_force
    from capytaine.post_pro.kochin import compute_kochin
    env = platform.environment
    rho, g, depth = env.water_density_kg_m3, env.gravity_m_s2, env.water_depth_m
    body = cpt.FloatingBody(mesh=bem.hull_mesh(platform, panel_size_m),
                            dofs=cpt.rigid_body_dofs(rotation_center=(0.0, 0.0, 0.0)), name=platform.name)
    solver = cpt.BEMSolver()
    mass = cummins.rigid_body_mass(platform)
    restoring = bem.hydrostatics(platform)[0] + mooring_stiffness(platform)
    theta = theta_grid(points)
    rows = []
    started = time.perf_counter()
    for omega in np.asarray(omegas_rad_s, float):
        common = dict(body=body, omega=float(omega), water_depth=depth, rho=rho, g=g)
        diffraction = solver.solve(cpt.DiffractionProblem(wave_direction=0.0, **common), method="indirect")
        radiation = [solver.solve(cpt.RadiationProblem(radiating_dof=dof, **common), method="indirect")
                     for dof in DOFS]
        k = diffraction.wavenumber
        added = np.array([[r.added_masses[i] for r in radiation] for i in DOFS])  # [influenced, radiating]
        damping = np.array([[r.radiation_dampings[i] for r in radiation] for i in DOFS])
        froude_krylov = froude_krylov_force(diffraction.problem)
        excitation = np.array([diffraction.forces[d] + froude_krylov[d] for d in DOFS])
        h_fixed = compute_kochin(diffraction, theta)
        h_radiated = np.array([compute_kochin(r, theta) for r in radiation])
        drift = lambda h, omega=omega, k=k: _drift_and_imbalance(far_field_amplitude(h, omega, k, depth, g),
                                                                 k, depth, rho, g)
        damped = rao(omega, mass + added, damping, restoring, excitation, damping_ratio)
        potential = rao(omega, mass + added, damping, restoring, excitation, 0.0)
        fixed, free = drift(h_fixed), drift(h_fixed + damped @ h_radiated)
        free_potential = drift(h_fixed + potential @ h_radiated)
        row = (omega, *fixed, *free, free_potential[0], free_potential[2], *np.abs(damped[[0, 2, 4]]))
        rows.append(tuple(row))
        LOG.info("w %.3f rad/s: D fixed %.4g, free %.4g N/m^2 (%.0f s)", omega, fixed[0], free[0],
                 time.perf_counter() - started)
    return DriftTable(*(np.array(column) for column in zip(*rows)))


# --------------------------------------------------------------------------- irregular seas
def spectral_mean_drift_n(waves: cummins.Waves, coefficient_n_m2) -> float:
    """Mean drift force of a sea of components, sum a_j^2 D(w_j) (= 2 int S D dw)."""
    return float(np.sum(waves.amplitude_m ** 2 * coefficient_n_m2(waves.omega_rad_s)))


def newman_force_spectrum(waves: cummins.Waves, coefficient_n_m2, mu_rad_s: np.ndarray) -> np.ndarray:
    """One-sided slow-drift force spectrum S_F(mu) [N^2 s/rad] by Newman's approximation,
    8 int S(w) S(w + mu) D(w + mu/2)^2 dw, from the components' spectrum S = a^2 / (2 dw)."""
    omega = waves.omega_rad_s
    d_omega = float(np.median(np.diff(omega)))
    density = waves.amplitude_m ** 2 / (2.0 * d_omega)
    fine = np.linspace(omega[0], omega[-1], 4000)
    s_fine = np.interp(fine, omega, density)
    step = fine[1] - fine[0]
    out = np.empty(len(mu_rad_s))
    for i, mu in enumerate(np.asarray(mu_rad_s, float)):
        shifted = np.interp(fine + mu, omega, density, right=0.0)
        out[i] = 8.0 * np.sum(s_fine * shifted * coefficient_n_m2(fine + 0.5 * mu) ** 2) * step
    return out
