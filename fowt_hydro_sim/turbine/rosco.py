"""NREL's ROSCO, the compiled controller shipped in the rosco wheel, called through its C
interface (``turbine.discon``): only the library and its files are used, not ROSCO's Python
toolbox, so that the turbine needs neither WISDEM nor the toolbox's start-up time.

ROSCO keeps its state in the library's globals: each controller loads a copy of the library
of its own (several turbines in one process, e.g. the offline coupled runs of a study, do
not share their state). It reads its DISCON.IN and writes its debug files under a folder
of its own (a copy of the DISCON.IN with the performance table's path made absolute, debug
output off unless asked)."""
from __future__ import annotations

import ctypes
import difflib
import logging
import re
import shutil
import tempfile
from collections.abc import Mapping
from pathlib import Path

from fowt_hydro_sim.physics.config import ConfigError
from fowt_hydro_sim.turbine.discon import ControllerError, Discon

log = logging.getLogger("fowt_hydro_sim.rosco")


def parse_changes(spec: str) -> dict[str, str]:
    """DISCON.IN entries to replace, from ``NAME=VALUE; NAME=VALUE`` (VALUE: the entry's
    numbers, space-separated for a list) as ``{NAME: VALUE}``; ConfigError naming what does
    not read."""
    changes = {}
    for item in filter(None, (part.strip() for part in spec.split(";"))):
        name, equals, value = (text.strip() for text in item.partition("="))
        if not equals or not name or not value:
            raise ConfigError(f"discon_changes: expected NAME=VALUE (entries separated by ';'), got {item!r}")
        try:
            [float(v) for v in value.split()]
        except ValueError:
            raise ConfigError(f"discon_changes: {name}: expected numbers, got {value!r}") from None
        changes[name] = value
    return changes


def entry_name(line: str) -> tuple[str, str]:
    """A DISCON.IN line ``VALUES ! NAME - comment`` as (NAME, VALUES); NAME empty for a
    line without one."""
    values, _, comment = line.partition("!")
    return (comment.split() or [""])[0], values


def changed_discon(text: str, changes: Mapping[str, str], where: str) -> str:
    """The DISCON.IN ``text`` (lines ``VALUES ! NAME - comment``) with each entry of
    ``changes`` given its new values; ConfigError for a name the file has not (with the
    nearest it has) or a list of another length than the entry's."""
    lines = text.splitlines(keepends=True)
    names = [entry_name(line)[0] for line in lines]
    for name, value in changes.items():
        if name not in names:
            near = difflib.get_close_matches(name, [n for n in names if n], n=1)
            raise ConfigError(f"discon_changes: {name} is not an entry of {where}"
                              + (f" (nearest: {near[0]})" if near else ""))
        i = names.index(name)
        values, bang, comment = lines[i].partition("!")
        if len(values.split()) != len(value.split()):
            raise ConfigError(f"discon_changes: {name} has {len(values.split())} value(s) in {where}, "
                              f"got {len(value.split())}")
        lines[i] = f"{value:<19s} {bang}{comment}"
    return "".join(lines)


def discon_text(source: Path, changes: Mapping[str, str] | None = None) -> str:
    """The text of the DISCON.IN ``source`` with ``changes`` (``changed_discon``);
    ConfigError if it cannot be read."""
    try:
        text = source.read_text()
    except OSError as exc:
        raise ConfigError(f"DISCON file {source}: cannot be read ({exc.strerror})") from None
    return changed_discon(text, changes, source.name) if changes else text


def discon_copy(source: Path, folder: Path, logging_level: int = 0, changes: Mapping[str, str] | None = None) -> Path:
    """DISCON.IN in ``folder``: ``changes`` made (``changed_discon``), its PerfFileName made
    absolute, its LoggingLevel set."""
    text = discon_text(source, changes)

    def absolute(match: re.Match) -> str:
        path = Path(match.group(1))
        return f'"{path if path.is_absolute() else (source.parent / path).resolve()}"{match.group(2)}'

    text = re.sub(r'^\s*"([^"]*)"(\s+!\s*PerfFileName)', absolute, text, flags=re.M)
    text = re.sub(r"^\s*\d+(\s+!\s*LoggingLevel)", rf"{logging_level}\1", text, flags=re.M)
    target = folder / "DISCON.IN"
    target.write_text(text)
    return target


class Rosco:
    """One ROSCO instance: ``step`` passes the turbine's measurements and returns the
    generator torque [N m] and collective blade pitch [rad] it commands. ``changes``: DISCON.IN
    entries replaced (``changed_discon``), the file itself left as it is."""

    def __init__(self, discon: Path, dt_s: float, generator_efficiency: float, logging_level: int = 0,
                 pitch_rad: float = 0.0, changes: Mapping[str, str] | None = None):
        from rosco import discon_lib_path  # the package's __init__ only locates the library

        self._folder = tempfile.TemporaryDirectory(prefix="fowt_rosco_")
        folder = Path(self._folder.name)
        param = discon_copy(Path(discon), folder, logging_level, changes)
        self.dt_s, self._efficiency = dt_s, generator_efficiency
        ctypes.CDLL(discon_lib_path)  # the installed library loads the libraries it needs beside it (its rpath)
        library = shutil.copy2(discon_lib_path, folder / Path(discon_lib_path).name)  # the copy: its own globals
        # its integrators start at pitch_rad
        self._discon = Discon(library, param, str(folder / "rosco"), dt_s, pitch_rad, name="ROSCO")

    def step(self, t_s: float, wind_m_s: float, rotor_speed_rad_s: float, generator_speed_rad_s: float,
             pitch_rad: float, generator_torque_nm: float, pitch_acceleration_rad_s2: float = 0.0,
             last: bool = False, fore_aft_acceleration_m_s2: float = 0.0) -> tuple[float, float]:
        """One controller call (status 1, or -1 for the last); ``discon.ControllerError`` if ROSCO fails.
        ``pitch_acceleration_rad_s2`` is the nacelle's fore-aft angular acceleration (ROSCO's
        NacIMU_FA_RAcc, its Fl_Mode 2), ``fore_aft_acceleration_m_s2`` the tower top's fore-aft
        translational acceleration (FA_Acc_TT: Fl_Mode 1 and the tower damper TD_Mode)."""
        torque, pitch, _ = self._discon.call(t_s, wind_m_s, rotor_speed_rad_s, generator_speed_rad_s, pitch_rad,
                                             generator_torque_nm, self._efficiency,
                                             nacelle_angular_acceleration_rad_s2=pitch_acceleration_rad_s2,
                                             tower_top_acceleration_m_s2=fore_aft_acceleration_m_s2, last=last)
        return torque, pitch

    def close(self, debug_dir: str | Path | None = None) -> list[Path]:
        """End ROSCO's run and remove its folder; with ``debug_dir``, its debug files
        (``rosco.RO.dbg``, ``.dbg2``, ``.dbg3``, as its LoggingLevel wrote them: time series of
        its internal channels, one column each) are copied there first; the copies."""
        copies = []
        try:
            if debug_dir:
                try:
                    self._discon.finish()  # ROSCO writes and closes its debug files at its last call
                except ControllerError as exc:
                    log.warning(f"{exc}; its debug files are kept as they are")
                target = Path(debug_dir)
                target.mkdir(parents=True, exist_ok=True)
                for path in sorted(Path(self._folder.name).glob("rosco.RO.dbg*")):
                    copies.append(Path(shutil.copy2(path, target / path.name)))
        finally:
            self._folder.cleanup()
        return copies
