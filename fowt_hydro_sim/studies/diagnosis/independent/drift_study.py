"""The BEM's second-order surge drift in the paper's load cases, the independent side of the
choice of the hydro options' defaults (``studies.hydro_options_study`` is the model's side):

- closed form: the mean drift force 2 int S D dw of the sea and the mean offset it gives on
  the mooring's linear surge stiffness;
- time domain: the independent Cummins simulator (quadratic drag, no second-order force of
  its own) run without and with Newman's slow drift from the BEM's drift coefficient D(w)
  (``drift.py``'s table, freely floating hull), same durations and bands as the model study;
- the basin's drift against the model's (``ratio``): the mean surge offset the drift adds in
  a regular wave, in each simulator (``basin.MODEL_DRIFT_RATIO``).
"""
from __future__ import annotations

import logging
import math
import sys
from dataclasses import replace

import numpy as np

from fowt_hydro_sim.physics.config import Platform, load_case, load_platform
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import WaveComponents
from fowt_hydro_sim.studies.diagnosis.independent import bem, cummins, drift
from fowt_hydro_sim.studies.psd import BANDS_HZ, band_std, psd

LOG = logging.getLogger(__name__)

CASES = ("lc5.0", "lc5.1", "lc5.2", "lc5.3")


def case_waves(case: str, period_s: float, seed: int = 1) -> cummins.Waves:
    spec = load_case(case).sea_state
    return cummins.jonswap_waves(spec.hs_m, spec.tp_s, spec.gamma, period_s, seed)


def drift_coefficients(table: drift.DriftTable, floating: bool = True) -> tuple[tuple[float, float], ...]:
    """(w, D) pairs for ``cummins.Effects`` (D >= 0: Newman's approximation takes its root)."""
    values = table.coefficient_n_m2(table.omega_rad_s, floating)
    return tuple((float(w), max(0.0, float(d))) for w, d in zip(table.omega_rad_s, values))


def surge_stiffness_n_m(platform: Platform) -> float:
    return float(drift.mooring_stiffness(platform)[0, 0])


def closed_form_row(platform: Platform, table: drift.DriftTable, case: str, period_s: float = 3900.0,
                    seed: int = 1) -> dict:
    """Mean drift force of the fixed and the floating hull and the floating hull's mean offset."""
    waves = case_waves(case, period_s, seed)
    floating = lambda w: table.coefficient_n_m2(w, floating=True)
    fixed = lambda w: table.coefficient_n_m2(w, floating=False)
    force = drift.spectral_mean_drift_n(waves, floating)
    return {"case": case, "mean_drift_fixed_n": drift.spectral_mean_drift_n(waves, fixed),
            "mean_drift_floating_n": force, "mean_offset_m": force / surge_stiffness_n_m(platform)}


def independent_row(platform: Platform, database: bem.HydroDatabase, table: drift.DriftTable | None, case: str,
                    duration_s: float = 3600.0, transient_s: float = 300.0, seed: int = 1) -> dict:
    """Mean surge and band STDs of the independent simulator, with Newman's drift from ``table``
    (or none), over the last ``duration_s``."""
    total = duration_s + transient_s
    waves = case_waves(case, total, seed)
    effects = cummins.Effects(drift_coefficient_n_m2=drift_coefficients(table)) if table else cummins.Effects()
    trajectory = cummins.integrate(platform, database, waves, total, effects=effects)
    step = 0.25
    time_s = np.arange(transient_s, total + 1e-9, step)
    surge = np.interp(time_s, trajectory.time_s, trajectory.position[:, 0])
    frequency, density = psd(surge, step)
    row = {"case": case, "drift": table is not None, "mean_surge_m": float(surge.mean()),
           **{f"surge_{band}_std_m": band_std(frequency, density, limits) for band, limits in BANDS_HZ.items()}}
    LOG.info("%s", row)
    return row


def drift_ratio_row(platform: Platform, database: bem.HydroDatabase, table: drift.DriftTable, period_s: float,
                    amplitude_m: float = 1.5, duration_s: float = 2400.0, transient_s: float = 800.0) -> dict:
    """The mean surge offset the slow drift adds in a regular wave (with the drift less without,
    averaged after ``transient_s``): the basin's (this simulator with ``table``'s floating-hull
    coefficients) and the model's (its platform's ``drift_coefficients_n_m2``), and their ratio."""
    omega = 2.0 * math.pi / period_s
    waves = cummins.Waves(np.array([omega]), np.array([amplitude_m]), np.array([0.0]), 0.0, period_s)
    basin = {}
    for on, coefficients in ((True, drift_coefficients(table)), (False, ())):
        trajectory = cummins.integrate(platform, database, waves, duration_s,
                                       baseline=cummins.Baseline(drift_coefficient_n_m2=coefficients))
        basin[on] = float(trajectory.position[trajectory.time_s > transient_s, 0].mean())
    model_waves = WaveComponents(np.array([1.0 / period_s]), np.array([amplitude_m]), np.zeros(1), np.zeros(1),
                                 period_s)
    model = {}
    for on, hull in ((True, platform), (False, replace(platform, drift_coefficients_n_m2=()))):
        result = PlatformModel(hull, model_waves, dt_s=0.1).run(duration_s, output_interval_s=0.5)
        model[on] = float(result.motion[result.time_s > transient_s, 0].mean())
    basin_m, model_m = basin[True] - basin[False], model[True] - model[False]
    row = {"period_s": period_s, "basin_offset_m": basin_m, "model_offset_m": model_m, "ratio": basin_m / model_m}
    LOG.info("%s", row)
    return row


def natural_period_s(platform: Platform, database: bem.HydroDatabase) -> float:
    """Surge natural period on the mooring's stiffness with the BEM's lowest-frequency added mass."""
    mass = cummins.rigid_body_mass(platform)[0, 0] + database.added_mass[0, 0, 0]
    return 2.0 * math.pi * math.sqrt(mass / surge_stiffness_n_m(platform))


if __name__ == "__main__":  # python -m fowt_hydro_sim.studies.diagnosis.independent.drift_study
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    hull, bem_database, drift_table = load_platform("windmoor12"), bem.load_database(), drift.load_table()
    if sys.argv[1:] == ["ratio"]:  # ... drift_study ratio
        for period in (7.0, 8.0, 10.0, 12.0):
            drift_ratio_row(hull, bem_database, drift_table, period)
        sys.exit(0)
    LOG.info("surge stiffness %.0f N/m, natural period %.1f s", surge_stiffness_n_m(hull),
             natural_period_s(hull, bem_database))
    for name in CASES:
        LOG.info("%s", closed_form_row(hull, drift_table, name))
        for with_drift in (drift_table, None):
            independent_row(hull, bem_database, with_drift, name)
