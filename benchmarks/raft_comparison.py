"""Benchmark: the coupled system `iea15_volturnus_s` (offline coupled loop, steady wind,
JONSWAP sea, wind and waves aligned along +x) against RAFT's frequency-domain response of
its own VolturnUS-S + IEA-15 design, in three conditions below, at and above rated.

RAFT's side (``--run-raft``, needs ``openraft`` 2.0.4): RAFT's design
(``test/data/raft/volturnus_s_raft_design.yaml``, transcribed from RAFT's repository) with
the blade and airfoil tables of the windIO file of the same turbine that ROSCO's wheel ships,
run for the three cases; its surge, heave and pitch means and STDs are written to
``test/data/raft/raft_response.yaml`` (what the test and the table read).

Our side: for each condition, --seeds runs of --duration s each after a --transient s cut
(the start from the static offset under the initial thrust, the surge mode's slow settling);
the mean and STD of surge, heave and pitch per seed, their mean over the seeds and the
seeds' spread (the range, max - min), against RAFT's, relative difference and whether it is
within 15 % (of RAFT's value); and for the STDs, ours of the wave-frequency part alone (at and
above half the peak frequency, where the sea is synthesised), to tell the wave-frequency
response from the low-frequency swing (slow drift, the surge and pitch modes) RAFT leaves out.

    python benchmarks/raft_comparison.py --run-raft     # RAFT's numbers, stored
    python benchmarks/raft_comparison.py [--seeds 3] [--duration 3600] [--transient 600]
"""
from __future__ import annotations

import argparse
import hashlib
import logging
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import yaml

from fowt_hydro_sim.physics.config import RunConfig, SeaState, load_platform
from fowt_hydro_sim.physics.model import RunResult
from fowt_hydro_sim.physics.waves.components import synthesize
from fowt_hydro_sim.studies.simulate import model_for
from fowt_hydro_sim.testing.references import turbine_without_tower_drag
from fowt_hydro_sim.turbine.coupled import run_coupled, static_offset, turbine_on_platform
from fowt_hydro_sim.turbine.system import load_system
from fowt_hydro_sim.turbine.wind import Wind

SYSTEM = "iea15_volturnus_s"
DATA = Path(__file__).resolve().parent.parent / "test" / "data" / "raft"
DESIGN = DATA / "volturnus_s_raft_design.yaml"
RESPONSE = DATA / "raft_response.yaml"
WINDIO = "Examples/example_inputs/windio/IEA-15-240-RWT_VolturnUS-S.yaml"  # in ROSCO's wheel
TOLERANCE = 0.15  # relative, the requirement's
DOFS = (("surge", 0, "m", 1.0), ("heave", 2, "m", 1.0), ("pitch", 4, "deg", 180.0 / np.pi))


@dataclass(frozen=True)
class Condition:
    """Steady hub-height wind and a JONSWAP sea, aligned."""

    name: str
    wind_m_s: float
    hs_m: float
    tp_s: float
    gamma: float = 3.3


CONDITIONS = (Condition("below rated", 8.0, 2.0, 8.0), Condition("at rated", 12.0, 4.0, 10.0),
              Condition("above rated", 18.0, 6.0, 12.0))


def sha256(path: Path) -> str:
    """The file's SHA-256."""
    return hashlib.sha256(path.read_bytes()).hexdigest()


def windio_file() -> Path:
    """The IEA-15 on VolturnUS-S windIO file of ROSCO's installed wheel."""
    from importlib import metadata
    for file in metadata.distribution("rosco").files or []:
        if str(file) == WINDIO:
            return Path(str(file.locate()))
    raise SystemExit(f"ROSCO's wheel has no {WINDIO}")


def rotor_from_windio(path: Path, rhub_m: float, n_span: int = 30) -> tuple[dict, list]:
    """RAFT's blade (``geometry`` rows r, chord, twist [deg], precurve, presweep at ``n_span``
    - 2 inner stations of an even spanwise grid, ``airfoils`` positions, tip values) and its
    airfoil polars (alpha [deg], cl, cd, cm) from a windIO 2 turbine file."""
    d = yaml.safe_load(path.read_text())
    blade, shape = d["components"]["blade"], d["components"]["blade"]["outer_shape"]
    axis = blade["reference_axis"]
    s = np.linspace(0.0, 1.0, n_span)[1:-1]

    def at(field: dict, grid: np.ndarray = s) -> np.ndarray:
        return np.interp(grid, field["grid"], field["values"])
    z, x, y = at(axis["z"]), at(axis["x"]), at(axis["y"])
    geometry = np.column_stack([rhub_m + z, at(shape["chord"]), at(shape["twist"]), x, y])
    tip = {k: float(np.interp(1.0, axis[k]["grid"], axis[k]["values"])) for k in ("x", "y", "z")}
    raft_blade = {"precurveTip": tip["x"], "presweepTip": tip["y"], "Rtip": rhub_m + tip["z"],
                  "geometry": geometry.round(4).tolist(),
                  "airfoils": [[float(a["spanwise_position"]), a["name"]] for a in shape["airfoils"]]}
    airfoils = []
    for foil in d["airfoils"]:
        polar = foil["polars"][0]["re_sets"][0]
        alpha = np.array(polar["cl"]["grid"], dtype=float)
        cd, cm = (np.interp(alpha, polar[k]["grid"], polar[k]["values"]) for k in ("cd", "cm"))
        data = np.column_stack([alpha, polar["cl"]["values"], cd, cm])
        airfoils.append({"name": foil["name"], "relative_thickness": float(foil["rthick"]),
                         "data": data.tolist()})
    return raft_blade, airfoils


def raft_design(windio: Path) -> dict:
    """RAFT's input: the stored design, the windIO rotor, the three cases."""
    design = yaml.safe_load(DESIGN.read_text())
    turbine = design["turbine"]
    turbine["blade"], turbine["airfoils"] = rotor_from_windio(windio, turbine["Rhub"])
    turbine["wt_ops"]["v"] = np.r_[np.linspace(3.0, 10.74, 30), np.linspace(10.74, 25.0, 30)[1:]].tolist()
    design["cases"] = {"keys": ["wind_speed", "wind_heading", "turbulence", "turbine_status", "yaw_misalign",
                                "wave_spectrum", "wave_period", "wave_height", "wave_heading", "wave_gamma"],
                       "data": [[c.wind_m_s, 0, 0.0, "operating", 0, "JONSWAP", c.tp_s, c.hs_m, 0, c.gamma]
                                for c in CONDITIONS]}
    return design


def run_raft() -> dict:
    """RAFT 2.0.4 on the three conditions: each one's surge, heave, pitch mean and STD."""
    from importlib import metadata

    import raft
    windio = windio_file()
    model = raft.Model(raft_design(windio))
    model.analyzeUnloaded()
    model.analyzeCases()
    cases = {}
    for i, c in enumerate(CONDITIONS):
        m = model.results["case_metrics"][i][0]
        cases[c.name] = {"wind_speed_m_s": c.wind_m_s, "hs_m": c.hs_m, "tp_s": c.tp_s, "gamma": c.gamma,
                         **{f"{dof}_{stat}": float(np.squeeze(m[f"{dof}_{key}"]))
                            for dof, *_ in DOFS for stat, key in (("mean", "avg"), ("std", "std"))}}
    return {"provenance": {
        "code": f"RAFT (openraft {metadata.version('openraft')})",
        "design": f"test/data/raft/{DESIGN.name} (sha256 {sha256(DESIGN)}), from WISDEM/RAFT designs/VolturnUS-S.yaml "
                  "at e52ef2e206e9b7603ddd10e9faaa47dd3df62a4d",
        "rotor": f"blade and airfoils from rosco {metadata.version('rosco')}'s {WINDIO} (sha256 {sha256(windio)})",
        "command": "python benchmarks/raft_comparison.py --run-raft",
        "units": "surge, heave [m]; pitch [deg]; means from RAFT's static solution, STDs from its spectra",
    }, "cases": cases}


def ours(condition: Condition, seed: int, duration_s: float, transient_s: float) -> dict:
    """One run of the offline coupled loop: each DOF's mean and STD after the transient."""
    system = load_system(SYSTEM)
    platform = load_platform(system.platform)
    run = RunConfig(platform=system.platform, mooring=system.mooring, duration_s=transient_s + duration_s)
    sea = SeaState(hs_m=condition.hs_m, tp_s=condition.tp_s, gamma=condition.gamma, seed=seed)
    model = model_for(platform, run, synthesize(sea, max(3600.0, run.duration_s)))
    with tempfile.TemporaryDirectory() as folder:  # RAFT loads its tower only under water: the loop's without drag
        rotor = turbine_on_platform(str(turbine_without_tower_drag(system.turbine, Path(folder))), platform,
                                    Wind(speed_m_s=condition.wind_m_s))
    try:
        model.reset(motion=static_offset(model, rotor))
        result = RunResult.joined([p.result for p in run_coupled(model, rotor, run.duration_s, run.output_interval_s)])
    finally:
        rotor.close()
    keep = result.time_s >= transient_s
    out = {}
    for dof, i, _, scale in DOFS:
        x = result.motion[keep, i] * scale
        out[f"{dof}_mean"], out[f"{dof}_std"] = float(x.mean()), float(x.std())
        out[f"{dof}_wave_std"] = wave_band_std(x, run.output_interval_s, 0.5 / condition.tp_s)
    return out


def wave_band_std(x: np.ndarray, dt_s: float, f_low_hz: float) -> float:
    """The STD of the record's part at and above ``f_low_hz`` (its periodogram summed there):
    the wave-frequency response, without the slow drift and the surge and pitch modes'
    low-frequency swing below it."""
    spectrum = np.abs(np.fft.rfft(x - x.mean())) ** 2
    f = np.fft.rfftfreq(x.size, dt_s)
    weight = np.where((f > 0) & (f < 0.5 / dt_s), 2.0, 1.0)  # one-sided: the bins that stand for two
    return float(np.sqrt((weight * spectrum)[f >= f_low_hz].sum()) / x.size)


def table(reference: dict, runs: dict[str, list[dict]]) -> list[str]:
    """The comparison's rows: condition, DOF, RAFT's mean/STD, ours +- the seeds' range, difference, within?"""
    lines = [f"{'condition':37s} {'DOF':11s} {'stat':4s} {'RAFT':>9s} {'ours':>9s} {'seeds range':>11s} "
             f"{'diff':>8s}  {'within 15 %':11s}  ours above f_p/2 (diff)"]
    for c in CONDITIONS:
        theirs = reference["cases"][c.name]
        label = f"{c.name}: {c.wind_m_s:g} m/s, Hs {c.hs_m:g} m, Tp {c.tp_s:g} s"
        for dof, _, unit, _ in DOFS:
            for stat in ("mean", "std"):
                values = np.array([r[f"{dof}_{stat}"] for r in runs[c.name]])
                ref, mine = theirs[f"{dof}_{stat}"], float(values.mean())
                diff = (mine - ref) / abs(ref)
                row = (f"{label:37s} {dof + ' [' + unit + ']':11s} {stat:4s} {ref:9.3f} {mine:9.3f} "
                       f"{np.ptp(values):11.3f} {100 * diff:+7.1f}%  {'yes' if abs(diff) <= TOLERANCE else 'no':11s}")
                if stat == "std":
                    wave = float(np.mean([r[f"{dof}_wave_std"] for r in runs[c.name]]))
                    row += f"  {wave:.3f} ({100 * (wave - ref) / abs(ref):+.1f}%)"
                lines.append(row)
    return lines


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--run-raft", action="store_true", help="run RAFT and store its numbers, then stop")
    parser.add_argument("--seeds", type=int, default=3, help="wave seeds per condition")
    parser.add_argument("--duration", type=float, default=3600.0, help="simulated seconds per seed after the transient")
    parser.add_argument("--transient", type=float, default=600.0, help="simulated seconds cut at the start")
    args = parser.parse_args()
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    if args.run_raft:
        response = run_raft()
        RESPONSE.write_text(yaml.safe_dump(response, sort_keys=False))
        print(yaml.safe_dump(response["cases"], sort_keys=False))
        return
    reference = yaml.safe_load(RESPONSE.read_text())
    runs: dict[str, list[dict]] = {}
    for c in CONDITIONS:
        runs[c.name] = []
        for seed in range(1, args.seeds + 1):
            start = time.perf_counter()
            runs[c.name].append(ours(c, seed, args.duration, args.transient))
            logging.info("%s, seed %d: %.0f s of wall time", c.name, seed, time.perf_counter() - start)
    print(f"{SYSTEM} (offline coupled loop, {args.seeds} seeds x {args.duration:g} s after {args.transient:g} s) "
          f"against {reference['provenance']['code']}")
    print("\n".join(table(reference, runs)))


if __name__ == "__main__":
    main()
