"""The reference tables of docs/reference/, written from the code's own registries: the
command line's parsers, the nodes' settings, the topic contract, the load registry and the
diagnosis's catalogue of effects. A table is never edited by hand; after a change of the
code, rewrite them all:

    python -m fowt_hydro_sim.cli.reference_tables            # into docs/reference/ of this checkout
    python -m fowt_hydro_sim.cli.reference_tables -o DIR     # elsewhere

A test (test/test_docs.py) fails while a committed table differs from what this writes.
Importing the nodes' settings imports rclpy (no ROS context is started). It lives with the
command line, the one layer that may import all the others it reads (the command parsers,
the nodes, the physics and the studies), but it is not a ``fowt-sim`` command: the tables
belong to a checkout's docs/.
"""
from __future__ import annotations

import argparse
import importlib
import re
import sys
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

COMMAND = "python -m fowt_hydro_sim.cli.reference_tables"
CHECKOUT_FOLDER = Path(__file__).resolve().parents[2] / "docs" / "reference"

# the ROS commands (cli.ROS_COMMANDS) whose arguments an argparse parser of their own reads:
# the module with its ``parser()``; the nodes' parameters are in node_parameters.md
ROS_COMMAND_PARSERS = {"closed-loop": "fowt_hydro_sim.cli.turbine", "play": "fowt_hydro_sim.ros.player",
                       "record": "fowt_hydro_sim.ros.recorder"}


def _cell(value: Any) -> str:
    """A Markdown table cell: one line, pipes escaped."""
    return " ".join(str(value).split()).replace("|", "\\|")


def _table(header: Iterable[str], rows: Iterable[Iterable[Any]]) -> list[str]:
    header = list(header)
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(_cell(v) for v in row) + " |" for row in rows]
    return lines


def _page(title: str, body: list[str]) -> str:
    return "\n".join([f"# {title}", "",
                      f"Generated from the code by `{COMMAND}`; do not edit by hand.", "", *body]).rstrip() + "\n"


# ---------------------------------------------------------------------- the command line
_SAID_DEFAULT = re.compile(r"\s*\((default[^()]*|required)\)$")


def _option_rows(p: argparse.ArgumentParser) -> list[tuple[str, str, str]]:
    """(option, default, help) of each argument of a parser but --help, in its order."""
    formatter = p._get_formatter()
    rows = []
    for action in p._actions:
        if isinstance(action, (argparse._HelpAction, argparse._SubParsersAction)) or action.help == argparse.SUPPRESS:
            continue
        text = _SAID_DEFAULT.sub("", formatter._expand_help(action) if action.help else "")
        if action.option_strings:
            metavar = "" if action.nargs == 0 else " " + formatter._format_args(action, action.dest.upper())
            option = ", ".join(f"`{flag}{metavar}`" for flag in action.option_strings)
        else:
            option = f"`{action.metavar or action.dest}`"
        rows.append((option, _default(action), text))
    return rows


def _default(action: argparse.Action) -> str:
    if action.required or not action.option_strings and action.nargs not in ("?", "*"):
        return "required"
    if action.nargs == 0:
        return "on" if action.default is True else "off"
    if action.default is None or action.default == argparse.SUPPRESS:
        return "none"
    value = " ".join(map(str, action.default)) if isinstance(action.default, (list, tuple)) else action.default
    return f"`{value}`"


def _subcommands(p: argparse.ArgumentParser) -> dict[str, tuple[str, argparse.ArgumentParser]]:
    """A parser's subcommands: name -> (one-line help, parser); none without."""
    sub = next((a for a in p._actions if isinstance(a, argparse._SubParsersAction)), None)
    if sub is None:
        return {}
    helps = {a.dest: a.help for a in sub._choices_actions}
    return {name: (helps.get(name, ""), command) for name, command in sub.choices.items()}


def _options(p: argparse.ArgumentParser) -> list[str]:
    rows = _option_rows(p)
    return _table(("option", "default", "meaning"), rows) if rows else ["No options."]


def _command_section(name: str, text: str, command: argparse.ArgumentParser) -> list[str]:
    """A command's heading, description and options, then its own subcommands' sections."""
    lines = ["", f"## fowt-sim {name}", "", (command.description or text).strip(), "", *_options(command)]
    for sub_name, (sub_text, sub_command) in _subcommands(command).items():
        lines += _command_section(f"{name} {sub_name}", sub_text, sub_command)
    return lines


def cli_page() -> str:
    """Every ``fowt-sim`` command with every option (from the command line's parsers)."""
    from fowt_hydro_sim.cli import ROS_COMMANDS, parser
    if unknown := set(ROS_COMMAND_PARSERS) - set(ROS_COMMANDS):
        raise ValueError(f"reference tables: no ROS command {', '.join(sorted(unknown))} (cli.ROS_COMMANDS)")
    commands = _subcommands(parser())
    body = ["`fowt-sim [-v] COMMAND ...`: `-v`, `--verbose` turns on debug logging. Each command's "
            "`--help` says the same as its table here.", ""]
    body += _table(("command", "what it does"), ((f"[`{name}`](#fowt-sim-{name})", text)
                                                for name, (text, _) in commands.items()))
    for name, (text, _) in commands.items():
        if name not in ROS_COMMANDS:  # the command's full parser: parser(name) defines it
            body += _command_section(name, text, _subcommands(parser(name))[name][1])
            continue
        own = importlib.import_module(ROS_COMMAND_PARSERS[name]).parser() if name in ROS_COMMAND_PARSERS else None
        body += ["", f"## fowt-sim {name}", "", (own and own.description or text).strip(), "",
                 f"Usage: `{ROS_COMMANDS[name].split(': ', 1)[1]}`"]
        if own:
            body += ["", *_options(own)]
        elif name in ("node", "turbine"):
            body += ["", f"Its parameters: [node_parameters.md](node_parameters.md#fowt-sim-{name})."]
    return _page("The `fowt-sim` command line", body)


# ---------------------------------------------------------------------- the nodes' parameters
def _type_text(item) -> str:
    name = item.scalar_type.__name__
    if item.size is not None:
        name = f"{name}[{item.size}]" if item.kind.__args__[-1] is not Ellipsis else f"{name}[]"
    return f"{name} or none" if item.optional else name


def _value_text(value: Any) -> str:
    if isinstance(value, tuple):
        return "`[" + ", ".join(f"{v:g}" if isinstance(v, float) else str(v) for v in value) + "]`"
    if isinstance(value, str):
        return f'`"{value}"`'
    if isinstance(value, bool):
        return f"`{str(value).lower()}`"
    return f"`{value:g}`" if isinstance(value, float) else f"`{value}`"


def settings_rows(settings: type) -> list[tuple[str, str, str, str, str]]:
    """(name, type, default, range, meaning) of each setting of a settings dataclass."""
    from fowt_hydro_sim.settings import described
    return [(f"`{name}`", _type_text(item), _value_text(item.default), item.setting.range_text(),
             item.setting.description) for name, item in described(settings).items()]


def node_parameters_page() -> str:
    """The simulator node's and the turbine node's ROS parameters."""
    from fowt_hydro_sim.ros.node import NodeSettings
    from fowt_hydro_sim.ros.turbine_node import TurbineSettings
    header = ("parameter", "type", "default", "range", "meaning")
    body = ["Set with `--ros-args -p name:=value` or `--params-file F`; `ros2 param describe` gives the same "
            "meanings and ranges. A value out of its range is refused at start-up with one line naming it.", "",
            "## fowt-sim node", "", "The platform simulator node (`NodeSettings` in `fowt_hydro_sim/ros/node.py`).",
            "", *_table(header, settings_rows(NodeSettings)), "",
            "## fowt-sim turbine", "",
            "The wind turbine node driven by NREL's ROSCO (`TurbineSettings` in "
            "`fowt_hydro_sim/ros/turbine_node.py`).", "", *_table(header, settings_rows(TurbineSettings))]
    return _page("The nodes' parameters", body)


# ---------------------------------------------------------------------- topics and loads
def topic_rows(names: Iterable[str], types: dict[str, str]) -> list[tuple[str, str, str]]:
    """(topic, type, meaning) of each topic named; a load topic's meaning is its component's."""
    from fowt_hydro_sim.physics.loads import COMPONENTS, SUMMED
    from msg_adapters import topics
    loads = {topics.load_topic(c.name): c for c in COMPONENTS}
    rows = []
    for topic in names:
        if topic == topics.load_topic(topics.TOTAL):
            meaning = " + ".join(SUMMED) + ", `world` axes, about the reference point"
        elif topic in loads:
            meaning = loads[topic].summary + ("" if loads[topic].summed else " (not in the total)")
        elif topic in topics.MEANINGS:
            meaning = topics.MEANINGS[topic]
        else:
            raise ValueError(f"reference tables: topic {topic} has no meaning in msg_adapters.topics.MEANINGS")
        rows.append((f"`{topic}`", types[topic].replace("/msg/", "/"), meaning))
    return rows


def topics_page() -> str:
    """Every topic of the contract with its type and meaning."""
    from fowt_hydro_sim.physics.loads import PUBLISHED
    from msg_adapters import topics
    outputs = dict(topics.outputs(PUBLISHED).values())
    turbine = dict(topics.TURBINE.values())
    header = ("topic", "type", "meaning")
    body = ["The topic contract of `msg_adapters/topics.py` ([ros_interface.md](../ros_interface.md) says how the "
            "node uses it). There is one `/platform/loads/NAME` topic per published load component of the load "
            "registry ([load_components.md](load_components.md)); all load topics are in `world` axes, about "
            "the reference point.", "",
            "## What the node subscribes to", "", *_table(header, topic_rows(topics.INPUTS, topics.INPUTS)), "",
            "## What the node publishes", "", *_table(header, topic_rows(outputs, outputs)), "",
            "## What the turbine node publishes", "",
            f"Besides `{topics.EXTERNAL_WRENCH}` (the rotor's thrust and moments, frame `hub`); it subscribes to "
            f"`{topics.MOTION['odom'][0]}`.", "", *_table(header, topic_rows(turbine, turbine))]
    return _page("Topics", body)


def load_components_page() -> str:
    """The load registry: its rows in order."""
    from fowt_hydro_sim.physics.loads import COMPONENTS
    rows = [(row, f"`{c.name}`", c.summary, "yes" if c.summed else "no", "yes" if c.restoring else "no",
             f"`/platform/loads/{c.name}`" if c.published else "none",
             f"`physics/loads/{c.module}.py`" if c.module else "Morison strip model (`physics/morison.py`)")
            for row, c in enumerate(COMPONENTS)]
    body = ["The rows of the loads the model computes, in order (`COMPONENTS` in "
            "`fowt_hydro_sim/physics/loads/__init__.py`): `RunResult.load(name)`, the `NAME_fx_n` ... "
            "`NAME_mz_nm` columns of `timeseries.csv` (`fowt-sim simulate`), the `NAME_Fx` ... `NAME_Mz` columns "
            "of `fowt-sim loads` and the node's topics follow it. "
            "`/platform/loads/total` is the sum of the components summed into the total; the restoring ones make "
            "the model's restoring matrix (`PlatformModel.restoring_matrix`). World axes, about the "
            "reference point.", "",
            *_table(("row", "component", "what it is", "summed into total", "restoring", "own topic", "code"), rows)]
    return _page("Load components", body)


# ---------------------------------------------------------------------- the diagnosis's effects
def _number(value: float) -> str:
    return f"{value:g}"


def effects_page() -> str:
    """The gap diagnosis's catalogue of candidate effects and their parameters."""
    from fowt_hydro_sim.studies.diagnosis.effects import CATALOGUE
    from fowt_hydro_sim.studies.diagnosis.effects.base import MATERIAL_SCALE
    header = ("parameter", "unit", "start", "fitted within", "plausible", "off at", "material departure",
              "why plausible")
    body = ["The candidate unmodelled effects the gap diagnosis (`fowt-sim diagnose`) fits, in catalogue order "
            "(`CATALOGUE` of `fowt_hydro_sim.studies.diagnosis.effects`). Each parameter starts its fit at "
            "`start` within its fit range; at `off` the effect is switched off; a fit outside the plausible "
            "range, or at the edge of the fit range, is a sign that the parameter absorbs something else. "
            "A scale of one of the model's own terms with a material departure set is no finding (never named) "
            "while every such scale lies within it of `off`.", ""]
    body += _table(("effect", "what it is", "parameters"),
                   ((f"[`{e.name}`](#{e.name})", e.summary, len(e.parameters))
                    for e in CATALOGUE.values()))
    for effect in CATALOGUE.values():
        body += ["", f"## {effect.name}", "", effect.summary, ""]
        if not effect.wave_coherent:
            body += ["Its loads are quadratic in the waves: their low-frequency part is not coherent with the "
                     "elevation.", ""]
        if effect.own_share is not None:
            body += [f"It adds to a term the model has: a fit adding less than {MATERIAL_SCALE:.0%} of the model's "
                     "own on the tuning runs is no finding (never named).", ""]
        body += _table(header, ((f"`{p.name}`", p.unit, _number(p.start), f"{_number(p.low)} to {_number(p.high)}",
                                 "{} to {}".format(*map(_number, p.plausible_range)), _number(p.off),
                                 _number(p.material) if p.material else "-", p.why)
                                for p in effect.parameters))
    return _page("Diagnosis effects", body)


PAGES: dict[str, Callable[[], str]] = {
    "cli.md": cli_page,
    "node_parameters.md": node_parameters_page,
    "topics.md": topics_page,
    "load_components.md": load_components_page,
    "effects.md": effects_page,
}


def write(folder: Path) -> list[Path]:
    """Write every reference table into ``folder`` (made if missing); returns the files."""
    folder.mkdir(parents=True, exist_ok=True)
    written = []
    for name, page in PAGES.items():
        path = folder / name
        path.write_text(page())
        written.append(path)
    return written


def main(argv: list[str] | None = None) -> int:
    """``python -m fowt_hydro_sim.cli.reference_tables [-o DIR]``: write the tables."""
    p = argparse.ArgumentParser(prog=COMMAND, description="Write the reference tables of docs/reference/ "
                                                          "from the code.")
    p.add_argument("-o", "--output", type=Path, help="folder to write to (default: docs/reference/ of the "
                                                     "checkout this package is in)")
    args = p.parse_args(argv)
    folder = args.output
    if folder is None:
        if not CHECKOUT_FOLDER.parent.is_dir():
            sys.stderr.write(f"{COMMAND}: error: no docs/ folder beside the package (an installed copy); "
                             f"give -o DIR\n")
            return 2
        folder = CHECKOUT_FOLDER
    for path in write(folder):
        sys.stdout.write(f"{path}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
