"""VolturnUS-S free decay against OpenFAST's linearisation (the A matrix of a ``.lin`` file
at the lowest wind speed) and MoorPy's mooring stiffness: references the model did not make."""
from __future__ import annotations

from dataclasses import replace
from importlib import resources
from pathlib import Path

import numpy as np
import pytest

from fowt_hydro_sim.physics.config import LinearMooring, load_platform
from fowt_hydro_sim.physics.model import PlatformModel

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


def equilibrium(model: PlatformModel) -> np.ndarray:
    """The still-water pose where the model's loads balance (Newton on its prescribed-motion loads)."""
    q, zero = np.zeros(6), np.zeros((1, 6))
    total = lambda pose: model.prescribed_motion_loads(np.zeros(1), pose[None], zero, zero)[0].sum(axis=0)  # noqa: E731
    for _ in range(4):
        f = total(q)
        jacobian = np.stack([(total(q + 1e-3 * np.eye(6)[j]) - f) / 1e-3 for j in range(6)], axis=1)
        q = q - np.linalg.solve(jacobian, f)
    return q


def decay_period(time_s: np.ndarray, x: np.ndarray) -> float:
    """The mean interval between up-crossings of zero."""
    up = np.flatnonzero((x[:-1] < 0) & (x[1:] >= 0))
    crossings = time_s[up] - x[up] * (time_s[up + 1] - time_s[up]) / (x[up + 1] - x[up])
    return float(np.diff(crossings).mean())


@pytest.fixture(scope="module")
def decays() -> dict[str, float]:
    """Free-decay periods of volturnus_s (still water, rotor absent from the loads) with the
    mooring linearised at the .lin's operating point: surge from +5 m (800 s), heave from +1 m
    (200 s), pitch from +2 deg (300 s), each about the model's own equilibrium."""
    platform = load_platform("volturnus_s")
    force, stiffness = moorpy_mooring(np.zeros(6))
    _, stiffness = moorpy_mooring(LIN_OPERATING_POINT)
    platform = replace(platform, linear_mooring=LinearMooring(tuple(force), tuple(map(tuple, stiffness))))
    model = PlatformModel(platform, None, dt_s=0.05)
    rest = equilibrium(model)
    periods = {}
    for name, dof, offset, duration in (("surge", 0, 5.0, 800.0), ("heave", 2, 1.0, 200.0),
                                        ("pitch", 4, np.radians(2.0), 300.0)):
        start = rest.copy()
        start[dof] += offset
        model.reset(motion=start)
        result = model.run(duration)
        periods[name] = decay_period(result.time_s, result.motion[:, dof] - rest[dof])
    return periods


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
DEVIATION_REASON = ("the .lin (Feb 2021) predates the packaged WAMIT data (Sep 2022) and ElastoDyn deck; "
                    "measured +3.15 % (surge) and +3.22 % (pitch): docs/physics/potential_flow.md")


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


def test_the_lin_periods_are_read_as_documented():
    assert LIN_PERIODS["surge"] == pytest.approx(123.24, abs=0.01)
    assert LIN_PERIODS["heave"] == pytest.approx(20.38, abs=0.01)
    assert LIN_PERIODS["pitch"] == pytest.approx(27.26, abs=0.01)
