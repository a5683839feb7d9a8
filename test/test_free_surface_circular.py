"""Hydrostatics up to the instantaneous free surface on circular, tapered, tilted members
(HydroDyn's MHstLMod 1 with wave stretching, ``physics/free_surface_hydrostatics.py``) against
closed forms: Archimedes under any surface, a column's keel pressure, and in still water the
exact cut frustum of the nonlinear member hydrostatics (checked against closed forms and a
numerical integral in test_rtest_hydrodyn.py). The r-test case hd_MHstLMod1_compare is in the
suite (test_rtest_suite.py)."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from fowt_hydro_sim.cli import main
from fowt_hydro_sim.physics import free_surface_hydrostatics as fsh
from fowt_hydro_sim.physics.config import HYDRODYN, load_platform
from fowt_hydro_sim.physics.loads import ROW
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.testing import REPO

RHO, G = 1025.0, 9.80665
DECK = REPO / "test" / "data" / "openfast_rtest" / "hd_MHstLMod1_compare" / "hydrodyn_input.dat"


def flat(elevation_m: float):
    return lambda t, x, y: elevation_m


def tilted(slope_x: float, slope_y: float, level_m: float):
    return lambda t, x, y: level_m + slope_x * x + slope_y * y


def test_submerged_tapered_tilted_frustum_under_any_surface_is_archimedes():
    """Every element below the surface, flat or sloped: rho g V up through the frustum's
    centroid (closed form), the end plates included."""
    a, b = np.array([-3.0, 2.0, -30.0]), np.array([5.0, -4.0, -12.0])
    member = fsh.CircularMember(tuple(a), tuple(b), (8.0, 5.0), 7)
    r0, r1, length = 4.0, 2.5, float(np.linalg.norm(b - a))
    volume = math.pi * length * (r0 * r0 + r0 * r1 + r1 * r1) / 3
    centroid = a + (b - a) * (r0 * r0 + 2 * r0 * r1 + 3 * r1 * r1) / (4 * (r0 * r0 + r0 * r1 + r1 * r1))
    expected = RHO * G * volume * np.concatenate([[0.0, 0.0, 1.0], np.cross(centroid, [0.0, 0.0, 1.0])])
    for eta in (flat(0.7), tilted(0.04, -0.02, -1.0)):
        load = fsh.circular_member_wrench(member, eta, 0.0, RHO, G)
        assert np.allclose(load, expected, rtol=0, atol=1e-12 * expected[2] * 10)


@pytest.mark.parametrize("elevation_m", [-1.5, 0.0, 1.5])
def test_vertical_column_carries_the_keel_pressure_whatever_the_elevation(elevation_m):
    """p = -rho g z up to the surface on a vertical column: the wall carries no vertical load,
    so Fz = rho g A d at any elevation, acting on the column's axis."""
    column = fsh.CircularMember((1.0, 1.0, -9.0), (1.0, 1.0, 6.0), (3.0, 3.0), 4)
    load = fsh.circular_member_wrench(column, flat(elevation_m), 0.0, RHO, G)
    fz = RHO * G * math.pi * 1.5**2 * 9.0
    assert load[2] == pytest.approx(fz, rel=1e-12)
    assert np.allclose(load[[0, 1, 5]], 0.0, atol=1e-9 * fz)
    assert np.allclose(load[3:5], [fz, -fz], rtol=1e-12)  # (1, 1, z) x (0, 0, Fz)


@pytest.mark.slow
@pytest.mark.parametrize("pose", [[0.0, 0.0, 0.0, 0.0, 0.0, 0.0], [0.5, -1.0, -0.8, 0.06, -0.09, 0.3],
                                  [0.0, 0.0, 1.3, 0.0, 0.0, 0.0]])
def test_circular_free_surface_hydrostatics_in_still_water_equal_the_exact_cut_frustum(pose, tmp_path):
    """hd_MHstLMod1_compare's tapered, tilted member (14 elements of 2.84 m) in still water,
    displaced: the free-surface path (the element through the surface cut by its plane, the
    part of the plane below its lower node taken off) equals the nonlinear hydrostatics' exact
    submerged frustum within 1e-9."""
    platform_file = tmp_path / "compare.yaml"
    assert main(["platform", "import", str(DECK), "-o", str(platform_file), "--water-depth", "200"]) == 0
    platform = load_platform(platform_file)
    still = np.zeros((1, 6))
    loads = {}
    for mode in ("nonlinear", "free_surface"):
        model = PlatformModel(platform, options=dataclasses.replace(HYDRODYN, hydrostatics=mode))
        loads[mode] = model.prescribed_motion_loads(np.zeros(1), np.array([pose]), still, still)[0, ROW["hydrostatic"]]
    scale = abs(loads["nonlinear"][2])
    assert np.allclose(loads["free_surface"], loads["nonlinear"], rtol=0, atol=1e-9 * scale * 40), (
        loads["free_surface"] - loads["nonlinear"]) / scale
