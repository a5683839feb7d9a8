"""SeaState input files as wave components (``physics/waves/seastate.py``): the sea SeaState
synthesises (RANLUX phases, JONSWAP amplitudes, its frequency grid) against the elevation
HydroDyn printed for it (Wave1Elev of two r-test baselines), and the fields it cannot
reproduce refused in one line naming them."""
from __future__ import annotations

import numpy as np
import pytest

from fowt_hydro_sim.physics.waves import seastate
from fowt_hydro_sim.physics.waves.components import read_comp_file
from fowt_hydro_sim.testing import REPO
from fowt_hydro_sim.testing.references import read_hydrodyn_out

pytestmark = pytest.mark.reference
RTEST = REPO / "test" / "data" / "openfast_rtest"
DEPTH, G = 200.0, 9.80665


def test_jonswap_sea_is_hydrodyns_to_single_precision():
    """hd_MCF_WaveStMod1: WaveMod 2, Hs 7 m, Tp 12 s, seeds 123456789 / RANLUX, 3600 s at
    0.05 s: 720 components inside the cut-offs, their elevation at (0, 0) HydroDyn's
    Wave1Elev within 5e-6 m (SeaState works in single precision; the baseline prints 7
    digits)."""
    case = RTEST / "hd_MCF_WaveStMod1"
    waves = seastate.seastate_waves(seastate.read_seastate(case / "MCF_SeaState.dat"))
    assert waves.period_s == 3600.0 and waves.frequency_hz.size == 720
    reference = read_hydrodyn_out(case / "driver_excerpt.out")
    eta = waves.elevation(0.0, 0.0, reference["Time"], DEPTH, G)
    assert np.max(np.abs(eta - reference["Wave1Elev"])) < 5e-6


def test_regular_wave_gets_the_phase_fitted_to_hydrodyns_elevation():
    """hd_MHstLMod2_RectMmbr: WaveMod 1 draws its phase from the same stream; it is the one
    fitted by least squares to the baseline's Wave1Elev (regular_wave.Comp) within 1e-4 deg."""
    case = RTEST / "hd_MHstLMod2_RectMmbr"
    waves = seastate.seastate_waves(seastate.read_seastate(case / "SeaState.dat"))
    fitted = read_comp_file(case / "regular_wave.Comp")
    assert waves.frequency_hz == pytest.approx(fitted.frequency_hz, rel=1e-9)
    assert waves.amplitude_m == pytest.approx([5.0])
    assert np.rad2deg(waves.phase_rad[0]) == pytest.approx(np.rad2deg(fitted.phase_rad[0]), abs=1e-4)
    assert np.rad2deg(waves.direction_rad[0]) == pytest.approx(15.0)


def test_regular_wave_of_given_phase_needs_no_random_seed(tmp_path):
    """WaveMod 1P# draws nothing: with an integer WaveSeed(2) (the compiler's generator) it is
    the regular wave of that phase, as with RANLUX; WaveMod 1 with it is refused."""
    text = (RTEST / "hd_MHstLMod2_RectMmbr" / "SeaState.dat").read_text()
    given = text.replace("             1   WaveMod", "\"1P79.244\"   WaveMod", 1)
    assert given != text
    waves = []
    for seed in ("RANLUX", "1011121314"):
        path = tmp_path / f"{seed}.dat"
        path.write_text(given.replace("RANLUX   WaveSeed(2)", f"{seed}   WaveSeed(2)", 1))
        waves.append(seastate.seastate_waves(seastate.read_seastate(path)))
    assert "1011121314   WaveSeed(2)" in path.read_text()
    assert np.rad2deg(waves[1].phase_rad) == pytest.approx([79.244], abs=1e-9)
    for name in ("frequency_hz", "amplitude_m", "phase_rad", "direction_rad"):
        assert getattr(waves[1], name) == pytest.approx(getattr(waves[0], name), abs=0)
    path.write_text(text.replace("RANLUX   WaveSeed(2)", "1011121314   WaveSeed(2)", 1))
    with pytest.raises(seastate.ConfigError, match="WaveSeed"):
        seastate.seastate_waves(seastate.read_seastate(path))


@pytest.mark.parametrize("edit, field", [
    (("RANLUX   WaveSeed(2)", "  1011   WaveSeed(2)"), "WaveSeed(2)"),
    (("2   WaveMod", "5   WaveMod"), "WaveMod 5"),
    (("1   WaveNDir", "3   WaveNDir"), None),  # WaveDirMod 0: the count is unused
    (("0   WaveDirMod", "1   WaveDirMod"), None),  # one direction
    (("0   ConstWaveMod", "1   ConstWaveMod"), "ConstWaveMod"),
    (("0   CurrMod", "1   CurrMod"), "CurrMod"),
    (("3600   WaveTMax", "  -1   WaveTMax"), "WaveTMax"),
])
def test_what_is_not_reproduced_is_refused_in_one_line_naming_the_field(tmp_path, capsys, edit, field):
    text = (RTEST / "hd_MCF_WaveStMod1" / "MCF_SeaState.dat").read_text()
    assert edit[0] in text
    path = tmp_path / "SeaState.dat"
    path.write_text(text.replace(edit[0], edit[1], 1))
    code = seastate.main([str(path), "-o", str(tmp_path / "waves.Comp")])
    err = capsys.readouterr().err.strip()
    if field is None:
        assert code == 0 and not err
        return
    assert code == 2 and field in err and len(err.splitlines()) == 1 and "Traceback" not in err


def test_spread_directions_are_refused(tmp_path):
    text = (RTEST / "hd_MCF_WaveStMod1" / "MCF_SeaState.dat").read_text()
    path = tmp_path / "SeaState.dat"
    path.write_text(text.replace("0   WaveDirMod", "1   WaveDirMod", 1).replace("1   WaveNDir", "3   WaveNDir", 1))
    with pytest.raises(seastate.ConfigError, match="WaveDirMod 1 with WaveNDir 3"):
        seastate.seastate_waves(seastate.read_seastate(path))


def test_written_components_read_back_on_their_grid(tmp_path):
    """The .Comp file the module writes is read back on SeaState's frequency grid (period
    3600 s), the same sea to print precision."""
    case = RTEST / "hd_MCF_WaveStMod1"
    out = tmp_path / "waves.Comp"
    assert seastate.main([str(case / "MCF_SeaState.dat"), "-o", str(out)]) == 0
    again = read_comp_file(out)
    waves = seastate.seastate_waves(seastate.read_seastate(case / "MCF_SeaState.dat"))
    assert again.period_s == pytest.approx(3600.0)
    t = np.linspace(0.0, 30.0, 7)
    assert np.allclose(again.elevation(0, 0, t, DEPTH, G), waves.elevation(0, 0, t, DEPTH, G), atol=1e-8)


@pytest.mark.parametrize("n, expected", [(36000, 36000), (37, 38), (29, 30), (31, 32), (47, 48)])
def test_grid_length_is_the_next_product_of_small_primes(n, expected):
    assert seastate.product_of_small_primes(n) == expected
