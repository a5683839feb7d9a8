"""The named system iea15_volturnus_s's steady platform offsets (surge, heave, pitch) per wind
speed from the offline coupled loop (still water, steady wind, 900 s, the last 400 s
averaged) against the operating points of OpenFAST's linearisations of the same system
(``test/data/volturnus_s/lin_operating_points.csv``: the 12 rotor azimuths of each wind
speed averaged), with the rotor's aerodynamic thrust (AeroDyn's RtAeroFxh), blade pitch and rotor
speed beside them.

    python benchmarks/lin_steady_offsets.py [--winds 5 6 ... 24]
"""
from __future__ import annotations

import argparse
import csv
from collections import defaultdict
from pathlib import Path

import numpy as np

from fowt_hydro_sim.studies.coupled_run import steady_state

TABLE = Path(__file__).resolve().parents[1] / "test" / "data" / "volturnus_s" / "lin_operating_points.csv"
QUANTITIES = ("surge_m", "heave_m", "pitch_rad", "rotor_aero_thrust_n", "blade_pitch_rad", "rotor_speed_rad_s")


def openfast_operating_points(path: Path = TABLE) -> dict[float, dict[str, float]]:
    """Per wind speed, each quantity of the linearisations' operating points averaged over the azimuths."""
    rows: dict[float, list[dict]] = defaultdict(list)
    with path.open() as f:
        for row in csv.DictReader(f):
            rows[float(row["wind_speed_m_s"])].append(row)
    return {wind: {q: float(np.mean([float(r[q]) for r in group])) for q in QUANTITIES} for wind, group in rows.items()}


def main() -> None:
    reference = openfast_operating_points()
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--winds", type=float, nargs="+", default=sorted(reference), help="wind speeds [m/s]")
    args = parser.parse_args()
    print("| wind [m/s] | surge [m] ours / OpenFAST (error) | heave [m] | pitch [deg] | thrust [MN] "
          "| blade pitch [deg] | rotor speed [rad/s] | surge STD [m] |")
    print("|---|---|---|---|---|---|---|---|")
    for wind in args.winds:
        ours, theirs = steady_state("iea15_volturnus_s", wind), reference[wind]
        ours["rotor_aero_thrust_n"] = ours["thrust_n"]
        cells = []
        for q, scale, fmt in (("surge_m", 1, ".2f"), ("heave_m", 1, ".3f"), ("pitch_rad", 180 / np.pi, ".2f"),
                              ("rotor_aero_thrust_n", 1e-6, ".2f"), ("blade_pitch_rad", 180 / np.pi, ".1f"),
                              ("rotor_speed_rad_s", 1, ".3f")):
            a, b = ours[q] * scale, theirs[q] * scale
            cells.append(f"{a:{fmt}} / {b:{fmt}} ({100 * (a - b) / abs(b):+.0f} %)")
        print(f"| {wind:g} | " + " | ".join(cells) + f" | {ours['surge_std_m']:.2f} |", flush=True)


if __name__ == "__main__":
    main()
