"""Potential-flow groundwork: the WAMIT readers, the radiation kernel, and the VolturnUS-S data,
each checked against a reference the model did not make (a closed-form transform pair, the BEM
solver's own added mass, the platform's published geometry, hand-written files)."""
from __future__ import annotations

from importlib import resources
from pathlib import Path

import numpy as np
import pytest

from fowt_hydro_sim.physics.hydro import radiation, wamit

HYDRO_DATA = Path(str(resources.files("fowt_hydro_sim.physics"))) / "data" / "platforms" / "volturnus_s" / "HydroData"
ROOT = HYDRO_DATA / "IEA-15-240-RWT-UMaineSemi"
RHO, G = 1025.0, 9.80665  # the WAMIT run's density (its .frc file); HydroDyn's default gravity


def test_hydrodyn_kernel_grid():
    """NStepRdtn as HydroDyn sets it: RdtnTMax 60 s at RdtnDT 0.025 s gives 2401 samples (2400 =
    2 x 1200, a product of small primes); 2 x 1201 (1201 prime) is rounded up to 2 x 1210."""
    assert radiation.kernel_steps(60.0, 0.025) == 2401
    assert radiation.kernel_steps(2402 * 0.025 - 1e-9, 0.025) == 2 * 1210 + 1
    assert radiation.product_of_small_primes(29) == 30


def test_the_kernel_of_an_analytic_damping_and_back():
    """B(w) = b w^2 exp(-a w^2) has K(t) = b / (2 sqrt(pi) a^1.5) (1 - t^2 / 2a) exp(-t^2 / 4a);
    tabulated like a WAMIT run (0.05 to 5 rad/s in steps of 0.05) and transformed as HydroDyn
    does (RdtnTMax 60 s, RdtnDT 0.025 s), K is within 0.1 % of its peak, and B back from K
    within 0.2 % of its peak."""
    a, b = 1.0, 2.0e6
    omega = np.arange(1, 101) * 0.05
    damping = b * omega**2 * np.exp(-a * omega**2)
    kernel = radiation.retardation_kernel(omega, damping, 60.0, 0.025)
    t = kernel.time_s
    exact = b / (2 * np.sqrt(np.pi) * a**1.5) * (1 - t**2 / (2 * a)) * np.exp(-t**2 / (4 * a))
    assert t[-1] == pytest.approx(60.0)
    assert np.abs(kernel.kernel_si - exact).max() < 1e-3 * exact.max()
    back = radiation.damping_from_kernel(t, kernel.kernel_si, omega)
    assert np.abs(back - damping).max() < 2e-3 * damping.max()


def test_a_table_beyond_the_kernel_step_is_refused():
    """HydroDyn refuses RdtnDT > pi / (highest frequency): the cosine transform would cut the table."""
    with pytest.raises(ValueError, match="RdtnDT must be below"):
        radiation.retardation_kernel(np.array([1.0, 10.0]), np.array([1.0, 1.0]), 60.0, 0.5)


@pytest.mark.reference
@pytest.mark.parametrize("dof, tolerance", [(0, 0.035), (2, 0.01)], ids=["surge", "heave"])
def test_ogilvie_reproduces_the_volturnus_added_mass(dof: int, tolerance: float):
    """WAMIT solved A(w) and B(w) separately; A from B alone (kernel as HydroDyn computes it,
    then Ogilvie's relation with the file's A_inf) matches the file's A(w) at its 100
    frequencies within ``tolerance`` x A_inf (surge 3.5 %, heave 1 %; largest near 1.4 rad/s in
    surge, where B's cut-off at 5 rad/s matters most), and the zero-frequency limit within 2 %."""
    rad = wamit.read_1(ROOT.with_suffix(".1"), RHO)
    kernel = radiation.retardation_kernel(rad.omega_rad_s, rad.damping_si, 60.0, 0.025)
    a_inf = rad.added_mass_inf_si
    a = radiation.added_mass_from_kernel(kernel.time_s, kernel.kernel_si, a_inf, rad.omega_rad_s)
    assert np.abs(a[:, dof, dof] - rad.added_mass_si[:, dof, dof]).max() < tolerance * a_inf[dof, dof]
    a0 = radiation.added_mass_from_kernel(kernel.time_s, kernel.kernel_si, a_inf, np.array([0.0]))[0]
    assert a0[dof, dof] == pytest.approx(rad.added_mass_zero_si[dof, dof], rel=0.02)


def test_the_heave_stiffness_is_rho_g_times_the_waterplane_area():
    """VolturnUS-S pierces the water with three 12.5 m outer columns and a 10 m centre column
    (Allen et al. 2020, NREL/TP-5000-76773; RAFT's VolturnUS-S example: ``d: 12.5`` and
    ``d: 10.0``): rho g A_wp, A_wp = pi/4 (3 x 12.5^2 + 10^2) = 446.7 m^2, is the .hst's C33
    within 2 % (it is 0.8 % below: the panel mesh's polygonal waterline)."""
    c = wamit.read_hst(ROOT.with_suffix(".hst"), RHO, G).stiffness_si
    waterplane_m2 = np.pi / 4 * (3 * 12.5**2 + 10.0**2)
    assert c[2, 2] == pytest.approx(RHO * G * waterplane_m2, rel=0.02)


def test_the_volturnus_set_reads_whole():
    """The packaged set as HydroDyn reads it: 100 frequencies 0.05-5 rad/s with both limits,
    37 headings, 6 DOF, the .3's frequencies those of the .1, the QTF's diagonal real."""
    data = wamit.read_potential_flow(ROOT, RHO, G)
    assert data.radiation.omega_rad_s == pytest.approx(np.arange(1, 101) * 0.05, rel=1e-6)
    assert data.radiation.added_mass_si.shape == (100, 6, 6)
    assert data.excitation.heading_deg == pytest.approx(np.arange(-180, 181, 10))
    assert data.excitation.force_per_amplitude_si.shape == (100, 37, 6)
    qtf = data.difference_qtf
    assert qtf is not None and qtf.heading_pairs_deg.tolist() == [[0.0, 0.0]]
    assert not np.isnan(qtf.qtf_per_amplitude_squared_si).any()
    diagonal = np.diagonal(qtf.qtf_per_amplitude_squared_si, axis1=1, axis2=2)
    assert np.abs(diagonal.imag).max() < 1e-6 * np.abs(diagonal).max()


HAND_1 = """\
 -1.0  1 1  2.0
 -1.0  3 3  4.0
  0.0  1 1  1.0
  0.0  3 3  3.0
  0.0  5 5  5.0
  6.283185307179586  1 1  1.5  0.25
  6.283185307179586  3 5  0.5  0.125
  3.141592653589793  1 1  1.25  0.5
"""
HAND_3 = """\
  6.283185307179586  0.0  1  1.0  0.0  1.0  0.0
  6.283185307179586  0.0  5  2.0  90.0  0.0  2.0
  6.283185307179586  90.0  2  1.0  0.0  1.0  0.0
  3.141592653589793  0.0  1  3.0  0.0  3.0  0.0
  3.141592653589793  90.0  2  1.0  0.0  0.5  -0.5
"""
HAND_HST = """\
 3 3  100.0
 4 4  7.0
 3 5  -1.0
"""
HAND_12D = """\
  6.283185307179586  6.283185307179586  0.0  0.0  1  0.5  0.0  0.5  0.0
  3.141592653589793  6.283185307179586  0.0  0.0  1  1.0  0.0  0.25  0.75
  3.141592653589793  3.141592653589793  0.0  0.0  4  2.0  0.0  2.0  0.0
"""


def test_the_readers_scale_a_hand_written_set(tmp_path: Path):
    """Hand-written files (rho 1000, g 10, WAMITULEN 2 m) give the values of the module's
    scaling table: A x rho L^k, B x rho w L^k, C and X x rho g L^k, QTF x rho g L^k."""
    for suffix, text in ((".1", HAND_1), (".3", HAND_3), (".hst", HAND_HST), (".12d", HAND_12D)):
        (tmp_path / f"hand{suffix}").write_text(text)
    rho, g, ell = 1000.0, 10.0, 2.0
    data = wamit.read_potential_flow(tmp_path / "hand", rho, g, ell)
    rad = data.radiation
    assert rad.omega_rad_s == pytest.approx([1.0, 2.0])
    assert rad.added_mass_zero_si[0, 0] == pytest.approx(2.0 * rho * ell**3)
    assert rad.added_mass_inf_si[4, 4] == pytest.approx(5.0 * rho * ell**5)
    assert rad.added_mass_si[0, 0, 0] == pytest.approx(1.5 * rho * ell**3)
    assert rad.damping_si[0, 0, 0] == pytest.approx(0.25 * rho * 1.0 * ell**3)
    assert rad.damping_si[1, 0, 0] == pytest.approx(0.5 * rho * 2.0 * ell**3)
    assert rad.added_mass_si[0, 2, 4] == pytest.approx(0.5 * rho * ell**4)
    assert rad.damping_si[0, 2, 4] == pytest.approx(0.125 * rho * 1.0 * ell**4)
    assert rad.added_mass_si[1, 2, 4] == 0.0
    c = data.hydrostatics.stiffness_si
    assert (c[2, 2], c[3, 3], c[2, 4]) == pytest.approx((100 * rho * g * ell**2, 7 * rho * g * ell**4,
                                                        -rho * g * ell**3))
    exc = data.excitation
    assert exc.heading_deg.tolist() == [0.0, 90.0]
    assert exc.force_per_amplitude_si[0, 0, 0] == pytest.approx(1.0 * rho * g * ell**2)
    assert exc.force_per_amplitude_si[0, 0, 4] == pytest.approx(2.0j * rho * g * ell**3)
    assert exc.force_per_amplitude_si[1, 1, 1] == pytest.approx((0.5 - 0.5j) * rho * g * ell**2)
    qtf = data.difference_qtf.qtf_per_amplitude_squared_si[0]
    assert qtf[0, 0, 0] == pytest.approx(0.5 * rho * g * ell)
    assert qtf[1, 0, 0] == pytest.approx((0.25 + 0.75j) * rho * g * ell)
    assert qtf[0, 1, 0] == pytest.approx((0.25 - 0.75j) * rho * g * ell)  # the mirror, conjugated
    assert qtf[1, 1, 3] == pytest.approx(2.0 * rho * g * ell**2)
    assert np.isnan(qtf[0, 0, 3])
    assert data.difference_qtf.mean_drift()[0, 1, 3] == pytest.approx(2.0 * rho * g * ell**2)


def test_the_1_writer_round_trips(tmp_path: Path):
    """write_1 then read_1 gives back the SI matrices (8 significant digits in the file)."""
    source = wamit.read_1(ROOT.with_suffix(".1"), RHO)
    wamit.write_1(tmp_path / "copy.1", source, 1000.0, 3.0)
    back = wamit.read_1(tmp_path / "copy.1", 1000.0, 3.0)
    assert back.omega_rad_s == pytest.approx(source.omega_rad_s, rel=1e-7)
    for name in ("added_mass_si", "damping_si", "added_mass_zero_si", "added_mass_inf_si"):
        mine, theirs = getattr(back, name), getattr(source, name)
        assert np.allclose(mine, theirs, rtol=1e-7, atol=1e-7 * np.abs(theirs).max()), name


@pytest.mark.parametrize("suffix, text, message", [
    (".1", " 6.28  1 1  1.5  x.25\n", r"bad\.1:1: 'x\.25' is not a number"),
    (".1", " 0.0  1 1  1.0\n 6.28  1 1  1.5\n", r"bad\.1:2: a finite-frequency row holds PER I J A B"),
    (".hst", " 3 3 100.0\n 3 0 1.0\n", r"bad\.hst:2: DOF index '0' is not a positive integer"),
    (".3", " 6.28 0.0 1 1 0 1 0\n 6.28 90.0 1 1 0 1 0\n 3.14 0.0 1 1 0 1 0\n",
     r"bad\.3:3: period 3\.14 s has headings \[0\.0\], not those of the first period \[0\.0, 90\.0\]"),
    (".12d", "", r"bad\.12d: no data"),
], ids=["not-a-number", "short-row", "zero-index", "headings-differ", "empty"])
def test_a_malformed_file_is_refused_in_one_line(tmp_path: Path, suffix: str, text: str, message: str):
    """A malformed file raises WamitFormatError, one line naming the file and the line."""
    path = tmp_path / f"bad{suffix}"
    path.write_text(text)
    reader = {".1": lambda p: wamit.read_1(p, RHO), ".hst": lambda p: wamit.read_hst(p, RHO, G),
              ".3": lambda p: wamit.read_3(p, RHO, G), ".12d": lambda p: wamit.read_12d(p, RHO, G)}[suffix]
    with pytest.raises(wamit.WamitFormatError, match=message) as caught:
        reader(path)
    assert "\n" not in str(caught.value)


def test_a_set_without_the_frequency_limits_is_refused(tmp_path: Path):
    """HydroDyn needs the zero- and infinite-frequency added mass in the .1 file."""
    (tmp_path / "set.1").write_text(" 6.283185307179586  1 1  1.5  0.25\n")
    with pytest.raises(wamit.WamitFormatError, match=r"set\.1: needs both the zero-frequency"):
        wamit.read_potential_flow(tmp_path / "set", RHO, G)


@pytest.mark.slow
@pytest.mark.reference
def test_a_capytaine_heaving_cylinder_through_a_wamit_file(tmp_path: Path):
    """A heaving truncated vertical cylinder (radius 5 m, draft 10 m, deep water) solved by
    capytaine (a BEM the project did not write) at zero, 25 finite (0.12-3 rad/s) and infinite
    frequency, written as a WAMIT .1 file with WAMITULEN = 5 m and read back: the file holds
    WAMIT's nondimensional values (A / rho L^3, B / rho w L^3; read with numpy, not the reader),
    the reader returns capytaine's A and B, and A from capytaine's B by the kernel and Ogilvie's
    relation is capytaine's A within 1 % of A_inf (2 % at w = 0)."""
    cpt = pytest.importorskip("capytaine")
    import logging
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    radius, draft, rho, g = 5.0, 10.0, 1025.0, 9.81
    mesh = cpt.mesh_vertical_cylinder(length=draft + 2.0, radius=radius, center=(0.0, 0.0, -draft / 2 + 1.0),
                                      resolution=(4, 24, 10)).immersed_part()
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0.0, 0.0, 0.0)), name="cylinder")
    omega = np.arange(1, 26) * 0.12
    problems = [cpt.RadiationProblem(body=body, radiating_dof="Heave", omega=w, rho=rho, g=g)
                for w in (0.0, *omega, np.inf)]
    results = cpt.BEMSolver().solve_all(problems, progress_bar=False)
    a_heave = np.array([r.added_mass["Heave"] for r in results])
    b_heave = np.array([r.radiation_damping["Heave"] for r in results])[1:-1]

    def six(value: float) -> np.ndarray:
        m = np.zeros((6, 6))
        m[2, 2] = value
        return m
    source = wamit.Radiation(omega_rad_s=omega, added_mass_si=np.stack([six(a) for a in a_heave[1:-1]]),
                             damping_si=np.stack([six(b) for b in b_heave]), added_mass_zero_si=six(a_heave[0]),
                             added_mass_inf_si=six(a_heave[-1]))
    wamit.write_1(tmp_path / "cylinder.1", source, rho, radius)

    rows = np.loadtxt(tmp_path / "cylinder.1", usecols=(0, 1, 2, 3))
    heave = rows[(rows[:, 1] == 3) & (rows[:, 2] == 3)]
    assert heave[:, 0].tolist()[:2] == [-1.0, 0.0]
    assert heave[:, 3] == pytest.approx(np.concatenate([[a_heave[0], a_heave[-1]], a_heave[1:-1]])
                                        / (rho * radius**3), rel=1e-7)
    lines = (tmp_path / "cylinder.1").read_text().splitlines()
    finite = np.array([line.split() for line in lines if len(line.split()) == 5], float)  # PER I J A B
    b_file = finite[(finite[:, 1] == 3) & (finite[:, 2] == 3), 4]
    assert b_file == pytest.approx(b_heave / (rho * omega * radius**3), rel=1e-7, abs=1e-12)

    back = wamit.read_1(tmp_path / "cylinder.1", rho, radius)
    assert back.added_mass_si[:, 2, 2] == pytest.approx(a_heave[1:-1], rel=1e-7)
    assert back.damping_si[:, 2, 2] == pytest.approx(b_heave, rel=1e-7, abs=1e-6 * b_heave.max())
    assert back.added_mass_inf_si[2, 2] == pytest.approx(a_heave[-1], rel=1e-7)

    kernel = radiation.retardation_kernel(back.omega_rad_s, back.damping_si[:, 2, 2], 60.0, 0.025)
    a_ogilvie = radiation.added_mass_from_kernel(kernel.time_s, kernel.kernel_si, a_heave[-1],
                                                 np.concatenate([[0.0], omega]))
    assert np.abs(a_ogilvie[1:] - a_heave[1:-1]).max() < 0.01 * a_heave[-1]
    assert a_ogilvie[0] == pytest.approx(a_heave[0], rel=0.02)
