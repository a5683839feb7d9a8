"""VolturnUS-S's lines in the project's mooring models (the packaged MoorDyn deck) against the
OpenFAST model's other deck of the same lines, its MAP++ deck (``test/data/volturnus_s``), read
into MoorPy by ``physics/mooring/map_file.py``: pretension, stiffness and the surge restoring
force."""
from __future__ import annotations

import logging
from pathlib import Path

import numpy as np
import pytest

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.config import load_platform
from fowt_hydro_sim.physics.loads import ROW
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.mooring.map_file import moorpy_system, read_map_deck

LOG = logging.getLogger(__name__)
MAP_DECK = Path(__file__).parent / "data" / "volturnus_s" / "IEA-15-240-RWT-UMaineSemi_MAP.dat"
VOLTURNUS_LINES = (Path(__file__).parents[1] / "fowt_hydro_sim" / "physics" / "data" / "platforms" / "volturnus_s"
                   / "IEA-15-240-RWT-UMaineSemi_MoorDyn.dat")
DEPTH = 200.0  # [m] the OpenFAST model's water depth (its SeaState deck), the MAP deck's "depth"
SURGE = np.arange(-20.0, 21.0, 5.0)  # [m] the offset sweep
STEPS = {0: 0.5, 2: 0.5, 4: 0.005}  # central-difference steps: surge, heave [m], pitch [rad]
# Tolerances, fixed from what differs between the two decks before they were compared (the
# figures below are the estimates made then). Both
# decks give the same chain (d 0.333 m, 685 kg/m, EA 3.27e9 N, 850 m, fairleads at 58 m radius,
# 14 m deep). The MAP deck's anchors are 0.2 m further out (837.8 m against 837.6 m) and its
# seabed friction CB 1.0 (none in the MoorDyn deck as MoorPy and MoorDyn read it) shortens the
# stretch of the grounded chain: with H ~ 1.9 MN and the chain's weight in water 5.84 kN/m,
# tension falls to zero 325 m from the touchdown point instead of staying H over ~456 m of
# seabed, 0.17 m less stretch. Together ~0.37 m tauter; at a line's horizontal stiffness of
# ~48 kN/m (the packaged surge stiffness, 71.9 kN/m, over three lines at cos^2) that is ~18 kN,
# ~1 % of H: pretension within 1.5 %. A catenary's stiffness grows faster than its tension
# (roughly H^1.5-2), so ~2-3 % on the stiffnesses and the swept restoring force: within 5 %.
PRETENSION_TOL = 0.015
STIFFNESS_TOL = 0.05
SWEEP_TOL = 0.05


def moorpy_wrench(system, motion: np.ndarray) -> np.ndarray:
    """The lines' wrench [N, N m] on the body of ``system`` held at ``motion``."""
    system.bodyList[0].setPosition(np.asarray(motion, dtype=float))
    system.solveEquilibrium()
    return system.bodyList[0].getForces(lines_only=True)


def stiffness(wrench) -> dict[int, float]:
    """Surge, heave and pitch stiffness (-dF/dx, central differences at ``STEPS``) of ``wrench``."""
    out = {}
    for dof, step in STEPS.items():
        ahead, behind = np.zeros(6), np.zeros(6)
        ahead[dof], behind[dof] = step, -step
        out[dof] = -(wrench(ahead)[dof] - wrench(behind)[dof]) / (2 * step)
    return out


@pytest.fixture(scope="module")
def map_figures() -> dict:
    """The MAP deck's lines in MoorPy: fairlead pretensions, stiffness, surge restoring force."""
    system = moorpy_system(read_map_deck(MAP_DECK, DEPTH), DEPTH)
    moorpy_wrench(system, np.zeros(6))
    pretension = np.array([line.TB for line in system.lineList])
    stiff = stiffness(lambda motion: moorpy_wrench(system, motion))
    surge = np.array([-moorpy_wrench(system, np.array([x, 0, 0, 0, 0, 0]))[0] for x in SURGE])
    LOG.info("MAP deck (MoorPy): pretension %s N, stiffness %s, surge force %s N", pretension, stiff, surge)
    return {"pretension": pretension, "stiffness": stiff, "surge": surge}


def test_the_map_deck_reads_three_lines_turned_by_its_repeat_angles():
    lines = read_map_deck(MAP_DECK, DEPTH)
    assert len(lines) == 3
    assert np.allclose([line.fairlead_m for line in lines],
                       [[-58.0, 0.0, -14.0], [29.0, -50.229, -14.0], [29.0, 50.229, -14.0]], atol=1e-3)
    assert all(line.anchor_m[2] == -DEPTH and line.length_m == 850.0 and line.line_type.cb == 1.0
               for line in lines)


@pytest.mark.parametrize("edit, message", [
    (lambda text: text.replace("2   Vessel", "2   Connect"), "node 2 is of type Connect; only fix and vessel"),
    (lambda text: text.replace("LINE PROPERTIES", "LINE THINGS"),
     "not a MAP\\+\\+ deck \\(no LINE PROPERTIES section\\)"),
    (lambda text: text.replace("850.00", "long"), "MAP\\+\\+ deck not readable \\(ValueError"),
])
def test_a_map_deck_that_cannot_be_read_is_refused_in_one_line_naming_the_file(tmp_path, edit, message):
    deck = tmp_path / "edited_MAP.dat"
    deck.write_text(edit(MAP_DECK.read_text()))
    with pytest.raises(InputError, match=f"^edited_MAP.dat: {message}"):
        read_map_deck(deck, DEPTH)


@pytest.mark.reference
def test_the_moorpy_model_gives_the_map_decks_pretension_stiffness_and_surge_restoring_force(map_figures):
    """The project's ``moorpy`` model (its tabulated catenaries) of ``volturnus_s`` on the
    packaged MoorDyn deck against MoorPy on the MAP++ deck: each fairlead's pretension at rest
    within 1.5 %, the surge, heave and pitch stiffness within 5 %, the surge restoring force
    at offsets -20 .. 20 m within 5 % of the MAP deck's at each (tolerances from the decks'
    differences: anchors 0.2 m further out and seabed friction CB 1.0 in the MAP deck, see the
    module's constants)."""
    model = PlatformModel(load_platform("volturnus_s"), None, mooring_model="moorpy")

    def wrench(motion: np.ndarray) -> np.ndarray:
        model.reset(motion=motion)
        return np.array(model.loads[ROW["mooring"]], dtype=float)

    pretension = model.mooring_tensions(np.zeros(1), np.zeros((1, 6)))[0][:, 0]
    stiff = stiffness(wrench)
    surge = np.array([-wrench(np.array([x, 0, 0, 0, 0, 0]))[0] for x in SURGE])
    model.reset()
    LOG.info("moorpy model: pretension %s N, stiffness %s, surge force %s N", pretension, stiff, surge)
    theirs = map_figures
    assert np.max(np.abs(pretension - theirs["pretension"].mean()) / theirs["pretension"].mean()) < PRETENSION_TOL
    for dof in STEPS:
        assert abs(stiff[dof] - theirs["stiffness"][dof]) / abs(theirs["stiffness"][dof]) < STIFFNESS_TOL, dof
    nonzero = SURGE != 0
    assert np.max(np.abs(surge - theirs["surge"])[nonzero] / np.abs(theirs["surge"][nonzero])) < SWEEP_TOL


def friction_wrench(motion: np.ndarray, cb: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """The MAP deck's lines with their seabed friction (CB, or ``cb`` if given), as MAP++ solves
    them, with the platform at ``motion``: MoorPy's catenary called directly for each line
    (MoorPy 1.2.1's System drops CB). The lines' wrench [N, N m] about the reference point and
    the fairlead tensions [N]."""
    from moorpy.Catenary import catenary

    from fowt_hydro_sim.frames import rotation_matrix
    wrench, tensions = np.zeros(6), []
    for line in read_map_deck(MAP_DECK, DEPTH):
        kind = line.line_type
        weight = (kind.mass_kg_m - 1025.0 * np.pi / 4 * kind.diameter_m**2) * 9.80665
        arm = rotation_matrix(*motion[3:6]) @ np.array(line.fairlead_m)
        span = np.array(line.anchor_m) - (motion[:3] + arm)
        across = np.hypot(span[0], span[1])
        _, _, horizontal, vertical, _ = catenary(across, -span[2], line.length_m, kind.ea_n, weight,
                                                 CB=kind.cb if cb is None else cb,
                                                 Tol=1e-8)
        # catenary's end-B forces in the line's plane, x from the anchor to the fairlead
        force = np.array([*(-horizontal * span[:2] / across), vertical])
        wrench += np.concatenate([force, np.cross(arm, force)])
        tensions.append(np.hypot(horizontal, vertical))
    return wrench, np.array(tensions)


def test_the_lines_solved_one_by_one_without_friction_give_moorpys_system(map_figures):
    """``friction_wrench`` with CB 0 against MoorPy's System on the same deck (which drops CB):
    the same pretension, stiffness and surge force within 0.05 %, so its directions and signs
    are MoorPy's."""
    assert np.allclose(friction_wrench(np.zeros(6), cb=0.0)[1], map_figures["pretension"], rtol=5e-4)
    stiff = stiffness(lambda motion: friction_wrench(motion, cb=0.0)[0])
    assert all(abs(stiff[dof] / map_figures["stiffness"][dof] - 1) < 5e-4 for dof in STEPS)
    surge = np.array([-friction_wrench(np.array([x, 0, 0, 0, 0, 0]), cb=0.0)[0][0] for x in SURGE])
    assert np.allclose(surge, map_figures["surge"], rtol=5e-4, atol=1.0)


@pytest.mark.reference
def test_the_moorpy_model_gives_the_map_decks_figures_with_its_seabed_friction():
    """MoorPy 1.2.1's System drops the MAP deck's seabed friction (CB 1.0); its catenary solves
    it when called directly (``friction_wrench``), as MAP++ does. Against that, the project's
    moorpy model: pretension within 1.5 %, surge, heave and pitch stiffness and the surge
    restoring force at -20 .. 20 m within 5 % (the same tolerances)."""
    model = PlatformModel(load_platform("volturnus_s"), None, mooring_model="moorpy")

    def wrench(motion: np.ndarray) -> np.ndarray:
        model.reset(motion=motion)
        return np.array(model.loads[ROW["mooring"]], dtype=float)

    pretension = model.mooring_tensions(np.zeros(1), np.zeros((1, 6)))[0][:, 0]
    stiff = stiffness(wrench)
    surge = np.array([-wrench(np.array([x, 0, 0, 0, 0, 0]))[0] for x in SURGE])
    model.reset()
    theirs_pretension = friction_wrench(np.zeros(6))[1]
    theirs_stiff = stiffness(lambda motion: friction_wrench(motion)[0])
    theirs_surge = np.array([-friction_wrench(np.array([x, 0, 0, 0, 0, 0]))[0][0] for x in SURGE])
    LOG.info("MAP deck with CB (catenary): pretension %s N, stiffness %s, surge force %s N",
             theirs_pretension, theirs_stiff, theirs_surge)
    assert np.max(np.abs(pretension - theirs_pretension.mean()) / theirs_pretension.mean()) < PRETENSION_TOL
    for dof in STEPS:
        assert abs(stiff[dof] - theirs_stiff[dof]) / abs(theirs_stiff[dof]) < STIFFNESS_TOL, dof
    nonzero = SURGE != 0
    assert np.max(np.abs(surge - theirs_surge)[nonzero] / np.abs(theirs_surge[nonzero])) < SWEEP_TOL


@pytest.mark.slow
@pytest.mark.reference
def test_moordyns_static_equilibrium_gives_the_map_decks_pretension(map_figures):
    """MoorDyn's static equilibrium (its dynamic relaxation) of the packaged deck at rest: each
    fairlead's tension within 1.5 % of the MAP deck's pretension in MoorPy (the same tolerance
    as the moorpy model's, from the decks' differences)."""
    from fowt_hydro_sim.physics.mooring.moordyn_lines import MoorDynLines
    lines = MoorDynLines(VOLTURNUS_LINES)
    try:
        lines.reset(0.0, np.zeros(12))
        pretension = lines.tensions[-1][:, 0]
    finally:
        lines.close()
    LOG.info("moordyn: pretension %s N", pretension)
    mean = map_figures["pretension"].mean()
    assert np.max(np.abs(pretension - mean) / mean) < PRETENSION_TOL
