"""SeaState's grid (physics/waves/grid.py) against closed forms: a field linear in the
interpolation's coordinates (t, x, y and the angle acos(1 + z / Z_Depth)) is reproduced exactly
between the nodes, an Airy wave between nodes within the linear-interpolation error bound
h^2 max|f''| / 8, the nodes are SeaState's, and the command line refuses the option without
its grid in one line."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from fowt_hydro_sim.cli import main
from fowt_hydro_sim.physics.config import ConfigError, HydroOptions
from fowt_hydro_sim.physics.waves.components import WaveComponents, wavenumber
from fowt_hydro_sim.physics.waves.grid import SeaStateGrid
from fowt_hydro_sim.physics.waves.kinematics import complex_amplitudes

MCF_SEASTATE = Path(__file__).parent / "data" / "openfast_rtest" / "hd_MCF_WaveStMod1" / "MCF_SeaState.dat"
DEPTH, G, RHO = 200.0, 9.80665, 1025.0
GRID = SeaStateGrid(x_half_width_m=30.0, y_half_width_m=20.0, z_depth_m=40.0, nx=4, ny=3, nz=6, dt_s=0.25)
RNG = np.random.default_rng(7)


def moving_point_kinematics(waves, points, t, depth_m, gravity_m_s2, density_kg_m3):
    """Exact Airy kinematics (n, 7) at points each at its own time (numpy, no compiled kernel)."""
    amplitudes = complex_amplitudes(waves, points, depth_m, gravity_m_s2, density_kg_m3)  # (n, 7, f)
    phasor = np.exp(1j * np.outer(t, 2 * np.pi * waves.frequency_hz))  # (n, f)
    return np.einsum("ncf,nf->nc", amplitudes, phasor).real


def _linear_field(grid: SeaStateGrid, depth_m: float):
    """A field of the seven channels linear in t, x, y and theta = acos(1 + z / Z_Depth) (each
    channel its own coefficients), as ``interpolate_kinematics`` takes an evaluator."""
    coefficients = RNG.normal(size=(5, 7))

    def evaluate(waves, points, t, *args):
        theta = np.arccos(np.clip(1.0 + np.minimum(points[:, 2], 0.0) / grid.depth(depth_m), 0.0, 1.0))
        basis = np.column_stack([np.ones(len(t)), t, points[:, 0], points[:, 1], theta])
        return basis @ coefficients

    return evaluate


def _points(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Points inside the grid off its nodes, and times off WaveDT."""
    points = np.column_stack([RNG.uniform(-29, 29, n), RNG.uniform(-19, 19, n), RNG.uniform(-39.5, -0.01, n)])
    return points, RNG.uniform(0.0, 10.0, n)


def test_a_field_linear_in_the_interpolation_coordinates_is_reproduced_exactly():
    evaluate = _linear_field(GRID, DEPTH)
    points, t = _points(200)
    gridded = GRID.interpolate_kinematics(evaluate)(None, points, t, DEPTH, G, RHO)
    np.testing.assert_allclose(gridded, evaluate(None, points, t), rtol=0, atol=1e-11)


def test_a_field_linear_in_z_is_not_linear_along_the_grid_angle():
    """HydroDyn interpolates along theta, not z: a field linear in z misses between the z nodes
    (within the bound of its curvature in theta), and is exact at them."""
    def linear_in_z(waves, points, t, *args):
        return np.repeat(points[:, 2:3], 7, axis=1)

    nodes = GRID.z_nodes(DEPTH)
    middle = 0.5 * (nodes[:-1] + nodes[1:])
    at = np.column_stack([np.zeros(len(middle)), np.zeros(len(middle)), middle])
    gridded = GRID.interpolate_kinematics(linear_in_z)(None, at, np.zeros(len(middle)), DEPTH, G, RHO)[:, 0]
    # z = Z (cos theta - 1): |d2z/dtheta2| <= Z_Depth, so the error is at most Z_Depth dtheta^2 / 8
    assert np.all(np.abs(gridded - middle) <= GRID.z_depth_m * GRID.dtheta**2 / 8 + 1e-12)
    assert np.max(np.abs(gridded - middle)) > 1e-3  # not linear in z
    on_nodes = np.column_stack([np.zeros(len(nodes)), np.zeros(len(nodes)), nodes])
    np.testing.assert_allclose(GRID.interpolate_kinematics(linear_in_z)(None, on_nodes, np.zeros(len(nodes)), DEPTH,
                                                                          G, RHO)[:, 0], nodes, atol=1e-12)


def test_nodes_are_seastates():
    """X[n] = n dX, n = -NX+1 .. NX-1, dX = X_HalfWidth / (NX - 1); Z[n] = (cos(n dtheta) - 1)
    Z_Depth, dtheta = pi / (2 (NZ - 1)) (SeaState's input file's own description)."""
    grid = SeaStateGrid.from_seastate_file(MCF_SEASTATE)
    assert (grid.x_half_width_m, grid.y_half_width_m, grid.z_depth_m, grid.nx, grid.ny, grid.nz, grid.dt_s) == (
        30.0, 30.0, 40.0, 2, 2, 30, 0.05)
    theta = np.arange(grid.nz) * math.pi / (2 * (grid.nz - 1))
    np.testing.assert_allclose(np.sort(grid.z_nodes(DEPTH)), np.sort((np.cos(theta) - 1.0) * 40.0), atol=1e-12)
    # a node is reproduced exactly, whatever the field (here the exact Airy kinematics)
    waves = _wave(0.08)
    node = np.array([[-30.0 + 30.0, 30.0, grid.z_nodes(DEPTH)[11]]])
    exact = moving_point_kinematics(waves, node, np.array([1.35]), DEPTH, G, RHO)
    gridded = grid.interpolate_kinematics(moving_point_kinematics)(waves, node, np.array([1.35]), DEPTH, G, RHO)
    np.testing.assert_allclose(gridded, exact, rtol=1e-9, atol=1e-9)


def test_z_depth_default_is_the_water_depth(tmp_path):
    text = MCF_SEASTATE.read_text(encoding="utf-8", errors="replace")
    path = tmp_path / "SeaState.dat"
    path.write_text(text.replace("          40.0   Z_Depth", '     "default"   Z_Depth'), encoding="utf-8")
    grid = SeaStateGrid.from_seastate_file(path)
    assert grid.z_depth_m is None and grid.z_nodes(DEPTH).min() == pytest.approx(-DEPTH)


def _wave(omega: float, amplitude: float = 2.0, heading_deg: float = 20.0) -> WaveComponents:
    period = 2 * np.pi / omega
    return WaveComponents(np.array([omega / (2 * np.pi)]), np.array([amplitude]), np.array([0.4]),
                          np.array([np.radians(heading_deg)]), period)


def test_an_airy_wave_between_nodes_is_within_the_linear_interpolation_bound():
    """eta = A cos(w t - k s + phase): between x nodes (t on a node) within A (k cos b)^2 dX^2 / 8;
    between t nodes (x on a node) within A w^2 dt^2 / 8; the horizontal velocity likewise with
    its amplitude A w C(z)."""
    omega = 0.6
    waves = _wave(omega)
    k = float(wavenumber(np.array([omega]), DEPTH, G)[0])
    kx = k * np.cos(np.radians(20.0))
    x = np.linspace(-29.9, 29.9, 301)
    t_node = np.full(x.size, 3 * GRID.dt_s)
    xy = np.column_stack([x, np.zeros(x.size)])
    eta = GRID.elevation(waves, xy, t_node, DEPTH, G)
    exact = waves.elevation_at(xy, t_node[0], DEPTH, G)
    error = np.max(np.abs(eta - exact))
    assert error <= 2.0 * kx**2 * GRID.dx_m**2 / 8 * (1 + 1e-9)
    assert error > 0.3 * 2.0 * kx**2 * GRID.dx_m**2 / 8  # the grid is coarse: the error is seen
    t = np.linspace(0.0, 20.0, 401)
    on_node = np.zeros((t.size, 2))
    eta_t = GRID.elevation(waves, on_node, t, DEPTH, G)
    exact_t = waves.elevation(0.0, 0.0, t, DEPTH, G)
    assert np.max(np.abs(eta_t - exact_t)) <= 2.0 * omega**2 * GRID.dt_s**2 / 8 * (1 + 1e-9)
    # the horizontal velocity at a z node, between x nodes
    z = GRID.z_nodes(DEPTH)[-2]
    points = np.column_stack([x, np.zeros(x.size), np.full(x.size, z)])
    u = GRID.interpolate_kinematics(moving_point_kinematics)(waves, points, t_node, DEPTH, G, RHO)[:, 0]
    u_exact = moving_point_kinematics(waves, points, t_node, DEPTH, G, RHO)[:, 0]
    amplitude = 2.0 * omega * np.cosh(k * (z + DEPTH)) / np.sinh(k * DEPTH) * np.cos(np.radians(20.0))
    assert np.max(np.abs(u - u_exact)) <= amplitude * kx**2 * GRID.dx_m**2 / 8 * (1 + 1e-9)


def test_outside_the_grid_the_boundary_value():
    waves = _wave(0.6)
    t = np.array([1.0, 1.0])
    outside = GRID.elevation(waves, np.array([[45.0, 5.0], [-80.0, -30.0]]), t, DEPTH, G)
    boundary = GRID.elevation(waves, np.array([[30.0, 5.0], [-30.0, -20.0]]), t, DEPTH, G)
    np.testing.assert_allclose(outside, boundary, rtol=0, atol=1e-12)
    deep = np.array([[0.0, 0.0, -60.0], [0.0, 0.0, -40.0]])
    values = GRID.interpolate_kinematics(moving_point_kinematics)(waves, deep, t, DEPTH, G, RHO)
    np.testing.assert_allclose(values[0], values[1], rtol=0, atol=1e-12)


def test_grid_option_refused_without_its_grid_in_one_line(tmp_path, capsys):
    motion = tmp_path / "motion.dat"
    np.savetxt(motion, np.column_stack([[0.0, 0.1], np.zeros((2, 18))]))
    code = main(["loads", "--motion", str(motion), "--still-water", "--wave-kinematics", "grid",
                 "-o", str(tmp_path / "loads.csv")])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "--seastate-grid" in err[0], err
    with pytest.raises(ConfigError, match="surface_grid_m and wave_kinematics"):
        HydroOptions(hydrostatics="free_surface", surface_grid_m=5.0, wave_kinematics="grid")
