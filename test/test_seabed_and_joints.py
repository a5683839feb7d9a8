"""Members at and through the seabed: HydroDyn's rule (Morison.f90: a member's nodes below the
seabed take no loads, a member that crosses the seabed keeps its upper end plate only, a member
wholly below it has no loads but that upper plate) against closed forms, on the nonlinear
hydrostatics and on the HydroDyn deck import."""
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
    segments of a leg or of the column); a joint of one member end, or of members that do not
    cancel, keeps its plates."""
    pytest.importorskip("openfast_io")
    from fowt_hydro_sim.io.hydrodyn import platform_from_deck, read_deck
    deck = DATA / "hd_primary.inp"
    document = platform_from_deck(read_deck(deck), "tripod", deck.name, 1025.0, 9.80665, DEPTH_M)
    names = [m["name"] for m in document["members"]]
    assert len(names) == 57 and not {"member58", "member59", "member60"} & set(names)
    legs = {m["name"]: m for m in document["members"] if m["name"] in ("member1", "member2", "member3")}
    assert all("end_a_plate" not in m and "end_b_plate" in m for m in legs.values())  # joint 4: with braces
    by_name = {m["name"]: m for m in document["members"]}
    assert "end_b_plate" in by_name["member57"]  # joint 52, the column's top: one member end
    assert "end_a_plate" not in by_name["member57"] and "end_b_plate" not in by_name["member56"]  # joint 51: in line
    assert "end_a_plate" in by_name["member47"]  # joint 41: the tapered base with three braces


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
