"""OpenFAST HydroDyn v5 input files as platforms: the strip-theory members of a HydroDyn deck
(joints, circular and rectangular sections, simple or member-based coefficient tables, joint
axial coefficients, MDivSize) as a platform YAML document.

The deck is read with ``openfast-io`` (``InputReader_OpenFAST().read_HydroDyn``), which reads
the file line by line by position: a deck of another layout is misread, not refused (its
SeaState reader misreads newer files silently the same way). So the values read here are
checked for what they must be (finite, known switches, joints that exist) and what the model
cannot represent is refused with one line naming the member: filled rectangular members, depth-based
coefficient tables whose rows differ (HydroDyn interpolates in depth, the model's zones are
piecewise constant; equal rows are read as constants), Cb other than 1, rectangular members
with different side-A and side-B Morison coefficients (which of the model's two drag and
added-mass directions HydroDyn's CdA, CaA act in has not been checked against HydroDyn), and
tapered rectangular members with axial added mass or drag (AxCa, AxCd). Cp is the zone's
``cp``. A tapered member keeps both end sizes (circular: diameters; rectangular: side A as
``width_m``/``width_b_m``, side B as ``height_m``/``height_b_m``) and the member's axial
coefficients (AxCa, AxCp, AxCd of its coefficient table: the tapered wall's axial terms,
strips.py); MSpinOrient is ``spin_deg`` (side A's direction turned about the axis from the
horizontal, as HydroDyn's Morison_DirCosMtrx; checked against HydroDyn's MHstLMod 2 loads on
the r-test case hd_MHstLMod2_RectMmbr). Whether member hydrostatics follow the waves is a run
option (``hydrostatics``: nonlinear to the still water level, free_surface to the instantaneous
surface, HydroDyn's HstMod); a circular member's MHstLMod 2 flags it ``hydrostatics_by_section``
(free_surface then wets each element section by section, as MHstLMod 2; MHstLMod 1 cuts it where
its axis crosses the surface), a rectangular member's free_surface hydrostatics are MHstLMod 2's
whatever its MHstLMod. A Cp of
``MCF`` flags the member ``maccamy_fuchs`` (waves/maccamy_fuchs.py; the correction's diameter
is the member's, which HydroDyn requires within 10 % of SeaState's MCFD). Marine growth
(MGDepths: MGDpth, MGThck, MGDens) is the platform's ``marine_growth`` table, and each circular
member's MG coefficients (CdMG, CaMG, CpMG; CbMG 1) its ``growth_zone``
(physics/marine_growth.py); the axial MG coefficients are not read (the grown pieces' tapered
walls, where the growth tapers between two nodes, take the member's own AxCa, AxCp, AxCd).
Filled members (NFillGroups: FillMList, FillFSLoc, FillDens, its DEFAULT the water's density)
are the platform's ``fill_groups``, each filled member keeping its wall (PropThck) as
``wall_thickness_m`` (physics/fill.py).

Decks of the OpenFAST 3.x layouts (the deck's own water depth and density, one cross-section
table, coefficient tables without Cb, members without MSecGeom, MSpinOrient, MHstLMod) are first
rewritten as the current fields by ``hydrodyn_layouts.current_layout``, or refused naming the
field it cannot map. Decks of older layouts (HydroDyn v4 as in the OpenFAST r-test, and the layouts before it),
which lack some of the lines openfast-io reads (NAddDOF, HstMod; ExctnDisp, ExctnCutOff,
PtfmYMod, PtfmRefY, PtfmYCutOff, NExctnHdg), are read with those lines added at the value
that keeps the older meaning (no additional DOF; HstMod 1: before HstMod existed HydroDyn
integrated the member hydrostatics up to the instantaneous free surface whenever SeaState's
WaveStMod was above 0, and up to the still water level otherwise, which is what HstMod 1 does;
the potential-flow settings at HydroDyn's example values, ExctnDisp 0 as before it
existed); decks of the newer layout are read without its potential-flow lines FKMod and
GeoFile. A deck openfast-io still cannot read is refused in one line naming the last field
it read, and the integer switches the import uses must read as integers.

Members wholly at or below the seabed (the water depth given) are not imported and the plates
of the members standing on them at the seabed joint are dropped, as HydroDyn runs them
(``_above_seabed``); a member crossing the seabed is refused. The joint axial coefficients
(JointAxID) become end plates as HydroDyn applies them, to the end areas of the members meeting
at a joint summed as vectors (of the grown radii under marine growth): none where they cancel,
none on a pair of ends in line, and one plate carrying the sums (``joint_area_m2``,
``joint_volume_m3``) where two or more ends are left.

A potential-flow deck (PotMod 1) is imported as HydroDyn runs it for one WAMIT body at the
reference point: PotFile (resolved relative to the deck, as HydroDyn resolves it), WAMITULEN,
PtfmVol0, PtfmCOBxt/yt, RdtnMod 1 (convolution), 2 (state space from PotFile's ``.ss`` file) or 0
(no memory), RdtnTMax (the kernel's step is the model's: HydroDyn's RdtnDT DEFAULT), AddF0,
AddCLin, AddBLin, AddBQuad, and NewmanApp from a ``.12d`` file as the drift table (the surge
QTF's diagonal, negative values set to 0). Refused, each in one line naming the field: PotMod 2
(FIT), NBody > 1, NAddDOF > 0, a reference point or rotation other than 0, ExctnMod other than
1, ExctnDisp other than 0, PtfmYMod 1, MnDrift, DiffQTF and SumQTF (full QTFs), NewmanApp from
another file than ``.12d``
Members with PropPot are imported drag only (``drag_only``: no
inertia, added mass or buoyancy of their own), as HydroDyn treats them.

A HydroDyn deck has no structural mass and no mooring: the platform written floats freely
(mass = rho V at the centre of buoyancy; one mooring line without stiffness or
pretension), which is what ``fowt-sim loads``
needs; give it real mass properties before simulating it.
"""
from __future__ import annotations

import gc
import math
import tempfile
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from fowt_hydro_sim.io.hydrodyn_layouts import current_layout
from fowt_hydro_sim.physics.config import ConfigError, MarineGrowthLevel, platform_from_dict
from fowt_hydro_sim.physics.marine_growth import thickness_and_density

# (field, the field it follows, value): lines older layouts lack, in the order to add them
_ADDED_LINES = (("ExctnDisp", "ExctnMod", "0"), ("ExctnCutOff", "ExctnDisp", "10"), ("PtfmYMod", "ExctnCutOff", "0"),
                ("PtfmRefY", "PtfmYMod", "0"), ("PtfmYCutOff", "PtfmRefY", "0.01"), ("NExctnHdg", "PtfmYCutOff", "36"),
                ("NAddDOF", "PtfmCOByt", "0"), ("AMMod", "WaveDisp", "0"), ("HstMod", "AMMod", "1"))
# lines of newer layouts openfast-io does not read: potential-flow settings the import does not use
_DROPPED_LINES = ("FKMod", "GeoFile")
# integer fields the import uses: a deck read out of step gives them text or a fraction
_INTEGER_FIELDS = ("PotMod", "NBody", "NBodyMod", "NAxCoef", "NJoints", "NPropSetsCyl", "NPropSetsRec",
                   "NCoefDpthCyl", "NCoefDpthRec", "NCoefMembersCyl", "NCoefMembersRec", "NMembers", "NFillGroups",
                   "NMGDepths")


def v5_layout(text: str) -> str:
    """A HydroDyn deck's text in the layout openfast-io reads: each line of ``_ADDED_LINES`` the
    deck lacks is added after the field it follows (when that field is there), and the lines
    of ``_DROPPED_LINES`` are left out; a deck of openfast-io's layout is unchanged."""
    lines = [line for line in text.splitlines(keepends=True)
             if len(line.split()) < 2 or line.split()[1] not in _DROPPED_LINES]
    for added, after, value in _ADDED_LINES:
        names = [line.split()[1] if len(line.split()) > 1 else "" for line in lines]
        if added not in names and after in names:
            lines.insert(names.index(after) + 1, f"{value:>14}   {added}        - (added by fowt-sim: older layout)\n")
    return "".join(lines)


def read_deck(path: str | Path) -> dict[str, Any]:
    """The deck as openfast-io reads it; ConfigError naming the field if it cannot be read."""
    try:
        from openfast_io.FAST_reader import InputReader_OpenFAST
    except ImportError:
        raise ConfigError("platform import needs the package openfast-io (pip install 'fowt_hydro_sim[hydrodyn]')") \
            from None
    path = Path(path)
    reader = InputReader_OpenFAST()
    try:
        text = v5_layout(current_layout(path.read_text(), str(path)))
    except (OSError, UnicodeDecodeError) as exc:
        raise ConfigError(f"{path}: cannot be read ({type(exc).__name__}: {exc})") from None
    failure = ""
    with tempfile.TemporaryDirectory() as folder, warnings.catch_warnings():
        warnings.simplefilter("ignore", ResourceWarning)  # openfast-io leaves its file open
        deck = Path(folder) / path.name
        deck.write_text(text)
        try:
            reader.read_HydroDyn(str(deck))
        except Exception as exc:  # openfast-io raises bare Exception, TypeError, ... on a misread deck
            failure = f"{type(exc).__name__}: {exc}"
        gc.collect()  # the failed read's open file, inside the warnings filter
    hd = reader.fst_vt["HydroDyn"]
    for name in _INTEGER_FIELDS:
        if name in hd and not isinstance(hd[name], int):
            raise ConfigError(f"{path}: field {name} reads as {hd[name]!r}, not an integer (a HydroDyn deck of "
                              "another layout, read out of step)")
    if failure:
        last = list(hd)[-1] if hd else "none"
        raise ConfigError(f"{path}: not a HydroDyn deck of a layout openfast-io reads: it stopped after field "
                          f"{last} ({failure})")
    # openfast-io resolves PotFile against the copy's folder; HydroDyn against the deck's
    files = hd.get("PotFile") or []
    hd["PotFile"] = [str((path.parent / Path(f).relative_to(folder)).resolve()) if f.startswith(folder) else f
                     for f in ([files] if isinstance(files, str) else files)]
    return hd


def _refuse_unsupported(hd: dict, source: str) -> None:
    if hd["PotMod"] not in (0, 1):
        raise ConfigError(f"{source}: PotMod {hd['PotMod']}: only 0 (strip theory) and 1 (WAMIT) are supported")


def _fill_groups(hd: dict, members: list[dict], source: str, water_density_kg_m3: float) -> dict:
    """The deck's fill groups (FillMList, FillFSLoc, FillDens; DEFAULT: the water's density) as
    the platform's ``fill_groups``, the members left above the seabed only, and each filled
    member's wall (PropThck of its two property sets) as its ``wall_thickness_m``
    (physics/fill.py); ConfigError for a filled rectangular member or one filled twice."""
    by_name = {m["name"]: m for m in members}
    groups, seen = [], set()
    for k in range(hd["NFillGroups"]):
        ids = [int(i) for i in hd["FillMList"][k][:hd["FillNumM"][k]]]
        density = hd["FillDens"][k]
        if isinstance(density, str):
            if density.upper() != "DEFAULT":
                raise ConfigError(f"{source}: FillDens {density!r}: a number or DEFAULT")
            density = water_density_kg_m3
        density, surface = float(density), float(hd["FillFSLoc"][k])
        if not (math.isfinite(density) and density > 0 and math.isfinite(surface)):
            raise ConfigError(f"{source}: fill group {k + 1}: FillFSLoc {surface}, FillDens {density}: finite "
                              "numbers, the density positive")
        names = []
        for member in ids:
            if member not in hd["MemberID"]:
                raise ConfigError(f"{source}: FillMList: member {member} is not in the member table")
            if member in seen:
                raise ConfigError(f"{source}: FillMList: member {member} is in more than one fill group")
            seen.add(member)
            index = hd["MemberID"].index(member)
            if hd["MSecGeom"][index] != 1:
                raise ConfigError(f"{source}: FillMList: member {member} is rectangular: filled rectangular members "
                                  "are not supported")
            if f"member{member}" not in by_name:  # wholly below the seabed: HydroDyn fills none of it
                continue
            walls = [float(hd["CylPropThck"][hd["CylPropSetID"].index(s)])
                     for s in (hd["MPropSetID1"][index], hd["MPropSetID2"][index])]
            by_name[f"member{member}"]["wall_thickness_m"] = walls[0]
            if walls[1] != walls[0]:
                by_name[f"member{member}"]["wall_thickness_b_m"] = walls[1]
            names.append(f"member{member}")
        if names:
            groups.append({"members": names, "free_surface_z_m": surface, "density_kg_m3": density})
    return {"fill_groups": groups} if groups else {}


def _table_values(hd: dict, index: int, kind: str, names: tuple[str, ...], source: str) -> dict[str, Any]:
    """The coefficients ``names`` of member ``index`` from the table its MCoefMod names
    (``kind``: Cyl or Rec), as written (numbers, or a word such as MCF)."""
    member = hd["MemberID"][index]
    mode = hd["MCoefMod"][index]
    if mode == 1:
        return {name: hd[f"{kind}Simpl{name}"] for name in names}
    if mode == 2:
        rows = hd[f"NCoefDpth{kind}"]
        if rows == 0:
            raise ConfigError(f"{source}: member {member}: MCoefMod 2 but the depth-based table is empty")
        for name in names:
            values = hd[f"{kind}Dpth{name}"][:rows]
            if any(value != values[0] for value in values):
                raise ConfigError(f"{source}: member {member}: MCoefMod 2: {name} varies with depth "
                                  f"({', '.join(str(v) for v in values)}): only depth-based tables whose rows "
                                  "agree are supported (HydroDyn interpolates in depth, the model's zones are "
                                  "piecewise constant)")
        return {name: hd[f"{kind}Dpth{name}"][0] for name in names}
    if mode == 3:
        ids = hd[f"MemberID_HydC{kind}"]
        if member not in ids:
            raise ConfigError(f"{source}: member {member}: MCoefMod 3 but no row in the member-based table")
        row = ids.index(member)
        get = {}
        for name in names:
            ends = hd[f"{kind}Member{name}1"][row], hd[f"{kind}Member{name}2"][row]
            if ends[0] != ends[1]:
                raise ConfigError(f"{source}: member {member}: {name} varies along the member ({ends[0]} to "
                                  f"{ends[1]}): not supported")
            get[name] = ends[0]
        return get
    raise ConfigError(f"{source}: member {member}: MCoefMod {mode}: only 1, 2 and 3 exist")


def _growth_zone(hd: dict, index: int, source: str) -> dict[str, Any]:
    """A circular member's coefficients where it carries marine growth (CdMG, CaMG, CpMG)."""
    member = hd["MemberID"][index]
    get = _table_values(hd, index, "Cyl", ("CdMG", "CaMG", "CpMG", "CbMG"), source)
    for name, value in get.items():
        if not isinstance(value, (int, float)):
            raise ConfigError(f"{source}: member {member}: {name} {value!r}: only numbers are supported")
    if get["CbMG"] != 1.0:
        raise ConfigError(f"{source}: member {member}: CbMG {get['CbMG']:g}: only 1 is supported")
    return {"name": "growth", "cd": get["CdMG"], "ca": get["CaMG"], "cp": get["CpMG"]}


def _coefficients(hd: dict, index: int, circular: bool, source: str) -> dict[str, Any]:
    """Cd, Ca per direction (d1, d2) of member ``index`` from its coefficient table."""
    member = hd["MemberID"][index]
    kind = "Cyl" if circular else "Rec"
    names = ("Cd", "Ca", "Cp", "Cb", "AxCd", "AxCa", "AxCp") if circular else ("CdA", "CdB", "CaA", "CaB", "Cp", "Cb",
                                                                                "AxCd", "AxCa", "AxCp")
    get = _table_values(hd, index, kind, names, source)
    maccamy_fuchs = isinstance(get["Cp"], str) and get["Cp"].upper() == "MCF"
    if maccamy_fuchs:
        if not circular:
            raise ConfigError(f"{source}: member {member}: Cp MCF (MacCamy-Fuchs) on a rectangular member: "
                              "HydroDyn applies it to circular members only")
        get["Cp"] = 1.0  # unused: the MacCamy-Fuchs inertia replaces Ca + Cp
    for name, value in get.items():
        if not isinstance(value, (int, float)):
            raise ConfigError(f"{source}: member {member}: {name} {value!r} is not a number")
    if get["Cb"] != 1.0:
        raise ConfigError(f"{source}: member {member}: Cb {get['Cb']:g}: only 1 is supported")
    axial = {"taper_axial": {"ca": get["AxCa"], "cp": get["AxCp"], "cd": get["AxCd"]}}
    if circular:
        return {"cd": get["Cd"], "ca": get["Ca"], "cp": get["Cp"], **axial, "maccamy_fuchs": maccamy_fuchs}
    if get["CdA"] != get["CdB"] or get["CaA"] != get["CaB"]:
        raise ConfigError(f"{source}: member {member}: side A and side B coefficients differ: not supported")
    return {"cd_horizontal": get["CdA"], "cd_vertical": get["CdB"], "ca_horizontal": get["CaA"],
            "ca_vertical": get["CaB"], "cp": get["Cp"], **axial}


def _end_plate(hd: dict, joint: int, circular: bool) -> dict | None:
    """The joint's axial coefficients as an end plate, or None if they are all zero."""
    row = hd["AxCoefID"].index(hd["JointAxID"][hd["JointID"].index(joint)])
    cd, ca, cp = hd["AxCd"][row], hd["AxCa"][row], hd["AxCp"][row]
    if cd == ca == cp == 0.0:
        return None
    if not circular:
        raise ConfigError(f"joint {joint}: axial coefficients on a rectangular member end are not supported")
    return {"ca": ca, "cp": cp, "cd": cd}


def _member(hd: dict, index: int, source: str) -> dict:
    member = hd["MemberID"][index]
    circular = hd["MSecGeom"][index] == 1
    if hd["MSecGeom"][index] not in (1, 2):
        raise ConfigError(f"{source}: member {member}: MSecGeom {hd['MSecGeom'][index]} is not 1 or 2")
    ends = []
    for key in ("MJointID1", "MJointID2"):
        joint = hd[key][index]
        if joint not in hd["JointID"]:
            raise ConfigError(f"{source}: member {member}: joint {joint} is not in the joint table")
        j = hd["JointID"].index(joint)
        ends.append([float(hd["Jointxi"][j]), float(hd["Jointyi"][j]), float(hd["Jointzi"][j])])
    sets = [hd["MPropSetID1"][index], hd["MPropSetID2"][index]]
    if circular:
        d = [hd["CylPropD"][hd["CylPropSetID"].index(s)] for s in sets]
        size = {"diameter_m": float(d[0])} if d[0] == d[1] else {"diameter_m": float(d[0]), "diameter_b_m": float(d[1])}
    else:
        a = [float(hd["RecPropA"][hd["RecPropSetID"].index(s)]) for s in sets]
        b = [float(hd["RecPropB"][hd["RecPropSetID"].index(s)]) for s in sets]
        size = {"width_m": a[0], "height_m": b[0]}
        if a[0] != a[1] or b[0] != b[1]:
            size.update(width_b_m=a[1], height_b_m=b[1])
        spin = float(hd["MSpinOrient"][index])
        if not math.isfinite(spin):
            raise ConfigError(f"{source}: member {member}: MSpinOrient {spin}: not a finite angle")
        if spin:
            size["spin_deg"] = spin
    coefficients = _coefficients(hd, index, circular, source)
    taper_axial = coefficients.pop("taper_axial")
    if coefficients.pop("maccamy_fuchs", False):
        if "diameter_b_m" in size:
            raise ConfigError(f"{source}: member {member}: Cp MCF (MacCamy-Fuchs) on a tapered member: not "
                              "supported (the correction's ka takes one diameter)")
        size["maccamy_fuchs"] = True
    if "diameter_b_m" in size or "width_b_m" in size:
        if not circular and (taper_axial["ca"] or taper_axial["cd"]):
            raise ConfigError(f"{source}: member {member}: tapered rectangular member with axial AxCa "
                              f"{taper_axial['ca']:g}, AxCd {taper_axial['cd']:g}: only 0 is supported")
        size["taper_axial"] = taper_axial
    if hd["PropPot"][index]:  # HydroDyn: the potential flow has its inertia and buoyancy, it keeps its drag
        size["drag_only"] = True
    if circular and hd["MHstLMod"][index] == 2:
        size["hydrostatics_by_section"] = True
    if hd["NMGDepths"] > 0 and circular:  # the coefficients of its nodes with growth (MG columns)
        size["growth_zone"] = _growth_zone(hd, index, source)
        size["taper_axial"] = taper_axial  # the axial terms of the growth's taper between its nodes
    out = {"name": f"member{member}", "section": "circular" if circular else "rectangular", **size,
           "end_a_m": ends[0], "end_b_m": ends[1], "strip_length_m": float(hd["MDivSize"][index]),
           "zones": [{"name": "all", **coefficients}]}
    for key, end in (("MJointID1", "end_a_plate"), ("MJointID2", "end_b_plate")):
        plate = _end_plate(hd, hd[key][index], circular)
        if plate is not None:
            out[end] = plate
    return out


# a joint's end areas cancel (HydroDyn: no joint end loads) when their sum is below this fraction of
# the areas summed: decks give joints to about 1e-5 m, so two members in line meet at slightly
# different directions; HydroDyn's joint loads scale with the residual area and volume vectors
# (drag with |An|, added mass with |Vn|, dynamic pressure with An), below 1e-4 of one end's here
_CANCEL = 1e-4


def _end_vectors(members: list[dict], ends: list[tuple[int, int]], joint: int,
                 growth_m: float = 0.0) -> list[tuple[int, str, np.ndarray]]:
    """Each member end at ``joint``: (member index, plate key, [pi r^2 n, 2 pi r^3 n / 3]) with n
    the end's outward normal and r the end's radius grown by the marine growth's thickness at
    the joint, ``growth_m`` (HydroDyn's terms of An and Vn, on RMG); NaN for a rectangular end."""
    vectors = []
    for i, (a, b) in enumerate(ends):
        for end, sign, key in ((a, -1.0, "end_a_plate"), (b, 1.0, "end_b_plate")):
            if end != joint:
                continue
            axis = np.subtract(members[i]["end_b_m"], members[i]["end_a_m"])
            normal = sign * axis / np.linalg.norm(axis)
            radius = (members[i]["diameter_b_m" if sign > 0 and "diameter_b_m" in members[i] else "diameter_m"]
                      if "diameter_m" in members[i] else math.nan) / 2 + growth_m
            vectors.append((i, key, np.array([math.pi * radius**2 * normal, 2 * math.pi / 3 * radius**3 * normal])))
    return vectors


def _cancel(vectors: list[np.ndarray]) -> bool:
    """Whether the end vectors sum to zero, area and volume (within ``_CANCEL`` of their sizes)."""
    total, size = np.sum(vectors, axis=0), np.sum([np.linalg.norm(v, axis=1) for v in vectors], axis=0)
    return bool(np.all(np.linalg.norm(total, axis=1) <= _CANCEL * size))


def _above_seabed(hd: dict, members: list[dict], water_depth_m: float, source: str) -> list[dict]:
    """The members without those wholly at or below the seabed (z = -water_depth_m), as HydroDyn
    runs them (Morison.f90: a member's nodes below the seabed take no loads; a member wholly
    below it keeps only its upper end plate's buoyancy, which the hydrostatics' seabed cut
    gives, physics/loads/hydrostatic.py), and the end plates as HydroDyn's joint end effects
    (JointAxID) act. HydroDyn sums the end areas of the members meeting at a joint as vectors
    (outward normals; ``An`` pi r^2 and ``Vn`` 2 pi r^3 / 3 weighted, buried members included) and loads the
    joint with the sums: drag with |An|, added mass with |Vn|, dynamic pressure with An. The
    model's plates are per member end, and their drag (|w| w along the normal) and added mass
    (along n n^T) do not change sign with the normal, so two plates in line add instead of
    cancelling. Hence: where the joint's vectors cancel (within ``_CANCEL``: two members of one
    diameter in line, a pile under a leg of its size, members whose ends balance) the joint
    has no plates; elsewhere each pair of ends that cancels (in line, one diameter) loses its
    plates, one end left keeps its own plate (its vectors are the joint's), and of two or
    more ends left one plate carries the joint's sums (``joint_area_m2``, ``joint_volume_m3``)
    and the others none (per end if one of them is drag only, PropPot). Under marine growth the
    radii are the grown ones, R + t at the joint's height (HydroDyn's RMG). A joint on the seabed
    whose areas do not cancel is refused. A member that crosses the seabed is refused too
    (HydroDyn loads the part above it only; the model's strips are whole members). ConfigError
    in one line naming the member or joint."""
    seabed = -water_depth_m
    ends = [(hd["MJointID1"][i], hd["MJointID2"][i]) for i in range(hd["NMembers"])]
    height = {joint: float(z) for joint, z in zip(hd["JointID"], hd["Jointzi"])}
    buried = set()
    for i, (a, b) in enumerate(ends):
        if max(height[a], height[b]) <= seabed:
            buried.add(i)
        elif min(height[a], height[b]) < seabed:
            raise ConfigError(f"{source}: member {hd['MemberID'][i]} crosses the seabed (z = {seabed:g} m): not "
                              "supported (split it into members meeting at the seabed)")
    on_seabed = {joint for i in buried for joint in ends[i] if abs(height[joint] - seabed) < 1e-6}
    table = tuple(MarineGrowthLevel(**row) for row in _marine_growth(hd, source).get("marine_growth", []))
    for joint in sorted({joint for pair in ends for joint in pair}):
        vectors = _end_vectors(members, ends, joint, float(thickness_and_density(table, [height[joint]])[0][0]))
        if _cancel([v for _, _, v in vectors]):  # HydroDyn's joint end effects act on the sums: none here
            dropped = vectors
        else:
            if joint in on_seabed:
                raise ConfigError(f"{source}: joint {joint} on the seabed: the end areas of its members do not "
                                  "cancel (a pile under a member of another size or direction): not supported")
            dropped, left, kept = [], list(vectors), []
            while left:
                first = left.pop(0)
                partner = next((other for other in left if _cancel([first[2], other[2]])), None)
                if partner is None:
                    kept.append(first)
                else:
                    left.remove(partner)
                    dropped += [first, partner]
            i, key, _ = kept[0] if kept else (0, "", None)
            if len(kept) > 1 and key in members[i] and not any(members[k].get("drag_only") for k, _, _ in kept):
                total = np.sum([v for _, _, v in vectors], axis=0)  # HydroDyn's An and Vn: one plate carries them
                members[i][key].update(joint_area_m2=total[0].tolist(), joint_volume_m3=total[1].tolist())
                dropped += kept[1:]
        for i, key, _ in dropped:
            members[i].pop(key, None)
    return [m for i, m in enumerate(members) if i not in buried]


def _first(value: Any) -> Any:
    """A per-body field's value for the one body (openfast-io reads them as lists)."""
    return value[0] if isinstance(value, (list, tuple, np.ndarray)) else value


def _potential_flow(hd: dict, source: str, water_density_kg_m3: float,
                    gravity_m_s2: float) -> tuple[dict, list[list[float]] | None]:
    """The ``potential_flow`` mapping of a PotMod 1 deck and its drift table (None without
    NewmanApp); ConfigError naming the field HydroDyn has that the model cannot represent."""
    from fowt_hydro_sim.physics.hydro.wamit import WamitFormatError, read_12d

    def refuse(field: str, value: Any, why: str) -> ConfigError:
        return ConfigError(f"{source}: {field} {value}: {why}")

    checks = (("NBody", 1, "one WAMIT body only"), ("NAddDOF", 0, "no additional DOF"),
              ("PtfmRefxt", 0, "the WAMIT body at the reference point only"),
              ("PtfmRefyt", 0, "the WAMIT body at the reference point only"),
              ("PtfmRefzt", 0, "the WAMIT body at the reference point only"),
              ("PtfmRefztRot", 0, "the WAMIT body unrotated only"), ("ExctnMod", 1, "DFT excitation (1) only"),
              ("ExctnDisp", 0, "excitation at the undisplaced position (0) only"),
              ("PtfmYMod", 0, "a static reference yaw (0) only"), ("MnDrift", 0, "mean drift alone is not supported; "
                                                                              "NewmanApp 12 is"),
              ("DiffQTF", 0, "the full difference-frequency QTF is not supported; NewmanApp 12 is"),
              ("SumQTF", 0, "sum-frequency QTFs are not supported"))
    for field, allowed, why in checks:
        value = _first(hd.get(field, allowed))
        if value != allowed:
            raise refuse(field, value, why)
    radiation = {0: "none", 1: "convolution", 2: "state_space"}.get(int(hd["RdtnMod"]))
    if radiation is None:
        raise refuse("RdtnMod", hd["RdtnMod"], "convolution (1), state space (2) or none (0) only")
    root = Path(_first(hd["PotFile"]))
    flow = {"wamit_root": str(root), "wamit_length_m": float(_first(hd["WAMITULEN"])),
            "displaced_volume_m3": float(_first(hd["PtfmVol0"])),
            "centre_of_buoyancy_xy_m": [float(_first(hd["PtfmCOBxt"])), float(_first(hd["PtfmCOByt"]))],
            "radiation": radiation, "radiation_tmax_s": float(hd["RdtnTMax"]),
            "added_force_n": [float(v) for v in np.ravel(hd["AddF0"])[:6]]}
    for field, key in (("AddCLin", "added_stiffness"), ("AddBLin", "added_linear_damping"),
                       ("AddBQuad", "added_quadratic_damping")):
        matrix = np.asarray(hd[field], dtype=float)
        if matrix.shape != (6, 6) or not np.all(np.isfinite(matrix)):
            raise refuse(field, f"of shape {matrix.shape}", "must be a finite 6x6 matrix (one body)")
        flow[key] = matrix.tolist()
    newman = int(hd.get("NewmanApp", 0))
    if newman == 0:
        return flow, None
    if newman != 12:
        raise refuse("NewmanApp", newman, "the drift table is read from the .12d file only (12)")
    try:
        qtf = read_12d(root.with_name(root.name + ".12d"), water_density_kg_m3, gravity_m_s2,
                       float(_first(hd["WAMITULEN"])))
    except (WamitFormatError, ValueError) as exc:
        raise refuse("NewmanApp", newman, str(exc)) from None
    heading = int(np.argmin(np.abs(qtf.heading_pairs_deg).sum(axis=1)))
    if np.any(qtf.heading_pairs_deg[heading] != 0):
        raise refuse("NewmanApp", newman, "the .12d file has no heading-0 pair")
    drift = np.maximum(qtf.mean_drift()[heading, :, 0], 0.0)
    return flow, [[float(w), float(d)] for w, d in zip(qtf.omega_rad_s, drift)]


def platform_from_deck(hd: dict, name: str, source: str, water_density_kg_m3: float = 1025.0,
                       gravity_m_s2: float = 9.80665, water_depth_m: float = 150.0) -> dict:
    """The platform YAML document of a deck read by ``read_deck``; ConfigError for what the
    model cannot represent."""
    _refuse_unsupported(hd, source)
    members = _above_seabed(hd, [_member(hd, i, source) for i in range(hd["NMembers"])], water_depth_m, source)
    growth = {**_marine_growth(hd, source), **_fill_groups(hd, members, source, water_density_kg_m3)}
    if hd["PotMod"] == 1:
        flow, drift = _potential_flow(hd, source, water_density_kg_m3, gravity_m_s2)
        volume = flow["displaced_volume_m3"]
        mass = water_density_kg_m3 * volume
        inertia = mass * volume ** (2 / 3) / 4
        document = {"name": name, "description": f"imported from the HydroDyn deck {source}: WAMIT potential flow "
                                                 f"and {len(members)} strip-theory members; placeholder mass "
                                                 "(rho PtfmVol0 at the reference point), no mooring",
                    "environment": {"water_density_kg_m3": water_density_kg_m3, "gravity_m_s2": gravity_m_s2,
                                    "water_depth_m": water_depth_m},
                    "mass": {"mass_kg": mass, "cog_m": [*flow["centre_of_buoyancy_xy_m"], 0.0],
                             "inertia_about_cog_kg_m2": {"ixx": inertia, "iyy": inertia, "izz": inertia}},
                    "hub_point_m": [0.0, 0.0, 0.0], "members": members, "potential_flow": flow,
                    "drift_coefficients_n_m2": drift, **growth,
                    "mooring": {"stiffness_n_m": 0.0, "pretension_n": 0.0, "unstretched_length_m": 1.0,  # no load
                                "lines": [{"fairlead_m": [0.0, 0.0, 0.0], "anchor_m": [1.0, 0.0, 0.0]}]}}
        platform_from_dict(document, source)  # the WAMIT files exist and are complete
        return document
    document = {"name": name, "description": f"imported from the HydroDyn deck {source}: strip-theory members only; "
                                             "placeholder mass (floating freely), no mooring",
                "environment": {"water_density_kg_m3": water_density_kg_m3, "gravity_m_s2": gravity_m_s2,
                                "water_depth_m": water_depth_m},
                "mass": {"mass_kg": 1.0, "cog_m": [0.0, 0.0, 0.0], "inertia_about_cog_kg_m2":
                         {"ixx": 1.0, "iyy": 1.0, "izz": 1.0}},
                "hub_point_m": [0.0, 0.0, 0.0], "members": members, **growth,
                "mooring": {"stiffness_n_m": 0.0, "pretension_n": 0.0, "unstretched_length_m": 1.0,  # no load
                            "lines": [{"fairlead_m": [0.0, 0.0, 0.0], "anchor_m": [1.0, 0.0, 0.0]}]}}
    return _floating_mass(document)


def _marine_growth(hd: dict, source: str) -> dict:
    """The deck's MGDepths table as the platform's ``marine_growth`` (MGDpth is the height
    above the mean sea level, MSL2SWL 0; HydroDyn takes the rows highest first)."""
    rows = [{"z_m": float(z), "thickness_m": float(t), "density_kg_m3": float(rho)}
            for z, t, rho in zip(hd["MGDpth"], hd["MGThck"], hd["MGDens"])][:hd["NMGDepths"]]
    heights = [r["z_m"] for r in rows]
    if heights != sorted(heights, reverse=True) or len(set(heights)) < len(heights):
        raise ConfigError(f"{source}: MGDpth {heights}: the marine-growth rows must go from the highest to the "
                          "lowest, each height once")
    return {"marine_growth": rows} if rows else {}


def _floating_mass(document: dict) -> dict:
    """The document with mass rho V at its centre of buoyancy and the inertia of that mass
    spread as the displaced volume (a placeholder that floats in equilibrium)."""
    from fowt_hydro_sim.physics.loads.hydrostatic import hydrostatics
    from fowt_hydro_sim.physics.strips import discretise

    platform = platform_from_dict(document, "imported deck")
    h = hydrostatics(platform, discretise(platform).strips)
    mass = platform.environment.water_density_kg_m3 * h.displaced_volume_m3
    if not math.isfinite(mass) or mass <= 0:
        raise ConfigError("imported deck: no member is below the still water line")
    radius = max(float(np.linalg.norm(np.array(m["end_a_m"]) - h.centre_of_buoyancy_m)) for m in document["members"])
    inertia = mass * max(radius, 1.0) ** 2 / 4
    document["mass"] = {"mass_kg": float(mass), "cog_m": [float(x) for x in h.centre_of_buoyancy_m],
                        "inertia_about_cog_kg_m2": {"ixx": inertia, "iyy": inertia, "izz": inertia}}
    return document
