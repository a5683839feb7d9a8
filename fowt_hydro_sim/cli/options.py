"""Command-line options derived from settings (``fowt_hydro_sim.settings``): the option's
name, type, default and help text (with the default and the range) come from the setting,
and ``values`` checks what was given against it, naming the option."""
from __future__ import annotations

import argparse
import re
from typing import Any

from fowt_hydro_sim.physics.config import ConfigError
from fowt_hydro_sim.settings import Described, SettingError, check, described

FLAGS = {"drag_model": "--drag", "initial_state": "--initial"}  # where the name without its unit is not the flag
_UNIT = re.compile(r"_(m_s|rad_s|s|m|hz|deg|rad|kg|n|n_m)$")


def flag(name: str) -> str:
    """``--dt`` for ``dt_s``, ``--output-interval`` for ``output_interval_s``."""
    return FLAGS.get(name) or "--" + _UNIT.sub("", name).replace("_", "-")


def _help(item: Described, default: Any, note: str) -> str:
    s = item.setting
    extras = [f"default {default if not isinstance(default, tuple) else ' '.join(map(str, default))}"
              if default not in (None, "") else "", s.range_text() if not s.choices else ""]
    text = s.description + note
    extras = [e for e in extras if e]
    return text + (f" ({'; '.join(extras)})" if extras else "")


def add(parser: argparse.ArgumentParser | argparse._ArgumentGroup, cls: type, names: tuple[str, ...],
        defaults: dict[str, Any] | None = None, notes: dict[str, str] | None = None) -> None:
    """Options for the settings ``names`` of ``cls``; ``defaults`` replace a setting's
    default for this command (e.g. None: not given), ``notes`` add to its help."""
    defaults, notes = defaults or {}, notes or {}
    for name, item in described(cls, names).items():
        default = defaults.get(name, item.default)
        kind = item.scalar_type
        kwargs: dict[str, Any] = {"dest": name, "default": default, "help": _help(item, default, notes.get(name, ""))}
        if kind is bool:
            parser.add_argument(flag(name), action="store_true", **kwargs)
            continue
        if item.setting.choices:
            kwargs["choices"] = item.setting.choices
        if item.size:
            kwargs.update(nargs=item.size, metavar="V")
        parser.add_argument(flag(name), type=kind, **kwargs)


def values(args: argparse.Namespace, cls: type, names: tuple[str, ...]) -> dict[str, Any]:
    """The options' values checked against their settings; ConfigError names the option.
    A value left at None (not given) stays None."""
    out = {}
    for name, item in described(cls, names).items():
        value = getattr(args, name)
        if value is None:
            out[name] = None
            continue
        try:
            out[name] = check(item, value)
        except SettingError as exc:
            raise ConfigError(f"{flag(name)}: {exc}") from None
    return out


# ---------------------------------------------------------------------- the sea state, as commands take it
SEA_OPTIONS = ("hs_m", "tp_s", "gamma", "heading_deg", "seed")


def add_sea_state(parser: argparse.ArgumentParser | argparse._ArgumentGroup, load_case: str = "lc5.3") -> None:
    """--load-case, or --hs and --tp (with --gamma) for any sea; --heading and --seed."""
    from fowt_hydro_sim.physics.config import SeaState
    parser.add_argument("--load-case", default=load_case, help="a load case of the paper, lc5.0 .. lc6.5 "
                                                               "(default %(default)s)")
    add(parser, SeaState, SEA_OPTIONS, defaults={"hs_m": None, "tp_s": None, "gamma": None},
        notes={"hs_m": ", with --tp instead of a load case", "gamma": " (default 1 with --hs and --tp)"})


def sea_state(args: argparse.Namespace):
    """The sea state of ``add_sea_state``'s options, and its load case's name (None for --hs/--tp)."""
    from fowt_hydro_sim.physics.config import SeaState, load_case
    given = values(args, SeaState, SEA_OPTIONS)
    common = {"heading_deg": given["heading_deg"], "seed": given["seed"]}
    if given["hs_m"] is not None or given["tp_s"] is not None:
        if given["hs_m"] is None or given["tp_s"] is None:
            raise ConfigError("--hs and --tp go together")
        gamma = given["gamma"] if given["gamma"] is not None else SeaState.gamma
        return SeaState(given["hs_m"], given["tp_s"], gamma, **common), None
    case = load_case(args.load_case)
    return SeaState(case.sea_state.hs_m, case.sea_state.tp_s, case.sea_state.gamma, **common), case.name
