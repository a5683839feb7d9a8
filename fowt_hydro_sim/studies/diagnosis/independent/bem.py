"""The independent simulator's hydrodynamic database: the hull's immersed surface meshed for
capytaine (a BEM solver from the package index), radiation and diffraction solved, and the
hydrostatics computed from the geometry. Only the platform's typed description is read from
the model (geometry, environment); nothing of its kernel.

The hull is three vertical cylinders (open at the waterline) and three rectangular
pontoons running into the columns, with the panels of each part that lie inside another
removed (the junctions stay open by about a panel: a coarse mesh's error)."""
from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.config import Platform

LOG = logging.getLogger(__name__)

DATA = Path(__file__).parent / "data"
DATABASE = DATA / "windmoor12_bem.npz"
FREQUENCIES_HZ = np.geomspace(0.005, 0.5, 30)
HEADINGS_DEG = (0.0, 30.0, 60.0, 90.0)
PANEL_SIZE_M = 2.6


@dataclass(frozen=True)
class HydroDatabase:
    """A(w), B(w), excitation X(w, heading) about the reference point (0, 0, 0), 6 DOF."""

    omega_rad_s: np.ndarray  # (n,)
    added_mass: np.ndarray  # (n, 6, 6)
    damping: np.ndarray  # (n, 6, 6)
    added_mass_inf: np.ndarray  # (6, 6), deep water at infinite frequency
    headings_deg: np.ndarray  # (h,)
    excitation: np.ndarray  # (n, h, 6) complex, per unit amplitude, elevation cos(w t - k x) at x=0
    hydrostatic_stiffness: np.ndarray  # (6, 6), from the geometry
    displaced_volume_m3: float
    panels: int

    def excitation_at(self, heading_deg: float) -> np.ndarray:
        """X(w) at the stored heading nearest ``heading_deg`` (n, 6)."""
        wrapped = (np.asarray(self.headings_deg) - heading_deg + 180.0) % 360.0 - 180.0
        index = int(np.argmin(np.abs(wrapped)))
        if abs(wrapped[index]) > 1e-6:
            raise ValueError(f"no BEM excitation at heading {heading_deg} deg (stored: {list(self.headings_deg)})")
        return self.excitation[:, index, :]


def load_database(path: str | Path = DATABASE) -> HydroDatabase:
    """Read a database written by :func:`save_database`."""
    with np.load(path) as data:
        return HydroDatabase(
            omega_rad_s=data["omega_rad_s"], added_mass=data["added_mass"], damping=data["damping"],
            added_mass_inf=data["added_mass_inf"], headings_deg=data["headings_deg"],
            excitation=data["excitation"], hydrostatic_stiffness=data["hydrostatic_stiffness"],
            displaced_volume_m3=float(data["displaced_volume_m3"]), panels=int(data["panels"]))


def save_database(database: HydroDatabase, path: str | Path = DATABASE) -> None:
    np.savez_compressed(path, **{name: getattr(database, name) for name in database.__dataclass_fields__})


# --------------------------------------------------------------------------- geometry
def _columns(platform: Platform):
    return [m for m in platform.members if m.end_a_m[0] == m.end_b_m[0] and m.end_a_m[1] == m.end_b_m[1]]


def _pontoons(platform: Platform):
    return [m for m in platform.members if m.end_a_m[2] == m.end_b_m[2]]


def _immersed_length_m(member) -> float:
    bottom, top = sorted((member.end_a_m[2], member.end_b_m[2]))
    return min(top, 0.0) - bottom


def hydrostatics(platform: Platform) -> tuple[np.ndarray, float]:
    """The 6x6 hydrostatic (and gravity) stiffness about (0, 0, 0) and the displaced volume,
    from the members' geometry: waterplane of the columns, volumes of columns and pontoons."""
    env = platform.environment
    rho_g = env.water_density_kg_m3 * env.gravity_m_s2
    volume, moment_z = 0.0, 0.0
    area, area_x2, area_y2 = 0.0, 0.0, 0.0
    for column in _columns(platform):
        radius = column.width_m / 2.0
        length = _immersed_length_m(column)
        bottom = min(column.end_a_m[2], column.end_b_m[2])
        v = math.pi * radius ** 2 * length
        volume += v
        moment_z += v * (bottom + length / 2.0)
        a = math.pi * radius ** 2
        x, y = column.end_a_m[0], column.end_a_m[1]
        area += a
        area_x2 += a * x ** 2 + a * radius ** 2 / 4.0
        area_y2 += a * y ** 2 + a * radius ** 2 / 4.0
    for pontoon in _pontoons(platform):
        length = float(np.linalg.norm(np.subtract(pontoon.end_b_m, pontoon.end_a_m)))
        v = pontoon.width_m * pontoon.height_m * length
        volume += v
        moment_z += v * pontoon.end_a_m[2]
    z_b = moment_z / volume
    mass = platform.mass.mass_kg
    z_g = platform.mass.cog_m[2]
    stiffness = np.zeros((6, 6))
    stiffness[2, 2] = rho_g * area
    stiffness[3, 3] = rho_g * (area_y2 + volume * z_b) - mass * env.gravity_m_s2 * z_g
    stiffness[4, 4] = rho_g * (area_x2 + volume * z_b) - mass * env.gravity_m_s2 * z_g
    return stiffness, volume


def _inside_column(points: np.ndarray, column) -> np.ndarray:
    """Points within the column's radius (over its immersed height, bottom included)."""
    bottom = min(column.end_a_m[2], column.end_b_m[2])
    radial = np.hypot(points[:, 0] - column.end_a_m[0], points[:, 1] - column.end_a_m[1])
    return (radial < column.width_m / 2.0 - 1e-6) & (points[:, 2] >= bottom - 1e-6)


def _inside_box(points: np.ndarray, centre: np.ndarray, angle: float, size: tuple[float, float, float]) -> np.ndarray:
    """Points strictly inside a box of ``size`` (along, across, up) about ``centre`` turned by ``angle``."""
    d = points - centre
    along = d[:, 0] * math.cos(angle) + d[:, 1] * math.sin(angle)
    across = -d[:, 0] * math.sin(angle) + d[:, 1] * math.cos(angle)
    return ((np.abs(along) < size[0] / 2 - 1e-6) & (np.abs(across) < size[1] / 2 - 1e-6)
            & (np.abs(d[:, 2]) < size[2] / 2 - 1e-6))


def hull_mesh(platform: Platform, panel_size_m: float = PANEL_SIZE_M):
    """The immersed hull as one capytaine mesh (normals outward): the panels of each part
    that lie inside another part are removed (pontoon panels within a column's radius,
    column panels inside a pontoon), which leaves the junctions open by about a panel."""
    import capytaine as cpt
    columns, boxes = [], []
    for column in _columns(platform):
        radius = column.width_m / 2.0
        length = _immersed_length_m(column)
        bottom = min(column.end_a_m[2], column.end_b_m[2])
        n_theta = max(12, round(2 * math.pi * radius / panel_size_m))
        n_z = max(3, round(length / panel_size_m))
        n_r = max(2, round(radius / panel_size_m))
        extra = length / n_z  # one panel row above the waterline, clipped off by immersed_part
        columns.append(cpt.mesh_vertical_cylinder(
            length=length + extra, radius=radius, center=(column.end_a_m[0], column.end_a_m[1],
                                                          bottom + (length + extra) / 2.0),
            resolution=(n_r, n_theta, n_z + 1), name=column.name))
    column_radius = _columns(platform)[0].width_m / 2.0
    for pontoon in _pontoons(platform):
        a, b = np.asarray(pontoon.end_a_m), np.asarray(pontoon.end_b_m)
        axis = b - a
        length = float(np.linalg.norm(axis))
        full = length + 2.0 * column_radius  # open ends at the column centres
        box = cpt.mesh_parallelepiped(
            size=(full, pontoon.width_m, pontoon.height_m), center=(0.0, 0.0, 0.0),
            resolution=(max(4, round(full / panel_size_m)), max(2, round(pontoon.width_m / panel_size_m)),
                        max(2, round(pontoon.height_m / panel_size_m))),
            missing_sides={"left", "right"}, name=pontoon.name)
        angle = math.atan2(axis[1], axis[0])
        centre = (a + b) / 2.0
        boxes.append((box.rotated_z(angle).translated(tuple(centre)), centre, angle,
                      (full, pontoon.width_m, pontoon.height_m)))
    kept = []
    for mesh in columns:
        centres = mesh.faces_centers
        inside = np.zeros(len(centres), bool)
        for _, centre, angle, size in boxes:
            inside |= _inside_box(centres, centre, angle, size)
        kept.append(mesh.extract_faces(np.flatnonzero(~inside)))
    for mesh, *_ in boxes:
        centres = mesh.faces_centers
        inside = np.zeros(len(centres), bool)
        for column in _columns(platform):
            inside |= _inside_column(centres, column)
        kept.append(mesh.extract_faces(np.flatnonzero(~inside)))
    mesh = kept[0].join_meshes(*kept[1:])
    return mesh.immersed_part(water_depth=platform.environment.water_depth_m)


def _problems_dataset(frequencies_hz, headings_deg, water_depth_m, rho, g):
    import xarray as xr
    return xr.Dataset(coords={
        "omega": 2.0 * np.pi * np.asarray(frequencies_hz), "wave_direction": np.radians(headings_deg),
        "radiating_dof": ["Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"],
        "water_depth": [water_depth_m], "rho": [rho], "g": [g]})


def solve(platform: Platform, frequencies_hz=FREQUENCIES_HZ, headings_deg=HEADINGS_DEG,
          panel_size_m: float = PANEL_SIZE_M) -> HydroDatabase:
    """Mesh, solve radiation and diffraction with capytaine, and collect the database."""
    import capytaine as cpt
    env = platform.environment
    mesh = hull_mesh(platform, panel_size_m)
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0.0, 0.0, 0.0)),
                            name=platform.name)
    LOG.info("mesh: %d panels", mesh.nb_faces)
    solver = cpt.BEMSolver()
    started = time.perf_counter()
    data = solver.fill_dataset(_problems_dataset(frequencies_hz, headings_deg, env.water_depth_m,
                                                 env.water_density_kg_m3, env.gravity_m_s2), body)
    infinite = solver.fill_dataset(_problems_dataset([np.inf], [0.0], np.inf, env.water_density_kg_m3,
                                                     env.gravity_m_s2).drop_vars("wave_direction"), body)
    LOG.info("solved in %.0f s", time.perf_counter() - started)
    dofs = ["Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"]

    def matrix(name, dataset):
        da = dataset[name].squeeze(drop=True)
        return da.sel(radiating_dof=dofs, influenced_dof=dofs).transpose(..., "radiating_dof", "influenced_dof")

    # capytaine's arrays are [radiating, influenced]; store as [influenced (row), radiating (col)]
    added = np.swapaxes(matrix("added_mass", data).values, -1, -2)
    damping = np.swapaxes(matrix("radiation_damping", data).values, -1, -2)
    added_inf = matrix("added_mass", infinite).values.T
    excitation = data["excitation_force"].squeeze(drop=True).sel(influenced_dof=dofs).transpose(
        "omega", "wave_direction", "influenced_dof").values
    # capytaine's finite-depth Green function fails at the lowest kh: those frequencies are dropped
    solved = np.isfinite(added).all(axis=(1, 2)) & np.isfinite(excitation).all(axis=(1, 2))
    if not solved.all():
        LOG.warning("dropped %d unsolved frequencies: %s rad/s", int((~solved).sum()),
                    np.round(data["omega"].values[~solved], 4).tolist())
    # the open junctions leave A and B slightly unsymmetric (surge-pitch ~13 %): symmetrised
    asymmetry = np.abs(added - np.swapaxes(added, 1, 2))[solved].max() / np.abs(added[solved]).max()
    LOG.info("added-mass asymmetry %.3f of its largest term; stored symmetrised", asymmetry)
    symmetric = lambda m: 0.5 * (m + np.swapaxes(m, -1, -2))
    stiffness, volume = hydrostatics(platform)
    return HydroDatabase(omega_rad_s=data["omega"].values[solved], added_mass=symmetric(added[solved]),
                         damping=symmetric(damping[solved]), added_mass_inf=symmetric(added_inf),
                         headings_deg=np.asarray(headings_deg, float), excitation=np.conj(excitation[solved]),
                         hydrostatic_stiffness=stiffness, displaced_volume_m3=volume, panels=int(mesh.nb_faces))
