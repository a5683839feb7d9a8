"""Tapered members against closed forms (frustum buoyancy and centre of buoyancy, a pitched
frustum by numerical integration, the Froude-Krylov force on a submerged frustum) and OpenFAST
r-test HydroDyn cases (test/data/openfast_rtest, their README gives the source): one imported
with ``fowt-sim platform import`` and run with ``fowt-sim loads``, one (a rectangular member in
a regular wave, hydrostatics up to the instantaneous free surface) against the independent
free-surface hydrostatics of ``physics/free_surface_hydrostatics.py``."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import yaml
from scipy import integrate

from fowt_hydro_sim.cli import main
from fowt_hydro_sim.physics import free_surface_hydrostatics as fsh
from fowt_hydro_sim.physics.config import HYDRODYN, EndPlate, HydroOptions, load_platform, platform_from_dict
from fowt_hydro_sim.physics.loads import ROW
from fowt_hydro_sim.physics.loads.hydrostatic import hydrostatics
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.strips import discretise
from fowt_hydro_sim.physics.waves.components import WaveComponents
from fowt_hydro_sim.testing import REPO
from fowt_hydro_sim.testing.references import read_hydrodyn_out

RHO, G = 1025.0, 9.80665
RTEST = REPO / "test" / "data" / "openfast_rtest"
R_A, R_B, Z_A, Z_B = 4.5, 4.45, -30.0, 10.0  # the r-test tapered cylinder


def radius_at(z: float) -> float:
    return R_A + (R_B - R_A) * (z - Z_A) / (Z_B - Z_A)


def tapered_column(strip_length_m: float = 10.0, top_z_m: float = Z_B, plates_cp: float = 1.0,
                   taper_cp: float = 1.0):
    """One tapered vertical column (the r-test's geometry by default), no drag, no added mass."""
    p = load_platform("windmoor12")
    plate = EndPlate(ca=0.0, cp=plates_cp, cd=0.0)
    zone = dataclasses.replace(p.members[0].zones[0], below_z_m=math.inf, ca=(0.0, 0.0))
    zone = dataclasses.replace(zone, cd=tuple(dataclasses.replace(c, constant=0.0) for c in zone.cd))
    column = dataclasses.replace(p.members[0], end_a_m=(0.0, 0.0, Z_A), end_b_m=(0.0, 0.0, top_z_m),
                                 width_m=2 * R_A, height_m=2 * R_A, diameter_b_m=2 * radius_at(top_z_m),
                                 taper_axial=EndPlate(ca=0.0, cp=taper_cp, cd=0.0), zones=(zone,),
                                 strip_length_m=strip_length_m, end_a_plate=plate, end_b_plate=plate)
    return dataclasses.replace(p, members=(column,))


def frustum_below(z_top_m: float) -> tuple[float, float]:
    """Closed form: volume and centroid height of the column's part below z_top (upright)."""
    h, r0, r1 = z_top_m - Z_A, R_A, radius_at(z_top_m)
    s = r0 * r0 + r0 * r1 + r1 * r1
    return math.pi * h * s / 3, Z_A + h * (r0 * r0 + 2 * r0 * r1 + 3 * r1 * r1) / (4 * s)


def hydrostatic_load(platform, pose: list[float]) -> np.ndarray:
    model = PlatformModel(platform, options=HYDRODYN)
    still = np.zeros((1, 6))
    return model.prescribed_motion_loads(np.zeros(1), np.array([pose]), still, still)[0, ROW["hydrostatic"]]


def test_tapered_column_volume_and_centre_of_buoyancy_are_the_frustums():
    """Linear hydrostatics' V and z_B (strip frustums) and the waterplane at the taper's
    diameter at z = 0, against the closed form."""
    platform = tapered_column()
    h = hydrostatics(platform, discretise(platform).strips)
    volume, z_b = frustum_below(0.0)
    assert h.displaced_volume_m3 == pytest.approx(volume, rel=1e-12)
    assert h.centre_of_buoyancy_m[2] == pytest.approx(z_b, rel=1e-12)
    assert h.waterplane_area_m2 == pytest.approx(math.pi * radius_at(0.0) ** 2, rel=1e-12)


@pytest.mark.parametrize("heave_m", [-3.0, 0.0, 2.5])
def test_heaved_tapered_column_buoyancy_is_the_exact_frustum(heave_m):
    """Nonlinear hydrostatics: rho g times the frustum below the water line, through its centroid."""
    load = hydrostatic_load(tapered_column(), [0.0, 0.0, heave_m, 0.0, 0.0, 0.0])
    volume, _ = frustum_below(-heave_m)
    assert load[2] == pytest.approx(RHO * G * volume, rel=1e-12)
    assert np.allclose(load[[0, 1, 3, 4, 5]], 0.0, atol=1e-9 * load[2])


@pytest.mark.parametrize("pitch_rad", [0.033161256, 0.15])
def test_pitched_tapered_column_buoyancy_matches_numerical_integration(pitch_rad):
    """A frustum pitched about the origin: volume below z = 0 and its moment, integrated over
    the body-frame axis s and section coordinate x (chord 2 sqrt(R(s)^2 - x^2)) by scipy."""
    load = hydrostatic_load(tapered_column(strip_length_m=1.0), [0.0, 0.0, 0.0, 0.0, pitch_rad, 0.0])
    sin, cos = math.sin(pitch_rad), math.cos(pitch_rad)

    def wet_x(s):  # world z = -x sin + s cos < 0
        r = radius_at(s)
        return min(r, max(-r, s * cos / sin)), r

    def chord(x, s):
        return 2.0 * math.sqrt(max(radius_at(s) ** 2 - x * x, 0.0))

    kw = dict(epsabs=1e-10, epsrel=1e-11)
    volume = integrate.dblquad(chord, Z_A, Z_B, lambda s: wet_x(s)[0], lambda s: wet_x(s)[1], **kw)[0]
    x_world = integrate.dblquad(lambda x, s: chord(x, s) * (x * cos + s * sin), Z_A, Z_B,
                                lambda s: wet_x(s)[0], lambda s: wet_x(s)[1], **kw)[0]
    assert load[2] == pytest.approx(RHO * G * volume, rel=1e-9)
    assert load[4] == pytest.approx(-RHO * G * x_world, rel=1e-8)
    assert np.allclose(load[[0, 1, 3, 5]], 0.0, atol=1e-9 * load[2])


@pytest.mark.parametrize("taper_cp, tolerance", [(1.0, 2e-4), (0.0, None)])
def test_submerged_frustum_vertical_froude_krylov_force_is_rho_times_volume_integral_of_acceleration(
        taper_cp, tolerance):
    """A submerged frustum held in a long regular wave: end pressures plus the tapered wall's
    dynamic pressure make -(closed surface integral of p n) = rho int a_z dV (Gauss; linear
    waves: rho dw/dt = -dp/dz). Without the wall term the force misses p times the wall's
    axial projection."""
    top = -8.0
    platform = tapered_column(strip_length_m=0.25, top_z_m=top, taper_cp=taper_cp)
    period_s, amplitude_m, depth = 12.0, 1.0, platform.environment.water_depth_m
    waves = WaveComponents(np.array([1 / period_s]), np.array([amplitude_m]), np.array([0.0]), np.array([0.0]),
                           period_s)
    model = PlatformModel(platform, waves, options=dataclasses.replace(HYDRODYN, hydrostatics="linear"),
                          wave_table_dt_s=period_s / 480)
    t = np.linspace(0.0, period_s, 25)[:-1]
    rest = np.zeros((t.size, 6))
    loads = model.prescribed_motion_loads(t, rest, rest, rest)
    fz = loads[:, ROW["inertia"], 2]
    omega = 2 * math.pi / period_s
    k = optimize_wavenumber(omega, depth)
    # eta = A cos(omega t) at x = 0: w = -omega A sinh(k(z+d))/sinh(kd) sin(omega t), a_z = dw/dt
    profile = integrate.quad(lambda z: math.pi * radius_at(z) ** 2 * math.sinh(k * (z + depth)) / math.sinh(k * depth),
                             Z_A, top, epsabs=1e-12, epsrel=1e-12)[0]
    expected = -RHO * omega**2 * amplitude_m * profile * np.cos(omega * t)
    error = np.max(np.abs(fz - expected)) / np.max(np.abs(expected))
    if tolerance is None:
        assert error > 1e-2
    else:
        assert error < tolerance


def optimize_wavenumber(omega: float, depth_m: float) -> float:
    """omega^2 = g k tanh(k d), by Newton from the deep-water value (independent of the model's)."""
    k = omega * omega / G
    for _ in range(50):
        f = G * k * math.tanh(k * depth_m) - omega * omega
        k -= f / (G * math.tanh(k * depth_m) + G * k * depth_m / math.cosh(k * depth_m) ** 2)
    return k


def test_tapered_member_round_trips_through_the_platform_document(tmp_path):
    platform = tapered_column()
    from fowt_hydro_sim.physics.config import platform_document
    again = platform_from_dict(yaml.safe_load(yaml.safe_dump(platform_document(platform))), "round trip")
    assert again.members == platform.members


# ---------------------------------------------------------------------- OpenFAST r-test cases
def test_rtest_tapered_cylinder_pitch_moment_matches_hydrodyn(tmp_path):
    """hd_TaperCylinderPitchMoment: the deck imported as is (a HydroDyn v4-layout file, tapered),
    its comma-separated PRP pitch file run by ``fowt-sim loads --hydrodyn --still-water``:
    buoyancy within 1e-6 (the reference prints 7 digits), the pitch moment within 1e-3
    relative RMS (HydroDyn integrates the surface-piercing element by its own approximation;
    our frustum is exact, test above), no other load."""
    case = RTEST / "hd_TaperCylinderPitchMoment"
    platform_file, out = tmp_path / "taper.yaml", tmp_path / "loads.csv"
    assert main(["platform", "import", str(case / "Taper_HD_primary.dat"), "-o", str(platform_file),
                 "--water-depth", "100"]) == 0
    member = yaml.safe_load(platform_file.read_text())["members"][0]
    assert (member["diameter_m"], member["diameter_b_m"]) == (9.0, 8.9)
    assert main(["loads", "--platform", str(platform_file), "--motion", str(case / "Ry.dat"), "--still-water",
                 "--hydrodyn", "-o", str(out)]) == 0
    ref = read_hydrodyn_out(case / "driver.out")
    table = np.genfromtxt(out, delimiter=",", names=True)[:ref["Time"].size]
    assert np.allclose(table["Time"], ref["Time"])
    assert np.max(np.abs(table["HydroFzi"] / ref["HydroFzi"] - 1)) < 1e-6
    my_error = np.sqrt(np.mean((table["HydroMyi"] - ref["HydroMyi"]) ** 2)) / np.sqrt(np.mean(ref["HydroMyi"] ** 2))
    assert my_error < 1e-3, my_error
    for name in ("HydroFxi", "HydroFyi", "HydroMxi", "HydroMzi"):
        assert np.max(np.abs(table[name])) < 1e-6 * ref["HydroFzi"][0], name


# ------------------------------------------- hydrostatics up to the free surface (MHstLMod 2)
def flat(elevation_m: float):
    return lambda t, x, y: elevation_m


def test_free_surface_hydrostatics_of_a_submerged_box_is_archimedes():
    """A tilted, spun box below the surface: rho g V up through its centre (closed surface),
    whatever the elevation above it; tapered, the prismatoid volume L (A_a + 4 A_mid + A_b) / 6."""
    a, b = np.array([-3.0, 2.0, -30.0]), np.array([5.0, -4.0, -12.0])
    box = fsh.RectangularMember(tuple(a), tuple(b), (4.0, 4.0), (2.5, 2.5), 35.0, 7)
    load = fsh.member_wrench(box, flat(0.7), 0.0, RHO, G)
    volume = 4.0 * 2.5 * float(np.linalg.norm(b - a))
    centre = 0.5 * (a + b)
    assert np.allclose(load[:3], [0.0, 0.0, RHO * G * volume], rtol=0, atol=1e-9 * RHO * G * volume)
    assert np.allclose(load[3:], RHO * G * volume * np.cross(centre, [0.0, 0.0, 1.0]), rtol=0,
                       atol=1e-9 * RHO * G * volume)
    tapered = fsh.RectangularMember(tuple(a), tuple(b), (8.0, 5.0), (4.0, 6.0), 60.0, 5)
    length = float(np.linalg.norm(b - a))
    prismatoid = length * (8.0 * 4.0 + 4 * 6.5 * 5.0 + 5.0 * 6.0) / 6
    assert fsh.member_wrench(tapered, flat(-2.0), 0.0, RHO, G)[2] == pytest.approx(RHO * G * prismatoid, rel=1e-12)


@pytest.mark.parametrize("elevation_m", [-1.5, 0.0, 1.5])
def test_free_surface_hydrostatics_uses_still_water_pressure_up_to_the_elevation(elevation_m):
    """HydroDyn's MHstLMod 2 pressure is -rho g z, wetted up to the surface: on a vertical
    column the walls carry no vertical load, so Fz = rho g A d whatever the elevation; a
    horizontal box half in the water gets rho g times its submerged half (surface at z = 0)."""
    column = fsh.RectangularMember((1.0, 1.0, -9.0), (1.0, 1.0, 6.0), (3.0, 3.0), (2.0, 2.0), 0.0, 4)
    load = fsh.member_wrench(column, flat(elevation_m), 0.0, RHO, G)
    assert load[2] == pytest.approx(RHO * G * 6.0 * 9.0, rel=1e-12)
    assert np.allclose(load[[0, 1, 5]], 0.0, atol=1e-9 * load[2])
    beam = fsh.RectangularMember((-6.0, 0.0, 0.0), (6.0, 0.0, 0.0), (3.0, 3.0), (2.0, 2.0), 0.0, 3)
    assert fsh.member_wrench(beam, flat(0.0), 0.0, RHO, G)[2] == pytest.approx(RHO * G * 12.0 * 3.0 * 1.0, rel=1e-12)


RECT_CASE = RTEST / "hd_MHstLMod2_RectMmbr"


def test_rtest_rectangular_member_in_regular_wave_matches_hydrodyn():
    """hd_MHstLMod2_RectMmbr: a tapered (8 x 4 to 5 x 6 m), spun (60 deg) rectangular member
    crossing the surface, held at rest in a regular wave (Hs 10 m, Tp 20 s, heading 15 deg,
    depth 200 m, vertical stretching, MHstLMod 2, all Morison coefficients 0: buoyancy only).
    The wave's phase (random in HydroDyn) and amplitude are fitted to Wave1Elev at the origin;
    the amplitude must come out Hs / 2. With SeaState's 5 m elevation grid every channel agrees
    within 1e-5 relative RMS (the baseline prints 7 digits); with the exact elevation within 1e-2
    (the grid's interpolation error)."""
    data = np.loadtxt(RECT_CASE / "driver_excerpt.out", skiprows=4)
    t, elevation, reference = data[:, 0], data[:, 1], data[:, 2:]
    omega = 2 * math.pi / 20.0
    basis = np.c_[np.cos(omega * t), -np.sin(omega * t)]
    (c, s), *_ = np.linalg.lstsq(basis, elevation, rcond=None)
    assert np.max(np.abs(basis @ [c, s] - elevation)) < 1e-6
    assert math.hypot(c, s) == pytest.approx(5.0, rel=1e-6)
    wave = fsh.regular_wave(5.0, omega, optimize_wavenumber(omega, 200.0), 15.0, math.atan2(s, c))
    a, b = (-10.0, -15.0, -2.0), (12.0, 24.0, 2.0)
    member = fsh.RectangularMember(a, b, (8.0, 5.0), (4.0, 6.0), 60.0, math.ceil(math.dist(a, b) / 1.0))
    scale = np.sqrt(np.mean(reference**2, axis=0))
    for eta, tolerance in ((fsh.on_grid(wave, 5.0, 5.0), 1e-5), (wave, 1e-2)):
        loads = np.array([fsh.member_wrench(member, eta, ti, RHO, G) for ti in t])
        error = np.sqrt(np.mean((loads - reference) ** 2, axis=0)) / scale
        assert np.all(error < tolerance), error


def rectangular_column(strip_length_m: float = 1.0):
    """One vertical rectangular column 6 x 4 m from z = -10 to +8 m, no drag, no added mass."""
    p = load_platform("windmoor12")
    source = next(m for m in p.members if m.section == "rectangular")
    zone = dataclasses.replace(source.zones[0], below_z_m=math.inf, ca=(0.0, 0.0))
    zone = dataclasses.replace(zone, cd=tuple(dataclasses.replace(c, constant=0.0) for c in zone.cd))
    column = dataclasses.replace(source, end_a_m=(1.0, 0.5, -10.0), end_b_m=(1.0, 0.5, 8.0), width_m=6.0,
                                 height_m=4.0, zones=(zone,), strip_length_m=strip_length_m)
    return dataclasses.replace(p, members=(column,))


@pytest.mark.parametrize("pose", [[0.0, 0.0, 1.2, 0.0, 0.0, 0.0], [0.5, -1.0, -0.8, 0.06, -0.09, 0.3]])
def test_free_surface_hydrostatics_in_still_water_equal_the_nonlinear_member_hydrostatics(pose):
    """In still water the free-surface option integrates the same pressure over the same wetted
    surface as the nonlinear option (rho g V_sub through the centroid, by line integrals): two
    independent computations of one load, about the displaced reference point."""
    platform = rectangular_column()
    still = np.zeros((1, 6))
    loads = {}
    for mode in ("nonlinear", "free_surface"):
        model = PlatformModel(platform, options=dataclasses.replace(HYDRODYN, hydrostatics=mode))
        loads[mode] = model.prescribed_motion_loads(np.zeros(1), np.array([pose]), still, still)[0, ROW["hydrostatic"]]
    scale = loads["nonlinear"][2]
    assert np.allclose(loads["free_surface"], loads["nonlinear"], rtol=0, atol=1e-9 * scale)


def test_fowt_sim_loads_with_free_surface_hydrostatics_in_a_regular_wave(tmp_path, capsys):
    """``fowt-sim loads --stretching vertical --hydrostatics free_surface`` with a .Comp wave: the
    hydrostatic columns are the free-surface integral along the prescribed motion (global axes,
    about the displaced reference point); HydroDyn's total includes them. A platform with a
    circular member and a time-stepping run are refused in one line."""
    platform = rectangular_column()
    platform_file = tmp_path / "column.yaml"
    from fowt_hydro_sim.physics.config import platform_document
    platform_file.write_text(yaml.safe_dump(platform_document(platform)))
    waves = WaveComponents(np.array([0.1]), np.array([2.0]), np.array([0.7]), np.array([math.radians(20.0)]), 10.0)
    from fowt_hydro_sim.physics.waves.components import write_comp_file
    write_comp_file(tmp_path / "wave.Comp", waves)
    t = np.arange(0.0, 2.0001, 0.05)
    motion = np.zeros((t.size, 6))
    motion[:, 0], motion[:, 4] = 0.8 * np.sin(0.5 * t), 0.05 * np.sin(0.5 * t)
    rates = np.zeros_like(motion)
    np.savetxt(tmp_path / "prp.dat", np.column_stack([t, motion, rates, rates]))
    out = tmp_path / "loads.csv"
    assert main(["loads", "--platform", str(platform_file), "--motion", str(tmp_path / "prp.dat"), "--waves-comp",
                 str(tmp_path / "wave.Comp"), "--hydrodyn", "--hydrostatics", "free_surface", "--stretching",
                 "vertical", "-o", str(out)]) == 0
    said = capsys.readouterr().out
    assert "hydrostatics='free_surface'" in said and "stretching='vertical'" in said, said
    table = np.genfromtxt(out, delimiter=",", names=True)
    env = platform.environment
    eta = fsh.wave_elevation(waves, env.water_depth_m, env.gravity_m_s2)
    expected = fsh.prescribed_motion_wrenches(fsh.platform_members(platform), eta, t, motion,
                                              env.water_density_kg_m3, env.gravity_m_s2)
    got = np.column_stack([table[f"hydrostatic_{axis}"] for axis in ("Fx", "Fy", "Fz", "Mx", "My", "Mz")])
    assert np.allclose(got, expected, rtol=1e-7, atol=1e-6 * np.max(np.abs(expected[:, 2])))
    assert np.ptp(got[:, 2]) > 1e-3 * np.mean(got[:, 2])  # the wave moves the wetted surface
    assert main(["loads", "--motion", str(tmp_path / "prp.dat"), "--still-water", "--hydrostatics", "free_surface",
                 "-o", str(tmp_path / "w.csv")]) == 2
    from fowt_hydro_sim.physics.config import ConfigError, RunConfig
    with pytest.raises(ConfigError, match="prescribed motion only"):
        RunConfig(hydrostatics="free_surface")


# ------------------------------------------------------------- vertical wave stretching (WaveStMod 1)
@pytest.mark.parametrize("stretching", ["none", "vertical", "wheeler"])
def test_stretching_wets_a_column_up_to_the_elevation_with_the_stretched_kinematics(stretching):
    """A vertical column (no drag, no added mass) held in a regular wave: its horizontal
    Froude-Krylov force is rho A int a_x(z) dz over the wetted length: up to z = 0 without
    stretching; up to eta with vertical stretching, a_x above z = 0 being a_x(0); up to eta
    with Wheeler stretching, a_x at z taken at z' = d (z - eta) / (d + eta) (closed form,
    Airy kinematics at x = 0 where eta = A cos(omega t))."""
    p = load_platform("windmoor12")
    zone = dataclasses.replace(p.members[0].zones[0], below_z_m=math.inf, ca=(0.0, 0.0))
    zone = dataclasses.replace(zone, cd=tuple(dataclasses.replace(c, constant=0.0) for c in zone.cd))
    radius, draft = 3.0, 20.0
    column = dataclasses.replace(p.members[0], end_a_m=(0.0, 0.0, -draft), end_b_m=(0.0, 0.0, 10.0),
                                 width_m=2 * radius, height_m=2 * radius, diameter_b_m=None, zones=(zone,),
                                 strip_length_m=0.05, end_a_plate=None, end_b_plate=None)
    platform = dataclasses.replace(p, members=(column,))
    period_s, amplitude_m, depth = 12.0, 2.0, platform.environment.water_depth_m
    waves = WaveComponents(np.array([1 / period_s]), np.array([amplitude_m]), np.array([0.0]), np.array([0.0]),
                           period_s)
    options = dataclasses.replace(HYDRODYN, stretching=stretching)
    model = PlatformModel(platform, waves, options=options, wave_table_dt_s=period_s / 960)
    t = np.linspace(0.0, period_s, 25)[:-1]
    rest = np.zeros((t.size, 6))
    fx = model.prescribed_motion_loads(t, rest, rest, rest)[:, ROW["inertia"], 0]
    omega = 2 * math.pi / period_s
    k = optimize_wavenumber(omega, depth)

    def a_x(z, time):  # eta = A cos(omega t): u = omega A cosh(k(z+d))/sinh(kd) cos(omega t)
        return -omega**2 * amplitude_m * math.cosh(k * (z + depth)) / math.sinh(k * depth) * math.sin(omega * time)

    expected = []
    for time in t:
        eta = amplitude_m * math.cos(omega * time) if stretching != "none" else 0.0
        if stretching == "wheeler":
            wetted = integrate.quad(lambda z: a_x(depth * (z - eta) / (depth + eta), time), -draft, eta,
                                    epsabs=1e-12)[0]
        else:
            wetted = (integrate.quad(lambda z: a_x(z, time), -draft, min(eta, 0.0), epsabs=1e-12)[0]
                      + max(eta, 0.0) * a_x(0.0, time))
        expected.append(RHO * math.pi * radius**2 * wetted)
    expected = np.array(expected)
    assert np.max(np.abs(fx - expected)) < 1e-5 * np.max(np.abs(expected))  # measured 8e-8, 4e-7
