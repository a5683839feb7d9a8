"""``fowt-sim closed-loop``: the platform node and the ROSCO-driven turbine node in lockstep,
recorded to one bag with the run's configuration (``ros.closed_loop``). Its options are the
two nodes' settings, or a parameter file of both (``--params-file``, as ``fowt-sim info``
writes it from a closed loop's bag) with the options given over it; the ROS modules are
imported only when the command runs."""
from __future__ import annotations

import argparse
import logging
import sys

NODE_OPTIONS = ("system", "platform", "drag_model", "load_case", "hs_m", "tp_s", "seed", "duration_s", "dt_s",
                "real_time_factor", "publish_rate_hz", "initial_state", "lockstep_timeout_s", "controller_lost",
                "controller_timeouts", "mooring")
TURBINE_OPTIONS = ("turbine", "hub_height_m", "wind", "wind_speed_m_s", "wind_end_m_s", "wind_start_s", "wind_ramp_s",
                   "wind_file", "wind_bag", "wind_topic", "rotor_start", "rotor_speed_rad_s", "pitch_rad",
                   "fixed_platform", "rosco_logging", "discon_changes")


def parser(defaults: bool = True) -> argparse.ArgumentParser:
    """The command's parser; ``defaults`` False: every option's default None (what was given)."""
    from fowt_hydro_sim.cli import options
    from fowt_hydro_sim.ros.node import NodeSettings
    from fowt_hydro_sim.ros.turbine_node import TurbineSettings

    p = argparse.ArgumentParser(prog="fowt-sim closed-loop",
                                description="Platform node + turbine node (NREL's ROSCO) in lockstep, both "
                                            "recorded to one bag with the run's configuration; the nodes' logs go "
                                            "to <bag>.logs/. Ctrl-C stops the run and closes the bag (exit 130).")
    p.add_argument("-o", "--output", required=True, help="bag directory to create")
    p.add_argument("--overwrite", action="store_true", help="replace an existing bag")
    p.add_argument("--params-file", help="both nodes' parameters from this file (fowt-sim info BAG --params-file "
                                         "writes it from a closed loop's bag: the run repeated); options given "
                                         "here override it (default: none)")
    platform = p.add_argument_group("platform node")
    options.add(platform, NodeSettings, NODE_OPTIONS,
                defaults={"duration_s": 600.0, "real_time_factor": 0.0, "load_case": "lc5.2", "initial_state": None},
                notes={"initial_state": "; not given: the static offset under the initial thrust"})
    platform.add_argument("--still-water", action="store_true", help="no waves (the node's wave_source none)")
    options.add(p.add_argument_group("turbine node"), TurbineSettings, TURBINE_OPTIONS)
    if not defaults:
        p.set_defaults(**{a.dest: None for a in p._actions if a.dest != "help"})
    return p


def _settings(argv: list[str], args: argparse.Namespace) -> tuple[dict, dict]:
    """The two nodes' parameters: the options', or the parameter file's with the options given
    on the command line over them. ConfigError names a bad one."""
    from fowt_hydro_sim.cli import options
    from fowt_hydro_sim.physics.config import ConfigError
    from fowt_hydro_sim.ros import closed_loop as loop
    from fowt_hydro_sim.ros.node import NodeSettings
    from fowt_hydro_sim.ros.turbine_node import TurbineSettings

    node = options.values(args, NodeSettings, NODE_OPTIONS)
    turbine = options.values(args, TurbineSettings, TURBINE_OPTIONS)
    if args.params_file:
        given = vars(parser(defaults=False).parse_args(argv))
        file_node, file_turbine = loop.read_params_file(args.params_file)
        node = {**file_node, **{k: v for k, v in node.items() if given[k] is not None}}
        turbine = {**file_turbine, **{k: v for k, v in turbine.items() if given[k] is not None}}
        for name in ("lockstep", "record", "record_overwrite"):  # the loop's own
            node.pop(name, None)
        for name in ("wait_for_subscribers", "rosco_debug_dir"):  # the loop's own (beside the new bag)
            turbine.pop(name, None)
    node, turbine = loop.with_systems(node, turbine)
    if args.still_water:
        node["wave_source"] = "none"
    if not node.get("duration_s"):
        raise ConfigError("--duration: a closed-loop run needs a duration > 0")
    # the rules between settings, before starting anything
    NodeSettings(**{k: v for k, v in node.items() if v is not None}, lockstep=True)
    TurbineSettings(**{k: v for k, v in turbine.items() if v is not None})
    if node.get("initial_state") is None:  # reads the turbine and the platform: their errors here
        node["initial_state"] = list(loop.static_offset(node, turbine))
    return node, turbine


def closed_loop(argv: list[str]) -> int:
    """``fowt-sim closed-loop``: the exit code (0 complete, 1 a process failed, 2 bad input,
    130 stopped by Ctrl-C), after one summary line."""
    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(name)s: %(message)s")
    from fowt_hydro_sim.ros import closed_loop as loop

    args = parser().parse_args(argv)
    try:
        node, turbine = _settings(argv, args)
    except ValueError as exc:
        sys.stderr.write(f"fowt-sim closed-loop: error: {exc}\n")
        return 2
    except KeyboardInterrupt:
        sys.stderr.write("fowt-sim closed-loop: interrupted before starting\n")
        return 130
    result = loop.run(args.output, node, turbine, overwrite=args.overwrite)
    failed = {name: code for name, code in result.returncodes.items() if code}
    for name, text in result.logs.items():
        errors = [line for line in text.splitlines() if "ERROR" in line]
        for line in errors[:3]:
            sys.stderr.write(f"{name}: {line}\n")
    sys.stdout.write(f"closed loop{' interrupted' if result.interrupted else ''}: {result.simulated_s:.1f} s "
                     f"simulated in {result.wall_s:.1f} s ({result.speed:.2f} x real time); bag {args.output}, "
                     f"logs {args.output}.logs/" + (f"; exit codes {failed}" if failed else "") + "\n")
    return 130 if result.interrupted else 1 if failed else 0
