"""Members at and through the seabed: HydroDyn's rule (Morison.f90: a member's nodes below the
seabed take no loads, a member that crosses the seabed keeps its upper end plate only, a member
wholly below it has no loads but that upper plate) against closed forms, on the nonlinear
hydrostatics and on the HydroDyn deck import; and the joint end effects as HydroDyn sums them over
the members meeting at a joint (Morison_Init: An, Vn), on small decks and closed forms."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from fowt_hydro_sim.physics.config import ConfigError, platform_from_dict
from fowt_hydro_sim.physics.loads.hydrostatic import member_records, members_submerged_volume

DEPTH_M, DIAMETER_M = 45.0, 3.15
AREA_M2 = math.pi * DIAMETER_M**2 / 4
DATA = Path(__file__).parent / "data" / "openfast_rtest" / "hd_OC3tripod_offshore_fixedbottom_wavesirr"


def _platform(*segments: tuple[float, float]):
    """Vertical circular members at (2, -1) from z0 to z1 each, in water DEPTH_M deep."""
    members = [{"name": f"m{i}", "section": "circular", "diameter_m": DIAMETER_M, "end_a_m": [2.0, -1.0, z0],
                "end_b_m": [2.0, -1.0, z1], "strip_length_m": 1.0, "zones": [{"name": "all", "cd": 1.0, "ca": 1.0}]}
               for i, (z0, z1) in enumerate(segments)]
    document = {"name": "pile", "environment": {"water_density_kg_m3": 1025.0, "gravity_m_s2": 9.80665,
                                                "water_depth_m": DEPTH_M},
                "mass": {"mass_kg": 1.0, "cog_m": [0.0, 0.0, 0.0],
                         "inertia_about_cog_kg_m2": {"ixx": 1.0, "iyy": 1.0, "izz": 1.0}},
                "hub_point_m": [0.0, 0.0, 0.0], "members": members,
                "mooring": {"stiffness_n_m": 0.0, "pretension_n": 0.0, "unstretched_length_m": 1.0,
                            "lines": [{"fairlead_m": [0.0, 0.0, 0.0], "anchor_m": [1.0, 0.0, 0.0]}]}}
    return platform_from_dict(document, "test")


@pytest.mark.parametrize("segments, heave_m", [
    (((-50.0, -10.0),), 0.0),                   # one pile through the seabed
    (((-50.0, -45.0), (-45.0, -10.0)), 0.0),    # a buried pile and the leg standing on it (the tripod's)
    (((-50.0, -45.0), (-45.0, -10.0)), -0.1),   # the same, lowered (the r-test's PRP offset)
    (((-45.0, -10.0),), 0.0),                   # a leg from the seabed up
])
def test_a_vertical_pile_through_the_seabed_has_its_top_plate_buoyancy_only(segments, heave_m):
    """The nonlinear buoyancy of a vertical pile that runs into the seabed is the pressure on its
    top plate alone, -rho g A |z_top| (downward): no water below the seabed, none under the
    section where the pile enters the soil (HydroDyn: no side loads below the seabed, the upper
    end plate only, the buried member's top plate cancelling the bottom plate of the member
    standing on it). A closed prism would give +rho g A (z_top + depth)."""
    platform = _platform(*segments)
    records, lines = member_records(platform)
    volume, moment = members_submerged_volume(np.eye(3), heave_m, records, lines)
    top = segments[-1][1] + heave_m
    assert volume == pytest.approx(AREA_M2 * top, rel=1e-9)
    assert moment[:2] / volume == pytest.approx([2.0, -1.0], rel=1e-9)


def test_a_member_above_the_seabed_keeps_both_plates():
    """A member wholly in the water column (its bottom 1 m above the seabed) is still the closed
    prism: +rho g A L."""
    platform = _platform((-44.0, -10.0))
    records, lines = member_records(platform)
    volume, _ = members_submerged_volume(np.eye(3), 0.0, records, lines)
    assert volume == pytest.approx(AREA_M2 * 34.0, rel=1e-9)


def test_the_tripod_deck_imports_without_its_buried_piles_and_the_plates_of_in_line_joints():
    """The OC3 tripod deck: the three piles wholly below the 45 m seabed (members 58-60, z -50
    to -45) are not imported (HydroDyn gives them no side loads), and the members meeting in
    line at a joint with one diameter lose their end plates there (HydroDyn sums a joint's end
    areas over the members that meet there: the pile's and the leg's cancel, as do two
    segments of a leg or of the column); a joint of one member end keeps its plate, and a joint
    where two or more ends are left after the pairs in line (joint 4: the two horizontal braces
    at a leg; joint 41: the three lower braces at the column's tapered base) has one plate
    carrying HydroDyn's summed vectors."""
    pytest.importorskip("openfast_io")
    from fowt_hydro_sim.io.hydrodyn import platform_from_deck, read_deck
    deck = DATA / "hd_primary.inp"
    document = platform_from_deck(read_deck(deck), "tripod", deck.name, 1025.0, 9.80665, DEPTH_M)
    names = [m["name"] for m in document["members"]]
    assert len(names) == 57 and not {"member58", "member59", "member60"} & set(names)
    by_name = {m["name"]: m for m in document["members"]}
    legs = [by_name[f"member{k}"] for k in (1, 2, 3)]
    assert all("end_a_plate" not in m and "end_b_plate" not in m for m in legs)  # the seabed; joint 4: in line
    assert "joint_area_m2" in by_name["member40"]["end_a_plate"] and "end_b_plate" not in by_name["member45"]
    assert "end_b_plate" in by_name["member57"]  # joint 52, the column's top: one member end
    assert "end_a_plate" not in by_name["member57"] and "end_b_plate" not in by_name["member56"]  # joint 51: in line
    base = by_name["member14"]["end_b_plate"]  # joint 41: members 46 and 47 in line, three braces left
    assert "end_a_plate" not in by_name["member47"] and "end_b_plate" not in by_name["member46"]
    assert base["joint_area_m2"][:2] == pytest.approx([0.0, 0.0], abs=1e-4) and base["joint_area_m2"][2] > 0


def test_a_deck_member_crossing_the_seabed_is_refused_in_one_line(tmp_path):
    """A member with one end below the seabed and the other above it is refused, naming it."""
    pytest.importorskip("openfast_io")
    from fowt_hydro_sim.io.hydrodyn import platform_from_deck, read_deck
    text = (DATA / "hd_primary.inp").read_text()
    joint = "    1   -24.80250     0.00000   -{:.5f}      1"
    text = text.replace(joint.format(45.0), joint.format(44.0), 1)  # joint 1 (pile 58's top) 1 m above the seabed
    deck = tmp_path / "hd_primary.inp"
    deck.write_text(text)
    with pytest.raises(ConfigError) as error:
        platform_from_deck(read_deck(deck), "tripod", deck.name, 1025.0, 9.80665, DEPTH_M)
    message = str(error.value)
    assert "member 58" in message and "seabed" in message
    assert len(message.splitlines()) == 1


def _small_deck(folder: Path, joints: list[tuple[float, float, float]], members: list[tuple[int, int, int]]) -> Path:
    """The tripod deck with its joints and members replaced (joint axial coefficients AxCd = AxCa
    = AxCp = 1; members: joint a, joint b, property set), no member outputs."""
    lines = (DATA / "hd_primary.inp").read_text().splitlines()
    at = {key: next(i for i, line in enumerate(lines) if key in line)
          for key in ("NJoints", "MEMBER CROSS-SECTION", "NMembers", "FILLED MEMBERS", "NMOutputs")}
    joint_rows = [f"{k + 1:5d} {x:12.5f} {y:12.5f} {z:12.5f}      1            0" for k, (x, y, z) in enumerate(joints)]
    member_rows = [f"{k + 1:5d} {a:9d} {b:9d} {s:11d} {s:12d}         1.0000      1        FALSE"
                   for k, (a, b, s) in enumerate(members)]
    outputs = lines[at["FILLED MEMBERS"]:at["NMOutputs"]] + ["             0   NMOutputs"] \
        + lines[at["NMOutputs"] + 1:at["NMOutputs"] + 3] + lines[at["NMOutputs"] + 4:]
    text = lines[:at["NJoints"]] + [f"{len(joints):14d}   NJoints"] + lines[at["NJoints"] + 1:at["NJoints"] + 3] \
        + joint_rows + lines[at["MEMBER CROSS-SECTION"]:at["NMembers"]] + [f"{len(members):14d}   NMembers"] \
        + lines[at["NMembers"] + 1:at["NMembers"] + 3] + member_rows + outputs
    deck = folder / "hd_primary.inp"
    deck.write_text("\r\n".join(text) + "\r\n")
    return deck


def _plates(deck: Path):
    from fowt_hydro_sim.io.hydrodyn import platform_from_deck, read_deck
    from fowt_hydro_sim.physics.strips import discretise
    document = platform_from_deck(read_deck(deck), "joints", deck.name, 1025.0, 9.80665, DEPTH_M)
    return document, discretise(platform_from_dict(document, "joints")).plates


def test_a_brace_split_at_a_rounded_joint_has_the_end_plates_of_the_whole_brace(tmp_path):
    """A tilted brace split at a joint whose coordinates are rounded to the deck's 5 decimals (the
    tripod's joints 19, 26, 29: in line to 2e-6) has HydroDyn's joint loads of the whole brace:
    at the split joint the two ends' area vectors cancel (HydroDyn's An, Vn ~ 1e-6 of one end's),
    so there are no plates there, only the two outer ends'. (Per-member plates there would add
    their drag and added mass instead of cancelling.)"""
    pytest.importorskip("openfast_io")
    joints = [(-12.40172, 0.0, -19.6538), (-6.31009, 0.0, -10.0), (-5.04807, 0.0, -8.0)]
    (tmp_path / "split").mkdir()
    (tmp_path / "whole").mkdir()
    _, split = _plates(_small_deck(tmp_path / "split", joints, [(1, 2, 4), (2, 3, 4)]))
    _, whole = _plates(_small_deck(tmp_path / "whole", [joints[0], joints[2]], [(1, 2, 4)]))
    assert len(split.centre_m) == len(whole.centre_m) == 2
    order = np.lexsort(split.centre_m.T), np.lexsort(whole.centre_m.T)
    for field in ("centre_m", "normal", "pressure_area_m2", "added_mass_kg", "drag_kg_m"):
        assert getattr(split, field)[order[0]] == pytest.approx(getattr(whole, field)[order[1]], rel=1e-5, abs=1e-5)


def test_a_joint_of_two_braces_at_an_angle_carries_hydrodyn_summed_area_and_volume(tmp_path):
    """Two braces of radius r meeting at 90 degrees, each 45 degrees from the vertical (a V): HydroDyn
    loads the joint with An = pi r^2 (n1 + n2) and Vn = 2 pi r^3 / 3 (n1 + n2), vertical, of size
    sqrt(2) times one end's: one pressure-and-drag plate of area sqrt(2) pi r^2 (Cp A, 0.25 rho Cd A)
    and one added-mass plate of volume sqrt(2) 2 pi r^3 / 3 (rho Ca V), both along the vertical;
    the outer ends keep their own plates."""
    pytest.importorskip("openfast_io")
    joints = [(-5.0, 0.0, -20.0), (0.0, 0.0, -15.0), (5.0, 0.0, -20.0)]
    document, plates = _plates(_small_deck(tmp_path, joints, [(1, 2, 3), (3, 2, 3)]))
    radius, rho = 1.875 / 2, 1025.0
    at_joint = np.all(np.isclose(plates.centre_m, [0.0, 0.0, -15.0]), axis=1)
    assert at_joint.sum() == 2 and (~at_joint).sum() == 2
    normals = plates.normal[at_joint]
    assert normals == pytest.approx(np.array([[0.0, 0.0, -1.0]] * 2), abs=1e-12)  # inward: down into the V
    area, volume = math.sqrt(2) * math.pi * radius**2, math.sqrt(2) * 2 * math.pi / 3 * radius**3
    assert plates.pressure_area_m2[at_joint] == pytest.approx([area, 0.0], abs=1e-12)
    assert plates.drag_kg_m[at_joint] == pytest.approx([0.25 * rho * area, 0.0], abs=1e-9)
    assert plates.added_mass_kg[at_joint] == pytest.approx([0.0, rho * volume], abs=1e-9)
    assert plates.pressure_area_m2[~at_joint] == pytest.approx([math.pi * radius**2] * 2, rel=1e-12)
    assert sum("end_b_plate" in m for m in document["members"]) == 1


def test_a_leg_joint_with_one_brace_keeps_the_brace_plate_alone():
    """The tripod's joint 7: two leg segments in line (their areas cancel) and one lower brace
    (member 13): HydroDyn's An and Vn are the brace end's, so the brace keeps its own plate and
    the leg segments have none there."""
    pytest.importorskip("openfast_io")
    from fowt_hydro_sim.io.hydrodyn import platform_from_deck, read_deck
    deck = DATA / "hd_primary.inp"
    by_name = {m["name"]: m for m in platform_from_deck(read_deck(deck), "tripod", deck.name, 1025.0, 9.80665,
                                                         DEPTH_M)["members"]}
    assert "end_b_plate" not in by_name["member4"] and "end_a_plate" not in by_name["member7"]
    assert by_name["member13"]["end_a_plate"] == {"ca": 1.0, "cp": 1.0, "cd": 1.0}


def test_a_joint_under_marine_growth_sums_the_grown_ends(tmp_path):
    """The V of two braces under marine growth (0.1 m thick from z = -10 to -30 m): HydroDyn sums the
    ends at the joint on their grown radii (Morison_Init: RMG = r + t at the joint), An = pi (r + t)^2
    (n1 + n2), Vn = 2 pi (r + t)^3 / 3 (n1 + n2): one plate of each along the vertical, of size sqrt(2)
    times one grown end's (not a plate per brace end, whose heave added mass would add)."""
    pytest.importorskip("openfast_io")
    joints = [(-5.0, 0.0, -20.0), (0.0, 0.0, -15.0), (5.0, 0.0, -20.0)]
    deck = _small_deck(tmp_path, joints, [(1, 2, 3), (3, 2, 3)])
    text = deck.read_text()
    old = "             0   NMGDepths"
    assert old in text
    text = text.replace(old, "             2   NMGDepths").replace(
        "(m)        (m)         (kg/m^3)", "(m)        (m)         (kg/m^3)\r\n-10.0      0.1         1100\r\n"
        "-30.0      0.1         1100", 1)
    deck.write_text(text)
    document, plates = _plates(deck)
    grown, rho = 1.875 / 2 + 0.1, 1025.0
    at_joint = np.all(np.isclose(plates.centre_m, [0.0, 0.0, -15.0]), axis=1)
    assert at_joint.sum() == 2
    assert plates.normal[at_joint] == pytest.approx(np.array([[0.0, 0.0, -1.0]] * 2), abs=1e-12)
    area, volume = math.sqrt(2) * math.pi * grown**2, math.sqrt(2) * 2 * math.pi / 3 * grown**3
    assert plates.pressure_area_m2[at_joint] == pytest.approx([area, 0.0], rel=1e-12)
    assert plates.added_mass_kg[at_joint] == pytest.approx([0.0, rho * volume], rel=1e-12)
    assert sum("end_b_plate" in m for m in document["members"]) == 1
