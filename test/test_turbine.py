"""The turbine model against ROSCO's own simulator and the performance table by hand, and
the floating platform's steady offset under the rotor thrust against closed-form statics and K^-1 F."""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from scipy.optimize import brentq, root

from fowt_hydro_sim.physics.config import ConfigError, HydroOptions, load_platform
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.testing import rosco_oracle
from fowt_hydro_sim.turbine.description import load_turbine, turbine_path
from fowt_hydro_sim.turbine.discon import ControllerError
from fowt_hydro_sim.turbine.performance import RotorCoefficients, read_table
from fowt_hydro_sim.turbine.rosco import Rosco
from fowt_hydro_sim.turbine.rotor import HubMotion, TurbineModel, aero_loads, hub_motion
from fowt_hydro_sim.turbine.wind import Wind, read_series

RPM = 2 * np.pi / 60
RATED_TORQUE_NM = 1.97868e7  # the DISCON.IN's VS_RtTq


def table_value(path, section: str, tsr: float, pitch_deg: float) -> float:
    """A coefficient read off the text table by hand: its row of TSR, its column of pitch."""
    lines = path.read_text().splitlines()
    pitches = [float(v) for v in lines[lines.index(next(l for l in lines if l.startswith("# Pitch"))) + 1].split()]
    tsrs = [float(v) for v in lines[lines.index(next(l for l in lines if l.startswith("# TSR"))) + 1].split()]
    start = lines.index(next(l for l in lines if l.split()[1:2] == [section])) + 2
    return float(lines[start + tsrs.index(tsr)].split()[pitches.index(pitch_deg)])


def test_thrust_at_the_rated_point_is_the_table_thrust_coefficient_by_hand():
    turbine = load_turbine()
    coefficients = RotorCoefficients(read_table(turbine.performance_path))
    speed, tsr = turbine.rated_rotor_speed_rad_s, 9.0  # a grid point of the table near rated (TSR 8.9)
    wind = speed * turbine.rotor_radius_m / tsr
    ct = table_value(turbine.performance_path, "Thrust", 9.0, 0.0)
    cp = table_value(turbine.performance_path, "Power", 9.0, 0.0)
    area = np.pi * turbine.rotor_radius_m ** 2
    thrust, torque = aero_loads(turbine, coefficients, wind, speed, 0.0)
    assert thrust == pytest.approx(0.5 * 1.225 * area * wind ** 2 * ct, rel=1e-6)
    assert torque * speed == pytest.approx(0.5 * 1.225 * area * wind ** 3 * cp, rel=1e-6)
    assert 2.0e6 < thrust < 3.0e6  # the IEA 15 MW rated thrust is about 2.5 MN


def run_model(turbine_name: str, dt_s: float, duration_s: float, wind: Wind, rpm: float,
              discon_changes: str = "") -> dict[str, np.ndarray]:
    turbine = load_turbine(turbine_name, controller_dt_s=dt_s, discon_changes=discon_changes)
    rosco = Rosco(turbine.discon_path, dt_s, turbine.generator_efficiency, changes=turbine.changes)
    model = TurbineModel(turbine, RotorCoefficients(read_table(turbine.performance_path)), rosco, rpm * RPM)
    n = int(round(duration_s / dt_s))
    rows = [(0.0, model.state.rotor_speed_rad_s, 0.0, 0.0)]
    try:
        for i in range(1, n + 1):
            s = model.step(wind.at(i * dt_s), last=i == n)
            rows.append((s.time_s, s.rotor_speed_rad_s, s.pitch_rad, s.generator_torque_nm))
    finally:
        rosco.close()
    return dict(zip(("time_s", "rotor_speed_rad_s", "pitch_rad", "generator_torque_nm"), np.array(rows).T))


@pytest.mark.slow
@pytest.mark.reference
@pytest.mark.rosco
def test_a_wind_step_gives_rosco_simulators_trajectories(tmp_path):
    """Platform held fixed: the turbine model with ROSCO against rosco.toolbox.sim.Sim, same
    turbine, same DISCON.IN, wind 10 -> 14 m/s (each in its own process: ROSCO is global)."""
    dt, duration, step, rpm = 0.05, 300.0, 50.0, 7.0
    oracle = rosco_oracle.in_child_process(tmp_path, "iea15_umaine", dt, duration, step, 10.0, 14.0, rpm)
    ours = run_model("iea15_umaine", dt, duration, Wind("step", 10.0, 14.0, start_s=step), rpm)
    assert np.allclose(ours["time_s"], oracle["time_s"])
    for name in ("rotor_speed_rad_s", "pitch_rad", "generator_torque_nm"):
        a, b = ours[name][1:], oracle[name][1:]
        assert np.all(np.isfinite(a))
        rms = np.sqrt(np.mean((a - b) ** 2)) / np.sqrt(np.mean(b ** 2))
        assert rms < 0.01, f"{name}: RMS difference {100 * rms:.3f} %"
    # the step is a real transient: the pitch opens from fine pitch to above-rated pitch
    assert oracle["pitch_rad"][int(step / dt) - 1] < 0.05
    # at the end, steady above rated: the pitch giving the rated torque at rated speed (table by hand)
    turbine = load_turbine()
    pitch, _ = steady_above_rated(turbine, RotorCoefficients(read_table(turbine.performance_path)), 14.0)
    assert ours["pitch_rad"][-1] == pytest.approx(pitch, abs=1e-3)
    assert ours["rotor_speed_rad_s"][-1] == pytest.approx(turbine.rated_rotor_speed_rad_s, rel=1e-3)


def steady_above_rated(turbine, coefficients, wind_m_s: float) -> tuple[float, float]:
    """Blade pitch and thrust where the rotor at rated speed gives the rated torque."""
    speed = turbine.rated_rotor_speed_rad_s
    pitch = brentq(lambda p: aero_loads(turbine, coefficients, wind_m_s, speed, p)[1] - RATED_TORQUE_NM, 0.0, 0.5)
    return pitch, aero_loads(turbine, coefficients, wind_m_s, speed, pitch)[0]


# windmoor12 as its spec gives it (docs/platform_windmoor12.md), for the static oracle
RHO_KG_M3, G_M_S2 = 1025.0, 9.80665
COLUMN_RADIUS_M, KEEL_Z_M = 7.5, -15.5
COLUMN_CENTRES_M = ((-35.2184, 0.0), (17.6092, 30.5), (17.6092, -30.5))
PONTOON_VOLUME_M3, PONTOON_Z_M = 3 * 46.0 * 10.0 * 4.0, -13.5  # their centroids average to (0, 0)
MASS_KG, COG_Z_M = 14.0807e6, 3.12
FAIRLEAD_RADIUS_M, ANCHOR_RADIUS_M, LINE_Z_M = 42.7184, 642.7184, -10.0
LINE_K_N_M, PRETENSION_N, UNSTRETCHED_M = 63.2e3, 1.2e6, 600.0


def static_loads(surge_m: float, heave_m: float, pitch_rad: float, thrust_n: float, hub_z_m: float,
                 exact_hydrostatics: bool) -> np.ndarray:
    """(Fx, Fz, My about the moved reference point) on the hull moved and pitched in still water, from closed
    forms: each column a wall-sided cylinder cut obliquely by the water plane (volume
    pi R^2 l, centroid tan(th) R^2 / 4 l aside and l / 2 + tan(th)^2 R^2 / 8 l up its axis, l
    its wet axis length), the pontoons wet, gravity at the CoG, the spring lines from the
    moved fairleads and the thrust along the rotor axis at the hub. Without
    ``exact_hydrostatics``: rho g (V - A_wp z) up and -rho g (I_wp + V z_B) th in pitch."""
    c, s = np.cos(pitch_rad), np.sin(pitch_rad)
    rotation = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    offset = np.array([surge_m, 0.0, heave_m])
    area = np.pi * COLUMN_RADIUS_M ** 2
    total = np.zeros(3)
    forces = [(np.array([0.0, 0.0, COG_Z_M]), np.array([0.0, 0.0, -MASS_KG * G_M_S2])),
              (np.array([0.0, 0.0, hub_z_m]), rotation @ np.array([thrust_n, 0.0, 0.0]))]
    if exact_hydrostatics:
        for cx, cy in COLUMN_CENTRES_M:
            wet = (s * cx - heave_m) / c - KEEL_Z_M
            centroid = [cx + np.tan(pitch_rad) * COLUMN_RADIUS_M ** 2 / (4 * wet), cy,
                        KEEL_Z_M + wet / 2 + np.tan(pitch_rad) ** 2 * COLUMN_RADIUS_M ** 2 / (8 * wet)]
            forces.append((np.array(centroid), np.array([0.0, 0.0, RHO_KG_M3 * G_M_S2 * area * wet])))
        forces.append((np.array([0.0, 0.0, PONTOON_Z_M]), np.array([0.0, 0.0, RHO_KG_M3 * G_M_S2 * PONTOON_VOLUME_M3])))
    else:
        volume = 3 * area * -KEEL_Z_M + PONTOON_VOLUME_M3
        buoyancy_z = (3 * area * KEEL_Z_M ** 2 / -2 + PONTOON_VOLUME_M3 * PONTOON_Z_M) / volume
        waterplane_inertia = sum(area * (COLUMN_RADIUS_M ** 2 / 4 + cx ** 2) for cx, _ in COLUMN_CENTRES_M)
        total += RHO_KG_M3 * G_M_S2 * np.array(
            [0.0, volume - 3 * area * heave_m, -(waterplane_inertia + volume * buoyancy_z) * pitch_rad])
    for cx, cy in COLUMN_CENTRES_M:
        direction = np.array([cx, cy, 0.0]) / np.hypot(cx, cy)
        fairlead = FAIRLEAD_RADIUS_M * direction + [0.0, 0.0, LINE_Z_M]
        line = ANCHOR_RADIUS_M * direction + [0.0, 0.0, LINE_Z_M] - (rotation @ fairlead + offset)
        length = np.linalg.norm(line)
        forces.append((fairlead, (PRETENSION_N + LINE_K_N_M * (length - UNSTRETCHED_M)) * line / length))
    for point, force in forces:
        total += [force[0], force[2], np.cross(rotation @ point, force)[1]]
    return total


def static_offset(thrust_n: float, hub_z_m: float, exact_hydrostatics: bool) -> np.ndarray:
    """(surge, heave, pitch) where the closed-form static loads balance."""
    solution = root(lambda q: static_loads(*q, thrust_n, hub_z_m, exact_hydrostatics) / [1e6, 1e6, 1e8],
                    np.zeros(3), tol=1e-12)
    assert solution.success
    return solution.x


def closed_form_stiffness(hub_z_m: float, exact_hydrostatics: bool, step: float = 1e-6) -> np.ndarray:
    """The closed forms' (surge, heave, pitch) stiffness at rest, by central differences."""
    def loads(q):
        return static_loads(*q, 0.0, hub_z_m, exact_hydrostatics)
    return -np.column_stack([(loads(step * e) - loads(-step * e)) / (2 * step) for e in np.eye(3)])


def linear_offset(thrust_n: float, hub_z_m: float, exact_hydrostatics: bool) -> np.ndarray:
    """K^-1 F of the closed forms."""
    return np.linalg.solve(closed_form_stiffness(hub_z_m, exact_hydrostatics), thrust_n * np.array([1.0, 0.0, hub_z_m]))


@pytest.mark.slow
@pytest.mark.parametrize("hydrostatics", ["linear", "nonlinear"])
def test_steady_platform_pitch_under_the_mean_thrust_is_the_static_offset(hydrostatics):
    """The mean thrust at 13 m/s (1.5 MN) at the hub of the floating platform.
    - The platform's restoring matrix against the closed forms' (surge, heave, pitch) K.
    - The steady offset against the closed forms' static offset (nonlinear: the thrust turning
      with the rotor, the lines from the moved fairleads, gravity, and with nonlinear
      hydrostatics the obliquely cut columns) within 0.3 %, at a quarter and at the full thrust.
    - Against the linear K^-1 F: within 2 % at a quarter of the thrust; at the full thrust
      (7 degrees) K^-1 F overestimates the pitch by 2 to 4 %, as much as the closed forms say."""
    turbine = load_turbine()
    coefficients = RotorCoefficients(read_table(turbine.performance_path))
    _, thrust = steady_above_rated(turbine, coefficients, 13.0)
    platform = load_platform("windmoor12")
    options = replace(HydroOptions(), hydrostatics=hydrostatics)
    model = PlatformModel(platform, None, dt_s=0.05, drag_model="constant", options=options)
    hub_z, exact = platform.hub_point_m[2], hydrostatics == "nonlinear"
    assert model.restoring_matrix()[np.ix_([0, 2, 4], [0, 2, 4])] == pytest.approx(
        closed_form_stiffness(hub_z, exact), rel=2e-3, abs=1e3)
    for share in (0.25, 1.0):
        model.reset()
        model.set_external_wrench(np.array([share * thrust, 0, 0, 0, 0, 0.0]), "hub")
        steady = model.run(3600.0, output_interval_s=1.0).motion[-900:].mean(axis=0)[[0, 2, 4]]
        static, linear = static_offset(share * thrust, hub_z, exact), linear_offset(share * thrust, hub_z, exact)
        assert steady == pytest.approx(static, rel=3e-3, abs=1e-3), share
        nonlinearity = static[2] / linear[2] - 1
        if share < 1.0:
            assert steady[2] == pytest.approx(linear[2], rel=0.02)
        else:
            assert -0.04 < nonlinearity < -0.02, nonlinearity
            assert steady[2] / linear[2] - 1 == pytest.approx(nonlinearity, abs=3e-3)


def test_wind_inputs(tmp_path):
    assert Wind("steady", 9.0).at(100.0) == 9.0
    step = Wind("step", 10.0, 14.0, start_s=5.0)
    assert step.at(4.9) == 10.0 and step.at(5.0) == 14.0
    assert Wind("ramp", 10.0, 14.0, start_s=10.0, ramp_s=40.0).at(20.0) == pytest.approx(11.0)
    csv = tmp_path / "wind.csv"
    csv.write_text("time_s,speed_m_s\n0,10\n10,12\n")
    t, u = read_series(csv)
    assert np.allclose(t, [0, 10]) and np.allclose(u, [10, 12])
    csv.write_text("0,10\n10,abc\n")
    with pytest.raises(ConfigError, match="line 2"):
        read_series(csv)
    csv.write_text("0,10\n0,12\n")
    with pytest.raises(ConfigError, match="increase"):
        read_series(csv)


def test_a_turbine_description_is_validated(tmp_path):
    with pytest.raises(ConfigError, match="rotor_radius_m"):
        load_turbine("iea15_umaine", rotor_radius_m=-1.0)
    with pytest.raises(ConfigError, match="not a packaged turbine"):
        load_turbine("nope")
    assert load_turbine(hub_height_m=131.7).hub_height_m == 131.7


def test_discon_changes_are_made_in_the_controllers_copy_and_refused_in_one_line(tmp_path):
    """``discon_changes`` replace entries of the text the controller reads, the file left as
    it is; a turbine file's own changes come first, those given after; a name the file has
    not (with the nearest it has), a list of another length, a value that is no number and
    an entry without '=' are refused naming it."""
    source = load_turbine().discon_path
    before = source.read_text()
    turbine = load_turbine(discon_changes="Fl_Kp=-5.0; VS_MinOMSpd=0.45")
    entries = {line.split("!")[1].split()[0]: line.split("!")[0].split()
               for line in turbine.controller_file().splitlines() if "!" in line and line.split("!")[1].split()}
    assert entries["Fl_Kp"] == ["-5.0"] and entries["VS_MinOMSpd"] == ["0.45"] and entries["Fl_U"] == ["11.2770"]
    assert source.read_text() == before
    own = tmp_path / "turbine.yaml"
    own.write_text(turbine_path("iea15_umaine").read_text()  # its files in the rosco wheel (rosco:...)
                   .replace("discon: ", "discon_changes: 'Fl_Kp=-1; VS_MinOMSpd=0.5'\ndiscon: "))
    assert load_turbine(str(own), discon_changes="Fl_Kp=-2").changes == {"Fl_Kp": "-2", "VS_MinOMSpd": "0.5"}
    for changes, message in (("Fl_kp=-5", "Fl_kp is not an entry of .*nearest: Fl_Kp"),
                             ("PS_BldPitchMin=0.1", "PS_BldPitchMin has 60 value"),
                             ("Fl_Kp=fast", "Fl_Kp: expected numbers"), ("Fl_Kp", "expected NAME=VALUE")):
        with pytest.raises(ConfigError, match=message):
            load_turbine(discon_changes=changes)


@pytest.mark.rosco
def test_rosco_holds_the_minimum_rotor_speed_it_was_given():
    """Below rated (5 m/s: the optimal tip-speed ratio would turn the rotor at 0.37 rad/s)
    ROSCO's torque controller holds the rotor at its minimum speed ``VS_MinOMSpd`` (the
    gearbox ratio is 1): started at 0.6 rad/s, the rotor settles at the file's 0.5236 rad/s,
    and at 0.45 rad/s when the entry is changed: the change reaches the controller."""
    for changes, minimum in (("", 0.52360), ("VS_MinOMSpd=0.45", 0.45)):
        run = run_model("iea15_umaine", 0.05, 240.0, Wind(speed_m_s=5.0), 0.6 / RPM, changes)
        settled = run["rotor_speed_rad_s"][run["time_s"] > 180.0]
        assert settled.mean() == pytest.approx(minimum, rel=2e-3) and np.ptp(settled) < 2e-3 * minimum, changes


def test_rosco_refusing_its_input_file_is_one_clear_error(tmp_path):
    turbine = load_turbine()
    bad = tmp_path / "DISCON.IN"
    bad.write_text(turbine.discon_path.read_text().replace("! PC_MaxPit", "! PC_MaxPitX", 1))
    with pytest.raises(ControllerError, match="ROSCO failed starting"):
        Rosco(bad, 0.05, 0.95)


_CALLS = """
import json, sys, tempfile
from pathlib import Path
import numpy as np
from rosco import discon_lib_path
from fowt_hydro_sim.turbine.rosco import discon_copy
from fowt_hydro_sim.turbine.description import load_turbine
folder = Path(tempfile.mkdtemp())
param = discon_copy(load_turbine().discon_path, folder)
t = np.arange(1, 2001) * 0.05
wind = 10.0 + 4.0 * np.sin(t / 7.0)
speed = 0.75 + 0.1 * np.sin(t / 5.0)
outputs = []
if sys.argv[1] == "toolbox":
    from rosco.toolbox.control_interface import ControllerInterface
    c = ControllerInterface(discon_lib_path, param_filename=str(param), sim_name=str(folder / "x"), DT=0.05)
    step = lambda k: c.call_controller({"iStatus": 1, "t": t[k], "dt": 0.05, "ws": wind[k], "bld_pitch": 0.02,
        "gen_torque": 1.5e7, "gen_speed": speed[k], "gen_eff": 0.95, "rot_speed": speed[k], "Yaw_fromNorth": 0.0,
        "Y_MeasErr": 0.0, "NacIMU_FA_RAcc": 0.01})
else:
    from fowt_hydro_sim.turbine.discon import Discon
    c = Discon(discon_lib_path, param, str(folder / "x"), 0.05)
    step = lambda k: c.call(t[k], wind[k], speed[k], speed[k], 0.02, 1.5e7, 0.95, 0.01)
for k in range(len(t)):
    outputs.append([float(v) for v in step(k)])
print(json.dumps(outputs))
"""


@pytest.mark.slow
@pytest.mark.reference
@pytest.mark.rosco
def test_the_c_interface_gives_the_rosco_toolboxs_commands_bit_for_bit():
    """The same 100 s of measurements through ROSCO's Python toolbox (ControllerInterface) and
    through this package's ctypes binding (turbine.discon), each in a fresh process."""
    import json
    import subprocess
    import sys

    from fowt_hydro_sim.testing import REPO
    runs = {}
    for kind in ("toolbox", "binding"):
        done = subprocess.run([sys.executable, "-c", _CALLS, kind], cwd=REPO, capture_output=True, text=True,
                              timeout=300)
        assert done.returncode == 0, done.stderr[-2000:]
        runs[kind] = np.array(json.loads(done.stdout.strip().splitlines()[-1]))
    assert runs["binding"].shape == (2000, 3)
    assert np.ptp(runs["binding"][:, 1]) > 0.01  # the pitch moves: above rated part of the time
    assert np.array_equal(runs["binding"], runs["toolbox"])


def test_a_wind_series_from_a_bag(tmp_path):
    """The turbine node's wind bag: a turbine quantity topic (Vector3Stamped, x) by stamp."""
    pytest.importorskip("rclpy")
    from fowt_hydro_sim.ros.turbine_node import TurbineSettings
    from fowt_hydro_sim.rosbag.writer import BagWriter
    from msg_adapters import cdr, topics

    bag = tmp_path / "wind"
    writer = BagWriter(bag)
    channel = writer.add_topic(*topics.TURBINE["wind_speed"])
    for i, speed in enumerate((10.0, 11.0, 13.0)):  # the same bytes as a PointStamped
        writer.write(channel, (5 - i) * 10**9, cdr.point(float(i), speed, 0.0, 0.0, "hub"))  # log times disagree
    writer.close()
    wind = TurbineSettings(wind="bag", wind_bag=str(bag)).make_wind()
    assert wind.at(0.5) == pytest.approx(10.5) and wind.at(2.0) == 13.0 and wind.at(9.0) == 13.0
    with pytest.raises(ConfigError, match="wind_bag"):
        TurbineSettings(wind="bag")


@pytest.mark.ros
@pytest.mark.slow
@pytest.mark.parametrize("args, message", [
    ({"wind_sped_m_s": 3.0}, "parameter wind_sped_m_s: unknown to fowt_turbine (did you mean wind_speed_m_s?)"),
    ({"wind_speed_m_s": -3.0}, "parameter wind_speed_m_s: must be 0 to 80, got -3"),
])
def test_bad_turbine_parameters_end_with_one_line(args: dict, message: str):
    from fowt_hydro_sim.testing.ros import finish, start

    turbine = start("turbine", **args)
    output = finish(turbine, 60)
    assert turbine.returncode == 2 and message in output and "Traceback" not in output, output
    assert "Invalid parameter" not in output, output


def test_the_hub_motion_from_the_platforms_twist():
    """The thrust point at h above the reference point: fore-aft velocity u + h q (body x of
    v + omega x r); accelerations as backward differences from the last odometry."""
    h, dt = 150.0, 0.05
    first = hub_motion(1.0, np.array([0.5, 0.0, 0.0, 0.0, 0.01, 0.0]), None, h)
    assert first.velocity_m_s == pytest.approx(0.5 + h * 0.01)
    assert first.pitch_acceleration_rad_s2 == first.fore_aft_acceleration_m_s2 == 0.0
    second = hub_motion(1.0 + dt, np.array([0.52, 0.0, 0.0, 0.0, 0.012, 0.0]), first, h)
    assert second.pitch_acceleration_rad_s2 == pytest.approx(0.002 / dt)
    assert second.fore_aft_acceleration_m_s2 == pytest.approx((0.02 + h * 0.002) / dt)
    assert hub_motion(2.0, np.ones(6), second, h, fixed=True) == HubMotion(2.0, 0.0, 0.0, 0.0, 0.0)


_ACCELERATIONS = """
import sys
from pathlib import Path
from fowt_hydro_sim.turbine.description import load_turbine
from fowt_hydro_sim.turbine.performance import RotorCoefficients, read_table
from fowt_hydro_sim.turbine.rosco import Rosco
from fowt_hydro_sim.turbine.rotor import TurbineModel
turbine = load_turbine()
rosco = Rosco(turbine.discon_path, turbine.controller_dt_s, turbine.generator_efficiency, logging_level=2)
model = TurbineModel(turbine, RotorCoefficients(read_table(turbine.performance_path)), rosco,
                     turbine.rated_rotor_speed_rad_s)
try:
    for _ in range(20):
        model.step(13.0, 0.1, 0.002, fore_aft_acceleration_m_s2=0.3)
finally:
    kept = rosco.close(Path(sys.argv[1]))
print(" ".join(sorted(p.name for p in kept)))
"""


@pytest.mark.slow
def test_rosco_gets_the_fore_aft_acceleration_and_its_debug_channels_are_kept(tmp_path):
    """ROSCO's own record of its inputs (LoggingLevel 2: its local variables, .dbg2) holds the
    fore-aft and pitch accelerations given, and its debug channels (.dbg) are kept. In a
    child process: ROSCO is one instance per process."""
    import subprocess
    import sys

    from fowt_hydro_sim.testing import REPO
    done = subprocess.run([sys.executable, "-c", _ACCELERATIONS, str(tmp_path / "debug")], cwd=REPO,
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip().splitlines()[-1] == "rosco.RO.dbg rosco.RO.dbg2"
    lines = (tmp_path / "debug" / "rosco.RO.dbg2").read_text().splitlines()
    names = lines[1].split()
    rows = np.array([[float(v) for v in line.split()] for line in lines[3:]])
    assert len(rows) == 21 and rows[0, 0] == 0.0  # its start (ROSCO zeroes the accelerations there), each step
    assert np.allclose(rows[1:, names.index("FA_Acc_TT")], 0.3, rtol=1e-6)
    assert np.allclose(rows[1:, names.index("NacIMU_FA_RAcc")], 0.002, rtol=1e-6)
    assert "FA_AccF" in (tmp_path / "debug" / "rosco.RO.dbg").read_text().splitlines()[1].split()
