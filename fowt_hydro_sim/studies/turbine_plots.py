"""The closed loop's time series (``fowt-sim analyze`` of a bag with the turbine's topics):
rotor speed, blade pitch, generator power, platform pitch and surge, and their statistics."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from fowt_hydro_sim.studies.figures import pyplot
from msg_adapters import topics

PANELS = (  # (label, scale, unit)
    ("rotor speed", 60 / (2 * np.pi), "rpm"),
    ("blade pitch", 180 / np.pi, "deg"),
    ("generator power", 1e-6, "MW"),
    ("platform pitch", 180 / np.pi, "deg"),
    ("platform surge", 1.0, "m"),
)


def has_turbine(bag) -> bool:
    return topics.TURBINE["rotor_speed"][0] in bag.topics


def closed_loop_series(bag) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Each panel's (time [s], values in the panel's unit)."""
    motion = bag.motion()
    raw = {"rotor speed": bag.scalar(topics.TURBINE["rotor_speed"][0]),
           "blade pitch": bag.scalar(topics.TURBINE["blade_pitch"][0]),
           "generator power": bag.scalar(topics.TURBINE["generator_power"][0])}
    out = {name: (s.time_s, s.values[:, 0]) for name, s in raw.items()}
    out["platform pitch"] = (motion.time_s, motion.values[:, 4])
    out["platform surge"] = (motion.time_s, motion.values[:, 0])
    return {name: (t, v * scale) for (name, scale, _), (t, v) in zip(PANELS, (out[p[0]] for p in PANELS))}


def stats_rows(name: str, series: dict[str, tuple[np.ndarray, np.ndarray]], transient_s: float) -> list[dict]:
    rows = []
    for label, _, unit in PANELS:
        t, v = series[label]
        kept = v[t >= min(transient_s, t[-1])]
        rows.append({"run": name, "quantity": label, "unit": unit, "mean": float(kept.mean()),
                     "std": float(kept.std()), "min": float(kept.min()), "max": float(kept.max())})
    return rows


def plot_closed_loop(name: str, series: dict[str, tuple[np.ndarray, np.ndarray]], path: Path) -> Path | None:
    """The closed loop's time series, one panel each, to ``path`` (None without matplotlib)."""
    plt = pyplot()
    if plt is None:
        return None

    fig, axes = plt.subplots(len(PANELS), 1, figsize=(8.0, 2.0 * len(PANELS)), sharex=True)
    for ax, (label, _, unit) in zip(axes, PANELS):
        t, v = series[label]
        ax.plot(t, v, lw=0.8)
        ax.set_ylabel(f"{label} [{unit}]")
        ax.grid(alpha=0.3)
    axes[0].set_title(f"closed loop: {name}")
    axes[-1].set_xlabel("time [s]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
