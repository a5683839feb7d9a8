"""Older HydroDyn deck layouts rewritten in the layout openfast-io reads.

HydroDyn's input file changed layout over OpenFAST's versions; openfast-io reads the newest by
position. The layout of OpenFAST 3.x (as the r-test's fixed-bottom cases hd_OC3tripod_* and
hd_5MW_OC4Jckt_* still hold it) differs from it in these lines, each recognised by its field
names and mapped here to the current fields:

- an ENVIRONMENTAL CONDITIONS section (WtrDens, WtrDpth, MSL2SWL) in the deck: dropped, the water
  depth and density being the import's options as the driver's are HydroDyn's; an MSL2SWL other
  than 0 (or "default") is refused;
- an axial-coefficient table of four columns (AxCoefID AxCd AxCa AxCp): AxFDMod 0, AxVnCOff 0,
  AxFDLoFSc 1 added (the axial drag as it was before those columns existed);
- one cross-section table (NPropSets: PropSetID PropD PropThck): the circular one (NPropSetsCyl)
  and an empty rectangular one;
- coefficient tables without Cb (simple: 12 columns, depth-based: 13, member-based: 25):
  Cb = CbMG = 1 added (the buoyancy as it was) and empty rectangular tables (NCoefDpthRec,
  NCoefMembersRec; the simple rectangular row all 0 with Cb 1);
- a member table without MSecGeom, MSpinOrient and MHstLMod (8 columns): circular (1), spin 0,
  MHstLMod 1 (the analytical member hydrostatics, the only one then).

The lines the layouts before HydroDyn v4 lack further on (AMMod, HstMod, NAddDOF, ...) are added
by ``hydrodyn.v5_layout``. A deck holding its own wave section (WaveMod, the layout before
SeaState existed) is refused naming WaveMod: its waves cannot be a platform's, give them as a
SeaState or ``.Comp`` file.
"""
from __future__ import annotations

import logging

from fowt_hydro_sim.physics.config import ConfigError

logger = logging.getLogger(__name__)

_ENVIRONMENT = ("WtrDens", "WtrDpth", "MSL2SWL")
_RECTANGULAR_SECTIONS = (
    "---------------- RECTANGULAR MEMBER CROSS-SECTION PROPERTIES (added by fowt-sim: older layout)",
    "             0   NPropSetsRec    - Number of rectangular member property sets (-), added by fowt-sim",
    "MPropSetID   PropA      PropB    PropThck",
    "   (-)        (m)        (m)       (m)")
_RECTANGULAR_SIMPLE = (
    "-------- SIMPLE RECTANGULAR-MEMBER HYDRODYNAMIC COEFFICIENTS (model 1) (added by fowt-sim: older layout)",
    "SimplCdA SimplCdAMG SimplCdB SimplCdBMG SimplCaA SimplCaAMG SimplCaB SimplCaBMG SimplCp SimplCpMG SimplAxCd "
    "SimplAxCdMG SimplAxCa SimplAxCaMG SimplAxCp SimplAxCpMG SimplCb SimplCbMG",
    " ".join(["(-)"] * 18),
    " ".join(["0.0"] * 16 + ["1.0", "1.0"]))
_RECTANGULAR_DEPTH = (
    "------ DEPTH-BASED RECTANGULAR-MEMBER HYDRODYNAMIC COEFFICIENTS (model 2) (added by fowt-sim: older layout)",
    "             0   NCoefDpthRec    - Number of depth-dependent rectangular member coefficients (-)",
    "Dpth DpthCdA DpthCdAMG DpthCdB DpthCdBMG DpthCaA DpthCaAMG DpthCaB DpthCaBMG DpthCp DpthCpMG DpthAxCd "
    "DpthAxCdMG DpthAxCa DpthAxCaMG DpthAxCp DpthAxCpMG DpthCb DpthCbMG",
    "(m) " + " ".join(["(-)"] * 18))
_RECTANGULAR_MEMBERS = (
    "------ MEMBER-BASED RECTANGULAR-MEMBER HYDRODYNAMIC COEFFICIENTS (model 3) (added by fowt-sim: older layout)",
    "             0   NCoefMembersRec - Number of member-based rectangular member coefficients (-)",
    "MemberID (the rectangular member-based table's columns)",
    "(-)")


def _name(line: str) -> str:
    words = line.split()
    return words[1] if len(words) > 1 else ""


def _count(line: str, field: str, source: str) -> int:
    try:
        return int(line.split()[0])
    except (IndexError, ValueError):
        raise ConfigError(f"{source}: field {field} reads as {line.split()[:1]}, not an integer") from None


def _values(row: str) -> list[str]:
    """A table row's values, without its trailing ``!`` comment."""
    return row.split("!", 1)[0].split()


def _widen(row: str, columns: int, added: list[str], field: str, source: str) -> str:
    """A table row of ``columns`` values with ``added`` appended (an older table's row; its
    comment dropped)."""
    values = _values(row)
    if len(values) < columns:
        raise ConfigError(f"{source}: a row of the {field} table has {len(values)} values, not {columns}: "
                          f"{row.strip()!r}")
    return " ".join(values[:columns] + added)


def _one_section_table(names: set[str]) -> bool:
    """A deck with one cross-section table (NPropSets) and no rectangular ones (v4 decks call
    theirs NRecPropSets, in the current positions)."""
    return "NPropSets" in names and not names & {"NPropSetsRec", "NRecPropSets"}


def is_older_layout(text: str) -> bool:
    """Whether the deck is of a layout this module rewrites (or refuses)."""
    lines = text.splitlines()
    names = {_name(line) for line in lines}
    if _one_section_table(names) or names & {"WaveMod", *_ENVIRONMENT}:
        return True
    if "NAxCoef" in names:  # an axial table of four columns
        start = [_name(line) for line in lines].index("NAxCoef")
        return any(len(_values(row)) == 4 for row in lines[start + 3:start + 3 + _count(lines[start], "NAxCoef", "")])
    return False


def current_layout(text: str, source: str) -> str:
    """The deck's text with the older layouts' lines rewritten as the current fields (module
    docstring); a deck of the current layout is returned unchanged. ConfigError naming the field
    that cannot be mapped."""
    if not is_older_layout(text):
        return text
    lines = text.splitlines()
    older_tables = _one_section_table({_name(line) for line in lines})
    out: list[str] = []
    i = 0
    while i < len(lines):
        line = lines[i]
        name = _name(line)
        first = line.split()[0] if line.split() else ""
        if name == "WaveMod":
            raise ConfigError(f"{source}: field WaveMod: a HydroDyn deck with its own waves section (the layout "
                              "before SeaState) is not read; give its members in a newer deck and the waves as a "
                              "SeaState or .Comp file")
        if "ENVIRONMENTAL CONDITIONS" in line:
            i += 1
            continue
        if name in _ENVIRONMENT:
            value = line.split()[0].strip('"')
            if name == "MSL2SWL" and value.lower() != "default":
                try:
                    offset = float(value)
                except ValueError:
                    raise ConfigError(f"{source}: field MSL2SWL reads as {value!r}, not a number") from None
                if offset != 0.0:
                    raise ConfigError(f"{source}: field MSL2SWL {offset:g}: only 0 is supported")
            if value.lower() != "default":
                logger.warning("%s: %s %s in the deck is not read: the import's --water-depth and --water-density "
                               "apply (HydroDyn's driver gives them in newer layouts)", source, name, value)
            i += 1
            continue
        if name == "NAxCoef":
            rows = _count(line, name, source)
            out.extend(lines[i:i + 3])
            for row in lines[i + 3:i + 3 + rows]:
                out.append(_widen(row, 4, ["0", "0.0", "1.0"], name, source) if len(_values(row)) == 4 else row)
            i += 3 + rows
            continue
        if name == "NPropSets" and older_tables:
            rows = _count(line, name, source)
            out.append(line.replace("NPropSets", "NPropSetsCyl", 1))
            out.extend(lines[i + 1:i + 3 + rows])
            out.extend(_RECTANGULAR_SECTIONS)
            i += 3 + rows
            continue
        if first == "SimplCd" and older_tables:
            if len(line.split()) == 12:
                out.extend([line + "  SimplCb  SimplCbMG", lines[i + 1] + "  (-)  (-)",
                            _widen(lines[i + 2], 12, ["1.0", "1.0"], "simple coefficient", source)])
            else:
                out.extend(lines[i:i + 3])
            out.extend(_RECTANGULAR_SIMPLE)
            i += 3
            continue
        if name in ("NCoefDpth", "NCoefMembers") and older_tables:
            rows = _count(line, name, source)
            columns, added, rectangular = ((13, ["1.0", "1.0"], _RECTANGULAR_DEPTH) if name == "NCoefDpth"
                                           else (25, ["1.0"] * 4, _RECTANGULAR_MEMBERS))
            out.append(line.replace(name, f"{name}Cyl", 1))
            out.extend(lines[i + 1:i + 3])
            out.extend(_widen(row, columns, added, name, source) if len(_values(row)) == columns else row
                       for row in lines[i + 3:i + 3 + rows])
            out.extend(rectangular)
            i += 3 + rows
            continue
        if name == "NMembers":
            rows = _count(line, name, source)
            header = lines[i + 1].split()
            out.extend(lines[i:i + 3])
            for row in lines[i + 3:i + 3 + rows]:
                values = _widen(row, 8 + ("MHstLMod" in header), [], name, source).split()
                if "MHstLMod" not in header:  # after MCoefMod
                    values.insert(7, "1")
                if "MSecGeom" not in header:  # MSecGeom and MSpinOrient after MPropSetID2
                    values[5:5] = ["1", "0"]
                out.append(" ".join(values))
            i += 3 + rows
            continue
        out.append(line)
        i += 1
    return "\n".join(out) + "\n"
