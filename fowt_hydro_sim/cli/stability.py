"""``fowt-sim stability``: the platform's surge and pitch natural periods and damping ratios
with the rotor and its controller (``studies.stability``), per wind speed."""
from __future__ import annotations

import argparse
import sys

from fowt_hydro_sim.cli import options
from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.config import DEFAULT_PLATFORM, RunConfig
from fowt_hydro_sim.turbine.settings import TurbineSettings
from fowt_hydro_sim.turbine.wind import MAX_WIND_M_S

DEFAULT_TURBINE = "iea15_umaine"
MIN_DECAY_S = 200.0  # a shorter decay holds under two surge periods


def stability(args: argparse.Namespace) -> int:
    from fowt_hydro_sim.studies.stability import stability as modes
    from fowt_hydro_sim.studies.stability import stability_text
    from fowt_hydro_sim.turbine.system import system_values

    if not all(0.0 < w <= MAX_WIND_M_S for w in args.wind_speed):
        raise InputError(f"--wind-speed: each must be above 0 and at most {MAX_WIND_M_S:g} m/s, got "
                         f"{' '.join(f'{w:g}' for w in args.wind_speed)}")
    if args.duration < MIN_DECAY_S:
        raise InputError(f"--duration: at least {MIN_DECAY_S:g} s (two surge periods), got {args.duration:g}")
    given = {"platform": args.platform, "mooring": args.mooring or "", "turbine": args.turbine}
    chosen = system_values(args.system or "", given, {"platform": DEFAULT_PLATFORM, "mooring": "",
                                                      "turbine": DEFAULT_TURBINE})
    title = (f"{chosen['platform']} + {chosen['turbine']} (ROSCO" + (f", {args.discon_changes}" if args.discon_changes
                                                                      else "")
             + f"), mooring {chosen['mooring'] or 'the platform default'}")
    for wind in args.wind_speed:
        result = modes(chosen["platform"], chosen["turbine"], wind, chosen["mooring"], args.duration,
                       args.discon_changes or "")
        sys.stdout.write(stability_text(result, title) + "\n")
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("stability", help="surge and pitch periods and damping with the rotor and its controller",
                       description="The platform's surge and pitch modes (natural period, damping ratio in % of "
                                   "critical) alone, with the rotor's controls held and with ROSCO, identified from "
                                   "free decays of the offline coupled loop in still water and steady wind, and the "
                                   "quasi-steady aerodynamic damping from dT/dU at the operating point.")
    p.add_argument("--system", help="named system (platform, turbine, mooring), e.g. iea15_volturnus_s")
    options.add(p, RunConfig, ("platform", "mooring"))
    p.add_argument("--turbine", default=DEFAULT_TURBINE, help="packaged turbine name or turbine YAML "
                                                              "(default %(default)s)")
    options.add(p, TurbineSettings, ("discon_changes",))
    p.add_argument("--wind-speed", type=float, nargs="+", default=[13.0],
                   help="hub-height wind speeds [m/s] (default %(default)s)")
    p.add_argument("--duration", type=float, default=600.0,
                   help="simulated seconds of each free decay (default %(default)s; several surge periods)")
    p.set_defaults(func=stability)
