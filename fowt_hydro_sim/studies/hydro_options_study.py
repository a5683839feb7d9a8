"""What each hydro option (``config.HydroOptions``) adds to the low-frequency surge and the mean
surge offset in the paper's load cases: the same sea, seed and drag model, one free-floating
run per option set; the rows feed the README's table on the choice of defaults.

This is the model's side only; the independent side (the capytaine BEM's mean drift and
Newman's slow drift for the same hull) is ``studies/diagnosis/independent/drift_study.py``.
"""
from __future__ import annotations

import logging
from dataclasses import asdict, replace

from fowt_hydro_sim.physics.config import EARLIER, HYDRODYN, HydroOptions, Platform, SeaState, load_case
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import repeat_period, synthesize
from fowt_hydro_sim.studies.psd import BANDS_HZ, band_std, psd

log = logging.getLogger(__name__)

OPTION_SETS = {
    "earlier (displaced, rotating, linear)": EARLIER,
    "undisplaced wetted length": replace(EARLIER, wetted_length="undisplaced"),
    "fixed directions": replace(EARLIER, load_directions="fixed"),
    "undisplaced + fixed (linear hydrostatics)": replace(HYDRODYN, hydrostatics="linear"),
    "HydroDyn (undisplaced, fixed, nonlinear)": HYDRODYN,
    "default: HydroDyn + Newman slow drift (BEM table)": HydroOptions(),
}


def surge_figures(platform: Platform, case: str, options: HydroOptions, duration_s: float, transient_s: float,
                  seed: int = 1, dt_s: float = 0.05) -> dict:
    """Mean surge and its low-frequency and wave-band STDs [m] over the last ``duration_s``."""
    spec = load_case(case).sea_state
    sea = SeaState(spec.hs_m, spec.tp_s, spec.gamma, seed=seed)
    total = transient_s + duration_s
    model = PlatformModel(platform, synthesize(sea, repeat_period(sea, total)), dt_s=dt_s, options=options)
    result = model.run(total, output_interval_s=0.25)
    surge = result.motion[result.time_s >= transient_s, 0]
    frequency, density = psd(surge, 0.25)
    row = {"case": case, **asdict(options), "mean_surge_m": float(surge.mean()),
           **{f"surge_{band}_std_m": band_std(frequency, density, limits) for band, limits in BANDS_HZ.items()}}
    log.info("%s", row)
    return row


def option_study(platform: Platform, cases: tuple[str, ...], duration_s: float = 3600.0,
                 transient_s: float = 300.0, seed: int = 1) -> list[dict]:
    """``surge_figures`` for every case and option set."""
    return [{"options": name, **surge_figures(platform, case, options, duration_s, transient_s, seed)}
            for case in cases for name, options in OPTION_SETS.items()]


if __name__ == "__main__":  # python -m fowt_hydro_sim.studies.hydro_options_study
    from fowt_hydro_sim.physics.config import load_platform

    logging.basicConfig(level=logging.INFO)
    rows = option_study(load_platform("windmoor12"), ("lc5.0", "lc5.1", "lc5.2", "lc5.3"))
    for r in rows:
        print(f"| {r['case']} | {r['options']} | {r['mean_surge_m']:.3f} | {r['surge_low_frequency_std_m']:.3f} | "
              f"{r['surge_wave_std_m']:.3f} |")
