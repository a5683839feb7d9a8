"""The mooring models: the choice (platform YAML, run), the paper's springs unchanged, MoorPy's
quasi-static catenary tabulated, MoorDyn's lumped-mass lines coupled, and their errors.

The lines are the VolturnUS-S mooring (the packaged OpenFAST MoorDyn file); the hull is
windmoor12's in 200 m of water (the lines on their own: fairlead kinematics in, forces out)."""
from __future__ import annotations

import contextlib
import dataclasses
import io
import shutil
from pathlib import Path

import numpy as np
import pytest
import yaml

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.config import (
    ConfigError,
    RunConfig,
    load_case,
    load_platform,
    platform_document,
    platform_from_dict,
)
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import synthesize

DATA = Path(__file__).parent / "data" / "mooring"
VOLTURNUS_LINES = (Path(__file__).parents[1] / "fowt_hydro_sim" / "physics" / "data" / "platforms" / "volturnus_s"
                   / "IEA-15-240-RWT-UMaineSemi_MoorDyn.dat")
DEPTH = 200.0
FAIRLEADS = np.array([[-58.0, 0.0, -14.0], [29.0, 50.229, -14.0], [29.0, -50.229, -14.0]])
ANCHORS = np.array([[-837.6, 0.0, -200.0], [418.8, 725.383, -200.0], [418.8, -725.383, -200.0]])


def with_lines(file: Path = VOLTURNUS_LINES, model: str = "spring"):
    """windmoor12 in 200 m of water with its springs and the lines of ``file``."""
    platform = load_platform("windmoor12")
    return dataclasses.replace(platform, environment=dataclasses.replace(platform.environment, water_depth_m=DEPTH),
                               mooring=dataclasses.replace(platform.mooring, model=model, file=str(file)))


def moorpy_tensions(offsets: np.ndarray) -> np.ndarray:
    """(n, lines, 2) fairlead and anchor tensions [N] that MoorPy's own System solves with the
    fairleads moved by ``offsets`` (n, 3)."""
    import moorpy
    with contextlib.redirect_stdout(io.StringIO()):
        system = moorpy.System(file=str(VOLTURNUS_LINES), depth=DEPTH)
        system.initialize()
    out = []
    for offset in offsets:
        rows = []
        for line in system.lineList:
            ends = [p for p in system.pointList if line.number in p.attached]
            for p in ends:
                if p.type == -1:
                    p.setPosition(FAIRLEADS[(p.number - 1) // 2] + offset)
            line.staticSolve()
            rows.append([line.TB, line.TA])  # end B the fairlead, end A the anchor (the file's order)
        out.append(rows)
    return np.array(out)


# ---------------------------------------------------------------------- the choice
def test_a_platform_yaml_chooses_its_mooring_and_names_the_file_relative_to_itself(tmp_path):
    shutil.copyfile(VOLTURNUS_LINES, tmp_path / "lines.dat")
    document = platform_document(load_platform("windmoor12"))
    document["mooring"] = {"model": "moorpy", "file": "lines.dat"}
    (tmp_path / "platform.yaml").write_text(yaml.safe_dump(document))
    platform = load_platform(tmp_path / "platform.yaml")
    assert platform.mooring.model == "moorpy"
    assert platform.mooring.file == str((tmp_path / "lines.dat").resolve())
    assert not platform.mooring.lines  # no springs: a run cannot choose them
    assert platform_from_dict(platform_document(platform)) == platform
    with pytest.raises(ConfigError, match="no spring lines"):
        platform.mooring.chosen("spring")
    assert platform.mooring.chosen("moordyn").model == "moordyn"
    assert platform.mooring.chosen("").model == "moorpy"


@pytest.mark.parametrize("mooring, message", [
    ({"model": "moordyn"}, "mooring.file: missing"),
    ({"model": "moorpy", "file": "nowhere.dat"}, "nowhere.dat: no such file"),
    ({"model": "catenary", "file": "lines.dat"}, "mooring.model: must be one of spring, linear, moorpy, moordyn"),
])
def test_a_mooring_section_that_cannot_work_is_refused_naming_the_field(tmp_path, mooring, message):
    shutil.copyfile(VOLTURNUS_LINES, tmp_path / "lines.dat")
    document = platform_document(load_platform("windmoor12"))
    document["mooring"] = mooring
    (tmp_path / "platform.yaml").write_text(yaml.safe_dump(document))
    with pytest.raises(ConfigError, match=message):
        load_platform(tmp_path / "platform.yaml")


def test_a_run_chooses_the_mooring_and_refuses_an_unknown_one():
    assert RunConfig().mooring == ""
    assert RunConfig(mooring="moordyn").mooring == "moordyn"
    with pytest.raises(ConfigError, match="run: mooring: must be one of spring, linear, moorpy, moordyn"):
        RunConfig(mooring="chain")
    with pytest.raises(ConfigError, match="mooring moorpy: the platform has no MoorDyn input file"):
        PlatformModel(load_platform("windmoor12"), mooring_model="moorpy")


@pytest.mark.slow
def test_the_paper_springs_move_the_platform_as_before_to_round_off():
    """The reference: windmoor12 in lc5.3 from an offset, written by the code before the
    mooring choice existed (test/data/mooring/PROVENANCE.md). Equal to 1e-12 of each record's
    largest value: another numpy or numba moves the last bits (the sway, roll and yaw that
    symmetry keeps at 1e-17, the surge at 4e-16 of its value); the default and the named
    spring mooring give the same run bit for bit."""
    reference = np.load(DATA / "windmoor12_spring_lc5.3_20s.npz")
    waves = synthesize(load_case("lc5.3").sea_state, 3600.0)
    runs = []
    for choice in ("", "spring"):
        model = PlatformModel(load_platform("windmoor12"), waves, mooring_model=choice)
        model.reset(motion=np.array([2.0, 0, 0, 0, 0.01, 0]))
        runs.append(model.run(20.0, 0.25))
    for key, value in (("motion", runs[0].motion), ("mooring", runs[0].load("mooring"))):
        np.testing.assert_allclose(value, reference[key], rtol=0, atol=1e-12 * np.abs(reference[key]).max())
    assert np.array_equal(runs[0].motion, runs[1].motion)
    assert np.array_equal(runs[0].load("mooring"), runs[1].load("mooring"))


# ---------------------------------------------------------------------- moorpy
@pytest.fixture(scope="module")
def moorpy_model() -> PlatformModel:
    return PlatformModel(with_lines(), None, mooring_model="moorpy")


@pytest.mark.reference
def test_the_tabulated_catenary_gives_moorpys_own_tensions(moorpy_model):
    """Fairlead and anchor tensions at 40 random platform offsets (surge and sway +-30 m, heave
    +-9 m) against MoorPy's System solving each line (Line.staticSolve) at that offset."""
    rng = np.random.default_rng(7)
    offsets = np.column_stack([rng.uniform(-30, 30, 40), rng.uniform(-30, 30, 40), rng.uniform(-9, 9, 40)])
    motion = np.column_stack([offsets, np.zeros((40, 3))])
    ours = moorpy_model.mooring_tensions(np.zeros(40), motion)
    theirs = moorpy_tensions(offsets)
    assert np.max(np.abs(ours - theirs) / theirs[..., :1]) < 2e-4


def test_the_tabulated_catenary_restores_the_platform_as_its_tensions_say(moorpy_model):
    """The kernel's mooring wrench at an offset: the fairlead forces the tensions' lines give
    (summed, with their moments about the reference point)."""
    motion = np.array([12.0, -5.0, 1.0, 0.02, -0.03, 0.05])
    moorpy_model.reset(motion=motion)
    wrench = moorpy_model.loads[moorpy_model_row()]
    from fowt_hydro_sim.frames import rotation_matrix
    from fowt_hydro_sim.physics.loads import FIRST_MODULE_ROW, ROW, params_of
    from fowt_hydro_sim.physics.mooring.catenary_tables import line_forces
    data = moorpy_model._data
    forces = line_forces(params_of("mooring", data.component_params),
                         data.component_tables[ROW["mooring"] - FIRST_MODULE_ROW], motion)[0]
    arms = FAIRLEADS @ rotation_matrix(*motion[3:6]).T
    expected = np.zeros(6)
    for arm, anchor, (h, v, _, _) in zip(arms, ANCHORS, forces):
        toward = anchor[:2] - (motion[:2] + arm[:2])
        force = np.array([*(h * toward / np.linalg.norm(toward)), -v])
        expected += np.concatenate([force, np.cross(arm, force)])
    assert np.allclose(wrench, expected, rtol=1e-12, atol=1e-6 * np.abs(expected).max())
    moorpy_model.reset()


def moorpy_model_row() -> int:
    from fowt_hydro_sim.physics.loads import ROW
    return ROW["mooring"]


def test_a_fairlead_leaving_its_table_stops_the_run_naming_the_line_and_time(moorpy_model):
    moorpy_model.reset(motion=np.array([80.0, 0, 0, 0, 0, 0]))
    with pytest.raises(InputError, match=r"IEA-15-240-RWT-UMaineSemi_MoorDyn.dat: line 1 left the moorpy model's "
                                         r"table .* at t = 0 s"):
        moorpy_model.run(1.0)
    moorpy_model.reset()


# ---------------------------------------------------------------------- MoorDyn
@pytest.fixture(scope="module")
def moordyn_model() -> PlatformModel:
    return PlatformModel(with_lines(), None, mooring_model="moordyn")


@pytest.mark.reference
def test_moordyn_starts_from_the_lines_static_equilibrium(moordyn_model):
    """At rest MoorDyn's initial equilibrium (its dynamic relaxation) gives MoorPy's static
    fairlead tensions within 0.2 %, and its anchor tensions within 1 %."""
    moordyn_model.reset()
    ours = moordyn_model.mooring_tensions(np.zeros(1), np.zeros((1, 6)))[0]
    theirs = moorpy_tensions(np.zeros((1, 3)))[0]
    assert np.max(np.abs(ours[:, 0] - theirs[:, 0]) / theirs[:, 0]) < 2e-3
    assert np.max(np.abs(ours[:, 1] - theirs[:, 1]) / theirs[:, 1]) < 1e-2


def truncated_line_type(folder: Path) -> Path:
    """The VolturnUS-S file with its line type's last column left out (row 7)."""
    text = VOLTURNUS_LINES.read_text().splitlines()
    assert text[6].startswith("main")
    text[6] = text[6].rsplit(maxsplit=1)[0]
    (folder / "short_type.dat").write_text("\n".join(text) + "\n")
    return folder / "short_type.dat"


def test_a_file_moordyn_refuses_stops_with_one_line_naming_the_file_and_line(tmp_path):
    with pytest.raises(InputError, match=r"short_type.dat: MoorDyn cannot read it \(Error in short_type.dat at line "
                                         r"7: 10 fields minimum are required, but just 9 are provided\)$") as caught:
        PlatformModel(with_lines(truncated_line_type(tmp_path)), None, mooring_model="moordyn")
    (tmp_path / "notes.dat").write_text("not a mooring\n")  # MoorDyn reads it as a file without lines
    with pytest.raises(InputError, match="notes.dat: MoorDyn couples 0 degrees of freedom; the moordyn model needs "
                                         "the fairleads as coupled") as caught:
        PlatformModel(with_lines(tmp_path / "notes.dat"), None, mooring_model="moordyn")
    assert "\n" not in str(caught.value)


def test_a_file_moorpy_refuses_stops_with_one_line_naming_the_file(tmp_path):
    (tmp_path / "no_lines.dat").write_text(VOLTURNUS_LINES.read_text().replace("1     main       2         1",
                                                                              "1     main       2         x"))
    with pytest.raises(InputError, match=r"no_lines.dat: MoorPy cannot read it") as caught:
        PlatformModel(with_lines(tmp_path / "no_lines.dat"), None, mooring_model="moorpy")
    assert "\n" not in str(caught.value)


@pytest.mark.parametrize("model", ["moorpy", "moordyn"])
def test_a_moordyn_v1_file_gives_the_lines_of_its_v2_twin(model):
    """The VolturnUS-S lines written in MoorDyn v1's layout (test/data/mooring) read as the
    packaged v2 file: the same tensions at rest, to the last digit MoorDyn prints."""
    v1 = PlatformModel(with_lines(DATA / "volturnus_s_moordyn_v1.dat"), None, mooring_model=model)
    v2 = PlatformModel(with_lines(), None, mooring_model=model)
    rest = (np.zeros(1), np.zeros((1, 6)))
    assert np.allclose(v1.mooring_tensions(*rest), v2.mooring_tensions(*rest), rtol=1e-9)



def test_moordyn_reads_the_file_without_its_output_channels(tmp_path):
    """The copy MoorDyn steps holds every section of the file but the OUTPUTS channels (their
    header and END kept): MoorDyn writes no channel file at its steps, and the sections after
    OUTPUTS are kept."""
    from fowt_hydro_sim.physics.mooring.moordyn_file import without_outputs
    copy = tmp_path / "lines.dat"
    shutil.copyfile(VOLTURNUS_LINES, copy)
    text = without_outputs(copy).read_text().splitlines()
    original = VOLTURNUS_LINES.read_text().splitlines()
    outputs = next(i for i, line in enumerate(text) if "OUTPUTS" in line)
    assert text[:outputs + 1] == original[:outputs + 1]
    assert text[outputs + 1].strip() == "END" and "need this line" in text[outputs + 2]
    assert not any(line.strip() in ("FairTen1", "Con1fx", "fx") for line in text)

# ---------------------------------------------------------------------- references
@pytest.mark.slow
@pytest.mark.reference
def test_moordyn_static_lines_give_moorpys_tensions_and_restoring_force_over_surge_offsets():
    """MoorDyn's static solution (its initial equilibrium, dynamic relaxation) of the VolturnUS-S
    lines at surge offsets -30 .. 30 m against MoorPy's on the same file: each line's fairlead
    tension and the platform's surge restoring force within 1 %."""
    from fowt_hydro_sim.physics.mooring.moordyn_lines import MoorDynLines
    offsets = np.arange(-30.0, 31.0, 10.0)
    lines = MoorDynLines(VOLTURNUS_LINES)
    try:
        ours, force = [], []
        for x in offsets:
            y = np.zeros(12)
            y[0] = x
            lines.reset(0.0, y)
            ours.append(lines.tensions[-1][:, 0])
            force.append(lines.wrench(0.0, y, False)[0])
    finally:
        lines.close()
    theirs = moorpy_tensions(np.column_stack([offsets, np.zeros((offsets.size, 2))]))
    assert np.max(np.abs(np.array(ours) - theirs[..., 0]) / theirs[..., 0]) < 0.01
    moorpy_force = PlatformModel(with_lines(), None, mooring_model="moorpy")
    surge = []
    for x in offsets:
        moorpy_force.reset(motion=np.array([x, 0, 0, 0, 0, 0]))
        surge.append(moorpy_force.loads[moorpy_model_row(), 0])
    assert np.max(np.abs(np.array(force) - surge) / np.abs(surge).max()) < 0.01


@pytest.mark.reference
def test_the_lines_hold_the_rotor_thrust_of_openfasts_operating_points(moorpy_model):
    """OpenFAST's linearisation operating points of VolturnUS-S (MAP++ lines, 5 to 24 m/s): at
    each mean platform position the lines' surge force holds the rotor's mean aerodynamic force
    (AD RtAeroFxh along the shaft, tilted 6 deg: its horizontal part) and the tower's drag, which
    the files do not give: the lines' force is at least the rotor's (2 % allowed for the MAP
    deck's anchors 0.2 m further out and its seabed friction), and what it holds beyond it is at
    most the drag of a cylinder (Cd 1.2) of the tower's frontal area (129.4 m tall, 10 m to
    6.5 m across: 1068 m^2) in the wind speed of the point."""
    table = np.genfromtxt(DATA / "volturnus_s_lin_operating_points.csv", delimiter=",", names=True, skip_header=1,
                          dtype=None, encoding=None)
    motion = np.column_stack([table["surge_m"], table["sway_m"], table["heave_m"],
                              *np.radians([table["roll_deg"], table["pitch_deg"], table["yaw_deg"]])])
    surge_force = []
    for row in motion:
        moorpy_model.reset(motion=row)
        surge_force.append(-moorpy_model.loads[moorpy_model_row(), 0])
    moorpy_model.reset()
    rotor = table["rt_aero_fxh_n"] * np.cos(np.radians(6.0))
    tower_drag_bound = 0.5 * 1.225 * 1.2 * 1068.0 * table["wind_m_s"] ** 2
    assert np.all(np.array(surge_force) >= 0.98 * rotor)
    assert np.all(np.array(surge_force) - rotor <= tower_drag_bound)


@pytest.mark.slow
def test_moordyn_coupled_once_per_step_moves_the_platform_as_a_smaller_step_does():
    """The coupling (MoorDyn advanced once per step, its forces extrapolated for the predictor
    and the Runge-Kutta stages) against half the step: a free surge decay from 10 m in still
    water, 20 s, the two surges within 1 cm (1e-3 of the offset)."""
    surges = []
    for dt in (0.05, 0.025):
        model = PlatformModel(with_lines(), None, dt_s=dt, mooring_model="moordyn")
        model.reset(motion=np.array([10.0, 0, 0, 0, 0, 0]))
        surges.append(model.run(20.0, 0.05).motion[:, 0])
        model.mooring_lines.close()
    assert surges[0][-1] < 9.0  # it moved
    assert np.max(np.abs(surges[0] - surges[1])) < 0.01


@pytest.mark.slow
def test_moordyns_time_step_from_the_platform_moves_the_platform_as_the_files_does(tmp_path):
    """``mooring.moordyn_dt_s`` replaces the file's dtM (0.001 s) in MoorDyn's copy: at 0.004 s
    (four times fewer of MoorDyn's steps, the speed the benchmark shows) a free surge decay from
    10 m over 20 s stays within 1 cm of the file's time step, as a halved model step does."""
    surges = []
    for dt_s in (None, 0.004):
        platform = with_lines()
        platform = dataclasses.replace(platform, mooring=dataclasses.replace(platform.mooring, moordyn_dt_s=dt_s))
        model = PlatformModel(platform, None, dt_s=0.05, mooring_model="moordyn")
        copy = next(model.mooring_lines._folder.glob("*.dat"), None)
        if dt_s is not None:
            assert copy is not None and any(line.split()[:2] == ["0.004", "dtM"]
                                            for line in copy.read_text().splitlines())
        model.reset(motion=np.array([10.0, 0, 0, 0, 0, 0]))
        surges.append(model.run(20.0, 0.05).motion[:, 0])
        model.mooring_lines.close()
    assert surges[0][-1] < 9.0  # it moved
    assert np.max(np.abs(surges[0] - surges[1])) < 0.01
    document = platform_document(dataclasses.replace(with_lines(), mooring=dataclasses.replace(
        with_lines().mooring, moordyn_dt_s=0.004)))
    assert document["mooring"]["moordyn_dt_s"] == 0.004
    with pytest.raises(ConfigError, match="moordyn_dt_s: must be a positive number"):
        platform_from_dict({**document, "mooring": {**document["mooring"], "moordyn_dt_s": 0}})


def test_moordyn_keeps_the_tensions_of_the_latest_advance_only(moordyn_model):
    """A node runs for days: MoorDyn's tensions are kept for the latest run or step (from its
    start), not for all of the past."""
    moordyn_model.reset(motion=np.array([5.0, 0, 0, 0, 0, 0]))
    first = moordyn_model.run(0.5)
    second = moordyn_model.run(0.5)
    assert moordyn_model.mooring_lines.times[0] == pytest.approx(0.5)
    assert len(moordyn_model.mooring_lines.times) == 11
    tensions = moordyn_model.mooring_tensions(second.time_s, second.motion)
    assert np.all(np.isfinite(tensions)) and np.all(np.isnan(moordyn_model.mooring_tensions(first.time_s[:-1],
                                                                                            first.motion[:-1])))
    moordyn_model.reset()
