"""MoorDyn input files: v1's layout rewritten in v2's, and the lines of a file as MoorPy reads
them (each line from a fixed anchor to a fairlead on the platform, with its unstretched
length, axial stiffness and weight in water per metre: what the quasi-static catenary needs).

MoorDyn-C 2.7 and MoorPy 1.2 read v2's layout only (``LINE TYPES``, ``POINTS``, ``LINES``);
a v1 file (``LINE DICTIONARY``, ``NODE PROPERTIES`` or ``CONNECTION PROPERTIES``, ``LINE
PROPERTIES``, as MoorDyn v1's documentation lays it out) is rewritten in v2's layout
(``v2_text``) before either reads it: line types' columns Diam MassDen EA BA/-zeta Can Cat
Cdn Cdt become Diam MassDen EA BA/-zeta EI=0 Cd=Cdn Ca=Can CdAx=Cdt CaAx=Cat; node types
Fixed/Fix/Anchor, Vessel/Vess/Fair and Connect/Con/Free become Fixed, Vessel and Free; lines'
NodeAnch NodeFair become AttachA AttachB. The other sections are kept as they are.

MoorPy prints while it reads a file; that text goes to the log at debug level.
"""
from __future__ import annotations

import contextlib
import io
import logging
import re
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fowt_hydro_sim.errors import InputError

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class CatenaryLine:
    """One line: its number in the file, fairlead (body frame: relative to the platform's
    reference point at rest) and anchor (world frame) [m], unstretched length [m], EA [N],
    weight in water per metre [N/m] and seabed friction coefficient."""

    number: int
    fairlead_m: tuple[float, float, float]
    anchor_m: tuple[float, float, float]
    length_m: float
    ea_n: float
    weight_n_m: float
    seabed_friction: float


_V1_SECTIONS = ("LINE DICTIONARY", "NODE PROPERTIES", "CONNECTION PROPERTIES", "LINE PROPERTIES")
_V1_TYPES = {"fixed": "Fixed", "fix": "Fixed", "anchor": "Fixed", "vessel": "Vessel", "vess": "Vessel",
             "fair": "Vessel", "connect": "Free", "con": "Free", "free": "Free"}


def _section(line: str) -> str | None:
    """The name of a section header line (``---- NAME ----``), upper case, or None."""
    if "---" not in line:
        return None
    name = re.sub(r"-+", " ", line).strip().upper()
    return name or None


def v2_text(text: str, name: str) -> str | None:
    """A v1 file's text rewritten in v2's layout, or None for a file that is not v1's.
    ``name`` (the file's) names a row that cannot be rewritten (InputError)."""
    lines = text.splitlines()
    if not any((_section(line) or "").startswith(_V1_SECTIONS) for line in lines):
        return None
    out, section, row = [], None, 0
    headers = {"LINE DICTIONARY": ("LINE TYPES", "Name Diam MassDen EA BA/-zeta EI Cd Ca CdAx CaAx",
                                   "(-) (m) (kg/m) (N) (N-s/-) (N-m^2) (-) (-) (-) (-)"),
               "NODE PROPERTIES": ("POINTS", "ID Attachment X Y Z M V CdA CA", "(-) (-) (m) (m) (m) (kg) (m^3) "
                                   "(m^2) (-)"),
               "LINE PROPERTIES": ("LINES", "ID LineType AttachA AttachB UnstrLen NumSegs Outputs",
                                   "(-) (-) (-) (-) (m) (-) (-)")}
    headers["CONNECTION PROPERTIES"] = headers["NODE PROPERTIES"]
    for number, line in enumerate(lines, 1):
        name_of = _section(line)
        if name_of is not None:
            section = next((s for s in _V1_SECTIONS if name_of.startswith(s)), None)
            row = 0
            if section is not None:
                out += [f"---------------------- {headers[section][0]} ----------------------", *headers[section][1:]]
                continue
            out.append(line)
            continue
        row += 1
        if section is None:
            out.append(line)
            continue
        if row <= 2 or not line.strip():  # the v1 column names and units: v2's were written
            continue
        f = line.split()
        try:
            if section == "LINE DICTIONARY":
                out.append(" ".join([f[0], f[1], f[2], f[3], f[4], "0", f[7], f[5], f[8], f[6]]))
            elif section == "LINE PROPERTIES":
                out.append(" ".join([f[0], f[1], f[4], f[5], f[2], f[3], *(f[6:7] or ["-"])]))
            else:
                out.append(" ".join([f[0], _V1_TYPES[f[1].lower()], f[2], f[3], f[4], f[5], f[6], f[10], f[11]]))
        except (IndexError, KeyError):
            raise InputError(f"{name}:{number}: not a row of MoorDyn v1's {section} section: {line.strip()!r}") \
                from None
    return "\n".join(out) + "\n"


def readable_copy(file: str | Path, folder: Path) -> Path:
    """``file`` copied into ``folder`` under its name, in v2's layout if it is a v1 file."""
    file = Path(file)
    copy = folder / file.name
    try:
        text = file.read_text(errors="replace")
    except OSError as exc:
        raise InputError(f"{file}: cannot be read ({exc.strerror or exc})") from None
    rewritten = v2_text(text, str(file))
    if rewritten is None:
        shutil.copyfile(file, copy)
    else:
        copy.write_text(rewritten)
        log.debug("%s: MoorDyn v1 layout rewritten in v2's", file)
    return copy


def without_outputs(copy: Path) -> Path:
    """The copy ``copy`` rewritten with its OUTPUTS section's channel list emptied (its header
    and END kept): MoorDyn then writes no channels at its steps."""
    lines = copy.read_text(errors="replace").splitlines()
    out, skipping = [], False
    for line in lines:
        name = _section(line)
        if skipping and (name is not None or line.strip().upper().startswith("END")):
            skipping = False
        if not skipping:
            out.append(line)
        if name is not None and name.startswith("OUTPUTS"):
            skipping = True
    copy.write_text("\n".join(out) + "\n")
    return copy


def with_time_step(copy: Path, dt_s: float) -> Path:
    """The copy ``copy`` (v2 layout) rewritten with MoorDyn's internal time step dtM set to
    ``dt_s``: its OPTIONS line replaced, or one added at the top of the OPTIONS section."""
    lines = copy.read_text(errors="replace").splitlines()
    option = f"{dt_s!r}    dtM       - time step to use in mooring integration (s)"
    for i, line in enumerate(lines):
        fields = line.split()
        if len(fields) >= 2 and fields[1] == "dtM":
            lines[i] = option
            break
    else:
        options = [i for i, line in enumerate(lines) if "OPTIONS" in (_section(line) or "")]
        if not options:
            raise InputError(f"{copy.name}: no OPTIONS section to set MoorDyn's time step dtM in")
        lines.insert(options[0] + 1, option)
    copy.write_text("\n".join(lines) + "\n")
    return copy


def read_lines(file: str | Path, depth_m: float) -> tuple[CatenaryLine, ...]:
    """The anchor-to-fairlead lines of a MoorDyn input file, read by MoorPy; InputError (one
    line naming the file) if MoorPy refuses it or a line does not run from a fixed point to a
    platform point."""
    import moorpy

    file = Path(file)
    text = io.StringIO()
    with tempfile.TemporaryDirectory(prefix="fowt_moorpy_") as folder:
        copy = readable_copy(file, Path(folder))
        try:
            with contextlib.redirect_stdout(text):
                system = moorpy.System(file=str(copy), depth=depth_m)
                system.initialize()
        except Exception as exc:  # MoorPy raises anything on a file it cannot read
            raise InputError(f"{file}: MoorPy cannot read it ({type(exc).__name__}: {exc})") from None
        finally:
            if text.getvalue():
                log.debug("MoorPy reading %s: %s", file, text.getvalue().strip())
    if not system.lineList:
        raise InputError(f"{file}: no mooring lines")
    points = {p.number: p for p in system.pointList}
    lines = []
    for line in system.lineList:
        ends = [p for p in points.values() if line.number in p.attached]
        types = sorted(p.type for p in ends)
        if len(ends) != 2 or types != [-1, 1]:
            raise InputError(f"{file}: line {line.number}: must run from a fixed anchor to a platform (vessel or "
                             "coupled) point; lines through free points, rods or bodies are not supported")
        fairlead, anchor = (ends[0], ends[1]) if ends[0].type == -1 else (ends[1], ends[0])
        lines.append(CatenaryLine(int(line.number), tuple(float(v) for v in fairlead.r),
                                  tuple(float(v) for v in anchor.r), float(line.L), float(line.type["EA"]),
                                  float(line.type["w"]), float(getattr(line, "cb", 0.0) or 0.0)))
    for line in lines:
        if not (line.length_m > 0 and line.ea_n > 0 and np.isfinite(line.weight_n_m)):
            raise InputError(f"{file}: line {line.number}: needs a positive length and EA")
    return tuple(lines)
