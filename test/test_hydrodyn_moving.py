"""The moving platform's hydrodynamics against OpenFAST HydroDyn (prescribed motion in still
water, constant offsets) and against closed forms (nonlinear hydrostatics), through the
``fowt-sim loads`` command and the model's HydroDyn-equivalent options."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import yaml

from fowt_hydro_sim.cli import main
from fowt_hydro_sim.physics.config import EARLIER, HYDRODYN, HydroOptions, load_platform, platform_document
from fowt_hydro_sim.physics.loads import ROW
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.platform_edits import uniform_drag
from fowt_hydro_sim.studies.prescribed_motion import CHANNELS, hydro_channels, motion_from_columns
from fowt_hydro_sim.testing.references import PRESCRIBED_STILL_CASE as CASE
from fowt_hydro_sim.testing.references import hydrodyn_case, hydrodyn_hull, read_hydrodyn_out, reference_motion

pytestmark = pytest.mark.reference  # against another code's output

RHO_G = 1025.0 * 9.80665


def relative_rms(ours: np.ndarray, reference: np.ndarray) -> float:
    return float(np.sqrt(np.mean((ours - reference) ** 2)) / reference.std())


def test_prescribed_motion_in_still_water_matches_hydrodyn(tmp_path):
    """The full hull along the reference's 6-DOF motion, through ``fowt-sim loads --hydrodyn``:
    every channel within 0.5 % relative RMS (Fy, Mz within 2 %); the angle-rate conversion
    equals the driver's."""
    ref = read_hydrodyn_out(hydrodyn_case(CASE) / "wm12_prescribed_still.out")
    columns = reference_motion()
    assert np.allclose(columns[:, 0], ref["Time"])
    motion = motion_from_columns(columns)
    for k, axis in enumerate("xyz"):
        assert np.allclose(motion.velocity[:, 3 + k], ref[f"PRPRV{axis}i"], rtol=0, atol=1e-8)
        assert np.allclose(motion.acceleration[:, 3 + k], ref[f"PRPRA{axis}i"], rtol=0, atol=1e-8)
    motion_file, platform_file, out = tmp_path / "prp.dat", tmp_path / "hull.yaml", tmp_path / "loads.csv"
    np.savetxt(motion_file, columns, fmt="%.6f" + " %.12e" * 18)
    platform_file.write_text(yaml.safe_dump(platform_document(hydrodyn_hull()), sort_keys=False))
    assert main(["loads", "--platform", str(platform_file), "--motion", str(motion_file), "--still-water",
                 "--hydrodyn", "-o", str(out)]) == 0
    table = np.genfromtxt(out, delimiter=",", names=True)
    errors = {c: relative_rms(table[c], ref[c]) for c in CHANNELS}
    print("relative RMS against HydroDyn:", errors)  # measured 1e-5 .. 3e-5
    assert all(errors[c] < 5e-3 for c in ("HydroFxi", "HydroFzi", "HydroMxi", "HydroMyi"))
    assert errors["HydroFyi"] < 2e-2 and errors["HydroMzi"] < 2e-2
    assert np.allclose(table["Time"], ref["Time"])
    # the channels are the sum of the hydrodynamic and hydrostatic component columns
    parts = sum(table[f"{name}_Fx"] for name in ("drag", "inertia", "added_mass", "hydrostatic"))
    assert np.allclose(parts, table["HydroFxi"], rtol=1e-8, atol=1e-3)


def test_the_earlier_choices_differ_from_hydrodyn_as_measured_before():
    """The model's earlier choices (displaced wetted length, rotating directions, linear
    hydrostatics) stay reachable and reproduce their measured still-water errors."""
    ref = read_hydrodyn_out(hydrodyn_case(CASE) / "wm12_prescribed_still.out")
    m = motion_from_columns(reference_motion())
    loads = PlatformModel(hydrodyn_hull(), options=EARLIER).prescribed_motion_loads(*m)
    errors = [relative_rms(hydro_channels(loads)[:, j], ref[c]) for j, c in enumerate(CHANNELS)]
    assert errors == pytest.approx([2.6e-2, 0.30, 2.2e-2, 3.0e-2, 1.1e-2, 0.35], rel=0.1)


@pytest.mark.parametrize("name, offset", [("surge10m", (10.0, 0, 0, 0, 0, 0)), ("heave0.5m", (0, 0, 0.5, 0, 0, 0)),
                                          ("pitch0.04", (0, 0, 0, 0, 0.04, 0)), ("roll0.04", (0, 0, 0, 0.04, 0, 0))])
def test_constant_offsets_match_hydrodyn(name, offset):
    """Constant offsets (moments about the displaced reference point, nonlinear hydrostatics):
    within 0.1 % of HydroDyn's loads (of the tilt moment for the moments, of the buoyancy for
    the forces)."""
    ref = read_hydrodyn_out(hydrodyn_case(CASE) / "static_offsets" / f"{name}.out")
    expected = np.array([ref[c][0] for c in CHANNELS])
    pose = np.array(offset, dtype=float)[None]
    still = np.zeros((1, 6))
    ours = hydro_channels(PlatformModel(hydrodyn_hull(), options=HYDRODYN).prescribed_motion_loads(
        np.zeros(1), pose, still, still))[0]
    buoyancy, tilt_moment = 138.0841e6, 7.9709e7
    assert np.all(np.abs(ours[:3] - expected[:3]) < 1e-3 * buoyancy)
    assert np.all(np.abs(ours[3:] - expected[3:]) < 1e-3 * tilt_moment)
    if name == "heave0.5m":  # rho g Awp 0.5 = 2.6644 MN less
        assert ours[2] - 138.0841e6 == pytest.approx(expected[2] - 138.0841e6, rel=1e-3)


def _column(draft_m: float = 15.5, freeboard_m: float = 15.0):
    p = load_platform("windmoor12")
    column = dataclasses.replace(p.members[0], end_a_m=(0.0, 0.0, -draft_m), end_b_m=(0.0, 0.0, freeboard_m))
    return dataclasses.replace(p, members=(column,))


@pytest.mark.parametrize("heave_m", [-3.0, 0.0, 0.37, 4.0])
def test_heaved_column_buoyancy_is_rho_g_times_the_exact_submerged_volume(heave_m):
    model = PlatformModel(_column(), options=HYDRODYN)
    pose, still = np.array([[0.0, 0.0, heave_m, 0.0, 0.0, 0.0]]), np.zeros((1, 6))
    loads = model.prescribed_motion_loads(np.zeros(1), pose, still, still)[0, ROW["hydrostatic"]]
    volume = math.pi * 7.5**2 * (15.5 - heave_m)
    assert loads[2] == pytest.approx(RHO_G * volume, rel=1e-12)
    assert np.allclose(loads[[0, 1, 3, 4, 5]], 0.0, atol=1e-6 * loads[2])


@pytest.mark.parametrize("pitch_rad", [0.04, 0.2])
def test_pitched_column_buoyancy_acts_at_the_metacentric_centre_of_buoyancy(pitch_rad):
    """A column pitched about its water-line centre: along the axis line through section point
    xi (body x) the submerged length is l0 + xi tan(th), so V = A l0 and the centre of
    buoyancy (body frame) is at x = tan(th) R^2 / (4 l0), z = -l0 / 2 + tan(th)^2 R^2 / (8 l0)
    (BM = I / V); the moment about the reference point is -x_world rho g V."""
    model = PlatformModel(_column(), options=HYDRODYN)
    pose, still = np.array([[0.0, 0.0, 0.0, 0.0, pitch_rad, 0.0]]), np.zeros((1, 6))
    loads = model.prescribed_motion_loads(np.zeros(1), pose, still, still)[0, ROW["hydrostatic"]]
    radius, draft, tan = 7.5, 15.5, math.tan(pitch_rad)
    volume = math.pi * radius**2 * draft
    x_b = tan * radius**2 / (4 * draft)
    z_b = -draft / 2 + tan**2 * radius**2 / (8 * draft)
    x_world = math.cos(pitch_rad) * x_b + math.sin(pitch_rad) * z_b
    assert loads[2] == pytest.approx(RHO_G * volume, rel=1e-12)
    assert loads[4] == pytest.approx(-x_world * RHO_G * volume, rel=1e-9)
    assert np.allclose(loads[[0, 1, 3, 5]], 0.0, atol=1e-6 * loads[2])


# ---------------------------------------------------------------------- HydroDyn decks as platforms
def _import(deck, tmp_path) -> str:
    out = tmp_path / "imported.yaml"
    assert main(["platform", "import", str(deck), "-o", str(out)]) == 0
    return str(out)


@pytest.mark.slow
def test_imported_deck_moving_in_still_water_matches_hydrodyn(tmp_path):
    """The reference's own HydroDyn.dat, imported, then moved along its motion by ``fowt-sim
    loads``: the same channels as HydroDyn's within the targets."""
    platform_file = _import(hydrodyn_case(CASE) / "HydroDyn.dat", tmp_path)
    motion_file, out = tmp_path / "prp.dat", tmp_path / "loads.csv"
    np.savetxt(motion_file, reference_motion()[::4], fmt="%.6f" + " %.12e" * 18)  # every 0.2 s
    assert main(["loads", "--platform", platform_file, "--motion", str(motion_file), "--still-water", "--hydrodyn",
                 "-o", str(out)]) == 0
    ref = read_hydrodyn_out(hydrodyn_case(CASE) / "wm12_prescribed_still.out")
    table = np.genfromtxt(out, delimiter=",", names=True)
    errors = {c: relative_rms(table[c], ref[c][::4]) for c in CHANNELS}
    assert all(errors[c] < 5e-3 for c in ("HydroFxi", "HydroFzi", "HydroMxi", "HydroMyi")), errors
    assert errors["HydroFyi"] < 2e-2 and errors["HydroMzi"] < 2e-2, errors


def test_imported_deck_held_fixed_in_waves_matches_hydrodyn(tmp_path):
    """The fixed-hull reference's deck, imported, held at rest in its wave components."""
    case = hydrodyn_case("windmoor12_fixed_waves")
    platform_file = _import(case / "HydroDyn.dat", tmp_path)
    ref = read_hydrodyn_out(case / "wm12_waves_fixed.out")
    rest = np.zeros((ref["Time"].size, 19))
    rest[:, 0] = ref["Time"]
    motion_file, out = tmp_path / "rest.dat", tmp_path / "loads.csv"
    np.savetxt(motion_file, rest)
    assert main(["loads", "--platform", platform_file, "--motion", str(motion_file), "--hydrodyn", "--waves-comp",
                 str(case / "waves_jonswap_Hs11_Tp12_g4.9.Comp"), "--wave-table-dt", "0.05", "-o", str(out)]) == 0
    table = np.genfromtxt(out, delimiter=",", names=True)
    errors = {c: relative_rms(table[c], ref[c]) for c in ("HydroFxi", "HydroFzi", "HydroMyi")}
    assert all(e < 2e-3 for e in errors.values()), errors


@pytest.mark.parametrize("edit, message", [
    (lambda text: text.replace("             0   PotMod", "             2   PotMod", 1), "PotMod 2"),
    (lambda text: text.replace("             0   NMGDepths", "             2   NMGDepths", 1).replace(
        "(m)        (m)         (kg/m^3)", "(m)        (m)         (kg/m^3)\n-10.0      0.1         1100.0\n"
        "-2.0       0.1         1100.0", 1),
     "MGDpth"),  # marine-growth rows from the lowest up: HydroDyn takes them highest first
    (lambda text: text.replace("0.5         1         2        FALSE", "0.5         2         2        FALSE", 1),
     "depth-based"),
])
def test_platform_import_refuses_what_the_model_cannot_represent(tmp_path, capsys, edit, message):
    deck = tmp_path / "HydroDyn.dat"
    deck.write_text(edit((hydrodyn_case(CASE) / "HydroDyn.dat").read_text()))
    assert main(["platform", "import", str(deck), "-o", str(tmp_path / "out.yaml")]) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and len(err.splitlines()) == 1 and "Traceback" not in err


@pytest.mark.parametrize("content, message", [("0 1 2 3\n1 1 2 3\n", "expected 19 columns"),
                                              ("not a number\n", "cannot be read"),
                                              (" ".join(["0"] * 19) + "\n" + " ".join(["0"] * 19) + "\n",
                                               "increasing time")])
def test_loads_refuses_a_bad_motion_file_in_one_line(tmp_path, capsys, content, message):
    motion = tmp_path / "prp.dat"
    motion.write_text(content)
    assert main(["loads", "--motion", str(motion), "--still-water", "-o", str(tmp_path / "out.csv")]) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and len(err.splitlines()) == 1


@pytest.mark.parametrize("wetted_length", ["displaced", "undisplaced"])
def test_mean_surge_force_of_surge_and_heave_motion_is_the_wetted_length_product(wetted_length):
    """A column (Cd 0) surging X sin(wt) and heaving Z sin(wt + phi) in still water: its added
    mass force -rho Ca A l(t) x'' has the mean rho Ca A <z x''> = -rho Ca A X Z w^2 cos(phi) / 2
    when the wetted length l = draft - z follows the body (a second-order force from the body
    motion alone: the part of Pinkster's decomposition these options add), and none when it
    stays undisplaced."""
    column = _column()
    column = dataclasses.replace(column, members=(uniform_drag(column.members[0], 0.0, 0.0),))
    amplitude_x, amplitude_z, omega, phase = 2.0, 0.3, 0.6, 0.4
    t = np.arange(0.0, 20 * 2 * np.pi / omega, 2 * np.pi / omega / 64)
    motion, velocity, acceleration = (np.zeros((t.size, 6)) for _ in range(3))
    for j, amp, ph in ((0, amplitude_x, 0.0), (2, amplitude_z, phase)):
        motion[:, j] = amp * np.sin(omega * t + ph)
        velocity[:, j] = amp * omega * np.cos(omega * t + ph)
        acceleration[:, j] = -amp * omega**2 * np.sin(omega * t + ph)
    options = HydroOptions(wetted_length=wetted_length, load_directions="rotating", hydrostatics="linear",
                           slow_drift="none")
    loads = PlatformModel(column, options=options).prescribed_motion_loads(t, motion, velocity, acceleration)
    mean_fx = loads[:, ROW["added_mass"], 0].mean()
    expected = -1025.0 * 1.0 * math.pi * 7.5**2 * amplitude_x * amplitude_z * omega**2 * math.cos(phase) / 2
    if wetted_length == "displaced":
        assert mean_fx == pytest.approx(expected, rel=1e-6)
    else:
        assert abs(mean_fx) < 1e-6 * abs(expected)


def test_run_files_take_the_hydro_options(tmp_path):
    from fowt_hydro_sim.physics.config import ConfigError, load_run_file

    good = tmp_path / "run.yaml"
    good.write_text("platform: windmoor12\nrun: {wetted_length: undisplaced, load_directions: fixed, "
                    "hydrostatics: nonlinear, slow_drift: none}\n")
    assert load_run_file(good).run.hydro_options == HYDRODYN
    default = tmp_path / "default.yaml"
    default.write_text("platform: windmoor12\n")
    assert load_run_file(default).run.hydro_options == dataclasses.replace(HYDRODYN, slow_drift="newman")
    bad = tmp_path / "bad.yaml"
    bad.write_text("platform: windmoor12\nrun: {load_directions: sideways}\n")
    with pytest.raises(ConfigError, match="load_directions: must be one of rotating, fixed"):
        load_run_file(bad)


# ---------------------------------------------------------------------- displaced kinematics (WaveDisp 1)
def _offset_column(offset_m, yaw_rad: float = 0.0):
    """A windmoor12 column placed at (20, 10) in the body frame, then yawed and shifted by
    ``offset_m`` (x, y): the platform a displaced one is at."""
    p = load_platform("windmoor12")
    c, s = math.cos(yaw_rad), math.sin(yaw_rad)

    def place(point):
        x, y = point[0] + 20.0, point[1] + 10.0
        return (c * x - s * y + offset_m[0], s * x + c * y + offset_m[1], point[2])

    column = dataclasses.replace(p.members[0], end_a_m=place((0.0, 0.0, -15.5)), end_b_m=place((0.0, 0.0, 15.0)),
                                 strip_length_m=0.5)
    return dataclasses.replace(p, members=(column,))


@pytest.mark.parametrize("yaw_rad", [0.0, 0.3])
def test_displaced_kinematics_of_an_offset_body_are_those_of_the_body_built_there(yaw_rad):
    """A body held at a surge/sway offset (and yaw) with kinematics at the displaced points
    (WaveDisp 1) gets the loads of the same body built at that place with undisplaced
    kinematics (moments moved to the displaced reference point); at the undisplaced points
    it does not."""
    from fowt_hydro_sim.physics.waves.components import WaveComponents
    waves = WaveComponents(np.array([0.08, 0.1, 0.13]), np.array([1.0, 1.5, 0.5]), np.array([0.3, 1.1, 2.0]),
                           np.array([0.0, 0.4, -0.2]), 100.0)
    offset = (7.0, -3.0)
    t = np.round(np.arange(0.0, 20.0, 0.1), 10)
    pose = np.tile([offset[0], offset[1], 0.0, 0.0, 0.0, yaw_rad], (t.size, 1))
    still = np.zeros((t.size, 6))
    loads = {}
    for kinematics in ("displaced", "undisplaced"):
        model = PlatformModel(_offset_column((0.0, 0.0)), waves, wave_table_dt_s=0.1,
                              options=dataclasses.replace(HYDRODYN, kinematics=kinematics))
        loads[kinematics] = hydro_channels(model.prescribed_motion_loads(t, pose, still, still))
    there = PlatformModel(_offset_column(offset, yaw_rad), waves, wave_table_dt_s=0.1, options=HYDRODYN)
    reference = hydro_channels(there.prescribed_motion_loads(t, still, still, still))
    arm = np.array([offset[0], offset[1], 0.0])
    reference[:, 3:6] -= np.cross(arm, reference[:, 0:3])
    scale = np.abs(reference).max(axis=0)
    assert np.max(np.abs(loads["displaced"] - reference) / scale) < 1e-5
    assert np.max(np.abs(loads["undisplaced"] - reference)[:, :2] / scale[:2]) > 0.1


def test_displaced_kinematics_keep_the_undisplaced_depth_without_stretching():
    """HydroDyn's WaveDisp 1 moves the kinematics points horizontally, and vertically only
    with wave stretching (Morison.f90: "intentionally using the undisplaced Z position"): a
    column heaved 2 m down and pitched gets, without stretching, the wave loads of the
    undisplaced depths at its displaced x; with vertical stretching, those of its displaced
    points."""
    from fowt_hydro_sim.physics.waves.components import WaveComponents
    waves = WaveComponents(np.array([0.08, 0.1]), np.array([1.0, 1.5]), np.array([0.3, 1.1]),
                           np.array([0.0, 0.0]), 100.0)
    t = np.round(np.arange(0.0, 10.0, 0.1), 10)
    still = np.zeros((t.size, 6))
    heaved = np.tile([0.0, 0.0, -2.0, 0.0, 0.0, 0.0], (t.size, 1))
    inertia = {}
    for kinematics, stretching in (("displaced", "none"), ("undisplaced", "none"), ("displaced", "vertical")):
        model = PlatformModel(_offset_column((0.0, 0.0)), waves, wave_table_dt_s=0.1,
                              options=dataclasses.replace(HYDRODYN, kinematics=kinematics, stretching=stretching))
        loads = model.prescribed_motion_loads(t, heaved, still, still)
        inertia[kinematics, stretching] = loads[:, ROW["inertia"], 0]
    scale = np.abs(inertia["displaced", "none"]).max()
    assert np.abs(inertia["displaced", "none"] - inertia["undisplaced", "none"]).max() < 1e-12 * scale
    difference = np.abs(inertia["displaced", "vertical"] - inertia["displaced", "none"]).max()
    assert difference > 1e-3 * scale


def test_displaced_kinematics_are_refused_for_time_stepping():
    model = PlatformModel(_offset_column((0.0, 0.0)), options=dataclasses.replace(HYDRODYN, kinematics="displaced"))
    with pytest.raises(ValueError, match="prescribed motion only"):
        model.run(1.0)
