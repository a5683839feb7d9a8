"""The paper's load cases with both drag models: surge, heave and pitch band STDs of the
constant-Cd (case 1) and filtered (case 2) models side by side, and a PSD plot per load case
(log frequency axis, Tp and the natural frequencies marked). A progress bar with the time
left runs on stderr, and the tables are rewritten as each load case finishes, so that an
interrupted study keeps the table of the cases done.

With no basin data this is not the paper's error table: it shows how large the effect of
frequency-dependent drag is and in which band it acts.
"""
from __future__ import annotations

import csv
import io
import logging
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fowt_hydro_sim.files import replace_text
from fowt_hydro_sim.physics.config import DRAG_MODELS, Platform, SeaState, load_case
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import repeat_period, synthesize
from fowt_hydro_sim.studies.analysis import natural_frequencies_hz
from fowt_hydro_sim.studies.figures import pyplot
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
    log.debug("%s %s: %.0fx real time, surge LF %.3f m", case, drag_model, rtf, stds["surge"]["low_frequency"])
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
    """band_stds.csv and .md, each replaced whole: an interrupt never leaves half a table."""
    table = io.StringIO(newline="")
    writer = csv.DictWriter(table, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows)
    replace_text(folder / "band_stds.csv", table.getvalue())
    bands = list(BANDS_HZ)
    lines = [header, "",
             "| load case | DOF | " + " | ".join(f"{b} STD case 1 | case 2 | change" for b in bands) + " |",
             "|---|---|" + "---:|---:|---:|" * len(bands)]
    for r in rows:
        cells = [f"{r[f'{b}_case1']:.3f} | {r[f'{b}_case2']:.3f} | {r[f'{b}_change_percent']:+.1f} %" for b in bands]
        lines.append(f"| {r['load_case']} | {r['dof']} [{r['unit']}] | " + " | ".join(cells) + " |")
    replace_text(folder / "band_stds.md", "\n".join(lines) + "\n")


def case_labels(platform_name: str, case: str, runs: list[CaseRun], duration_s: float,
                natural_hz: dict[str, float]) -> dict[str, object]:
    """A load case figure's title and marked frequencies (label: Hz)."""
    sea = load_case(case).sea_state
    df = float(runs[0].frequency_hz[1] - runs[0].frequency_hz[0])
    marks = {f"{dof} {1 / f:.0f} s": f for dof, f in natural_hz.items() if dof in {d for d, _, _ in STUDY_DOFS}}
    marks[f"Tp {sea.tp_s:g} s"] = 1.0 / sea.tp_s
    return {"title": f"{platform_name}, {case}: Hs {sea.hs_m:g} m, Tp {sea.tp_s:g} s, gamma {sea.gamma:g}\n"
                     f"constant vs frequency-dependent (filtered) drag; {duration_s:g} s analysed, df {df:.4f} Hz",
            "marks": marks}


def plot_case(case: str, runs: list[CaseRun], path: Path, labels: dict[str, object]) -> None:
    """Surge, heave and pitch PSDs of both drag models on log axes, the analysis bands
    shaded, ``labels`` (``case_labels``) as title and marks (nothing without matplotlib)."""
    plt = pyplot()
    if plt is None:
        return

    fig, axes = plt.subplots(3, 1, figsize=(7.5, 8.5), sharex=True)
    for ax, (name, _, unit) in zip(axes, STUDY_DOFS):
        for (band, (low, high)), colour in zip(BANDS_HZ.items(), ("tab:orange", "tab:blue")):
            ax.axvspan(low, high, color=colour, alpha=0.08, label=f"{band} band" if name == "surge" else None)
        for run, style in zip(runs, ("-", "--")):
            label = f"case {DRAG_MODELS.index(run.drag_model) + 1}: {run.drag_model} Cd"
            ax.loglog(run.frequency_hz[1:], run.psd[name][1:], style, lw=1.1, label=label)
        for text, frequency in labels["marks"].items():
            ax.axvline(frequency, color="0.4", ls=":", lw=0.8)
            if name == STUDY_DOFS[-1][0]:
                ax.annotate(text, (frequency, 0.02), xycoords=("data", "axes fraction"), rotation=90, fontsize=7,
                            va="bottom", ha="right", color="0.3")
        ax.set_ylabel(f"{name} PSD [{unit}$^2$/Hz]")
        ax.set_xlim(0.003, 0.5)
        ax.grid(alpha=0.3, which="both")
        top = max(run.psd[name][run.frequency_hz <= 0.5].max() for run in runs)
        ax.set_ylim(top * 1e-6, top * 3)
    axes[0].legend(fontsize=8, loc="lower left")
    axes[0].set_title(labels["title"], fontsize=9)
    axes[-1].set_xlabel("frequency [Hz]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def run_study(platform: Platform, cases: tuple[str, ...], duration_s: float, transient_s: float, seed: int,
              folder: Path) -> list[dict]:
    """Run every case with both drag models; write band_stds.csv / .md (rewritten as each
    case finishes) and psd_<case>.png, with a progress bar and the time left on stderr."""
    from tqdm import tqdm
    folder.mkdir(parents=True, exist_ok=True)
    natural = natural_frequencies_hz(platform)
    header = (f"{platform.name}: band STDs, {duration_s:g} s analysed after {transient_s:g} s of start-up, "
              f"seed {seed}; case 1 constant Cd, case 2 filtered Cd")
    runs, rows = [], []
    with tqdm(total=len(cases) * len(DRAG_MODELS), desc="load cases", unit="run", file=sys.stderr,
              bar_format="{desc}: {n}/{total} runs |{bar}| {elapsed} elapsed, {remaining} left {postfix}") as bar:
        for case in cases:
            pair = []
            for drag in DRAG_MODELS:
                bar.set_postfix_str(f"{case} {drag}")
                pair.append(run_case(platform, case, drag, duration_s, transient_s, seed))
                bar.update()
            runs += pair
            rows = table_rows(runs)
            write_tables(rows, folder, header + ("" if len(runs) == len(cases) * len(DRAG_MODELS) else
                                                 f" (partial: {len(runs) // len(DRAG_MODELS)} of {len(cases)} "
                                                 f"load cases)"))
            plot_case(case, pair, folder / f"psd_{case}.png", case_labels(platform.name, case, pair, duration_s,
                                                                          natural))
    return rows
