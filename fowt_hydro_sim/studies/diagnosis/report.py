"""The gap diagnosis's report: report.md (what a person reads), diagnosis.json (for
scripts) and PNG figures: the gap matrix before and after the chosen effect, PSD overlays
measured / model / model + effect with their ratio and wave coherence, and each
candidate's closure."""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from fowt_hydro_sim.studies.diagnosis.gap import GROSS_RATIO, Gap
from fowt_hydro_sim.studies.diagnosis.method import COHERENCE_DEFICIT, Diagnosis

SPECTRA_F_MAX_HZ = 0.3  # the figures' and JSON's frequency range


def _matplotlib():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _label(dof: str, metric: str) -> str:
    return f"{dof} {metric.replace('low_frequency', 'LF').replace('frequency.', 'freq.')}"


def _value_text(metric: str, value: float) -> str:
    if metric == "lag":
        return f"{value:+.2f} s"
    if metric == "offset":
        return f"{value:+.2f} STD"
    return f"{100 * value:+.1f} %"


def plot_gap_matrix(diagnosis: Diagnosis, path: Path) -> None:
    """Residuals (value / tolerance) per run and cell, plain model and with the chosen
    effect; flagged cells dotted, cells not judged grey."""
    plt = _matplotlib()
    cells = diagnosis.settings.cells()
    panels = [("plain model", diagnosis.baseline)]
    if diagnosis.chosen:
        after = diagnosis.candidate(diagnosis.chosen).gaps + diagnosis.blind_after
        panels.append((f"with {diagnosis.chosen} (blind runs not refitted)", after))
    runs = diagnosis.tuning + [f"{r} (blind)" for r in diagnosis.blind]
    fig, axes = plt.subplots(len(panels), 1,
                             figsize=(max(8, 0.45 * len(cells)), 1.2 + 0.45 * len(runs) * len(panels) + 1),
                             squeeze=False)
    for ax, (title, gaps) in zip(axes[:, 0], panels):
        residual = np.array([g.residual for g in gaps])
        shown = np.ma.masked_where(np.array([~np.isfinite(g.tolerance) for g in gaps]), np.clip(residual, -5, 5))
        image = ax.imshow(shown, cmap="RdBu_r", vmin=-5, vmax=5, aspect="auto")
        ax.set_facecolor("0.85")
        for i, g in enumerate(gaps):
            for j in np.flatnonzero(g.flagged):
                ax.plot(j, i, "k.", markersize=6)
        ax.set_yticks(range(len(gaps)), runs[:len(gaps)], fontsize=7)
        ax.set_xticks(range(len(cells)), [_label(*c) for c in cells], rotation=70, fontsize=7)
        ax.set_title(title, fontsize=9)
        fig.colorbar(image, ax=ax, label="gap / tolerance")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_spectra(run: str, spectra: dict[str, dict], dofs: tuple[str, ...], path: Path) -> None:
    """Per DOF: PSDs, their ratio to the measured one, and coherence with the waves."""
    plt = _matplotlib()
    fig, axes = plt.subplots(3, len(dofs), figsize=(4.2 * len(dofs), 8.5), sharex=True, squeeze=False)
    styles = {"measured": "k-", "model": "C0-", "model + effect": "C3--"}
    for col, dof in enumerate(dofs):
        measured = spectra["measured"]
        keep = (measured["frequency_hz"] > 0) & (measured["frequency_hz"] <= SPECTRA_F_MAX_HZ)
        f = measured["frequency_hz"][keep]
        for name, s in spectra.items():
            axes[0, col].semilogy(f, s[f"psd.{dof}"][keep], styles.get(name, "-"), label=name, lw=1)
            axes[2, col].plot(f, s[f"coherence.{dof}"][keep], styles.get(name, "-"), lw=1)
            if name != "measured":
                ratio = s[f"psd.{dof}"][keep] / np.maximum(measured[f"psd.{dof}"][keep], 1e-300)
                axes[1, col].semilogy(f, ratio, styles.get(name, "-"), lw=1)
        axes[1, col].axhline(1.0, color="k", lw=0.5)
        axes[0, col].set_title(f"{run}: {dof}", fontsize=9)
        axes[2, col].set_xlabel("frequency [Hz]")
        for row in axes[:, col]:
            row.axvline(0.05, color="0.6", lw=0.5, ls=":")
    axes[0, 0].set_ylabel("PSD")
    axes[1, 0].set_ylabel("PSD / measured")
    axes[2, 0].set_ylabel("coherence with waves")
    axes[0, 0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_closure(diagnosis: Diagnosis, path: Path) -> None:
    """Each candidate's closure of the tuning gap, and the chosen one's on the blind runs."""
    plt = _matplotlib()
    names = [c.effect for c in diagnosis.candidates]
    fig, ax = plt.subplots(figsize=(7, 0.45 * len(names) + 1.5))
    colours = ["C3" if n == diagnosis.chosen else ("C0" if c.fits else "0.6")
               for n, c in zip(names, diagnosis.candidates)]
    ax.barh(range(len(names)), [100 * max(c.closure, -1.0) for c in diagnosis.candidates], color=colours)
    if diagnosis.blind_after:
        i = names.index(diagnosis.chosen)
        ax.plot(100 * diagnosis.blind_closure, i, "kD", label="blind runs, not refitted")
        ax.legend(fontsize=7)
    ax.axvline(50, color="k", lw=0.5, ls=":")
    ax.set_yticks(range(len(names)), names, fontsize=8)
    ax.invert_yaxis()
    ax.set_xlabel("gap closed on the tuning runs [%] (best score at top)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _rms_flagged(before: list[Gap], after: list[Gap]) -> tuple[float, float]:
    """RMS residual (tolerance units) over the cells flagged before, before and after."""
    b = np.concatenate([g.residual[g.flagged] for g in before]) if before else np.empty(0)
    a = np.concatenate([ga.residual[gb.flagged] for gb, ga in zip(before, after)]) if after else np.empty(0)
    rms = lambda x: float(np.sqrt(np.mean(x ** 2))) if x.size else float("nan")
    return rms(b), rms(a)


def gross_lines(diagnosis: Diagnosis) -> list[str]:
    """One line per STD cell of the plain model whose ratio to the measurement is gross, with
    its direction: 'lc5.3: surge std.low_frequency: model 12.0x the measured (too high)'."""
    out = []
    for g in diagnosis.baseline:
        for i in np.flatnonzero(g.gross(diagnosis.settings)):
            dof, metric = diagnosis.settings.cells()[i]
            ratio = 1.0 + g.value[i]
            out.append(f"{g.run}: {dof} {metric}: model {ratio:.2g}x the measured "
                       f"({'too high' if ratio > 1 else 'too low'})")
    return out


def summary_lines(diagnosis: Diagnosis) -> list[str]:
    """The diagnosis in a few lines: flagged cells, candidates, verdict, blind closure."""
    lines = [f"gap: {len(diagnosis.flagged_cells(diagnosis.tuning_before))} flagged cells on the tuning runs"]
    lines += [f"  {run}: {dof} {metric}" for run, dof, metric in diagnosis.flagged_cells(diagnosis.tuning_before)]
    lines += [f"gross: {line}" for line in gross_lines(diagnosis)]
    if diagnosis.candidates:
        lines.append(f"{'candidate':<26}{'score':>9}{'closure':>9}  parameters")
        lines += [f"{c.effect:<26}{c.score:>9.1f}{100 * c.closure:>8.0f}%  "
                  + ", ".join(f"{k} {v:.4g}" for k, v in c.values.items())
                  + ("  (fit failed)" if c.failed else "")
                  + (f"  (screened: {c.screened})" if c.screened else "") for c in diagnosis.candidates]
    lines.append(f"verdict: {diagnosis.verdict}" + (f": {diagnosis.chosen}" if diagnosis.chosen else "")
                 + (f", the model's term: {diagnosis.reading.effect}" if diagnosis.reading else "")
                 + f" ({diagnosis.reason})")
    if diagnosis.blind_after:
        lines.append(f"blind runs (not refitted): {100 * diagnosis.blind_closure:.0f} % of the gap closed")
    if diagnosis.reading_blind_after:
        lines.append(f"blind runs (not refitted): {100 * diagnosis.reading_closure[1]:.0f} % of the gap of the "
                     "mismatches it reads closed")
    return lines


def coherence_sentence(deficit: float, dof: str) -> str:
    """What the low-frequency wave-response coherence says, worded from its value."""
    head = (f"Wave-response coherence, low-frequency {dof}: the model's exceeds the measured runs' by "
            f"{deficit:+.2f} on average")
    if not np.isfinite(deficit):
        return f"Wave-response coherence, low-frequency {dof}: not estimated."
    if deficit > COHERENCE_DEFICIT:
        return head + " (clearly positive: part of the measured response is not explained linearly by the waves)."
    if deficit < -COHERENCE_DEFICIT:
        return head + (" (clearly negative: the measured response is more coherent with the waves than the "
                       "model's; the model's has a part the waves do not explain).")
    return head + (f" (within +-{COHERENCE_DEFICIT:g}: measured and modelled responses are about as coherent with "
                   "the waves).")


def markdown(diagnosis: Diagnosis, figures: list[str]) -> str:
    d, cells = diagnosis, diagnosis.settings.cells()
    lines = ["# Sim-to-real gap diagnosis", "",
             f"Tuning runs: {', '.join(d.tuning)}. Blind runs: {', '.join(d.blind) or 'none'}. "
             f"Model runs: {d.model_runs}.", "",
             f"**Verdict: {d.verdict}**" + (f": **{d.chosen}**" if d.chosen else "")
             + (f", the model's term: **{d.reading.effect}**" if d.reading else "") + f". {d.reason}.", ""]
    lines += ["## Where the gap lies", "",
              "Cells flagged: significant (the paired block test's "
              f"{100 * d.settings.confidence:g} % interval excludes zero) and beyond tolerance "
              "(STD 5 %, mean frequency 3 %, offset 0.2 STD, lag 0.25 s"
              + ("; free decays: half-period 3 %, damping ratio 10 %" if d.settings.decays else "")
              + "). Values are model against measured.", "",
              "| run | DOF | metric | gap | interval | tolerance |", "|---|---|---|---|---|---|"]
    for g in d.baseline:
        for i in np.flatnonzero(g.flagged):
            dof, metric = cells[i]
            lines.append(f"| {g.run} | {dof} | {metric} | {_value_text(metric, g.value[i])} | "
                         f"[{_value_text(metric, g.low[i])}, {_value_text(metric, g.high[i])}] | "
                         f"{_value_text(metric, g.tolerance[i]).lstrip('+')} |")
    if not d.flagged_cells(d.baseline):
        lines.append("| (none) | | | | | |")
    if d.mismatches:
        lines += ["", "Baseline mismatches (one sign in every tuning run, significant pooled over the runs):", ""]
        lines += [f"- {m.text()}" for m in d.mismatches]
    if d.differences:
        lines += ["", "Set aside as the baseline's too (flagged in some tuning runs only, or of a sign that changes "
                      "between runs; no catalogue effect explains them; values per tuning run): "
                      + d.differences_text() + "."]
    gross = gross_lines(d)
    if gross:
        lines += ["", f"Gross differences (a band STD ratio outside {GROSS_RATIO[0]:g}-{GROSS_RATIO[1]:g}x), "
                      "whether flagged or not:", ""] + [f"- {line}" for line in gross]
    lines += ["", coherence_sentence(d.coherence_deficit, d.settings.dofs[0]), ""]
    if d.candidates:
        lines += ["## Which effect", "",
                  f"Each candidate fitted to all tuning runs at once; score = BIC (lower is better; the plain "
                  f"model's is {d.baseline_score:.1f}). Named only if it beats the plain model by 6, closes "
                  "half the gap, its values are plausible (within the range a real platform's lie in, not at the "
                  "edge of the fit's bounds), its signature can close the flagged gap's sign, and on blind runs it "
                  "closes at least half of what it closes on the tuning runs; a candidate with a concern ranks "
                  "after every one without. A fit that leaves the gap larger than the plain model from every "
                  "start is a failed fit (\"fit failed\"), never named.", "",
                  "| effect | fitted parameters | score | closure (tuning) | fits | concerns |",
                  "|---|---|---|---|---|---|"]
        for c in d.candidates:
            values = ", ".join(f"{k} = {v:.4g}" for k, v in c.values.items())
            lines.append(f"| {c.effect} | {values} | {c.score:.1f} | {100 * c.closure:.0f} % | "
                         f"{'yes' if c.fits else 'fit failed' if c.failed else 'no'} | "
                         f"{'; '.join(c.concerns + [c.screened] * bool(c.screened)) or '-'} |")
        lines.append("")
    if d.chosen:
        chosen = d.candidate(d.chosen)
        tb, ta = _rms_flagged(d.tuning_before, chosen.gaps)
        lines += ["## How far it shrinks", "",
                  "| runs | closure | RMS flagged gap before | after |", "|---|---|---|---|",
                  f"| tuning (fitted) | {100 * chosen.closure:.0f} % | {tb:.2f} | {ta:.2f} |"]
        if d.blind_after:
            bb, ba = _rms_flagged(d.blind_before, d.blind_after)
            lines.append(f"| blind (not refitted) | {100 * d.blind_closure:.0f} % | {bb:.2f} | {ba:.2f} |")
        lines += ["", "RMS in units of each cell's tolerance. Cell by cell (flagged before):", "",
                  "| run | DOF | metric | gap before | after |", "|---|---|---|---|---|"]
        for before, after in zip(d.baseline, chosen.gaps + d.blind_after):
            for i in np.flatnonzero(before.flagged):
                dof, metric = cells[i]
                lines.append(f"| {before.run} | {dof} | {metric} | {_value_text(metric, before.value[i])} | "
                             f"{_value_text(metric, after.value[i])} |")
        lines.append("")
    if d.reading is not None:
        tuning, blind = d.reading_closure
        cells_read = ", ".join(f"{dof} {metric}" for dof, metric in d.reading_cell_names)
        lines += ["## How far the term read off the mismatch closes it", "",
                  f"{d.reading.effect} at its first fit's values ("
                  + ", ".join(f"{k} = {v:.4g}" for k, v in d.reading.values.items())
                  + f"), over the mismatch's cells it reads ({cells_read}):", "",
                  "| runs | closure |", "|---|---|", f"| tuning (fitted) | {100 * tuning:.0f} % |"]
        if d.reading_blind_after:
            lines.append(f"| blind (not refitted) | {100 * blind:.0f} % |")
        lines.append("")
    lines += ["## Figures", ""] + [f"![{name}]({name})" for name in figures] + [""]
    return "\n".join(lines)


def _jsonable(spectra: dict) -> dict:
    out = {}
    for run, variants in spectra.items():
        out[run] = {}
        for name, s in variants.items():
            keep = s["frequency_hz"] <= SPECTRA_F_MAX_HZ
            out[run][name] = {k: v[keep].tolist() for k, v in s.items()}
    return out


def write_report(diagnosis: Diagnosis, folder: str | Path) -> Path:
    """report.md, diagnosis.json and the figures in ``folder``; returns report.md's path."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    figures = ["gap_matrix.png"]
    plot_gap_matrix(diagnosis, folder / "gap_matrix.png")
    for run, spectra in diagnosis.spectra.items():
        name = f"spectra_{run.replace('/', '_')}.png"
        plot_spectra(run, spectra, diagnosis.settings.dofs, folder / name)
        figures.append(name)
    if diagnosis.candidates:
        plot_closure(diagnosis, folder / "closure.png")
        figures.append("closure.png")
    data = {**diagnosis.as_dict(), "spectra": _jsonable(diagnosis.spectra),
            "cells": [list(c) for c in diagnosis.settings.cells()]}
    (folder / "diagnosis.json").write_text(json.dumps(_finite(data), indent=1) + "\n")
    path = folder / "report.md"
    path.write_text(markdown(diagnosis, figures))
    return path


def _finite(value):
    """The data with every non-finite number as None (JSON has no NaN)."""
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value
