"""``fowt-sim waves`` (a wave bag for a sea state), ``info`` (a bag's topics and run
configuration) and ``recover`` (a killed recording rebuilt)."""
from __future__ import annotations

import argparse
import logging
import sys

from fowt_hydro_sim.cli import options
from fowt_hydro_sim.physics.config import RunConfig, load_platform

log = logging.getLogger("fowt_hydro_sim")


def waves(args: argparse.Namespace) -> int:
    from fowt_hydro_sim.studies.wave_bags import write_wave_bag
    sea, case = options.sea_state(args)
    environment = load_platform(args.platform).environment
    n = write_wave_bag(args.output, sea, args.duration, environment, args.sample_dt, tuple(args.point),
                       overwrite=args.overwrite, load_case=case)
    log.info(f"{args.output}: {n} elevation samples, {args.duration:g} s")
    return 0


def recover(args: argparse.Namespace) -> int:
    from fowt_hydro_sim.rosbag.recover import recover as rebuild
    count = rebuild(args.bag)
    if count is not None:
        log.info(f"{args.bag}: {count} messages recovered")
    return 0


def info(args: argparse.Namespace) -> int:
    from fowt_hydro_sim.ros.run_config import write_params_file
    from fowt_hydro_sim.rosbag.reader import Bag
    bag = Bag(args.bag)
    sys.stdout.write(bag.summary() + "\n")
    if args.params_file:
        written = write_params_file(bag.config or {}, args.params_file)
        rerun = (f"fowt-sim closed-loop -o NEW_BAG --params-file {args.params_file}"
                 if "turbine_parameters" in (bag.config or {}) else
                 f"fowt-sim node --ros-args --params-file {args.params_file}")
        log.info(f"{written}: rerun with {rerun}")
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("waves", help="write a bag of /waves/elevation for a sea state or load case",
                       description="Synthesise the sea state's elevation at one point and write it as a bag of "
                                   "/waves/elevation (geometry_msgs/PointStamped), log time = sample time.")
    options.add_sea_state(p)
    p.add_argument("--duration", type=float, default=10800.0, help="seconds of record (default %(default)s)")
    p.add_argument("--sample-dt", type=float, default=0.1, help="sample step [s] (default %(default)s)")
    p.add_argument("--point", type=float, nargs=2, default=(0.0, 0.0), metavar=("X", "Y"),
                   help="where the elevation is measured, world x y [m] (default 0 0)")
    options.add(p, RunConfig, ("platform",), notes={"platform": ", whose water depth and gravity apply"})
    p.add_argument("-o", "--output", required=True, help="bag directory to write")
    p.add_argument("--overwrite", action="store_true", help="replace an existing bag")
    p.set_defaults(func=waves)

    p = sub.add_parser("recover", help="rebuild a bag whose recording was killed",
                       description="Rewrite a bag left incomplete (killed recording) from its complete chunks; "
                                   "the damaged file is kept as *.mcap.damaged. An intact bag is left alone.")
    p.add_argument("bag", help="bag directory")
    p.set_defaults(func=recover)

    p = sub.add_parser("info", help="a bag's topics, counts and run configuration",
                       description="Print a bag's topics and run configuration; --params-file writes the node "
                                   "parameter file that reruns a recorded run.")
    p.add_argument("bag", help="bag directory")
    p.add_argument("--params-file", help="write the node parameters reproducing the run to this file (a closed "
                                          "loop's: both nodes', for fowt-sim closed-loop --params-file)")
    p.set_defaults(func=info)
