"""The HydroDyn decks and wave files a user brings from the OpenFAST r-test: decks of older
layouts import as the current layout does or are refused in one line naming the field;
``.Comp`` files comma- or blank-separated, with frequencies on no common grid summed
directly (test/data/openfast_rtest, README)."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import yaml

from fowt_hydro_sim.cli import main
from fowt_hydro_sim.physics.config import HYDRODYN, ConfigError, load_platform
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import WaveComponents, read_comp_file
from fowt_hydro_sim.testing import REPO

RTEST = REPO / "test" / "data" / "openfast_rtest"
TAPER_DECK = RTEST / "hd_TaperCylinderPitchMoment" / "Taper_HD_primary.dat"
EXAMPLE_COMP = RTEST / "hd_WaveStMod2" / "example.Comp"
# the potential-flow lines HydroDyn added after v3 (openfast-io reads them by position)
NEWER_LINES = ("ExctnCutOff", "PtfmYMod", "PtfmRefY", "PtfmYCutOff", "NExctnHdg")


def test_deck_of_the_older_layout_imports_as_the_current_one(tmp_path):
    """The r-test's tapered-cylinder deck without the five potential-flow lines of the newer
    layout (as decks before them are) gives the same platform; openfast-io alone reads it
    out of step and raises."""
    lines = TAPER_DECK.read_text().splitlines(keepends=True)
    older = tmp_path / "older.dat"
    older.write_text("".join(line for line in lines if len(line.split()) < 2 or line.split()[1] not in NEWER_LINES))
    assert len(older.read_text().splitlines()) == len(lines) - len(NEWER_LINES)
    documents = []
    for deck in (TAPER_DECK, older):
        out = tmp_path / f"{deck.stem}.yaml"
        assert main(["platform", "import", str(deck), "-o", str(out), "--water-depth", "100"]) == 0
        documents.append(yaml.safe_load(out.read_text()))
    for key in ("name", "description"):  # the source file's name
        documents[1][key] = documents[0][key]
    assert documents[0] == documents[1]


@pytest.mark.parametrize("field, value, message", [
    ("NBodyMod", "unused", "field NBodyMod reads as 'unused', not an integer"),
    ("NMembers", "1.5", "field NMembers reads as '1.5', not an integer"),
])
def test_deck_read_out_of_step_is_refused_in_one_line_naming_the_field(tmp_path, capsys, field, value, message):
    """A switch openfast-io reads as text (its TypeError on NBodyMod, or a member count read
    as a fraction) ends in exit code 2 and one line naming the field, no traceback."""
    lines = TAPER_DECK.read_text().splitlines(keepends=True)
    changed = [f"{value:>14}   {field}   - changed\n" if len(line.split()) > 1 and line.split()[1] == field else line
               for line in lines]
    assert changed != lines
    deck = tmp_path / "deck.dat"
    deck.write_text("".join(changed))
    assert main(["platform", "import", str(deck), "-o", str(tmp_path / "x.yaml")]) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and len(err.splitlines()) == 1, err


def test_comma_separated_comp_file_on_no_common_grid_is_read_for_direct_summation():
    """The r-test's example.Comp: 76 comma-separated components, frequencies printed to 6
    decimals (multiples of 2 pi / 500 s to 4e-5 of a step only). The time loop's tables refuse
    it in one line; for direct summation it is read as written, period 0."""
    with pytest.raises(ConfigError, match="not on a common grid") as refused:
        read_comp_file(EXAMPLE_COMP)
    assert len(str(refused.value).splitlines()) == 1
    waves = read_comp_file(EXAMPLE_COMP, direct_sum=True)
    assert waves.frequency_hz.size == 76 and not waves.periodic and waves.period_s == 0.0
    assert 2 * math.pi * waves.frequency_hz[0] == 0.703717 and 2 * waves.amplitude_m[0] == 0.54768768
    assert math.degrees(waves.direction_rad[0]) == pytest.approx(-100.83703341, rel=1e-14)
    assert math.degrees(waves.phase_rad[0]) == pytest.approx(-109.22570984, rel=1e-14)
    spaced = read_comp_file_text(EXAMPLE_COMP.read_text().replace(",", "  "))
    assert np.array_equal(spaced.frequency_hz, waves.frequency_hz)
    assert np.array_equal(spaced.phase_rad, waves.phase_rad)


def read_comp_file_text(text: str) -> WaveComponents:
    import tempfile
    from pathlib import Path
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "w.Comp"
        path.write_text(text)
        return read_comp_file(path, direct_sum=True)


@pytest.mark.slow
def test_components_summed_directly_give_the_loads_of_the_same_sea_on_a_grid(tmp_path):
    """example.Comp summed directly against the same components moved onto the 500 s grid
    (by at most 5e-7 rad/s: a phase change of 1e-5 rad over 20 s) through the kinematics
    tables, on the r-test tapered cylinder at rest: loads within 2e-3 relative RMS (the tables'
    cubic interpolation); the time loop refuses the direct sum in one line."""
    platform_file = tmp_path / "taper.yaml"
    assert main(["platform", "import", str(TAPER_DECK), "-o", str(platform_file), "--water-depth", "100"]) == 0
    platform = load_platform(platform_file)
    direct = read_comp_file(EXAMPLE_COMP, direct_sum=True)
    harmonic = np.round(direct.frequency_hz * 500.0)
    gridded = dataclasses.replace(direct, frequency_hz=harmonic / 500.0, period_s=500.0)
    t = np.arange(0.0, 20.0, 0.25)
    rest = np.zeros((t.size, 6))
    loads = [PlatformModel(platform, waves, options=HYDRODYN).prescribed_motion_loads(t, rest, rest, rest).sum(axis=1)
             for waves in (direct, gridded)]
    error = np.sqrt(np.mean((loads[0] - loads[1]) ** 2, axis=0)) / np.sqrt(np.mean(loads[1] ** 2, axis=0))
    assert np.all(error[:5] < 2e-3), error  # Mz is zero on the axisymmetric column
    with pytest.raises(ConfigError, match="summed directly, for prescribed motion only"):
        PlatformModel(platform, direct, options=HYDRODYN).run(1.0)


def test_deck_of_the_newer_layout_imports_without_its_potential_flow_lines(tmp_path):
    """hd_MHstLMod1_compare's deck has FKMod and GeoFile after NAddDOF (a layout newer than
    openfast-io's, which reads it out of step): imported without them, its one tapered,
    tilted circular member as written (D 8 m at (-5, 3, -21), 6 m at (2, 6, 18), MDivSize 3,
    every coefficient 0)."""
    out = tmp_path / "compare.yaml"
    assert main(["platform", "import", str(RTEST / "hd_MHstLMod1_compare" / "hydrodyn_input.dat"), "-o", str(out),
                 "--water-depth", "200"]) == 0
    (member,) = yaml.safe_load(out.read_text())["members"]
    assert (member["end_a_m"], member["end_b_m"]) == ([-5.0, 3.0, -21.0], [2.0, 6.0, 18.0])
    assert (member["diameter_m"], member["diameter_b_m"], member["strip_length_m"]) == (8.0, 6.0, 3.0)
    assert member["zones"] == [{"name": "all", "cd": 0.0, "ca": 0.0, "cp": 0.0}]


def test_steady_prp_inputs_of_a_driver_are_a_motion_row(tmp_path):
    """PRPInputsMod 1 (the OC3 tripod's driver): uPRPInSteady, uDotPRPInSteady and
    uDotDotPRPInSteady, comma-separated, as the 18 values of a PRP motion row; a driver
    without one of them is refused naming it."""
    from fowt_hydro_sim.testing.rtest_suite import steady_prp_inputs

    driver = RTEST / "hd_OC3tripod_offshore_fixedbottom_wavesirr" / "hd_driver.inp"
    row = steady_prp_inputs(driver)
    assert row.tolist() == [0.1, 0.1, -0.1] + [0.0] * 15
    lacking = tmp_path / "hd_driver.inp"
    lacking.write_text("".join(line for line in driver.read_text().splitlines(keepends=True)
                               if "uDotDotPRPInSteady" not in line))
    with pytest.raises(ValueError, match="uDotDotPRPInSteady"):
        steady_prp_inputs(lacking)
