"""HydroDyn decks of the layouts before the current one (OpenFAST 3.x: the deck's own water
depth, one cross-section table, coefficient tables without Cb, members without MSecGeom /
MSpinOrient / MHstLMod) import through ``platform import``, or are refused in one line naming
the field; decks of the current layout are read unchanged (io/hydrodyn_layouts.py, r-test
decks in test/data/openfast_rtest with their commits in its README)."""
from __future__ import annotations

import pytest
import yaml

from fowt_hydro_sim.cli import main
from fowt_hydro_sim.io.hydrodyn import read_deck
from fowt_hydro_sim.io.hydrodyn_layouts import current_layout, is_older_layout
from fowt_hydro_sim.testing import REPO

RTEST = REPO / "test" / "data" / "openfast_rtest"
TRIPOD = RTEST / "hd_OC3tripod_offshore_fixedbottom_wavesirr" / "hd_primary.inp"
JACKET = RTEST / "hd_5MW_OC4Jckt_DLL_WTurb_WavesIrr_MGrowth" / "NRELOffshrBsline5MW_OC4Jacket_HydroDyn.dat"
COLUMN_OLDER = RTEST / "hd_WaveStMod3" / "hydrodyn_input_e4f825bd.dat"  # one cross-section table
OC4_SEMI = RTEST / "hd_5MW_OC4Semi_WSt_WavesWN" / "NRELOffshrBsline5MW_OC4DeepCwindSemi_HydroDyn.dat"
COLUMN_VERTICAL = RTEST / "hd_WaveStMod1" / "hydrodyn_input.dat"  # the same layout as COLUMN_OLDER
OLDER = (TRIPOD, JACKET, COLUMN_OLDER, COLUMN_VERTICAL, OC4_SEMI)
COLUMN = RTEST / "hd_WaveStMod3" / "hydrodyn_input.dat"  # the same column, r-test c00e123e


def _import(deck, out, capsys=None, depth: str = "45") -> tuple[int, str]:
    code = main(["platform", "import", str(deck), "-o", str(out), "--overwrite", "--water-depth", depth])
    return code, capsys.readouterr().err.strip() if capsys else ""


@pytest.mark.slow
def test_deck_with_one_cross_section_table_imports_as_its_newer_version(tmp_path):
    """hd_WaveStMod3's deck at r-test e4f825bd (NPropSets, no rectangular tables, members without
    MSecGeom) gives the platform its newer version (c00e123e) gives."""
    documents = []
    for deck in (COLUMN, COLUMN_OLDER):
        assert _import(deck, tmp_path / f"{deck.stem}.yaml")[0] == 0
        documents.append(yaml.safe_load((tmp_path / f"{deck.stem}.yaml").read_text()))
    for key in ("name", "description"):
        documents[1][key] = documents[0][key]
    assert documents[0] == documents[1]


@pytest.mark.slow
def test_deck_of_the_openfast3_layout_reads_field_by_field():
    """The OC3 tripod's deck (environment section, four axial columns, no Cb, eight member
    columns): every table read in step, with the values the older layout meant."""
    hd = read_deck(TRIPOD)
    assert hd["NMembers"] == 60 and hd["NJoints"] == 55 and hd["NPropSetsCyl"] == 8 and hd["NPropSetsRec"] == 0
    assert hd["CylPropD"] == [3.15, 3.15, 1.875, 2.475, 1.2, 3.14188, 3.4, 5.7]
    assert hd["MSecGeom"] == [1] * 60 and hd["MSpinOrient"] == [0.0] * 60 and hd["MHstLMod"] == [1] * 60
    assert hd["MPropSetID1"][45:47] == [6, 7] and hd["MPropSetID2"][45:47] == [7, 8]
    assert hd["MDivSize"] == [1.0] * 60 and hd["MCoefMod"] == [1] * 60 and hd["PropPot"] == [False] * 60
    assert (hd["CylSimplCd"], hd["CylSimplCa"], hd["CylSimplCp"], hd["CylSimplCb"]) == (1.0, 1.0, 1.0, 1.0)
    assert (hd["AxCd"], hd["AxFDMod"], hd["AxFDLoFSc"]) == ([1.0], [0.0], [1.0])
    assert hd["NFillGroups"] == 0 and hd["NMGDepths"] == 0 and hd["AMMod"] == 0


def test_decks_of_the_openfast3_layout_import_the_tripod_and_the_jacket_with_its_fill_group(tmp_path, capsys):
    """The tripod imports (57 circular members: its three piles below the seabed are left out);
    the OC4 jacket (in its driver's 320 m) reads in step and imports with its fill group (32 members, FillFSLoc 0,
    FillDens 1025), each filled member with its property sets' PropThck."""
    code, _ = _import(TRIPOD, tmp_path / "tripod.yaml", capsys)
    assert code == 0
    members = yaml.safe_load((tmp_path / "tripod.yaml").read_text())["members"]
    assert len(members) == 57 and {m["section"] for m in members} == {"circular"}
    assert members[46]["diameter_m"] == 3.4 and members[46]["diameter_b_m"] == 5.7
    code, err = _import(JACKET, tmp_path / "jacket.yaml", capsys, "320")  # its driver's WtrDpth
    assert code == 0, err
    document = yaml.safe_load((tmp_path / "jacket.yaml").read_text())
    (group,) = document["fill_groups"]
    assert len(group["members"]) == 32 and group["free_surface_z_m"] == 0.0 and group["density_kg_m3"] == 1025.0
    walls = {m["name"]: m.get("wall_thickness_m") for m in document["members"]}
    assert (walls["member1"], walls["member17"], walls["member105"], walls["member109"]) == (0.05, 0.035, 0.491, 0.06)
    assert walls["member19"] is None  # not filled


@pytest.mark.parametrize("edit, message", [
    (("\"default\"        MSL2SWL", "           2.5   MSL2SWL"), "field MSL2SWL 2.5: only 0 is supported"),
    (("\"default\"        WtrDpth", "            45   WtrDpth\n  2   WaveMod"), "field WaveMod: a HydroDyn deck with "
                                                                                 "its own waves section"),
    (("    1         1          4           1            1         1.0000      1        FALSE",
      "    1         1          4           1"), "a row of the NMembers table has 4 values, not 8"),
])
def test_older_layout_field_that_cannot_be_mapped_is_refused_in_one_line(tmp_path, capsys, edit, message):
    text = TRIPOD.read_text()
    assert edit[0] in text
    deck = tmp_path / "deck.inp"
    deck.write_text(text.replace(edit[0], edit[1], 1))
    code, err = _import(deck, tmp_path / "x.yaml", capsys)
    assert code == 2 and message in err and len(err.splitlines()) == 1, err


def test_decks_of_the_current_layout_are_not_rewritten():
    """Every deck of the suite in the current or v4 layout passes through unchanged, so they
    import exactly as before."""
    decks = [p for p in RTEST.glob("*/*") if p.suffix in (".dat", ".inp") and "HydroDyn Input" in p.read_text()[:200]]
    current = [p for p in decks if p not in OLDER]
    assert len(current) >= 8
    for deck in current:
        assert not is_older_layout(deck.read_text()), deck
        assert current_layout(deck.read_text(), str(deck)) == deck.read_text()
    assert all(is_older_layout(p.read_text()) for p in OLDER)


def test_older_layout_rows_with_trailing_comments_read_as_without(tmp_path):
    """Rows ending in a ``!`` comment (as the OC4 semi's member-based coefficients do) are
    widened by their values, not their words."""
    lines = TRIPOD.read_text().splitlines(keepends=True)
    rows = ("    1     1.00     1.00     1.00", "       1.00        0.00        1.00",
            "    1         1          4           1            1         1.0000      1        FALSE")
    commented = [line.rstrip("\r\n") + "   ! a comment\n" if line.startswith(rows) else line for line in lines]
    assert sum(a != b for a, b in zip(lines, commented)) == 3
    deck = tmp_path / "commented.inp"
    deck.write_text("".join(commented))
    plain, with_comments = read_deck(TRIPOD), read_deck(deck)
    for field in ("AxFDMod", "CylSimplCb", "CylSimplCbMG", "MSecGeom", "MHstLMod", "MDivSize", "MCoefMod", "PropPot"):
        assert with_comments[field] == plain[field], field
