"""The first-order hydrodynamic coefficients of the OC4-DeepCwind semi's columns (the hull of
``oc4_semi``) by capytaine's BEM, written as WAMIT ``.1``, ``.3`` and ``.hst`` files.

The geometry is the r-test HydroDyn deck's (``NRELOffshrBsline5MW_OC4DeepCwindSemi_HydroDyn.dat``,
its joints and property sets): the main column (D 6.5 m, z -20 to 0), three upper columns
(D 12 m, z -14 to 0, at radius 28.87 m, one at x = -28.87 m) and three base columns (D 24 m,
z -20 to -14) below them; the pontoons and braces (D 1.6 m) are Morison members of the
platform, not in this mesh. The base column's top is the annulus outside the upper column. Each circle is a polygon
of the circle's area (16 to 36 sides).
Frequencies: 0 and infinity (capytaine's limits, infinite depth) and 29 from 0.05 to 3 rad/s in
200 m of water; headings 0 to 180 deg every 30 deg, the negative ones by the hull's symmetry
about the x-z plane. The hydrostatic restoring is the columns' in closed form (exact circles),
with the centre of gravity at the origin (buoyancy terms only, as WAMIT's ``.hst`` for HydroDyn).
Run: ``python make_hydrodata.py`` (the BEM, some 6 minutes on one core, kept in
``capytaine_results.npz``), then ``python make_hydrodata.py --write`` (the WAMIT files).
"""
from __future__ import annotations

import logging
import sys
from pathlib import Path

import capytaine as cpt
import numpy as np
from capytaine.bem.airy_waves import froude_krylov_force

RHO, G, DEPTH = 1025.0, 9.80665, 200.0
FOLDER = Path(__file__).parent
ROOT = FOLDER / "oc4_semi"
OUTER = [(14.43376, 25.0), (-28.86751, 0.0), (14.43376, -25.0)]
OMEGA = np.concatenate([np.linspace(0.05, 0.5, 10), np.linspace(0.6, 2.0, 15), [2.25, 2.5, 2.75, 3.0]])
HEADINGS = np.radians(np.arange(0.0, 181.0, 30.0))


def _r(radius: float, n_theta: int) -> float:
    """The radius of an n-sided polygon with the circle's area (the mesh's panels are chords)."""
    return radius * np.sqrt(2 * np.pi / (n_theta * np.sin(2 * np.pi / n_theta)))


def _annulus(inner: float, outer: float, z: float, x: float, y: float, n_r: int, n_theta: int):
    disk = cpt.mesh_disk(radius=outer, center=(x, y, z), normal=(0, 0, 1), resolution=(n_r, n_theta))
    r = np.hypot(disk.faces_centers[:, 0] - x, disk.faces_centers[:, 1] - y)
    return disk.extract_faces(np.flatnonzero(r > inner))  # (the upper column stands on the rest)


def hull_mesh():
    """The columns' wetted surface, normals out of the hull."""
    parts = [cpt.mesh_vertical_cylinder(length=20.0, radius=_r(3.25, 16), center=(0, 0, -10.0),
                                        resolution=(0, 16, 10)),
             cpt.mesh_disk(radius=_r(3.25, 16), center=(0, 0, -20.0), normal=(0, 0, -1), resolution=(2, 16))]
    for x, y in OUTER:
        parts += [cpt.mesh_vertical_cylinder(length=14.0, radius=_r(6.0, 24), center=(x, y, -7.0),
                                             resolution=(0, 24, 8)),
                  cpt.mesh_vertical_cylinder(length=6.0, radius=_r(12.0, 36), center=(x, y, -17.0),
                                             resolution=(0, 36, 4)),
                  cpt.mesh_disk(radius=_r(12.0, 36), center=(x, y, -20.0), normal=(0, 0, -1), resolution=(5, 36)),
                  _annulus(_r(6.0, 24), _r(12.0, 36), -14.0, x, y, 5, 36)]
    mesh = parts[0]
    for part in parts[1:]:
        mesh = mesh.join_meshes(part)
    return mesh


def main() -> None:
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    body = cpt.FloatingBody(mesh=hull_mesh(), dofs=cpt.rigid_body_dofs(rotation_center=(0.0, 0.0, 0.0)),
                            name="oc4_semi")
    dofs = list(body.dofs)
    solver = cpt.BEMSolver()
    print(f"{body.mesh.nb_faces} panels, volume {body.mesh.volumes[0]:.1f} m^3", flush=True)
    limits = {}
    for omega in (0.0, np.inf):
        results = solver.solve_all([cpt.RadiationProblem(body=body, radiating_dof=d, omega=omega, rho=RHO, g=G)
                                    for d in dofs], progress_bar=False)
        a = np.zeros((6, 6))
        for r in results:
            a[:, dofs.index(r.radiating_dof)] = [r.added_masses[d] for d in dofs]
        limits[omega] = a
    added, damping, force = np.zeros((OMEGA.size, 6, 6)), np.zeros((OMEGA.size, 6, 6)), \
        np.zeros((OMEGA.size, HEADINGS.size, 6), complex)
    for k, omega in enumerate(OMEGA):
        problems = [cpt.RadiationProblem(body=body, radiating_dof=d, omega=omega, rho=RHO, g=G, water_depth=DEPTH)
                    for d in dofs]
        problems += [cpt.DiffractionProblem(body=body, wave_direction=b, omega=omega, rho=RHO, g=G, water_depth=DEPTH)
                     for b in HEADINGS]
        for r in solver.solve_all(problems, progress_bar=False):
            if isinstance(r.problem, cpt.RadiationProblem):
                j = dofs.index(r.radiating_dof)
                added[k, :, j] = [r.added_masses[d] for d in dofs]
                damping[k, :, j] = [r.radiation_dampings[d] for d in dofs]
            else:
                b = int(np.argmin(np.abs(HEADINGS - r.wave_direction)))
                fk = froude_krylov_force(r.problem)
                force[k, b] = [r.forces[d] + fk[d] for d in dofs]
        print(f"w {omega:.3f} rad/s done", flush=True)
    np.savez(FOLDER / "capytaine_results.npz", omega=OMEGA, headings=HEADINGS, added=added, damping=damping,
             force=force, zero=limits[0.0], inf=limits[np.inf], volume=body.mesh.volumes[0])


def hydrostatics_si() -> tuple[np.ndarray, float]:
    """The columns' restoring matrix (buoyancy terms, centre of gravity at the origin) and
    displaced volume, exact circles."""
    columns = [(0.0, 0.0, 3.25, -20.0)] + [(x, y, 6.0, -14.0) for x, y in OUTER]  # (x, y, r, bottom): pierce z = 0
    volumes = [(np.pi * 3.25**2 * 20.0, -10.0)] + [(np.pi * 36.0 * 14.0, -7.0)] * 3 + [(np.pi * 144.0 * 6.0, -17.0)] * 3
    volume = sum(v for v, _ in volumes)
    moment_z = sum(v * z for v, z in volumes)  # V z_B
    area = sum(np.pi * r**2 for _, _, r, _ in columns)
    ixx = sum(np.pi * r**4 / 4 + np.pi * r**2 * y**2 for _, y, r, _ in columns)
    iyy = sum(np.pi * r**4 / 4 + np.pi * r**2 * x**2 for x, _, r, _ in columns)
    c = np.zeros((6, 6))
    c[2, 2] = RHO * G * area
    c[3, 3] = RHO * G * (ixx + moment_z)
    c[4, 4] = RHO * G * (iyy + moment_z)
    return c, volume


def write() -> None:
    """The WAMIT files from ``capytaine_results.npz`` and ``hydrostatics_si``: the excitation in
    WAMIT's time convention (capytaine's e^(-i w t) conjugated), the headings -180 to 180 deg
    (the negative ones mirrored: sway, roll and yaw change sign)."""
    sys.path.insert(0, str(FOLDER.parents[5]))  # this checkout first
    from fowt_hydro_sim.physics.hydro import wamit

    data = np.load(FOLDER / "capytaine_results.npz")
    force = np.conj(data["force"])
    headings = np.degrees(data["headings"])
    mirror = force[:, 1:][:, ::-1] * np.array([1, -1, 1, -1, 1, -1])
    all_headings = np.concatenate([-headings[1:][::-1], headings])
    all_force = np.concatenate([mirror, force], axis=1)
    omega = data["omega"]
    wamit.write_1(ROOT.with_suffix(".1"), wamit.Radiation(omega_rad_s=omega, added_mass_si=data["added"],
                                                          damping_si=data["damping"], added_mass_zero_si=data["zero"],
                                                          added_mass_inf_si=data["inf"]), RHO)
    wamit.write_3(ROOT.with_suffix(".3"), wamit.Excitation(omega, all_headings, all_force), RHO, G)
    stiffness, _ = hydrostatics_si()
    wamit.write_hst(ROOT.with_suffix(".hst"), wamit.Hydrostatics(stiffness_si=stiffness), RHO, G)


if __name__ == "__main__":
    write() if sys.argv[1:] == ["--write"] else main()
