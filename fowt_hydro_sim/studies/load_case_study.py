"""The paper's load cases with both drag models: surge, heave and pitch band STDs of the
constant-Cd (case 1) and filtered (case 2) models side by side, and a PSD plot per load case.

With no basin data this is not the paper's error table: it shows how large the effect of
frequency-dependent drag is and in which band it acts.
"""
from __future__ import annotations

import csv
import logging
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.config import DRAG_MODELS, Platform, SeaState, load_case
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import repeat_period, synthesize
from fowt_hydro_sim.studies.psd import BANDS_HZ, band_std, psd

log = logging.getLogger(__name__)

STUDY_CASES = ("lc5.0", "lc5.1", "lc5.2", "lc5.3", "lc5.4", "lc6.1")
STUDY_DOFS = (("surge", 0, "m"), ("heave", 2, "m"), ("pitch", 4, "deg"))


@dataclass(frozen=True)
class CaseRun:
    """Spectra and band STDs of one load case with one drag model."""

    case: str
    drag_model: str
    frequency_hz: np.ndarray
    psd: dict[str, np.ndarray]  # by DOF, unit^2/Hz
    band_std: dict[str, dict[str, float]]  # DOF -> band -> STD
    real_time_factor: float


def run_case(platform: Platform, case: str, drag_model: str, duration_s: float, transient_s: float,
             seed: int, dt_s: float = 0.05) -> CaseRun:
    """Simulate ``transient_s + duration_s`` and analyse the last ``duration_s``."""
    spec = load_case(case).sea_state
    sea = SeaState(spec.hs_m, spec.tp_s, spec.gamma, seed=seed)
    total = transient_s + duration_s
    model = PlatformModel(platform, synthesize(sea, repeat_period(sea, total)), dt_s=dt_s, drag_model=drag_model)
    start = time.perf_counter()
    result = model.run(total, output_interval_s=0.25)
    rtf = total / (time.perf_counter() - start)
    keep = result.time_s >= transient_s
    spectra, stds = {}, {}
    for name, j, unit in STUDY_DOFS:
        x = result.motion[keep, j] * (180 / np.pi if unit == "deg" else 1.0)
        frequency, spectra[name] = psd(x, 0.25)
        stds[name] = {band: band_std(frequency, spectra[name], limits) for band, limits in BANDS_HZ.items()}
    log.info("%s %s: %.0fx real time, surge LF %.3f m", case, drag_model, rtf, stds["surge"]["low_frequency"])
    return CaseRun(case, drag_model, frequency, spectra, stds, rtf)


def table_rows(runs: list[CaseRun]) -> list[dict]:
    """One row per load case and DOF: both models' band STDs and the change of case 2."""
    by_key = {(r.case, r.drag_model): r for r in runs}
    rows = []
    for case in dict.fromkeys(r.case for r in runs):
        constant, filtered = by_key[(case, "constant")], by_key[(case, "filtered")]
        for name, _, unit in STUDY_DOFS:
            row = {"load_case": case, "dof": name, "unit": unit}
            for band in BANDS_HZ:
                c1, c2 = constant.band_std[name][band], filtered.band_std[name][band]
                row[f"{band}_case1"], row[f"{band}_case2"] = c1, c2
                row[f"{band}_change_percent"] = 100.0 * (c2 / c1 - 1.0) if c1 > 0 else float("nan")
            rows.append(row)
    return rows


def write_tables(rows: list[dict], folder: Path, header: str) -> None:
    with open(folder / "band_stds.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    bands = list(BANDS_HZ)
    lines = [header, "",
             "| load case | DOF | " + " | ".join(f"{b} STD case 1 | case 2 | change" for b in bands) + " |",
             "|---|---|" + "---:|---:|---:|" * len(bands)]
    for r in rows:
        cells = [f"{r[f'{b}_case1']:.3f} | {r[f'{b}_case2']:.3f} | {r[f'{b}_change_percent']:+.1f} %" for b in bands]
        lines.append(f"| {r['load_case']} | {r['dof']} [{r['unit']}] | " + " | ".join(cells) + " |")
    (folder / "band_stds.md").write_text("\n".join(lines) + "\n")


def plot_case(case: str, runs: list[CaseRun], path: Path) -> None:
    """Surge, heave and pitch PSDs of both drag models, the analysis bands shaded."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(3, 1, figsize=(7.5, 8.5), sharex=True)
    for ax, (name, _, unit) in zip(axes, STUDY_DOFS):
        for (band, (low, high)), colour in zip(BANDS_HZ.items(), ("tab:orange", "tab:blue")):
            ax.axvspan(low, high, color=colour, alpha=0.08, label=f"{band} band" if name == "surge" else None)
        for run, style in zip(runs, ("-", "--")):
            label = f"case {DRAG_MODELS.index(run.drag_model) + 1}: {run.drag_model} Cd"
            ax.semilogy(run.frequency_hz, run.psd[name], style, lw=1.1, label=label)
        ax.set_ylabel(f"{name} PSD [{unit}$^2$/Hz]")
        ax.set_xlim(0.0, 0.3)
        ax.grid(alpha=0.3)
        top = max(run.psd[name][run.frequency_hz <= 0.3].max() for run in runs)
        ax.set_ylim(top * 1e-5, top * 3)
    axes[0].legend(fontsize=8, loc="upper right")
    axes[0].set_title(f"windmoor12, {case}: constant vs frequency-dependent (filtered) drag")
    axes[-1].set_xlabel("frequency [Hz]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def run_study(platform: Platform, cases: tuple[str, ...], duration_s: float, transient_s: float, seed: int,
              folder: Path) -> list[dict]:
    """Run every case with both drag models; write band_stds.csv / .md and psd_<case>.png."""
    folder.mkdir(parents=True, exist_ok=True)
    runs = []
    for case in cases:
        pair = [run_case(platform, case, drag, duration_s, transient_s, seed) for drag in DRAG_MODELS]
        plot_case(case, pair, folder / f"psd_{case}.png")
        runs += pair
    rows = table_rows(runs)
    write_tables(rows, folder, f"{platform.name}: band STDs, {duration_s:g} s analysed after {transient_s:g} s "
                               f"of start-up, seed {seed}; case 1 constant Cd, case 2 filtered Cd")
    return rows
