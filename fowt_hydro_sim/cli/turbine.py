"""``fowt-sim closed-loop``: the platform node and the ROSCO-driven turbine node in lockstep,
recorded to one bag (``ros.closed_loop``). Its options are the two nodes' settings; the
ROS modules are imported only when the command runs."""
from __future__ import annotations

import argparse
import logging
import sys

NODE_OPTIONS = ("platform", "drag_model", "load_case", "hs_m", "tp_s", "seed", "duration_s", "dt_s",
                "real_time_factor", "publish_rate_hz", "initial_state", "lockstep_timeout_s", "controller_lost",
                "controller_timeouts")
TURBINE_OPTIONS = ("turbine", "hub_height_m", "wind", "wind_speed_m_s", "wind_end_m_s", "wind_start_s", "wind_ramp_s",
                   "wind_file", "wind_bag", "wind_topic", "rotor_start", "rotor_speed_rad_s", "pitch_rad",
                   "fixed_platform")


def parser() -> argparse.ArgumentParser:
    from fowt_hydro_sim.cli import options
    from fowt_hydro_sim.ros.node import NodeSettings
    from fowt_hydro_sim.ros.turbine_node import TurbineSettings

    p = argparse.ArgumentParser(prog="fowt-sim closed-loop",
                                description="Platform node + turbine node (NREL's ROSCO) in lockstep, both "
                                            "recorded to one bag; the nodes' logs go to <bag>.logs/.")
    p.add_argument("-o", "--output", required=True, help="bag directory to create")
    p.add_argument("--overwrite", action="store_true", help="replace an existing bag")
    options.add(p.add_argument_group("platform node"), NodeSettings, NODE_OPTIONS,
                defaults={"duration_s": 600.0, "real_time_factor": 0.0, "load_case": "lc5.2", "initial_state": None},
                notes={"initial_state": "; not given: the static offset under the initial thrust"})
    options.add(p.add_argument_group("turbine node"), TurbineSettings, TURBINE_OPTIONS,
                defaults={"wind_speed_m_s": 13.0})
    return p


def closed_loop(argv: list[str]) -> int:
    logging.basicConfig(level=logging.INFO, format="%(levelname)s %(name)s: %(message)s")
    from fowt_hydro_sim.cli import options
    from fowt_hydro_sim.physics.config import ConfigError
    from fowt_hydro_sim.ros import closed_loop as loop
    from fowt_hydro_sim.ros.node import NodeSettings
    from fowt_hydro_sim.ros.turbine_node import TurbineSettings

    args = parser().parse_args(argv)
    try:
        node = options.values(args, NodeSettings, NODE_OPTIONS)
        turbine = options.values(args, TurbineSettings, TURBINE_OPTIONS)
        if not node["duration_s"]:
            raise ConfigError("--duration: a closed-loop run needs a duration > 0")
        # the rules between settings, before starting anything
        NodeSettings(**{k: v for k, v in node.items() if v is not None}, lockstep=True)
        TurbineSettings(**{k: v for k, v in turbine.items() if v is not None})
        if node["initial_state"] is None:  # reads the turbine and the platform: their errors here
            node["initial_state"] = list(loop.static_offset(node, turbine))
    except ValueError as exc:
        sys.stderr.write(f"fowt-sim closed-loop: error: {exc}\n")
        return 2
    result = loop.run(args.output, node, turbine, overwrite=args.overwrite)
    failed = {name: code for name, code in result.returncodes.items() if code}
    for name, text in result.logs.items():
        errors = [line for line in text.splitlines() if "ERROR" in line]
        for line in errors[:3]:
            sys.stderr.write(f"{name}: {line}\n")
    sys.stdout.write(f"closed loop: {result.simulated_s:.1f} s simulated in {result.wall_s:.1f} s "
                     f"({result.speed:.2f} x real time); bag {args.output}, logs {args.output}.logs/"
                     + (f"; exit codes {failed}" if failed else "") + "\n")
    return 1 if failed else 0
