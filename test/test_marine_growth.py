"""Marine growth (``physics/marine_growth.py``, HydroDyn's MGDepths) against closed forms on a
vertical cylinder with a growth layer: the table's interpolation, the layer's mass, centroid
and the hydrostatic component's weight, buoyancy and inertial reaction, and the fluid
inertia on the grown diameter with the growth coefficients, the growth tapering over the
elements that hold the table's ends as HydroDyn's nodes give it (its axial added mass there)
and a joint plate's growth end mass; the platform document and the HydroDyn importer carry the
table."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from fowt_hydro_sim.cli import main
from fowt_hydro_sim.physics.config import (
    HYDRODYN,
    ConfigError,
    EndPlate,
    MarineGrowthLevel,
    load_platform,
    platform_document,
    platform_from_dict,
)
from fowt_hydro_sim.physics.loads import ROW
from fowt_hydro_sim.physics.marine_growth import grown_platform, growth_mass, thickness_and_density
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import WaveComponents, wavenumber
from fowt_hydro_sim.testing import REPO

RHO, G, DEPTH = 1025.0, 9.80665, 50.0
R, T, RHO_MG, X = 3.0, 0.1, 1100.0, 4.0  # column radius, growth thickness and density, column axis x
TOP, BOTTOM = -2.0, -15.0  # the growth between these heights, none elsewhere
TABLE = (MarineGrowthLevel(TOP, T, RHO_MG), MarineGrowthLevel(BOTTOM, T, RHO_MG))


def column(table=TABLE, growth_ca: float = 1.5):
    """A vertical cylinder D 6 m at x = 4 m from z = -20 to +5 m, Ca 1, Cp 1, no drag, no end
    plates; where it carries growth Ca ``growth_ca``."""
    p = load_platform("windmoor12")
    zone = dataclasses.replace(p.members[0].zones[0], below_z_m=math.inf, ca=(1.0, 1.0), cp=1.0)
    zone = dataclasses.replace(zone, cd=tuple(dataclasses.replace(c, constant=0.0) for c in zone.cd))
    growth = dataclasses.replace(zone, name="growth", ca=(growth_ca, growth_ca))
    member = dataclasses.replace(p.members[0], end_a_m=(X, 0.0, -20.0), end_b_m=(X, 0.0, 5.0), width_m=2 * R,
                                 height_m=2 * R, diameter_b_m=None, taper_axial=EndPlate(0.0, 1.0, 0.0),
                                 zones=(zone,), strip_length_m=0.25, end_a_plate=None, end_b_plate=None,
                                 growth_zone=growth)
    env = dataclasses.replace(p.environment, water_depth_m=DEPTH, water_density_kg_m3=RHO, gravity_m_s2=G)
    return dataclasses.replace(p, members=(member,), environment=env, marine_growth=table)


LAYER = RHO_MG * math.pi * ((R + T) ** 2 - R**2) * (TOP - BOTTOM)  # the layer's mass between the rows, closed form
# HydroDyn's nodes, every 0.25 m (the strip length) from z = -20 m: the grown radius tapers over the element holding
# each table end, from R + T at -2 m to R at -1.75 m and from R at -15.25 m to R + T at -15 m
H = 0.25
TAPER_VOLUME = math.pi * H * (R * T + T**2 / 3)  # int pi ((R + t)^2 - R^2) dz, t linear from T to 0 over H
TAPER_RISE = H * (R * T / 3 + T**2 / 12) / (R * T + T**2 / 3)  # its centroid above the end where t = T
# each element takes the density of its lower node: the upper taper's (-2 m) is RHO_MG, the lower one's (-15.25 m) 0
GROWTH = LAYER + RHO_MG * TAPER_VOLUME


def test_thickness_and_density_follow_hydrodyns_table():
    """Linear between rows, none outside (HydroDyn's SetNodeMG); rows highest first."""
    table = (MarineGrowthLevel(0.0, 0.2, 1000.0), MarineGrowthLevel(-10.0, 0.1, 1200.0))
    t, rho = thickness_and_density(table, [1.0, 0.0, -5.0, -10.0, -10.5])
    assert np.allclose(t, [0.0, 0.2, 0.15, 0.1, 0.0]) and np.allclose(rho, [0.0, 1000.0, 1100.0, 1200.0, 0.0])


def test_growth_mass_and_centroid_are_the_layers():
    """The layer between the rows and HydroDyn's tapers at their ends (closed forms), the inertia
    against a fine midpoint sum of thick rings (20000 slices)."""
    mass, centroid, inertia = growth_mass(column())
    assert mass == pytest.approx(GROWTH, rel=1e-12)
    z_c = (LAYER * (TOP + BOTTOM) / 2 + RHO_MG * TAPER_VOLUME * (TOP + TAPER_RISE)) / GROWTH
    assert np.allclose(centroid, [X, 0.0, z_c], atol=1e-12)
    z = np.linspace(BOTTOM, TOP + H, 20001)
    z = (z[1:] + z[:-1]) / 2
    t = np.interp(z, [BOTTOM, TOP, TOP + H], [T, T, 0.0])
    dm = RHO_MG * math.pi * ((R + t) ** 2 - R**2) * (z[1] - z[0])
    ring = (R + t) ** 2 + R**2
    assert inertia[2, 2] == pytest.approx(np.sum(dm * ring / 2), rel=1e-7)
    assert inertia[0, 0] == pytest.approx(np.sum(dm * (ring / 4 + (z - z_c) ** 2)), rel=1e-7)


def test_member_is_cut_at_hydrodyns_nodes_and_tapers_over_the_elements_holding_the_rows():
    pieces = grown_platform(column()).members
    heights = [(-20.0, BOTTOM - H), (BOTTOM - H, BOTTOM), (BOTTOM, TOP), (TOP, TOP + H), (TOP + H, 5.0)]
    assert np.array([(p.end_a_m[2], p.end_b_m[2]) for p in pieces]) == pytest.approx(np.array(heights), abs=1e-12)
    assert [p.width_m for p in pieces] == pytest.approx([2 * R, 2 * R, 2 * (R + T), 2 * (R + T), 2 * R], abs=1e-12)
    assert [p.diameter_b_m for p in pieces] == [None, pytest.approx(2 * (R + T)), None, pytest.approx(2 * R), None]
    assert [p.zones[0].ca[0] for p in pieces] == [1.0, 1.5, 1.5, 1.5, 1.0]


def test_the_growths_tapers_carry_the_axial_added_mass_in_heave():
    """With the member's AxCa 1 each taper of the growth adds HydroDyn's axial added mass
    2 rho AxCa pi R^2 |dR/dl| over its length, rho 2 pi ((R + T)^3 - R^3) / 3 integrated (closed
    form; one strip each, its midpoint: within 1e-3), under a heave acceleration."""
    base = column()
    member = dataclasses.replace(base.members[0], taper_axial=EndPlate(ca=1.0, cp=1.0, cd=0.0))
    model = PlatformModel(dataclasses.replace(base, members=(member,)), options=HYDRODYN)
    still, heave = np.zeros((2, 6)), np.zeros((2, 6))
    heave[1, 2] = 0.3
    load = model.prescribed_motion_loads(np.array([0.0, 0.1]), still, still, heave)[:, ROW["added_mass"]]
    expected = -2 * RHO * 2 * math.pi / 3 * ((R + T) ** 3 - R**3) * 0.3
    assert load[1, 2] - load[0, 2] == pytest.approx(expected, rel=1e-3)


def test_a_joint_plate_under_growth_carries_hydrodyns_end_mass():
    """A plate at the column's lower end (z = -20 m) inside a growth table reaching it: the growth's
    mass there is rho_mg t |An| with An the end's grown area pi (R + t)^2 (HydroDyn's Mass_MG_End),
    a point mass at the end; without the plate none."""
    table = (MarineGrowthLevel(TOP, T, RHO_MG), MarineGrowthLevel(-30.0, T, RHO_MG))
    bare = column(table)
    plate = EndPlate(ca=1.0, cp=1.0, cd=0.0)
    plated = dataclasses.replace(bare, members=(dataclasses.replace(bare.members[0], end_a_plate=plate),))
    (m0, c0, _), (m1, c1, _) = growth_mass(bare), growth_mass(plated)
    end = RHO_MG * T * math.pi * (R + T) ** 2
    assert m1 - m0 == pytest.approx(end, rel=1e-12)
    assert (m1 * c1 - m0 * c0) / end == pytest.approx([X, 0.0, -20.0], abs=1e-9)


@pytest.mark.parametrize("hydrostatics", ["nonlinear", "free_surface"])
def test_hydrostatic_component_carries_buoyancy_weight_and_inertia_of_the_layer(hydrostatics):
    """At rest: Fz = rho g V(bare, 20 m) + (rho - rho_mg) g V(layer), My = -x Fz (x = 4 m);
    heaving with acceleration a: the layer's reaction -m a on top (HydroDyn's F_IMG)."""
    model = PlatformModel(column(), options=dataclasses.replace(HYDRODYN, hydrostatics=hydrostatics))
    still, heave = np.zeros((2, 6)), np.zeros((2, 6))
    heave[1, 2] = 0.3
    load = model.prescribed_motion_loads(np.array([0.0, 0.1]), still, still, heave)[:, ROW["hydrostatic"]]
    volume_layer = LAYER / RHO_MG + 2 * TAPER_VOLUME  # both tapers displace water, one has growth mass
    fz = RHO * G * (math.pi * R**2 * 20.0 + volume_layer) - G * GROWTH
    assert load[0, 2] == pytest.approx(fz, rel=1e-9)
    assert load[0, 4] == pytest.approx(-X * fz, rel=1e-9)
    assert load[1, 2] - load[0, 2] == pytest.approx(-GROWTH * 0.3, rel=1e-9)


def test_fluid_inertia_takes_the_grown_diameter_and_the_growth_coefficients():
    """A regular wave (T 8 s, H 2 m), at rest, undisplaced: the inertia force's amplitude is
    the integral of rho Cm pi r(z)^2 a(z) over the wetted column, Cm = 2 bare and 2.5 grown,
    r = R + T between the table's rows (closed form of the cosh profile) and tapering to R over
    the elements holding them (HydroDyn's nodes; a fine trapezoid sum there), within 1e-4."""
    period, height = 8.0, 2.0
    waves = WaveComponents(np.array([1 / period]), np.array([height / 2]), np.zeros(1), np.zeros(1), period)
    t = np.arange(20) * period / 20
    rest = np.zeros((t.size, 6))
    model = PlatformModel(column(), waves, options=HYDRODYN, wave_table_dt_s=period / 40)
    fx = model.prescribed_motion_loads(t, rest, rest, rest)[:, ROW["inertia"], 0]
    omega = 2 * np.pi / period
    k = float(wavenumber(np.array([omega]), DEPTH, G)[0])

    def profile(z0: float, z1: float) -> float:  # int cosh k(z+h) / sinh kh dz
        return (math.sinh(k * (z1 + DEPTH)) - math.sinh(k * (z0 + DEPTH))) / (k * math.sinh(k * DEPTH))

    def tapered(z0: float, z1: float, r0: float, r1: float) -> float:  # int r(z)^2 cosh k(z+h) / sinh kh dz
        z = np.linspace(z0, z1, 2001)
        f = np.interp(z, [z0, z1], [r0, r1]) ** 2 * np.cosh(k * (z + DEPTH)) / math.sinh(k * DEPTH)
        return float(np.sum((f[1:] + f[:-1]) / 2) * (z[1] - z[0]))

    acc = omega**2 * height / 2
    amplitude = RHO * math.pi * acc * (2.0 * R**2 * (profile(-20.0, BOTTOM - H) + profile(TOP + H, 0.0))
                                       + 2.5 * (R + T) ** 2 * profile(BOTTOM, TOP)
                                       + 2.5 * tapered(BOTTOM - H, BOTTOM, R, R + T)
                                       + 2.5 * tapered(TOP, TOP + H, R + T, R))
    phase = np.sin(omega * t - k * X)
    assert np.max(np.abs(fx + amplitude * phase)) < 1e-4 * amplitude


def test_table_round_trips_and_bad_tables_are_refused():
    platform = column()
    document = platform_document(platform)
    assert document["marine_growth"][0] == {"z_m": TOP, "thickness_m": T, "density_kg_m3": RHO_MG}
    assert platform_from_dict(document, "round trip") == platform
    document["marine_growth"].reverse()
    with pytest.raises(ConfigError, match="z_m must decrease"):
        platform_from_dict(document, "reversed")


@pytest.mark.slow
def test_importer_reads_mgdepths_and_the_growth_coefficients(tmp_path):
    """A deck's MGDepths rows become the platform's table, its MG columns each member's growth
    zone (hd_WaveStMod2's column, its MG columns edited to Cd 0.9, Ca 1.2)."""
    deck = (REPO / "test" / "data" / "openfast_rtest" / "hd_WaveStMod2" / "hydrodyn_input.dat").read_text()
    old = "             0   NMGDepths"
    assert old in deck
    deck = deck.replace(old, "             2   NMGDepths", 1).replace(
        "(m)        (m)         (kg/m^3)", "(m)        (m)         (kg/m^3)\n-2.0       0.1         1100\n"
        "-15.0      0.2         1200", 1)
    path = tmp_path / "grown.dat"
    path.write_text(deck)
    out = tmp_path / "grown.yaml"
    assert main(["platform", "import", str(path), "-o", str(out), "--water-depth", "200"]) == 0
    platform = load_platform(out)
    assert platform.marine_growth == (MarineGrowthLevel(-2.0, 0.1, 1100.0), MarineGrowthLevel(-15.0, 0.2, 1200.0))
    assert platform.members[0].growth_zone is not None
