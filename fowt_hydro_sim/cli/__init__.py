"""``fowt-sim``: the command line. Each subcommand's module parses its options and calls a
function of the studies, bags or ROS packages that tests and Python users call directly.

Errors in the user's input (``errors.InputError``) end the command with one line naming the
problem (exit 2), and its traceback too with ``-v``; any other exception is a defect and ends
the command with its traceback (exit 1).

Only the chosen command's module is imported (start-up time: the modules import numba,
scipy and the model); ``fowt-sim --help`` and an unknown command import none of them: the
top-level help comes from the static table ``COMMAND_HELP``.
"""
from __future__ import annotations

import argparse
import copy
import importlib
import logging
import sys
import traceback

from fowt_hydro_sim.errors import ClusterError, InputError

# each subcommand and the module (fowt_hydro_sim.cli.<module>) whose add_parsers defines it
COMMAND_MODULES = {
    "simulate": "simulate", "load-cases": "simulate", "waves": "bags", "recover": "bags", "info": "bags",
    "analyze": "analyze", "calibrate": "calibrate", "diagnose": "diagnose", "diagnose-benchmark": "diagnose",
    "loads": "prescribed_motion", "platform": "platform", "measured": "measured", "sweep": "sweep",
    "compile": "compile", "stability": "stability",
}
# each subcommand's one-line help, as its module gives it (the top-level help imports no module)
COMMAND_HELP = {
    "simulate": "run the platform model offline and write its time series",
    "load-cases": "the paper's load cases with both drag models: band STDs and PSDs",
    "waves": "write a bag of /waves/elevation for a sea state or load case",
    "recover": "rebuild a bag whose recording was killed",
    "info": "a bag's topics, counts and run configuration",
    "analyze": "PSDs, band STDs and errors against a reference, of recorded runs",
    "calibrate": "fit drag coefficients to measured runs; regress and predict",
    "diagnose": "where the sim-to-real gap lies, which effect causes it, how far it shrinks",
    "diagnose-benchmark": "score the diagnosis on runs whose effect is withheld",
    "loads": "loads for a prescribed motion (the HydroDyn driver's job), to CSV",
    "platform": "platform files: import an OpenFAST HydroDyn deck",
    "measured": "measured runs: import basin files as bags",
    "sweep": "load cases x seeds x drag models x platform variants on a Dask cluster",
    "compile": "compile the model's kernels into the cache (set-up; first runs start fast)",
    "stability": "surge and pitch periods and damping with the rotor and its controller",
}

# commands whose arguments are their own (ROS arguments after --ros-args, or the bag tools')
ROS_COMMANDS = {
    "node": "the ROS 2 simulator node: fowt-sim node [--ros-args -p name:=value ... --params-file F]",
    "controller": "the example thrust controller node: fowt-sim controller [--ros-args ...]",
    "turbine": "the wind turbine node driven by NREL's ROSCO: fowt-sim turbine [--ros-args -p name:=value ...]",
    "closed-loop": "platform and turbine nodes in lockstep, recorded to one bag: fowt-sim closed-loop -o BAG "
                   "[--wind-speed 13 --duration 600 ...] (--help)",
    "play": "publish a bag's messages on the ROS graph: fowt-sim play BAG [--rate R] [--clock] ...",
    "record": "record topics of the ROS graph to a bag: fowt-sim record -o DIR [--topics ...]",
}


# the ROS node commands and the settings (module, class) their parameters come from
NODE_SETTINGS = {"node": ("fowt_hydro_sim.ros.node", "NodeSettings"),
                 "controller": ("fowt_hydro_sim.ros.thrust_controller", "ControllerSettings"),
                 "turbine": ("fowt_hydro_sim.ros.turbine_node", "TurbineSettings")}


def node_help(command: str = "node") -> str:
    """A node command's parameters with their defaults, meanings and ranges (from its settings)."""
    from fowt_hydro_sim.settings import described
    module, name = NODE_SETTINGS[command]
    settings = getattr(importlib.import_module(module), name)
    lines = ["", "parameters (-p name:=value):"]
    for name, item in described(settings).items():
        default = list(item.default) if isinstance(item.default, tuple) else item.default
        limits = item.setting.range_text()
        lines.append(f"  {name} (default {default!r}{'; ' + limits if limits else ''}): {item.setting.description}")
    return "\n".join(lines)


def _ros_command(name: str, argv: list[str]) -> int:
    if name in NODE_SETTINGS and any(a in ("-h", "--help") for a in argv[:1]):
        sys.stdout.write(f"usage: {ROS_COMMANDS[name].split(': ', 1)[1]}\n{node_help(name)}\n")
        return 0
    if name == "node":
        from fowt_hydro_sim.ros.node import main as run
        return run(["fowt-sim", *argv])
    if name == "controller":
        from fowt_hydro_sim.ros.thrust_controller import main as run
        return run(["fowt-sim", *argv])
    if name == "turbine":
        from fowt_hydro_sim.ros.turbine_node import main as run
        return run(["fowt-sim", *argv])
    if name == "closed-loop":
        from fowt_hydro_sim.cli.turbine import closed_loop
        return closed_loop(argv)
    if name == "play":
        from fowt_hydro_sim.ros.player import main as play
        return play(argv)
    from fowt_hydro_sim.ros.recorder import main as record
    return record(argv)


def _words(value: object) -> object:
    """A list or tuple default as the option takes it (``lc5.3 lc5.4``), anything else as it is."""
    return " ".join(map(str, value)) if isinstance(value, (list, tuple)) else value


class HelpFormatter(argparse.HelpFormatter):
    """Argparse's help, with list defaults (``%(default)s``) written as the option takes them."""

    def _expand_help(self, action: argparse.Action) -> str:
        if isinstance(action.default, (list, tuple)):
            action = copy.copy(action)
            action.default = _words(action.default)
        return super()._expand_help(action)


def _default_text(action: argparse.Action) -> str:
    """What an option's help says when it does not name its default itself."""
    if action.required:
        return "required"
    if isinstance(action, (argparse._StoreTrueAction, argparse._StoreFalseAction)):
        return "default off" if action.default is False else "default on"
    if action.default == "":
        return "default: empty"
    return "default: none" if action.default is None else f"default {_words(action.default)}"


def say_defaults(parser: argparse.ArgumentParser) -> None:
    """Every option's help names its default (or says it has none, or is required), list
    defaults written as the option takes them."""
    parser.formatter_class = HelpFormatter
    for action in parser._actions:
        if action.option_strings and action.help not in (None, argparse.SUPPRESS) and "default" not in action.help \
                and not isinstance(action, argparse._HelpAction):
            action.help += f" ({_default_text(action)})"


def chosen_command(argv: list[str]) -> str | None:
    """The subcommand named in ``argv`` (its first word that is not an option), if known."""
    word = next((a for a in argv if not a.startswith("-")), None)
    return word if word in COMMAND_MODULES else None


def _define(sub: argparse._SubParsersAction, module: str) -> None:
    """The subcommands of ``fowt_hydro_sim.cli.<module>``, every option's help naming its default."""
    known = set(sub.choices)
    importlib.import_module(f"fowt_hydro_sim.cli.{module}").add_parsers(sub)
    for name, command in sub.choices.items():
        if name not in known:
            say_defaults(command)


def parser(command: str | None = None) -> argparse.ArgumentParser:
    """The command line's parser: with ``command``, only that command's module is imported
    and defines its subcommands; without, the commands are listed from ``COMMAND_HELP``
    and no command's module is imported (the parser parses no command's options)."""
    top = argparse.ArgumentParser(prog="fowt-sim", description="Floating offshore wind platform simulator")
    top.add_argument("-v", "--verbose", action="store_true", help="debug logging")
    sub = top.add_subparsers(dest="command", required=True, metavar="COMMAND")
    if command:
        _define(sub, COMMAND_MODULES[command])
    else:
        for name, text in COMMAND_HELP.items():
            sub.add_parser(name, help=text, add_help=False)
    for name, text in ROS_COMMANDS.items():
        sub.add_parser(name, help=text.split(": ", 1)[0], add_help=False)
    return top


def command_parsers() -> dict[str, argparse.ArgumentParser]:
    """Every command's full parser by name (imports every command's module: for the tests
    and the reference pages, not for running a command)."""
    sub = argparse.ArgumentParser(prog="fowt-sim").add_subparsers()
    for module in dict.fromkeys(COMMAND_MODULES.values()):
        _define(sub, module)
    return dict(sub.choices)


def main(argv: list[str] | None = None) -> int:
    """Run ``fowt-sim`` with ``argv`` (default: the process's arguments); the exit code."""
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] and argv[0] in ROS_COMMANDS:
        return _ros_command(argv[0], argv[1:])
    args = parser(chosen_command(argv)).parse_args(argv)
    logging.basicConfig(level=logging.DEBUG if args.verbose else logging.INFO,
                        format="%(levelname)s %(name)s: %(message)s")
    try:
        return args.func(args)
    except (InputError, ClusterError) as exc:  # the user's input (ConfigError, BagError...), or lost runs
        if args.verbose:
            traceback.print_exc()
        sys.stderr.write(f"fowt-sim {args.command}: error: {exc}\n")
        return 2 if isinstance(exc, InputError) else 1
    except KeyboardInterrupt:
        sys.stderr.write(f"fowt-sim {args.command}: interrupted\n")
        return 130
