"""A potential-flow hull in the model (HydroDyn's PotMod 1): the packaged VolturnUS-S and its
load components, each checked against what the model did not make: WAMIT's own added mass and
damping at the forcing frequency, the .3 file's excitation, ElastoDyn's mass inputs."""
from __future__ import annotations

import csv
import subprocess
import sys
from dataclasses import replace
from importlib import resources
from pathlib import Path

import numpy as np
import pytest

from fowt_hydro_sim.io.elastodyn import hub_point, system_mass_properties
from fowt_hydro_sim.physics.config import ConfigError, load_platform, platform_document, platform_from_dict
from fowt_hydro_sim.physics.hydro import wamit
from fowt_hydro_sim.physics.hydro.potential_flow import excitation_series, wamit_data
from fowt_hydro_sim.physics.loads import radiation as radiation_load
from fowt_hydro_sim.physics.waves.components import WaveComponents

DATA = Path(str(resources.files("fowt_hydro_sim.physics"))) / "data" / "platforms" / "volturnus_s"
ROOT = DATA / "HydroData" / "IEA-15-240-RWT-UMaineSemi"
RHO, G = 1025.0, 9.80665


@pytest.fixture(scope="module")
def volturnus():
    return load_platform("volturnus_s")


def test_volturnus_s_mass_is_the_rigid_elastodyn_structure(volturnus):
    """The YAML's mass, centre of mass, inertia and hub point are those computed from the
    ElastoDyn deck's platform, tower, nacelle, hub and blade inputs; the mass is the sum of
    ElastoDyn's lumped and distributed masses (checked by hand: PtfmMass 17,838 t plus tower,
    RNA), and the hub is at the IEA 15 MW's 150 m hub height."""
    computed = system_mass_properties(DATA / "IEA-15-240-RWT-UMaineSemi_ElastoDyn.dat",
                                      DATA / "IEA-15-240-RWT_ElastoDyn_blade.dat")
    mass = volturnus.mass
    assert mass.mass_kg == pytest.approx(computed.mass_kg, rel=1e-8)
    assert np.allclose(mass.cog_m, computed.cog_m, atol=1e-3)
    assert np.allclose(mass.inertia_about_cog_kg_m2, computed.inertia_about_cog_kg_m2, rtol=1e-8, atol=1.0)
    assert volturnus.hub_point_m == pytest.approx(hub_point(DATA / "IEA-15-240-RWT-UMaineSemi_ElastoDyn.dat"),
                                                  abs=1e-3)
    assert volturnus.hub_point_m[2] == pytest.approx(150.0, abs=0.01)
    assert 17.838e6 < mass.mass_kg < 17.838e6 + 2.7e6  # platform plus a 15 MW tower and RNA


def test_the_platform_document_round_trips_and_a_missing_wamit_file_is_named(volturnus, tmp_path):
    assert platform_from_dict(platform_document(volturnus), "copy") == volturnus
    document = platform_document(volturnus)
    document["potential_flow"]["wamit_root"] = "no_such/hull"
    with pytest.raises(ConfigError, match=r"potential_flow.wamit_root: no WAMIT file hull.1"):
        platform_from_dict(document, "broken.yaml", tmp_path)


def _radiation_response(platform, dof: int, omega: float, dt: float = 0.05) -> tuple[np.ndarray, np.ndarray]:
    """The radiation component driven by v = cos(w t) in one DOF, its compiled wrench called at
    every step as the kernel calls it: the steady memory force's (cos, sin) coefficients (6, 2)
    over the last two periods, and the left-hand-side mass it reported."""
    from fowt_hydro_sim.physics.loads import ComponentInputs
    params, table = radiation_load.parameters(ComponentInputs(platform, None, None, None, None, None, dt))
    t = np.arange(int(300 / dt)) * dt
    forces = np.zeros((t.size, 6))
    y, out, mass = np.zeros(12), np.zeros(6), np.zeros((6, 6))
    for n, time in enumerate(t):
        y[6 + dof] = np.cos(omega * time)
        out[:] = 0.0
        mass[:] = 0.0
        radiation_load.wrench(time, y, np.eye(3), params, table, out, mass)
        forces[n] = out
    last = t > t[-1] - 4 * np.pi / omega
    basis = np.stack([np.cos(omega * t[last]), np.sin(omega * t[last])], axis=1)
    return np.linalg.lstsq(basis, forces[last], rcond=None)[0].T, mass


@pytest.mark.slow
def test_radiation_memory_is_cummins_with_the_kernel_and_wamit_where_the_kernel_resolves_it(volturnus):
    """Driven by v = cos(w t) in surge or pitch, the steady memory force is -B v - (A - A_inf)
    dv/dt (Cummins): B and A are those of the kernel itself (its cosine transform and Ogilvie's
    relation over RdtnTMax, ``physics.hydro.radiation``) within 0.3 % at 0.5 and 1 rad/s, and
    WAMIT's surge B and A (the .1 file) within 1.5 %: A is not an input of the convolution, so
    matching it is Ogilvie's relation holding in the time domain. (Below 0.5 rad/s the deck's
    60 s kernel is too short for the small pitch damping: its transform gives B55 67 % above
    WAMIT's at 0.3 rad/s, as HydroDyn's kernel would; docs/physics/potential_flow.md.)"""
    from fowt_hydro_sim.physics.hydro.radiation import added_mass_from_kernel, damping_from_kernel, retardation_kernel
    one = wamit.read_1(ROOT.with_name(ROOT.name + ".1"), RHO)
    kernel = retardation_kernel(one.omega_rad_s, one.damping_si, volturnus.potential_flow.radiation_tmax_s, 0.05)
    for omega in (0.5, 1.0):
        k = int(np.argmin(np.abs(one.omega_rad_s - omega)))
        b_k = damping_from_kernel(kernel.time_s, kernel.kernel_si, np.array([omega]))[0]
        a_k = added_mass_from_kernel(kernel.time_s, kernel.kernel_si, one.added_mass_inf_si, np.array([omega]))[0]
        for dof in (0, 4):
            coefficients, mass = _radiation_response(volturnus, dof, omega)
            b, a = -coefficients[:, 0], coefficients[:, 1] / omega + one.added_mass_inf_si[:, dof]
            for i in (0, 4):
                assert b[i] == pytest.approx(b_k[i, dof], rel=3e-3), (omega, i, dof)
                assert a[i] == pytest.approx(a_k[i, dof], rel=3e-3), (omega, i, dof)
            if dof == 0:
                assert b[0] == pytest.approx(one.damping_si[k, 0, 0], rel=0.015)
                assert a[0] == pytest.approx(one.added_mass_si[k, 0, 0], rel=0.015)
    assert np.array_equal(mass, one.added_mass_inf_si)


def test_excitation_is_the_3_files_for_a_regular_wave_between_headings(volturnus):
    """One wave component at w = 0.6 rad/s travelling at 25 deg (between the file's 20 and 30
    deg): the component's series is Re(a X e^{i (w t + phase)}) with X from the .3 file,
    interpolated half way in heading, to 1e-5 of its amplitude (the file's frequency is
    2 pi / PER, 0.6 rad/s to its printed digits)."""
    period = 10 * 2 * np.pi / 0.6
    waves = WaveComponents(np.array([10 / period]), np.array([1.5]), np.array([0.7]), np.radians([25.0]), period)
    samples, step = excitation_series(wamit_data(volturnus.potential_flow, volturnus.environment), waves)
    three = wamit.read_3(ROOT.with_name(ROOT.name + ".3"), RHO, G)
    k = int(np.argmin(np.abs(three.omega_rad_s - 0.6)))
    h20, h30 = (int(np.flatnonzero(three.heading_deg == h)[0]) for h in (20.0, 30.0))
    x = 0.5 * (three.force_per_amplitude_si[k, h20] + three.force_per_amplitude_si[k, h30])
    t = np.arange(samples.shape[0]) * step
    expected = (1.5 * x[None, :] * np.exp(1j * (0.6 * t[:, None] + 0.7))).real
    assert np.abs(samples - expected).max() < 1e-5 * np.abs(1.5 * x).max()


@pytest.mark.slow
def test_volturnus_s_simulates_from_the_command_line(tmp_path):
    """``fowt-sim simulate --platform volturnus_s --load-case lc5.2``: each potential-flow
    component has its columns, and the hull heaves and surges in the 6.3 m sea."""
    out = tmp_path / "run"
    done = subprocess.run([sys.executable, "-m", "fowt_hydro_sim.cli", "simulate", "--platform", "volturnus_s",
                           "--load-case", "lc5.2", "--duration", "120", "-o", str(out)],
                          capture_output=True, text=True, timeout=600, cwd=Path(__file__).resolve().parents[1])
    assert done.returncode == 0, done.stderr
    with open(out / "timeseries.csv") as f:
        rows = list(csv.DictReader(f))
    for name in ("potential_hydrostatic", "radiation", "excitation", "added_matrices", "linear_mooring"):
        assert any(float(r[f"{name}_fx_n"]) or float(r[f"{name}_fz_n"]) for r in rows), name
    heave = np.array([float(r["heave_m"]) for r in rows])
    assert 0.1 < heave.std() < 3.0


def test_radiation_none_keeps_the_infinite_frequency_added_mass(volturnus):
    from fowt_hydro_sim.physics.loads import ComponentInputs
    plain = replace(volturnus, potential_flow=replace(volturnus.potential_flow, radiation="none"))
    params, table = radiation_load.parameters(ComponentInputs(plain, None, None, None, None, None, 0.05))
    mass = np.zeros((6, 6))
    out = np.zeros(6)
    y = np.zeros(12)
    y[6] = 1.0
    radiation_load.wrench(0.0, y, np.eye(3), params, table, out, mass)
    assert not out.any()
    assert np.array_equal(mass, wamit_data(plain.potential_flow, plain.environment).radiation.added_mass_inf_si)


def test_newman_drift_of_a_regular_wave_is_the_12d_diagonal(volturnus):
    """The drift component (Newman's approximation) of volturnus_s in a regular wave of 2 m at
    1.25 rad/s is the constant a^2 F(w, w), F the surge QTF's diagonal of the .12d file (read
    here, not from the YAML), within 1e-4."""
    from fowt_hydro_sim.physics.loads.drift import newman_force
    period = 25 * 2 * np.pi / 1.25
    waves = WaveComponents(np.array([25 / period]), np.array([2.0]), np.array([0.3]), np.array([0.0]), period)
    samples, _ = newman_force(waves, volturnus.drift_coefficients_n_m2)
    qtf = wamit.read_12d(ROOT.with_name(ROOT.name + ".12d"), RHO, G)
    k = int(np.argmin(np.abs(qtf.omega_rad_s - 1.25)))
    expected = 4.0 * qtf.mean_drift()[0, k, 0]
    assert np.allclose(samples[:, 0], expected, rtol=1e-4)
    assert np.allclose(samples[:, 1], 0.0, atol=1e-6 * expected)


@pytest.mark.slow
@pytest.mark.ros
def test_the_node_runs_volturnus_s_as_the_offline_model():
    """``fowt-sim node`` with ``platform:=volturnus_s`` (20 s of lc5.2 as fast as possible): its
    poses are the offline model's, bit for bit in position (the radiation memory's ring is
    stepped the same way one dt at a time as in a batch run)."""
    pytest.importorskip("rclpy")
    import time

    from geometry_msgs.msg import PoseStamped

    import msg_adapters as adapt
    from fowt_hydro_sim.physics.config import load_case
    from fowt_hydro_sim.physics.model import PlatformModel
    from fowt_hydro_sim.physics.waves.components import repeat_period, synthesize
    from fowt_hydro_sim.testing.ros import Listener, finish, start

    listener = Listener({"/platform/pose": PoseStamped})
    node = start("node", platform="volturnus_s", drag_model="constant", duration_s=20.0, real_time_factor=0.0,
                 load_case="lc5.2", seed=3, wait_for_subscribers=1)
    try:
        listener.wait_for(lambda: node.poll() is not None, 180.0)
        output = finish(node, 10)
        time.sleep(0.3)
    finally:
        listener.close()
    assert "duration 20 s reached" in output, output
    rows = dict(adapt.motion_from_pose(msg) for msg in listener.messages["/platform/pose"])
    t = np.array(sorted(rows))
    motion = np.array([rows[k] for k in t])
    sea = load_case("lc5.2").sea_state
    sea = type(sea)(sea.hs_m, sea.tp_s, sea.gamma, seed=3)
    offline = PlatformModel(load_platform("volturnus_s"), synthesize(sea, repeat_period(sea, 20.0)),
                            dt_s=0.05).run(20.0, output_interval_s=0.05)
    index = np.rint(t / 0.05).astype(int)
    assert len(t) > 300 and np.abs(motion[:, 2]).max() > 0.05
    np.testing.assert_array_equal(motion[:, :3], offline.motion[index, :3])


HYDRODYN_DECK = DATA / "IEA-15-240-RWT-UMaineSemi_HydroDyn.dat"


def _deck_copy(folder: Path, **fields: str) -> Path:
    """The VolturnUS-S HydroDyn deck in ``folder`` with some switches changed (``NAME=value``)
    and its HydroData beside it (a link to the packaged files)."""
    lines = HYDRODYN_DECK.read_text().splitlines()
    for name, value in fields.items():
        k = next(i for i, line in enumerate(lines) if line.split()[1:2] == [name])
        lines[k] = f"{value:>14}   {name}" + lines[k].split(name, 1)[1]
    deck = folder / "deck" / "HydroDyn.dat"
    deck.parent.mkdir()
    deck.write_text("\n".join(lines) + "\n")
    (deck.parent / "HydroData").symlink_to(DATA / "HydroData")
    return deck


@pytest.mark.slow
def test_platform_import_refuses_the_full_qtf_in_one_line(tmp_path, capsys):
    """The OpenFAST deck itself asks for the full difference-frequency QTF (DiffQTF 12), which
    the model does not have: refused, naming the field; so are RdtnMod 3 (no such model) and
    ExctnMod 2 (the excitation's state space)."""
    from fowt_hydro_sim.cli import main
    for fields, message in (({}, "DiffQTF 12"), ({"DiffQTF": "0", "RdtnMod": "3"}, "RdtnMod 3"),
                            ({"DiffQTF": "0", "ExctnMod": "2"}, "ExctnMod 2")):
        folder = tmp_path / str(len(message)) / message.split()[0]
        folder.mkdir(parents=True)
        deck = _deck_copy(folder, **fields)
        assert main(["platform", "import", str(deck), "-o", str(folder / "out.yaml")]) == 2
        err = capsys.readouterr().err.strip()
        assert message in err and len(err.splitlines()) == 1 and "Traceback" not in err, err


@pytest.mark.slow
def test_platform_import_of_a_potmod_1_deck_is_the_packaged_hull(tmp_path, volturnus):
    """The deck with NewmanApp 12 in place of DiffQTF 12, imported: its potential flow is the
    packaged volturnus_s's (the WAMIT files found relative to the deck, as HydroDyn finds them),
    its drift table the packaged one (the .12d diagonal), and ``fowt-sim loads`` at rest gives
    the buoyancy rho g PtfmVol0 in the potential_hydrostatic row."""
    from fowt_hydro_sim.cli import main
    deck = _deck_copy(tmp_path, DiffQTF="0", NewmanApp="12")
    out = tmp_path / "imported" / "hull.yaml"
    out.parent.mkdir()
    assert main(["platform", "import", str(deck), "-o", str(out), "--water-depth", "200"]) == 0
    imported = load_platform(out)
    assert Path(imported.potential_flow.wamit_root).resolve() == Path(volturnus.potential_flow.wamit_root).resolve()
    assert replace(imported.potential_flow, wamit_root="") == replace(volturnus.potential_flow, wamit_root="")
    assert np.allclose(imported.drift_coefficients_n_m2, volturnus.drift_coefficients_n_m2, atol=0.06)
    rest = np.zeros((3, 19))
    rest[:, 0] = [0.0, 0.05, 0.1]
    motion, loads = tmp_path / "rest.dat", tmp_path / "loads.csv"
    np.savetxt(motion, rest)
    assert main(["loads", "--platform", str(out), "--motion", str(motion), "--still-water", "-o", str(loads)]) == 0
    table = np.genfromtxt(loads, delimiter=",", names=True)
    assert np.allclose(table["potential_hydrostatic_Fz"], RHO * G * 20206.34889, rtol=1e-8)


def test_radiation_memory_of_a_coarser_prescribed_motion_is_the_stepped_ones(volturnus):
    """``fowt-sim loads`` evaluates the loads only at the motion's samples: sampled every 0.2 s
    (four model steps of 0.05 s), a harmonic surge velocity at 0.5 rad/s gives the memory force
    of the same motion evaluated at every step within 0.2 % of its amplitude (the skipped
    steps' velocities filled linearly; read as stale ring entries, they put the force off by
    1.3 times its amplitude)."""
    from fowt_hydro_sim.physics.loads import ComponentInputs
    params, table = radiation_load.parameters(ComponentInputs(volturnus, None, None, None, None, None, 0.05))
    forces = {}
    for every in (1, 4):
        p, tab = params.copy(), table.copy()
        times = np.arange(0, 6000, every) * 0.05
        y, out, mass = np.zeros(12), np.zeros(6), np.zeros((6, 6))
        force = np.zeros(times.size)
        for n, time in enumerate(times):
            y[6] = np.cos(0.5 * time)
            out[:] = 0.0
            radiation_load.wrench(time, y, np.eye(3), p, tab, out, mass)
            force[n] = out[0]
        forces[every] = force
    fine, coarse = forces[1][::4], forces[4]
    tail = slice(coarse.size // 2, None)
    assert np.abs(coarse[tail] - fine[tail]).max() < 2e-3 * np.abs(fine[tail]).max()


def test_a_drag_only_member_loads_the_hull_with_its_drag_alone(volturnus, tmp_path):
    """HydroDyn's PropPot member on a potential-flow hull: a vertical column (D 10 m, 20 m
    draft, Cd 0.6, Ca 1) marked ``drag_only`` moving in surge at v = 1.5 m/s with a = 0.4 m/s^2
    in still water carries the drag -0.5 rho Cd D T |v| v and nothing else: no inertia, added
    mass or buoyancy (the WAMIT data hold those); unmarked, the same member has them."""
    from fowt_hydro_sim.physics.loads import ROW
    from fowt_hydro_sim.physics.model import PlatformModel
    document = platform_document(volturnus)
    document["members"] = [{"name": "column", "section": "circular", "diameter_m": 10.0, "end_a_m": [0, 0, -20.0],
                            "end_b_m": [0, 0, 10.0], "strip_length_m": 1.0, "drag_only": True,
                            "zones": [{"name": "all", "ca": 1.0, "cd": 0.6}]}]
    state = np.zeros((1, 6))
    velocity, acceleration = state.copy(), state.copy()
    velocity[0, 0], acceleration[0, 0] = 1.5, 0.4
    rows = {}
    for drag_only in (True, False):
        document["members"][0]["drag_only"] = drag_only
        model = PlatformModel(platform_from_dict(document, "hybrid", tmp_path), None, dt_s=0.05)
        rows[drag_only] = model.prescribed_motion_loads(np.zeros(1), state, velocity, acceleration)[0]
    hybrid, plain = rows[True], rows[False]
    assert hybrid[ROW["drag"], 0] == pytest.approx(-0.5 * RHO * 0.6 * 10.0 * 20.0 * 1.5**2, rel=1e-9)
    for name in ("inertia", "added_mass", "hydrostatic"):
        assert not np.any(hybrid[ROW[name]]), name
    assert plain[ROW["added_mass"], 0] == pytest.approx(-RHO * np.pi * 25.0 * 20.0 * 0.4, rel=1e-9)
    assert plain[ROW["hydrostatic"], 2] == pytest.approx(RHO * G * np.pi * 25.0 * 20.0, rel=1e-9)
    assert np.array_equal(hybrid[ROW["potential_hydrostatic"]], plain[ROW["potential_hydrostatic"]])


def test_a_hull_without_members_runs_with_either_drag_model(volturnus):
    """Without Morison members there is no drag to filter: the node's default ``filtered``
    drag model runs volturnus_s, as the ``constant`` one does, to the same numbers."""
    from fowt_hydro_sim.physics.model import PlatformModel
    runs = [PlatformModel(volturnus, None, dt_s=0.05, drag_model=drag).run(5.0).motion for drag in ("filtered",
                                                                                                     "constant")]
    assert np.array_equal(runs[0], runs[1])


def test_a_malformed_wamit_file_stops_a_run_in_one_line(volturnus, tmp_path, capsys):
    """A WAMIT file with a word where a number belongs: ``fowt-sim simulate`` ends with exit
    code 2 and one line naming the file and the line, no traceback."""
    import yaml

    from fowt_hydro_sim.cli import main
    folder = tmp_path / "HydroData"
    folder.mkdir()
    for extension in (".1", ".hst", ".3"):
        text = ROOT.with_name(ROOT.name + extension).read_text()
        if extension == ".1":
            lines = text.splitlines()
            lines[40] = lines[40].replace(lines[40].split()[3], "oops", 1)
            text = "\n".join(lines) + "\n"
        (folder / ("hull" + extension)).write_text(text)
    document = platform_document(volturnus)
    document["potential_flow"]["wamit_root"] = str(folder / "hull")
    platform_file = tmp_path / "hull.yaml"
    platform_file.write_text(yaml.safe_dump(document))
    assert main(["simulate", "--platform", str(platform_file), "--still-water", "--duration", "1",
                 "-o", str(tmp_path / "run")]) == 2
    err = capsys.readouterr().err.strip()
    assert "hull.1:41: 'oops' is not a number" in err and len(err.splitlines()) == 1, err


def test_the_restoring_matrix_of_a_potential_flow_hull_is_the_hst_with_gravity_and_mooring():
    """Oracle: the WAMIT .hst (redimensionalised), the linear mooring's and AddCLin matrices as
    the platform gives them, and the weight's stiffness in closed form (K44 = K55 = -m g z_G,
    K46 = m g x_G, K56 = m g y_G for small rotations): the model's restoring matrix by central
    differences equals their sum within 1e-8 of each entry's diagonal scale. Once it held only the
    Morison rows: a potential-flow hull's matrix was singular and its natural periods wrong."""
    from fowt_hydro_sim.physics.model import PlatformModel
    platform = load_platform("volturnus_s")
    env, pf = platform.environment, platform.potential_flow
    g, mass, (x, y, z) = env.gravity_m_s2, platform.mass.mass_kg, platform.mass.cog_m
    expected = (wamit.read_hst(pf.wamit_root + ".hst", env.water_density_kg_m3, g).stiffness_si
                + np.array(platform.linear_mooring.stiffness) + np.array(pf.added_stiffness))
    expected[3, 3] -= mass * g * z
    expected[4, 4] -= mass * g * z
    expected[3, 5] += mass * g * x
    expected[4, 5] += mass * g * y
    restoring = PlatformModel(platform, None, dt_s=0.05).restoring_matrix()
    scale = np.sqrt(np.outer(np.diag(expected), np.diag(expected)))
    assert np.all(np.abs(restoring - expected) <= 1e-8 * scale), (restoring - expected) / scale
