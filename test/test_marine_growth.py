"""Marine growth (``physics/marine_growth.py``, HydroDyn's MGDepths) against closed forms on a
vertical cylinder with a growth layer: the table's interpolation, the layer's mass, centroid
and the hydrostatic component's weight, buoyancy and inertial reaction, and the fluid
inertia on the grown diameter with the growth coefficients; the platform document and the
HydroDyn importer carry the table."""
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


LAYER = RHO_MG * math.pi * ((R + T) ** 2 - R**2) * (TOP - BOTTOM)  # the layer's mass, closed form


def test_thickness_and_density_follow_hydrodyns_table():
    """Linear between rows, none outside (HydroDyn's SetNodeMG); rows highest first."""
    table = (MarineGrowthLevel(0.0, 0.2, 1000.0), MarineGrowthLevel(-10.0, 0.1, 1200.0))
    t, rho = thickness_and_density(table, [1.0, 0.0, -5.0, -10.0, -10.5])
    assert np.allclose(t, [0.0, 0.2, 0.15, 0.1, 0.0]) and np.allclose(rho, [0.0, 1000.0, 1100.0, 1200.0, 0.0])


def test_growth_mass_and_centroid_are_the_layers():
    mass, centroid, inertia = growth_mass(column())
    assert mass == pytest.approx(LAYER, rel=1e-12)
    assert np.allclose(centroid, [X, 0.0, (TOP + BOTTOM) / 2], atol=1e-12)
    # about its own axis a thick ring: m (Ro^2 + Ri^2) / 2; transverse: m ((Ro^2 + Ri^2) / 4 + L^2 / 12)
    ring = (R + T) ** 2 + R**2
    assert inertia[2, 2] == pytest.approx(LAYER * ring / 2, rel=1e-12)
    assert inertia[0, 0] == pytest.approx(LAYER * (ring / 4 + (TOP - BOTTOM) ** 2 / 12), rel=1e-10)


def test_member_is_cut_at_the_table_and_grown_in_between():
    pieces = grown_platform(column()).members
    assert [(p.end_a_m[2], p.end_b_m[2]) for p in pieces] == [(-20.0, BOTTOM), (BOTTOM, TOP), (TOP, 5.0)]
    assert [p.width_m for p in pieces] == [2 * R, 2 * (R + T), 2 * R]
    assert [p.zones[0].ca[0] for p in pieces] == [1.0, 1.5, 1.0]


@pytest.mark.parametrize("hydrostatics", ["nonlinear", "free_surface"])
def test_hydrostatic_component_carries_buoyancy_weight_and_inertia_of_the_layer(hydrostatics):
    """At rest: Fz = rho g V(bare, 20 m) + (rho - rho_mg) g V(layer), My = -x Fz (x = 4 m);
    heaving with acceleration a: the layer's reaction -m a on top (HydroDyn's F_IMG)."""
    model = PlatformModel(column(), options=dataclasses.replace(HYDRODYN, hydrostatics=hydrostatics))
    still, heave = np.zeros((2, 6)), np.zeros((2, 6))
    heave[1, 2] = 0.3
    load = model.prescribed_motion_loads(np.array([0.0, 0.1]), still, still, heave)[:, ROW["hydrostatic"]]
    volume_layer = LAYER / RHO_MG
    fz = RHO * G * math.pi * R**2 * 20.0 + (RHO - RHO_MG) * G * volume_layer
    assert load[0, 2] == pytest.approx(fz, rel=1e-9)
    assert load[0, 4] == pytest.approx(-X * fz, rel=1e-9)
    assert load[1, 2] - load[0, 2] == pytest.approx(-LAYER * 0.3, rel=1e-9)


def test_fluid_inertia_takes_the_grown_diameter_and_the_growth_coefficients():
    """A regular wave (T 8 s, H 2 m), at rest, undisplaced: the inertia force's amplitude is
    the integral of rho Cm pi r(z)^2 a(z) over the wetted column, Cm = 2 bare and 2.5 grown,
    r = R + T between the table's rows (closed form of the cosh profile), within 1e-4."""
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

    acc = omega**2 * height / 2
    amplitude = RHO * math.pi * acc * (2.0 * R**2 * (profile(-20.0, BOTTOM) + profile(TOP, 0.0))
                                       + 2.5 * (R + T) ** 2 * profile(BOTTOM, TOP))
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
