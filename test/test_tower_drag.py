"""The wind's drag on the tower (AeroDyn's TwrAero) against closed forms, and AeroDyn's
tower table as read from the IEA-15 example's file."""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.io.aerodyn import TowerTable, tower_table
from fowt_hydro_sim.turbine.description import load_turbine
from fowt_hydro_sim.turbine.tower import tower_drag, tower_points

RHO = 1.225
UNIFORM = TowerTable(np.array([10.0, 40.0, 100.0]), np.array([8.0, 8.0, 8.0]), np.array([0.6, 0.6, 0.6]))


def test_a_uniform_tower_in_uniform_wind_gets_half_rho_cd_d_length_u_squared():
    points = tower_points(UNIFORM, 150.0, 0.0)
    force, moment = tower_drag(points, RHO, 12.0, 0.0, 0.0, 150.0)
    expected = 0.5 * RHO * 0.6 * 8.0 * 90.0 * 12.0 ** 2
    assert force == pytest.approx(expected, rel=1e-12)
    assert moment == pytest.approx(expected * (55.0 - 150.0), rel=1e-12)


def test_a_power_law_profile_and_a_tapered_top_give_their_integrals():
    table = TowerTable(np.array([15.0, 132.0, 144.386]), np.array([10.0, 10.0, 6.5]), np.array([0.5, 0.5, 0.5]))
    alpha, hub, wind = 0.12, 150.0, 24.0
    points = tower_points(table, hub, alpha)
    force, moment = tower_drag(points, RHO, wind, 0.0, 0.0, 0.0)
    e = 2 * alpha  # u^2 = U^2 (z/H)^e
    # the column: D int (z/H)^e dz; the taper: int (a + b z) (z/H)^e dz, both in closed form
    column = 10.0 * (132.0 ** (e + 1) - 15.0 ** (e + 1)) / ((e + 1) * hub ** e)
    b = (6.5 - 10.0) / (144.386 - 132.0)
    a = 10.0 - b * 132.0
    z0, z1 = 132.0, 144.386
    taper = (a * (z1 ** (e + 1) - z0 ** (e + 1)) / (e + 1) + b * (z1 ** (e + 2) - z0 ** (e + 2)) / (e + 2)) / hub ** e
    taper_moment = (a * (z1 ** (e + 2) - z0 ** (e + 2)) / (e + 2) + b * (z1 ** (e + 3) - z0 ** (e + 3)) / (e + 3)) \
        / hub ** e
    column_moment = 10.0 * (132.0 ** (e + 2) - 15.0 ** (e + 2)) / ((e + 2) * hub ** e)
    scale = 0.5 * RHO * 0.5 * wind ** 2
    assert force == pytest.approx(scale * (column + taper), rel=1e-6)
    assert moment == pytest.approx(scale * (column_moment + taper_moment), rel=1e-6)


def test_the_towers_own_motion_is_taken_off_the_wind():
    points = tower_points(UNIFORM, 150.0, 0.0)
    wind, surge_velocity, pitch_rate = 10.0, 1.5, 0.02  # u = 10 - 1.5 - 0.02 z > 0 along the tower
    force, moment = tower_drag(points, RHO, wind, surge_velocity, pitch_rate, 0.0)
    c = wind - surge_velocity

    def integral(power: int) -> float:  # int z^power (c - q z)^2 dz from 10 to 100
        def f(z):
            return (c ** 2 * z ** (power + 1) / (power + 1) - 2 * c * pitch_rate * z ** (power + 2) / (power + 2)
                    + pitch_rate ** 2 * z ** (power + 3) / (power + 3))
        return f(100.0) - f(10.0)

    scale = 0.5 * RHO * 0.6 * 8.0
    assert force == pytest.approx(scale * integral(0), rel=1e-12)
    assert moment == pytest.approx(scale * integral(1), rel=1e-12)
    assert tower_drag(points, RHO, 0.0, 2.0, 0.0, 0.0)[0] == pytest.approx(-0.5 * RHO * 0.6 * 8.0 * 90.0 * 4.0)


def test_the_iea15_examples_aerodyn_tower_table_is_read():
    turbine = load_turbine("iea15_umaine")
    table = turbine.tower_table()
    assert table is not None and len(table.heights_m) == 11
    assert (table.heights_m[0], table.heights_m[-1]) == (15.0, 144.386)
    assert (table.diameters_m[0], table.diameters_m[-1]) == (10.0, 6.5)
    assert np.all(table.drag_coefficients == 0.5)
    # 117 m of a 10 m column and a 12.4 m taper to 6.5 m: 1,272 m^2 of frontal area
    area = np.sum(tower_points(table, 150.0, 0.0).areas_m2) / 0.5
    assert area == pytest.approx(10.0 * 117.0 + 0.5 * (10.0 + 6.5) * 12.386, rel=1e-12)


def _aerodyn(tmp_path: Path, flag: str = "True", rows: str = "0. 6. 1.0 0.1\n90. 4. 1.0 0.1\n") -> Path:
    n = len(rows.splitlines())
    path = tmp_path / "AeroDyn15.dat"
    path.write_text(f"------- AERODYN v15 --------\n{flag}   TwrAero  - Calculate tower aerodynamic loads? (flag)\n"
                    f"{n}   NumTwrNds  - Number of tower nodes\nTwrElev TwrDiam TwrCd TwrTI\n(m) (m) (-) (-)\n{rows}")
    return path


def test_aerodyn_files_without_tower_aero_or_with_a_bad_table_are_read_or_refused_in_one_line(tmp_path):
    assert tower_table(_aerodyn(tmp_path, "False")) is None
    table = tower_table(_aerodyn(tmp_path))
    assert table.diameters_m.tolist() == [6.0, 4.0]
    with pytest.raises(InputError, match=r"TwrElev must increase"):
        tower_table(_aerodyn(tmp_path, rows="90. 6. 1.0 0.1\n0. 4. 1.0 0.1\n"))
    with pytest.raises(InputError, match=r"TwrElev table does not hold 2 rows"):
        tower_table(_aerodyn(tmp_path, rows="0. 6. 1.0 0.1\nx 4. 1.0 0.1\n"))
    with pytest.raises(InputError, match=r"TwrAero is not True or False"):
        tower_table(_aerodyn(tmp_path, "maybe"))
    assert math.isfinite(tower_drag(tower_points(table, 90.0, 0.2), RHO, 10.0, 0.0, 0.0, 0.0)[0])
