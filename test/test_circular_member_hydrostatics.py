"""Hydrostatics up to the free surface on circular members wetted section by section, as
HydroDyn's MHstLMod 2 (``physics/free_surface_hydrostatics.py``), against references the model
did not produce: Archimedes on the circular segment of a horizontal cylinder at any depth of its
axis, Archimedes on a submerged tapered tilted frustum, and the pressure -rho g z integrated over
a fine polygonal model of a tapered tilted member (3600 planar facets, each clipped by the
surface plane, the pressure linear on each: exact there) cut by still water and by a sloped
plane. MHstLMod from the deck: a circular member of MHstLMod 2 is flagged
``hydrostatics_by_section``. The r-test case hd_MHstLMod2 is in the suite (test_rtest_suite.py)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from fowt_hydro_sim.cli import main
from fowt_hydro_sim.physics import free_surface_hydrostatics as fsh
from fowt_hydro_sim.physics.config import ConfigError, load_platform, platform_document, platform_from_dict
from fowt_hydro_sim.testing import REPO

RHO, G = 1025.0, 9.80665
RTEST = REPO / "test" / "data" / "openfast_rtest"


def flat(elevation_m: float):
    return lambda t, x, y: elevation_m


def sloped(level_m: float, slope_x: float, slope_y: float):
    return lambda t, x, y: level_m + slope_x * x + slope_y * y


# ------------------------------------------------------------------ the polygonal reference
def _axes(k: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors with (k, y, z) right-handed."""
    y = np.cross(k, [0.0, 0.0, 1.0] if abs(k[2]) < 0.9 else [1.0, 0.0, 0.0])
    y /= np.linalg.norm(y)
    return y, np.cross(k, y)


def _below(polygon: np.ndarray, point: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """The part of a convex planar polygon where (r - point) . normal <= 0, its order kept."""
    height = (polygon - point) @ normal
    kept = []
    for i in range(len(polygon)):
        j = (i + 1) % len(polygon)
        if height[i] <= 0.0:
            kept.append(polygon[i])
        if (height[i] <= 0.0) != (height[j] <= 0.0):
            kept.append(polygon[i] + (polygon[j] - polygon[i]) * height[i] / (height[i] - height[j]))
    return np.array(kept).reshape(-1, 3)


def _polygon_wrench(polygons: list[np.ndarray], point: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """rho g (int z n dA, int z r x n dA) over the parts of the polygons (area vectors outward)
    below the plane: on each triangle of a fan, with z and r linear, int z dA = A (z1 + z2 + z3)
    / 3 and int z r dA = A (sum z_i r_i + sum z_i sum r_i) / 12."""
    triangles = []
    for polygon in polygons:
        wet = _below(polygon, point, normal)
        triangles += [(wet[0], wet[j], wet[j + 1]) for j in range(1, len(wet) - 1)]
    t = np.array(triangles)  # (n, 3 vertices, 3)
    area_vector = 0.5 * np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    z = t[:, :, 2]
    force = (z.sum(axis=1) / 3)[:, None] * area_vector
    zr = ((z[:, :, None] * t).sum(axis=1) + z.sum(axis=1)[:, None] * t.sum(axis=1)) / 12
    moment = np.cross(zr, area_vector)
    return RHO * G * np.concatenate([force.sum(axis=0), moment.sum(axis=0)])


def _frustum_polygons(a: np.ndarray, b: np.ndarray, r_a: float, r_b: float, n: int = 3600,
                      ends: bool = True) -> list[np.ndarray]:
    """The frustum's surface as n planar wall facets (trapezoids) and its two end n-gons."""
    k = (b - a) / np.linalg.norm(b - a)
    y, z = _axes(k)
    theta = 2 * np.pi * np.arange(n) / n
    rim = np.cos(theta)[:, None] * y + np.sin(theta)[:, None] * z
    ring_a, ring_b = a + r_a * rim, b + r_b * rim
    walls = [np.array([ring_a[i], ring_a[(i + 1) % n], ring_b[(i + 1) % n], ring_b[i]]) for i in range(n)]
    return walls + ([ring_a[::-1], ring_b] if ends else [])


def _plane(eta) -> tuple[np.ndarray, np.ndarray]:
    """The plane of a flat or sloped elevation (point over the origin, upward unit normal)."""
    slope_x, slope_y = eta(0.0, 1.0, 0.0) - eta(0.0, 0.0, 0.0), eta(0.0, 0.0, 1.0) - eta(0.0, 0.0, 0.0)
    normal = np.array([-slope_x, -slope_y, 1.0])
    return np.array([0.0, 0.0, eta(0.0, 0.0, 0.0)]), normal / np.linalg.norm(normal)


# ------------------------------------------------------------------ closed forms
@pytest.mark.parametrize("above_axis_m", [0.0, 1.2, 2.9, -2.4, 3.5, -3.5])
def test_horizontal_cylinder_carries_archimedes_on_its_circular_segment(above_axis_m):
    """A horizontal cylinder (radius 3 m, 12 m long, its axis 30 deg from x through (2, -1))
    with still water h above its axis: rho g L (r^2 acos(-h/r) + h sqrt(r^2 - h^2)) up through
    the axis' midpoint (half the volume at h = 0), the end plates' thrusts cancelling."""
    r, length, h = 3.0, 12.0, above_axis_m
    centre, k = np.array([2.0, -1.0, -h]), np.array([math.cos(math.pi / 6), math.sin(math.pi / 6), 0.0])
    member = fsh.CircularMember(tuple(centre - 0.5 * length * k), tuple(centre + 0.5 * length * k),
                                (2 * r, 2 * r), 4, mhstlmod=2)
    c = min(max(h, -r), r)
    area = r * r * math.acos(-c / r) + c * math.sqrt(r * r - c * c)
    fz = RHO * G * area * length
    expected = np.array([0.0, 0.0, fz, centre[1] * fz, -centre[0] * fz, 0.0])
    load = fsh.circular_member_wrench(member, flat(0.0), 0.0, RHO, G)
    scale = RHO * G * math.pi * r * r * length
    assert np.allclose(load, expected, rtol=0, atol=1e-10 * scale * length), (load - expected) / scale
    if abs(h) < r:
        assert 0 < fz < scale


@pytest.mark.parametrize("eta", [flat(0.7), sloped(-1.0, 0.04, -0.02)], ids=["flat", "sloped"])
def test_submerged_tapered_tilted_member_is_archimedes(eta):
    """Every section below the surface, level or sloped: rho g V of the frustum up through its
    centroid (closed forms), the end plates included."""
    a, b = np.array([-3.0, 2.0, -30.0]), np.array([5.0, -4.0, -12.0])
    member = fsh.CircularMember(tuple(a), tuple(b), (8.0, 5.0), 7, mhstlmod=2)
    r0, r1, length = 4.0, 2.5, float(np.linalg.norm(b - a))
    volume = math.pi * length * (r0 * r0 + r0 * r1 + r1 * r1) / 3
    centroid = a + (b - a) * (r0 * r0 + 2 * r0 * r1 + 3 * r1 * r1) / (4 * (r0 * r0 + r0 * r1 + r1 * r1))
    expected = RHO * G * volume * np.concatenate([[0.0, 0.0, 1.0], np.cross(centroid, [0.0, 0.0, 1.0])])
    load = fsh.circular_member_wrench(member, eta, 0.0, RHO, G)
    assert np.allclose(load, expected, rtol=0, atol=1e-10 * expected[2] * length)


# ------------------------------------------------------------------ the polygonal integral
def test_tapered_tilted_member_cut_by_still_water_matches_the_polygonal_pressure_integral():
    """A tapered member (6 to 4 m) rising 2.5 m over 21.5 m through still water, every section
    and both end plates cut: the wrench within 1e-5 (of rho g V, of rho g V L) of -rho g z
    integrated over 3600 clipped facets and the two clipped end polygons."""
    a, b = np.array([-10.0, 4.0, -1.0]), np.array([10.0, -4.0, 1.5])
    member = fsh.CircularMember(tuple(a), tuple(b), (6.0, 4.0), 6, mhstlmod=2)
    reference = _polygon_wrench(_frustum_polygons(a, b, 3.0, 2.0), *_plane(flat(0.0)))
    load = fsh.circular_member_wrench(member, flat(0.0), 0.0, RHO, G)
    length = float(np.linalg.norm(b - a))
    scale = RHO * G * math.pi * length * (9.0 + 6.0 + 4.0) / 3
    assert abs(reference[2]) > 0.2 * scale  # a fair part of it wet
    assert np.allclose(load[:3], reference[:3], rtol=0, atol=1e-5 * scale), (load - reference) / scale
    assert np.allclose(load[3:], reference[3:], rtol=0, atol=1e-5 * scale * length), (load - reference) / scale


def test_section_integral_under_a_sloped_plane_and_hydrodyn_s_side_term():
    """Side walls under a sloped plane (slopes 0.05, -0.08): with the pressure integral's sign
    the element integrals match the polygonal integral within 1e-5; with HydroDyn's C1 sign
    (the model's) Fz is the same and the side force departs (by more than 1e-3 here)."""
    a, b = np.array([-8.0, 3.0, -4.0]), np.array([9.0, -2.0, 0.0])  # wet whole at a, the rim out at b
    r_a, r_b, n = 2.5, 3.5, 5
    eta = sloped(0.3, 0.05, -0.08)
    length = float(np.linalg.norm(b - a))
    k, dl, taper = (b - a) / length, length / n, (r_b - r_a) / length
    walls = {}
    for sign in (1.0, -1.0):
        total = np.zeros(6)
        for i in range(n):
            start = a + i * dl * k
            mid = start + 0.5 * dl * k
            plane = fsh.surface_plane(eta, 0.0, mid[0], mid[1], r_a + taper * (i + 0.5) * dl)
            total += fsh._sectioned_element(start, k, r_a + taper * i * dl, taper, dl, plane, cross_sign=sign)
        walls[sign] = RHO * G * total
    reference = _polygon_wrench(_frustum_polygons(a, b, r_a, r_b, ends=False), *_plane(eta))
    scale = RHO * G * math.pi * length * (r_a * r_a + r_a * r_b + r_b * r_b) / 3
    tolerance = np.array([1.0, 1.0, 1.0, length, length, length]) * 1e-5 * scale
    assert np.all(np.abs(walls[1.0] - reference) <= tolerance), (walls[1.0] - reference) / scale
    assert abs(walls[-1.0][2] - reference[2]) <= tolerance[2]
    assert np.hypot(*(walls[-1.0] - reference)[:2]) > 1e-3 * scale


# ------------------------------------------------------------------ MHstLMod from the deck
@pytest.mark.slow  # openfast-io read twice (7 s the first time in a process: its import)
@pytest.mark.parametrize(("case", "deck", "mhstlmod"), [("hd_MHstLMod2", "HydroDyn.dat", 2),
                                                       ("hd_MHstLMod1_compare", "hydrodyn_input.dat", 1)])
def test_deck_mhstlmod_reaches_the_circular_member(case, deck, mhstlmod, tmp_path):
    """``platform import`` flags a circular member of MHstLMod 2 ``hydrostatics_by_section``;
    the free-surface hydrostatics take it as MHstLMod 2, the flag surviving the YAML."""
    out = tmp_path / f"{case}.yaml"
    assert main(["platform", "import", str(RTEST / case / deck), "-o", str(out), "--water-depth", "200"]) == 0
    platform = load_platform(out)
    assert [m.mhstlmod for m in fsh.platform_members(platform)] == [mhstlmod]
    assert platform_from_dict(platform_document(platform)).members == platform.members


def test_hydrostatics_by_section_on_a_rectangular_member_is_refused_in_one_line():
    document = platform_document(load_platform("windmoor12"))
    rectangular = next(m for m in document["members"] if m["section"] == "rectangular")
    rectangular["hydrostatics_by_section"] = True
    with pytest.raises(ConfigError) as refused:
        platform_from_dict(document)
    assert "hydrostatics_by_section" in str(refused.value) and len(str(refused.value).splitlines()) == 1
