"""VolturnUS-S in the time domain against references the model did not make: free decay
against OpenFAST's linearisation (the A matrix of a ``.lin`` file at the lowest wind speed),
the mooring against MoorPy, and the regular-wave response against the frequency-domain
solution of WAMIT's own coefficients."""
from __future__ import annotations

from dataclasses import replace
from importlib import resources
from pathlib import Path

import numpy as np
import pytest

from fowt_hydro_sim.physics.config import LinearMooring, load_platform
from fowt_hydro_sim.physics.hydro import wamit
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import WaveComponents
from fowt_hydro_sim.testing import decay
from fowt_hydro_sim.testing.decay import equilibrium

LIN = Path(__file__).parent / "data" / "volturnus_s" / "lin_00.1.A.lin"
MOORDYN = (Path(str(resources.files("fowt_hydro_sim.physics"))) / "data" / "platforms" / "volturnus_s"
           / "IEA-15-240-RWT-UMaineSemi_MoorDyn.dat")
# the .lin's operating point: ElastoDyn's platform surge, heave, pitch (its state list)
LIN_OPERATING_POINT = np.array([5.636, 0.0, -2.106e-2, 0.0, -4.887e-3, 0.0])


def lin_state_matrix(path: Path) -> np.ndarray:
    """The A matrix of an OpenFAST ``.lin`` file."""
    lines = path.read_text().splitlines()
    start = next(k for k, line in enumerate(lines) if line.startswith("A:"))
    n = int(lines[start].split()[1])
    return np.array([[float(v) for v in lines[start + 1 + r].split()] for r in range(n)])


def lin_platform_periods(a: np.ndarray) -> dict[str, float]:
    """The damped periods 2 pi / Im(lambda) of the platform modes: for each of surge, heave and
    pitch (states 1-3), the lightly damped (zeta < 0.3) eigenvalue whose eigenvector's largest
    displacement (pitch weighted by 50 m) is in that DOF."""
    values, vectors = np.linalg.eig(a)
    periods: dict[str, float] = {}
    for k in np.argsort(np.abs(values)):
        value = values[k]
        if value.imag <= 0 or -value.real / abs(value) > 0.3:
            continue
        displacement = np.abs(vectors[:4, k]) * np.array([1.0, 1.0, 50.0, 1.0])
        dof = ("surge", "heave", "pitch", "tower")[int(np.argmax(displacement))]
        periods.setdefault(dof, 2 * np.pi / value.imag)
    return periods


def moorpy_mooring(offset: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The MoorDyn deck's three lines in MoorPy, the body at ``offset``: the lines' wrench on it
    and their 6x6 stiffness (about the reference point)."""
    import moorpy as mp
    lines = MOORDYN.read_text().splitlines()
    row = lambda key: next(line.split() for line in lines if line.split()[:1] == [key])  # noqa: E731
    diameter, mass_density, ea = (float(v) for v in row("main")[1:4])
    points = {int(p[0]): (p[1], tuple(float(v) for v in p[2:5]))
              for p in (line.split() for line in lines) if len(p) >= 5 and p[1] in ("Vessel", "Fixed")}
    system = mp.System(depth=200.0, rho=1025.0, g=9.80665)
    system.addBody(-1, offset)
    weight = (mass_density - 1025.0 * np.pi / 4 * diameter**2) * 9.80665
    system.lineTypes["main"] = {"name": "main", "d_vol": diameter, "m": mass_density, "EA": ea, "w": weight,
                                "input_d": diameter, "MBL": 0, "EI": 0, "Cd": 0, "Ca": 0, "CdAx": 0, "CaAx": 0}
    for anchor, fairlead in ((2, 1), (4, 3), (6, 5)):
        system.addPoint(1, points[anchor][1])
        system.addPoint(1, points[fairlead][1])
        system.bodyList[0].attachPoint(len(system.pointList), points[fairlead][1])
        system.addLine(850.0, "main", pointA=len(system.pointList) - 1, pointB=len(system.pointList))
    system.initialize()
    system.bodyList[0].setPosition(offset)
    system.solveEquilibrium()
    return system.bodyList[0].getForces(lines_only=True), system.getCoupledStiffness(lines_only=True)


def lin_mooring_platform(platform):
    """The platform with its mooring linearised by MoorPy at the .lin's operating point (the
    force at rest kept at the undisplaced position's)."""
    force, _ = moorpy_mooring(np.zeros(6))
    _, stiffness = moorpy_mooring(LIN_OPERATING_POINT)
    return replace(platform, linear_mooring=LinearMooring(tuple(force), tuple(map(tuple, stiffness))))


def free_decay_periods(platform) -> dict[str, float]:
    """Free-decay periods (still water, rotor absent from the loads): surge from +5 m (800 s),
    heave from +1 m (200 s), pitch from +2 deg (300 s), each about the model's own equilibrium."""
    return decay.free_decay_periods(platform, {"surge": 800.0, "heave": 200.0, "pitch": 300.0})


@pytest.fixture(scope="module")
def decays() -> dict[str, float]:
    """Free-decay periods of volturnus_s with the mooring linearised at the .lin's operating point."""
    return free_decay_periods(lin_mooring_platform(load_platform("volturnus_s")))


def lin_operating_point_mass_kg(platform) -> float:
    """The system mass the .lin's operating point balances in heave: rho g (PtfmVol0 + A_wp
    (-heave)) buoyancy less the lines' downward pull there (MoorPy), over g; A_wp from the .hst.
    (The rotor's thrust, tilted 6 deg, would pull some 45 kN more down: 4.5 t, left out.)"""
    env = platform.environment
    rho, g = env.water_density_kg_m3, env.gravity_m_s2
    c33 = wamit.read_hst(platform.potential_flow.wamit_root + ".hst", rho, g).stiffness_si[2, 2]
    force, _ = moorpy_mooring(LIN_OPERATING_POINT)
    return (rho * g * platform.potential_flow.displaced_volume_m3 - c33 * LIN_OPERATING_POINT[2] + force[2]) / g


def with_tower_mass_adjusted(platform, folder: Path, mass_kg: float):
    """The platform with the rigid system's mass properties recomputed from the packaged ElastoDyn
    deck with the tower's mass density scaled (ElastoDyn's AdjTwMa) so that the system's mass is
    ``mass_kg``."""
    from fowt_hydro_sim.io.elastodyn import system_mass_properties

    packaged = MOORDYN.parent
    deck, blade = folder / "IEA-15-240-RWT-UMaineSemi_ElastoDyn.dat", packaged / "IEA-15-240-RWT_ElastoDyn_blade.dat"
    deck.write_text((packaged / deck.name).read_text())
    tower = (packaged / "IEA-15-240-RWT-UMaineSemi_ElastoDyn_tower.dat").read_text()

    def mass_with(factor: float) -> float:
        lines = [f"{float(factor)!r}   AdjTwMa     - Factor to adjust tower mass density (-)" if " AdjTwMa " in line
                 else line for line in tower.splitlines()]
        (folder / "IEA-15-240-RWT-UMaineSemi_ElastoDyn_tower.dat").write_text("\n".join(lines) + "\n")
        return system_mass_properties(deck, blade).mass_kg

    full, empty = mass_with(1.0), mass_with(0.0)  # the system's mass is linear in AdjTwMa
    mass_with((mass_kg - empty) / (full - empty))
    mass = system_mass_properties(deck, blade)
    assert mass.mass_kg == pytest.approx(mass_kg, rel=1e-9)
    return replace(platform, mass=mass)


@pytest.fixture(scope="module")
def decays_at_the_lin_mass(tmp_path_factory) -> dict[str, float]:
    """Free-decay periods as ``decays``, the tower 153 t lighter: the system's mass the .lin's
    operating point balances (``lin_operating_point_mass_kg``)."""
    platform = load_platform("volturnus_s")
    target = lin_operating_point_mass_kg(platform)
    assert platform.mass.mass_kg - target == pytest.approx(153e3, abs=1e3)
    lighter = with_tower_mass_adjusted(platform, tmp_path_factory.mktemp("elastodyn"), target)
    return free_decay_periods(lin_mooring_platform(lighter))


@pytest.mark.slow
@pytest.mark.reference
def test_the_packaged_linear_mooring_is_moorpys_at_rest():
    """The YAML's linear mooring is MoorPy's linearisation of the MoorDyn deck's lines at the
    undisplaced position (its heave force and the surge, heave, pitch and yaw stiffness;
    symmetrised, as the YAML says)."""
    platform = load_platform("volturnus_s")
    force, stiffness = moorpy_mooring(np.zeros(6))
    packaged = np.array(platform.linear_mooring.stiffness)
    assert platform.linear_mooring.force_at_rest_n[2] == pytest.approx(force[2], rel=1e-4)
    for i, j in ((0, 0), (2, 2), (4, 4), (5, 5), (0, 4)):
        assert packaged[i, j] == pytest.approx((stiffness[i, j] + stiffness[j, i]) / 2, rel=1e-3), (i, j)


LIN_PERIODS = lin_platform_periods(lin_state_matrix(LIN))
DEVIATION_REASON = ("the .lin (Feb 2021) balances a system 153 t lighter than the packaged ElastoDyn deck's "
                    "(its floating tower redesigned since); measured +3.15 % (surge) and +3.22 % (pitch): "
                    "docs/physics/potential_flow.md")


@pytest.mark.slow
@pytest.mark.reference
@pytest.mark.parametrize("dof", [
    "heave",
    pytest.param("surge", marks=pytest.mark.xfail(reason=DEVIATION_REASON, strict=True)),
    pytest.param("pitch", marks=pytest.mark.xfail(reason=DEVIATION_REASON, strict=True)),
])
def test_free_decay_periods_match_openfasts_linearisation(decays, dof):
    """The damped free-decay period of each platform mode within 3 % of the .lin's eigenvalue
    (5 m/s, azimuth 0: surge 123.2 s, heave 20.38 s, pitch 27.26 s; 9 of the 12 azimuths of the
    set give these to 0.2 %, the other three 2 % longer surge and 1.3 % longer pitch)."""
    assert decays[dof] == pytest.approx(LIN_PERIODS[dof], rel=0.03)


@pytest.mark.slow
@pytest.mark.reference
@pytest.mark.parametrize("dof", ["surge", "heave", "pitch"])
def test_free_decay_periods_match_openfasts_linearisation_at_its_own_system_mass(decays_at_the_lin_mass, dof):
    """Like for like with the .lin: the system's mass the .lin's own operating point balances in
    heave (20,099 t against the packaged deck's 20,252 t), the difference taken off the tower (the
    floating tower was redesigned after the .lin was made), mooring linearised at its operating
    point: each period within 3 % of the .lin's eigenvalue (measured: surge +2.98 %, heave +0.19 %,
    pitch +0.94 %). Surge passes by a margin of 0.02 % and the mass does not explain it (it moves
    surge by 0.2 %); with the 153 t taken off the platform's centre of mass instead of the tower,
    pitch stays 3.6 % long: docs/physics/potential_flow.md."""
    assert decays_at_the_lin_mass[dof] == pytest.approx(LIN_PERIODS[dof], rel=0.03)


def test_the_lin_periods_are_read_as_documented():
    assert LIN_PERIODS["surge"] == pytest.approx(123.24, abs=0.01)
    assert LIN_PERIODS["heave"] == pytest.approx(20.38, abs=0.01)
    assert LIN_PERIODS["pitch"] == pytest.approx(27.26, abs=0.01)


def _skew(v: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def _gravity_stiffness(mass_kg: float, cog_m: np.ndarray, g: float) -> np.ndarray:
    """-d(weight's wrench about the reference point)/dq at rest, R = Rz Ry Rx (central differences)."""
    def wrench(q: np.ndarray) -> np.ndarray:
        (cx, sx), (cy, sy), (cz, sz) = ((np.cos(a), np.sin(a)) for a in q[3:])
        rotation = (np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]]) @ np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
                    @ np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]]))
        force = np.array([0.0, 0.0, -mass_kg * g])
        return np.concatenate([force, np.cross(rotation @ cog_m, force)])
    return np.stack([-(wrench(1e-6 * e) - wrench(-1e-6 * e)) / 2e-6 for e in np.eye(6)], axis=1)


@pytest.mark.slow
@pytest.mark.reference
@pytest.mark.parametrize("omega", [0.5, 0.8, 1.2])
def test_regular_wave_response_is_the_frequency_domain_solution_of_the_wamit_coefficients(omega):
    """A 0.5 m regular wave at heading 0: the steady surge, heave and pitch of the time-domain
    model (excitation, radiation memory, hydrostatics, gravity, mooring) are the solution of
    [-w^2 (M + A(w)) + i w (B(w) + B_lin) + C + K_mooring + K_gravity] xi = X(w) a, with A, B,
    C and X read from the .1, .hst and .3 files at w, M the rigid body's 6x6 mass, within 1 % in
    amplitude and 1 deg in phase. AddBQuad and the slow drift are left out (nonlinear), a linear
    damping of 20 % of critical in surge, heave and pitch put in both (so that the start's free
    oscillation dies within the 400 s); the run starts at rest plus the expected response."""
    platform = load_platform("volturnus_s")
    env, mass = platform.environment, platform.mass
    rho, g = env.water_density_kg_m3, env.gravity_m_s2
    root = platform.potential_flow.wamit_root
    one, three = wamit.read_1(root + ".1", rho), wamit.read_3(root + ".3", rho, g)
    k = int(np.argmin(np.abs(one.omega_rad_s - omega)))
    assert one.omega_rad_s[k] == pytest.approx(omega)
    added, damping = one.added_mass_si[k], one.damping_si[k]
    excitation = three.force_per_amplitude_si[k, int(np.flatnonzero(three.heading_deg == 0.0)[0])]
    m, cog, inertia = mass.mass_kg, np.array(mass.cog_m), np.array(mass.inertia_about_cog_kg_m2)
    rigid = np.block([[m * np.eye(3), -m * _skew(cog)], [m * _skew(cog), inertia - m * _skew(cog) @ _skew(cog)]])
    stiffness = (wamit.read_hst(root + ".hst", rho, g).stiffness_si + np.array(platform.linear_mooring.stiffness)
                 + _gravity_stiffness(m, cog, g))
    linear = np.zeros((6, 6))
    for i in (0, 2, 4):
        linear[i, i] = 0.4 * np.sqrt(stiffness[i, i] * (rigid[i, i] + added[i, i]))
    amplitude, phase = 0.5, 0.3
    expected = np.linalg.solve(-omega**2 * (rigid + added) + 1j * omega * (damping + linear) + stiffness,
                               excitation) * amplitude * np.exp(1j * phase)
    flow = replace(platform.potential_flow, added_quadratic_damping=((0.0,) * 6,) * 6,
                   added_linear_damping=tuple(map(tuple, linear)))
    platform = replace(platform, potential_flow=flow, drift_coefficients_n_m2=())
    period = 40 * 2 * np.pi / omega
    waves = WaveComponents(np.array([40 / period]), np.array([amplitude]), np.array([phase]), np.zeros(1), period)
    rest = equilibrium(PlatformModel(platform, None, dt_s=0.05))
    model = PlatformModel(platform, waves, dt_s=0.05)
    model.reset(motion=rest + expected.real, velocity=(1j * omega * expected).real)
    result = model.run(400.0, output_interval_s=0.05)
    last = result.time_s > result.time_s[-1] - 8 * 2 * np.pi / omega
    t = result.time_s[last]
    basis = np.stack([np.ones(t.size), np.cos(omega * t), np.sin(omega * t)], axis=1)
    for dof in (0, 2, 4):
        (_, c_cos, c_sin), *_ = np.linalg.lstsq(basis, result.motion[last, dof], rcond=None)
        measured = c_cos - 1j * c_sin
        assert abs(measured) == pytest.approx(abs(expected[dof]), rel=0.01), dof
        assert abs(np.degrees(np.angle(measured / expected[dof]))) < 1.0, dof


def test_volturnus_s_moors_by_its_matrix_or_by_the_lines_it_is_given():
    """The default ``linear`` mooring is the packaged matrix; a run that chooses ``moorpy`` gets
    the MoorDyn deck's catenaries instead (the matrix then off, not added to them). Reference:
    MoorPy's catenaries through the tables, their surge stiffness by central differences at
    +-0.5 m and their force at rest, against the matrix's K and F0."""
    from fowt_hydro_sim.physics.loads import ComponentInputs
    from fowt_hydro_sim.physics.loads import linear_mooring as linear_load
    from fowt_hydro_sim.physics.loads import mooring as lines_load

    platform = load_platform("volturnus_s")
    assert platform.mooring.model == "linear" and platform.mooring.file.endswith("_MoorDyn.dat")

    def wrenches(mooring_model: str, surge_m: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
        y = np.zeros(12)
        y[0] = surge_m
        chosen = replace(platform, mooring=platform.mooring.chosen(mooring_model))
        inputs = ComponentInputs(chosen, None, None, None, None, None, 0.05)
        out = []
        for load in (linear_load, lines_load):
            params, table = load.parameters(inputs)
            wrench = np.zeros(6)
            load.wrench(0.0, y, np.eye(3), params, table, wrench, np.zeros((6, 6)))
            out.append(wrench)
        return out[0], out[1]

    stiffness = platform.linear_mooring.stiffness[0][0]
    matrix, lines = wrenches("", 5.0)
    assert not lines.any() and matrix[0] == pytest.approx(-5.0 * stiffness)
    matrix, lines = wrenches("moorpy")
    assert not matrix.any() and lines[2] == pytest.approx(platform.linear_mooring.force_at_rest_n[2], rel=0.01)
    central = (wrenches("moorpy", -0.5)[1][0] - wrenches("moorpy", 0.5)[1][0]) / 1.0
    assert central == pytest.approx(stiffness, rel=0.01)
