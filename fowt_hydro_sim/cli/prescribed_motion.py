"""``fowt-sim loads``: loads for a prescribed motion (HydroDyn driver PRP file) to CSV."""
from __future__ import annotations

import argparse
import dataclasses
import sys
from pathlib import Path

from fowt_hydro_sim.cli import options
from fowt_hydro_sim.physics.config import (
    HYDRO_OPTION_NAMES,
    HYDRODYN,
    ConfigError,
    HydroOptions,
    RunConfig,
    load_platform,
)
from fowt_hydro_sim.physics.waves.grid import SeaStateGrid
from fowt_hydro_sim.studies import prescribed_motion as study
from fowt_hydro_sim.studies.simulate import comp_file_waves, sea_state_waves

# kinematics, stretching, surface_grid_m and wave_kinematics: prescribed motion only
OPTION_NAMES = (*HYDRO_OPTION_NAMES, "kinematics", "stretching", "surface_grid_m", "wave_kinematics")


def loads(args: argparse.Namespace) -> int:
    out = Path(args.output)
    if out.exists() and not args.overwrite:
        raise ConfigError(f"{out}: exists (pass --overwrite to replace it)")
    base = HYDRODYN if args.hydrodyn else HydroOptions()
    given = {k: v for k, v in options.values(args, HydroOptions, OPTION_NAMES).items() if v is not None}
    hydro = dataclasses.replace(base, **given)
    platform = load_platform(args.platform)
    motion = study.read_prp_motion(args.motion)
    if args.still_water:
        waves = None
    elif args.waves_comp:
        waves, _ = comp_file_waves(args.waves_comp, direct_sum=True)
    else:
        sea, case = options.sea_state(args)
        waves, _ = sea_state_waves(sea, float(motion.time_s[-1]), case)
    if (hydro.wave_kinematics == "grid") != (args.seastate_grid is not None):
        raise ConfigError("--wave-kinematics grid and --seastate-grid go together: the grid is the SeaState file's")
    grid = None if args.seastate_grid is None else SeaStateGrid.from_seastate_file(args.seastate_grid)
    mooring = options.values(args, RunConfig, ("mooring",))["mooring"]
    result, tensions = study.prescribed_run(platform, waves, motion, hydro, args.wave_table_dt, mooring,
                                            wave_grid=grid)
    study.write_loads_csv(out, motion.time_s, result, tensions)
    sys.stdout.write(f"wrote {out}: {len(motion.time_s)} rows, {hydro}\n")
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("loads", help="loads for a prescribed motion (the HydroDyn driver's job), to CSV",
                       description="Loads along a prescribed 6-DOF motion of the platform reference point "
                                   "(HydroDyn driver PRP file, 19 columns), written as CSV with Time, "
                                   "HydroFxi .. HydroMzi (global axes, about the displaced reference point) "
                                   "and one column per load component and axis.")
    p.add_argument("--platform", default="windmoor12", help="packaged platform name or platform YAML file")
    p.add_argument("--motion", required=True, type=Path, help="HydroDyn driver PRP motion file (19 columns)")
    p.add_argument("-o", "--output", required=True, type=Path, help="CSV file to write")
    p.add_argument("--overwrite", action="store_true", help="replace the output file")
    waves = p.add_mutually_exclusive_group()
    waves.add_argument("--still-water", action="store_true", help="no waves")
    waves.add_argument("--waves-comp", type=Path,
                       help="OpenFAST wave components file (.Comp; frequencies on no common grid: summed directly)")
    options.add_sea_state(p)
    p.add_argument("--wave-table-dt", type=float, default=None,
                   help="kinematics table step [s] (default: chosen for 1e-3 interpolation error)")
    p.add_argument("--hydrodyn", action="store_true",
                   help="HydroDyn's choices: undisplaced wetted length, fixed directions, nonlinear hydrostatics")
    options.add(p, HydroOptions, OPTION_NAMES, defaults={name: None for name in OPTION_NAMES},
                notes={name: " (default: the model's, or HydroDyn's with --hydrodyn)" for name in OPTION_NAMES})
    p.add_argument("--seastate-grid", type=Path, default=None, metavar="SEASTATE_FILE",
                   help="SeaState input file whose grid (X/Y_HalfWidth, NX/NY, Z_Depth, NZ, WaveDT) "
                        "--wave-kinematics grid samples the waves on")
    options.add(p, RunConfig, ("mooring",), notes={"mooring": " (moordyn needs the time loop: not here)"})
    p.set_defaults(func=loads)
