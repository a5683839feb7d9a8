"""Filled (flooded) members as HydroDyn computes them (physics/fill.py), against closed forms:
the fill's weight on the inner end caps of a vertical column filled whole and in part, and its
moment about the origin; a tilted member filled in part (the fill's mass and centroid, the caps'
load against the interior pressure integrated over the cap); the fill's reaction -m a under a
heave acceleration; the importer reading a deck's fill group, and refusing in one line what is
not modelled."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import yaml

from fowt_hydro_sim.cli import main
from fowt_hydro_sim.physics.config import (
    HYDRODYN,
    ConfigError,
    EndPlate,
    FillGroup,
    load_platform,
    platform_document,
    platform_from_dict,
)
from fowt_hydro_sim.physics.fill import fill_extent, fill_mass, fill_records, fill_wrench
from fowt_hydro_sim.physics.loads import ROW
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.testing import REPO

RHO, G, RHO_F = 1025.0, 9.80665, 1200.0
R, WALL, X, Y = 3.0, 0.05, 4.0, -2.0  # outer radius, wall, the column's axis (x, y)
BOTTOM, TOP = -20.0, -5.0
R_IN = R - WALL


def platform(end_a=(X, Y, BOTTOM), end_b=(X, Y, TOP), surface: float | None = 0.0):
    """One circular member D 6 m, wall 5 cm, Ca 1, Cp 1, no drag, no end plates; with
    ``surface`` a fill group (density 1200 kg/m^3) up to that height."""
    p = load_platform("windmoor12")
    zone = dataclasses.replace(p.members[0].zones[0], below_z_m=math.inf, ca=(1.0, 1.0), cp=1.0)
    zone = dataclasses.replace(zone, cd=tuple(dataclasses.replace(c, constant=0.0) for c in zone.cd))
    member = dataclasses.replace(p.members[0], name="column", end_a_m=end_a, end_b_m=end_b, width_m=2 * R,
                                 height_m=2 * R, diameter_b_m=None, taper_axial=EndPlate(0.0, 1.0, 0.0),
                                 zones=(zone,), strip_length_m=0.5, end_a_plate=None, end_b_plate=None,
                                 wall_thickness_m=WALL)
    env = dataclasses.replace(p.environment, water_depth_m=50.0, water_density_kg_m3=RHO, gravity_m_s2=G)
    groups = () if surface is None else (FillGroup(("column",), surface, RHO_F),)
    return dataclasses.replace(p, members=(member,), environment=env, marine_growth=(), fill_groups=groups)


def cap_loads(p, state: np.ndarray | None = None, rotation: np.ndarray | None = None) -> np.ndarray:
    """The fill's end-cap loads at the pose (at rest by default)."""
    out = np.zeros(6)
    fill_wrench(np.zeros(12) if state is None else state, np.eye(3) if rotation is None else rotation,
                np.ravel(fill_records(p)), out)
    return out


@pytest.mark.parametrize("surface, height", [(0.0, TOP - BOTTOM), (2.0, TOP - BOTTOM), (-8.0, -8.0 - BOTTOM)])
def test_vertical_column_carries_its_fills_weight_on_the_axis(surface, height):
    """Filled whole (the surface at or above its top: the top cap's head cancels the overfill)
    or in part (to z = -8 m): -rho_f g pi (R - t)^2 h_fill, about the origin (-y W, x W, 0)."""
    weight = RHO_F * G * math.pi * R_IN**2 * height
    assert cap_loads(platform(surface=surface)) == pytest.approx([0, 0, -weight, -Y * weight, X * weight, 0],
                                                                 rel=1e-12, abs=1e-6)
    mass, centroid, _ = fill_mass(platform(surface=surface))
    assert mass == pytest.approx(RHO_F * math.pi * R_IN**2 * height, rel=1e-12)
    assert centroid == pytest.approx([X, Y, BOTTOM + height / 2], rel=1e-12)


def test_column_above_the_fill_surface_holds_none_and_the_order_of_its_ends_does_not_matter():
    assert len(fill_records(platform(surface=BOTTOM - 1.0))) == 0
    assert fill_mass(platform(surface=BOTTOM - 1.0))[0] == 0.0
    flipped = platform(end_a=(X, Y, TOP), end_b=(X, Y, BOTTOM), surface=-8.0)
    assert cap_loads(flipped) == pytest.approx(cap_loads(platform(surface=-8.0)), rel=1e-12, abs=1e-6)


TILT = math.radians(30.0)
AXIS = np.array([math.sin(TILT), 0.0, math.cos(TILT)])
LOW = np.array([X, Y, BOTTOM])
SURFACE = -12.0  # the fill's surface: the member (20 m long) is filled in part
L_FILL = (SURFACE - BOTTOM) / math.cos(TILT)


def test_tilted_member_filled_in_part_fill_mass_and_centroid():
    """Tilted 30 deg from the vertical, 20 m long from z = -20 m, the fill to z = -12 m: filled
    l_fill = 8 / cos(30 deg) m along the axis (HydroDyn's l_fill, the fill ending normal to the
    axis), the fill a cylinder of radius R - t, its centroid half way along it; inertia about
    the centroid that of a solid cylinder."""
    p = platform(end_a=tuple(LOW), end_b=tuple(LOW + 20.0 * AXIS), surface=SURFACE)
    assert fill_extent(p.members[0], SURFACE) == (2, 0.0, pytest.approx(L_FILL, rel=1e-12))
    mass, centroid, inertia = fill_mass(p)
    assert mass == pytest.approx(RHO_F * math.pi * R_IN**2 * L_FILL, rel=1e-12)
    assert centroid == pytest.approx(LOW + L_FILL / 2 * AXIS, rel=1e-12)
    axial, transverse = mass * R_IN**2 / 2, mass * (3 * R_IN**2 + L_FILL**2) / 12
    expected = transverse * (np.eye(3) - np.outer(AXIS, AXIS)) + axial * np.outer(AXIS, AXIS)
    assert inertia == pytest.approx(expected, rel=1e-10, abs=1e-6)


def test_tilted_member_filled_in_part_caps_load_is_the_interior_pressure_on_its_bottom_cap():
    """HydroDyn applies the fill's weight as the pressure on the inner end caps: here the bottom
    cap only, under the fill's head l_fill cos(phi) at its centre. Integrated over the cap
    (polar Gauss, the pressure rho_f g (z_f - z) at each point, normal -k): the same force and
    moment about the origin. Its vertical part is the weight's times cos^2(phi): the walls'
    share, across the axis, HydroDyn does not apply."""
    p = platform(end_a=tuple(LOW), end_b=tuple(LOW + 20.0 * AXIS), surface=SURFACE)
    across, other = np.array([math.cos(TILT), 0.0, -math.sin(TILT)]), np.array([0.0, 1.0, 0.0])
    radii, weights = np.polynomial.legendre.leggauss(12)
    radii, weights = R_IN * (radii + 1) / 2, weights * R_IN / 2
    angles = 2 * math.pi * (np.arange(64) + 0.5) / 64
    force, moment = np.zeros(3), np.zeros(3)
    for r, w in zip(radii, weights):
        for a in angles:
            point = LOW + r * (math.cos(a) * across + math.sin(a) * other)
            df = RHO_F * G * (SURFACE - point[2]) * (-AXIS) * r * w * 2 * math.pi / 64
            force += df
            moment += np.cross(point, df)
    load = cap_loads(p)
    assert load[:3] == pytest.approx(force, rel=1e-10)
    assert load[3:] == pytest.approx(moment, rel=1e-10)
    weight = RHO_F * G * math.pi * R_IN**2 * L_FILL
    assert load[2] == pytest.approx(-weight * math.cos(TILT) ** 2, rel=1e-12)


def test_caps_load_follows_the_pose():
    """The column filled whole to z = 0 and pitched by 0.1 rad: the fill's head at the bottom
    is the overfill plus the column's height at the pose; the load stays along the member's
    axis, rho_f g pi (R - t)^2 (z_top - z_bottom) (the caps' net), with the caps' couples."""
    theta = 0.1
    c, s = math.cos(theta), math.sin(theta)
    rotation = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    state = np.zeros(12)
    state[4] = theta
    load = cap_loads(platform(), state, rotation)
    bottom, top = rotation @ LOW, rotation @ np.array([X, Y, TOP])
    k = (top - bottom) / np.linalg.norm(top - bottom)
    overfill = -TOP
    f_bottom = -RHO_F * G * math.pi * R_IN**2 * (overfill + top[2] - bottom[2])
    f_top = RHO_F * G * math.pi * R_IN**2 * overfill
    assert load[:3] == pytest.approx((f_bottom + f_top) * k, rel=1e-12)
    moment = np.cross(bottom, f_bottom * k) + np.cross(top, f_top * k)  # the two caps' couples cancel
    assert load[3:] == pytest.approx(moment, rel=1e-12)


@pytest.fixture(scope="module", params=["nonlinear", "free_surface"])
def loads_with_and_without_fill(request):
    """The hydrostatic row at rest and heaving with 0.3 m/s^2 (both hydrostatics that follow
    the pose), the column filled whole and empty."""
    still, heave = np.zeros((2, 6)), np.zeros((2, 6))
    heave[1, 2] = 0.3
    rows = []
    for surface in (0.0, None):
        model = PlatformModel(platform(surface=surface),
                              options=dataclasses.replace(HYDRODYN, hydrostatics=request.param))
        rows.append(model.prescribed_motion_loads(np.array([0.0, 0.1]), still, still, heave)[:, ROW["hydrostatic"]])
    return rows


def test_hydrostatic_component_carries_the_fills_weight_and_reaction(loads_with_and_without_fill):
    """Through the model: the filled column's hydrostatic load less the empty one's is the
    fill's weight at rest and, heaving with a = 0.3 m/s^2, the reaction -m a on top."""
    filled, empty = loads_with_and_without_fill
    mass = RHO_F * math.pi * R_IN**2 * (TOP - BOTTOM)
    weight = mass * G
    assert filled[0] - empty[0] == pytest.approx([0, 0, -weight, -Y * weight, X * weight, 0], rel=1e-9, abs=1e-3)
    assert (filled[1] - empty[1]) - (filled[0] - empty[0]) == pytest.approx(
        [0, 0, -mass * 0.3, -Y * mass * 0.3, X * mass * 0.3, 0], rel=1e-9, abs=1e-3)


def test_fill_groups_round_trip_and_bad_groups_are_refused():
    p = platform(surface=-8.0)
    document = platform_document(p)
    assert document["fill_groups"] == [{"members": ["column"], "free_surface_z_m": -8.0, "density_kg_m3": RHO_F}]
    again = platform_from_dict(yaml.safe_load(yaml.safe_dump(document)))
    assert again.fill_groups == p.fill_groups and again.members[0].wall_thickness_m == WALL
    for group, words in (({"members": ["nothing"], "free_surface_z_m": 0.0}, "no member named"),
                         ({"members": ["column"]}, "free_surface_z_m: missing")):
        with pytest.raises(ConfigError, match=words):
            platform_from_dict({**document, "fill_groups": [group]})
    thick = {**document, "members": [{**document["members"][0], "wall_thickness_m": R}]}
    with pytest.raises(ConfigError, match="thinner than the radius"):
        platform_from_dict(thick)


def deck_with_fill(name: str, rows: str) -> str:
    """An r-test deck of the suite with its FILLED MEMBERS section given ``rows``."""
    deck = (REPO / "test" / "data" / "openfast_rtest" / name).read_text()
    old = "             0   NFillGroups"
    assert old in deck or old[1:] in deck
    old = old if old in deck else old[1:]
    count = len(rows.strip().splitlines())
    return deck.replace(old, f"             {count}   NFillGroups", 1).replace(
        "(-)      (-)                   (m)           (kg/m^3)",
        "(-)      (-)                   (m)           (kg/m^3)\n" + rows.rstrip("\n"), 1)


@pytest.mark.slow
def test_importer_reads_a_fill_group_and_the_members_wall(tmp_path):
    """hd_WaveStMod2's column (D 12 m, PropThck 0.06 m, z = -20 to +20 m) filled to -5 m with
    FillDens DEFAULT: the platform's fill group (the water's density), the member's wall."""
    path = tmp_path / "filled.dat"
    path.write_text(deck_with_fill("hd_WaveStMod2/hydrodyn_input.dat", "1   1   -5.0   DEFAULT"))
    out = tmp_path / "filled.yaml"
    assert main(["platform", "import", str(path), "-o", str(out), "--water-depth", "200",
                 "--water-density", "1020"]) == 0
    p = load_platform(out)
    assert p.fill_groups == (FillGroup(("member1",), -5.0, 1020.0),)
    assert p.members[0].wall_thickness_m == 0.06
    mass = fill_mass(p)[0]
    assert mass == pytest.approx(1020.0 * math.pi * (6.0 - 0.06) ** 2 * 15.0, rel=1e-12)


@pytest.mark.slow
def test_importer_refuses_a_filled_rectangular_member_in_one_line(tmp_path, capsys):
    path = tmp_path / "filled_rectangle.dat"
    path.write_text(deck_with_fill("hd_MHstLMod2_RectMmbr/HydroDyn.dat", "1   1   0.0   1025"))
    assert main(["platform", "import", str(path), "-o", str(tmp_path / "x.yaml"), "--water-depth", "200"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "FillMList: member 1 is rectangular" in err[0]
