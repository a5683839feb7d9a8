"""Writes ``../oc4_semi.yaml``: the OC4-DeepCwind semi-submersible under the NREL 5 MW turbine from
the OpenFAST r-test's ``5MW_OC4Semi_WSt_WavesWN`` decks (PROVENANCE.md gives each number's file
and commit): the rigid structure's mass from ElastoDyn (its deck's point masses and inertias, its
summary file's tower and blade mass distributions) plus HydroDyn's water ballast (the deck's two
filled-member groups) as rigid water; the Morison members of the HydroDyn deck (the columns drag
only, their inertia and buoyancy in the capytaine hull of ``HydroData``; the pontoons and braces
full Morison members); the MAP++ deck's three catenaries linearised by MoorPy about the
undisplaced position. Run: ``python make_platform.py`` (after ``HydroData/make_hydrodata.py``).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.mooring.map_file import MapLine, MapLineType, moorpy_system, turned

HERE = Path(__file__).parent
RHO, G, DEPTH = 1025.0, 9.80665, 200.0
# ElastoDyn deck (NRELOffshrBsline5MW_OC4DeepCwindSemi_ElastoDyn.dat)
PTFM_MASS, PTFM_CMZ, PTFM_RINER, PTFM_PINER, PTFM_YINER = 3852180.0, -8.6588, 2.56193e9, 2.56193e9, 4.24265e9
TOWER_HT, TOWER_BS_HT, TWR2SHFT, OVERHANG, SHFT_TILT_DEG = 87.6, 10.0, 1.96256, -5.0191, -5.0
NAC_MASS, NAC_CMXN, NAC_CMZN, NAC_YINER = 240000.0, 1.9, 1.75, 2607890.0
HUB_MASS, HUB_INER, GEN_INER, GB_RATIO, PRECONE_DEG = 56780.0, 115926.0, 534.116, 97.0, -2.5
# ElastoDyn summary (5MW_OC4Semi_WSt_WavesWN.ED.sum): tower nodes (height above the tower base, kg/m),
# 3.88 m apart; blade nodes (distance from the rotor apex, kg/m), 3.618 m apart
TOWER_H = 1.94 + 3.88 * np.arange(20)
TOWER_DENSITY = np.array([4586.570, 4425.710, 4267.650, 4112.390, 3959.930, 3810.270, 3663.410, 3519.350, 3378.090,
                          3239.630, 3103.972, 2971.117, 2841.062, 2713.807, 2589.355, 2467.705, 2348.852, 2232.797,
                          2119.545, 2009.095])
BLADE_R = np.array([3.309, 6.926, 10.544, 14.162, 17.779, 21.397, 25.015, 28.632, 32.250, 35.868, 39.485, 43.103,
                    46.721, 50.338, 53.956, 57.574, 61.191])
BLADE_DENSITY = np.array([787.554, 464.487, 414.917, 412.664, 361.957, 346.452, 330.982, 304.395, 272.375, 250.787,
                          211.668, 177.049, 153.160, 128.005, 102.116, 77.547, 51.403])
OUTER = [(14.43376, 25.0), (-28.86751, 0.0), (14.43376, -25.0)]
# HydroDyn deck: joints (x, y, z) and members (name, joint a, joint b, property set, Cd)
JOINTS = {1: (0.0, 0.0, -20.0), 2: (0.0, 0.0, 10.0), 3: (14.43376, 25.0, -14.0), 4: (14.43376, 25.0, 12.0),
          5: (-28.86751, 0.0, -14.0), 6: (-28.86751, 0.0, 12.0), 7: (14.43376, -25.0, -14.0),
          8: (14.43376, -25.0, 12.0), 9: (14.43375, 25.0, -20.0), 10: (-28.8675, 0.0, -20.0),
          11: (14.43375, -25.0, -20.0), 12: (9.2376, 22.0, 10.0), 13: (-23.6713, 3.0, 10.0),
          14: (-23.6713, -3.0, 10.0), 15: (9.2376, -22.0, 10.0), 16: (14.43375, -19.0, 10.0),
          17: (14.43375, 19.0, 10.0), 18: (4.04145, 19.0, -17.0), 19: (-18.4752, 6.0, -17.0),
          20: (-18.4752, -6.0, -17.0), 21: (4.04145, -19.0, -17.0), 22: (14.43375, -13.0, -17.0),
          23: (14.43375, 13.0, -17.0), 24: (1.625, 2.815, 10.0), 25: (11.43376, 19.80385, 10.0),
          26: (-3.25, 0.0, 10.0), 27: (-22.87, 0.0, 10.0), 28: (1.625, -2.815, 10.0), 29: (11.43376, -19.80385, 10.0),
          30: (1.625, 2.815, -17.0), 31: (8.43376, 14.6077, -17.0), 32: (-3.25, 0.0, -17.0), 33: (-16.87, 0.0, -17.0),
          34: (1.625, -2.815, -17.0), 35: (8.43376, -14.6077, -17.0), 36: (1.625, 2.815, -16.2),
          37: (11.43376, 19.80385, 9.13), 38: (-3.25, 0.0, -16.2), 39: (-22.87, 0.0, 9.13),
          40: (1.625, -2.815, -16.2), 41: (11.43376, -19.80385, 9.13), 42: (14.43376, 25.0, -19.94),
          43: (-28.86751, 0.0, -19.94), 44: (14.43376, -25.0, -19.94)}
DIAMETER = {1: 6.5, 2: 12.0, 3: 24.0, 4: 1.6}
MEMBERS = [("main_column", 1, 2, 1, 0.56), ("upper_column_1", 3, 4, 2, 0.61), ("upper_column_2", 5, 6, 2, 0.61),
           ("upper_column_3", 7, 8, 2, 0.61), ("base_column_1", 42, 3, 3, 0.68), ("base_column_2", 43, 5, 3, 0.68),
           ("base_column_3", 44, 7, 3, 0.68), ("base_column_cap_1", 9, 42, 3, 0.68),
           ("base_column_cap_2", 10, 43, 3, 0.68), ("base_column_cap_3", 11, 44, 3, 0.68),
           ("delta_pontoon_upper_1", 12, 13, 4, 0.63), ("delta_pontoon_upper_2", 14, 15, 4, 0.63),
           ("delta_pontoon_upper_3", 16, 17, 4, 0.63), ("delta_pontoon_lower_1", 18, 19, 4, 0.63),
           ("delta_pontoon_lower_2", 20, 21, 4, 0.63), ("delta_pontoon_lower_3", 22, 23, 4, 0.63),
           ("y_pontoon_upper_1", 24, 25, 4, 0.63), ("y_pontoon_upper_2", 26, 27, 4, 0.63),
           ("y_pontoon_upper_3", 28, 29, 4, 0.63), ("y_pontoon_lower_1", 30, 31, 4, 0.63),
           ("y_pontoon_lower_2", 32, 33, 4, 0.63), ("y_pontoon_lower_3", 34, 35, 4, 0.63),
           ("cross_brace_1", 36, 37, 4, 0.63), ("cross_brace_2", 38, 39, 4, 0.63), ("cross_brace_3", 40, 41, 4, 0.63)]
HEAVE_PLATE_JOINTS = {9, 10, 11}  # JointAxID 2: AxCd 9.6 (the base columns' bottoms)
# HydroDyn deck, FILLED MEMBERS: the upper columns (PropThck 0.06 m) filled from z = -14 m to -6.17 m,
# the base columns (from joint 42's z, -19.94 m) to -14.89 m, FillDens 1025 kg/m^3
BALLAST = [(6.0 - 0.06, -14.0, -6.17), (12.0 - 0.06, -19.94, -14.89)]
# MAP++ deck (NRELOffshrBsline5MW_OC4DeepCwindSemi_MAP.dat): line, anchor, fairlead (then 240 and 120 deg)
LINE_D, LINE_MASS, LINE_EA, LINE_LENGTH = 0.0766, 113.35, 7.536e8, 835.35
ANCHOR, FAIRLEAD = (418.8, 725.383, -DEPTH), (20.434, 35.393, -14.0)


def _shaft() -> np.ndarray:
    tilt = math.radians(SHFT_TILT_DEG)
    return np.array([math.cos(tilt), 0.0, math.sin(tilt)])  # downwind along the shaft


def parts() -> list[tuple[float, np.ndarray, np.ndarray]]:
    """(mass, centre, inertia about the own centre) of every rigid part, about the reference point."""
    out = [(PTFM_MASS, np.array([0.0, 0.0, PTFM_CMZ]), np.diag([PTFM_RINER, PTFM_PINER, PTFM_YINER]))]
    out += [(d * 3.88, np.array([0.0, 0.0, TOWER_BS_HT + h]), np.zeros((3, 3))) for h, d in zip(TOWER_H, TOWER_DENSITY)]
    out.append((NAC_MASS, np.array([NAC_CMXN, 0.0, TOWER_HT + NAC_CMZN]),
                np.diag([0.0, 0.0, NAC_YINER - NAC_MASS * NAC_CMXN**2])))
    shaft = _shaft()
    apex = hub_point()
    out.append((HUB_MASS, apex, (HUB_INER + GEN_INER * GB_RATIO**2) * np.outer(shaft, shaft)))
    cone = math.radians(PRECONE_DEG)
    for k in range(3):
        azimuth = 2 * math.pi * k / 3
        radial = np.array([0.0, -math.sin(azimuth), math.cos(azimuth)])
        radial = radial - shaft * (shaft @ radial)
        radial /= np.linalg.norm(radial)
        direction = math.cos(cone) * radial + math.sin(cone) * shaft
        out += [(d * 3.618, apex + r * direction, np.zeros((3, 3))) for r, d in zip(BLADE_R, BLADE_DENSITY)]
    for radius, bottom, top in BALLAST:
        h = top - bottom
        m = RHO * math.pi * radius**2 * h
        own = np.diag([m * (3 * radius**2 + h**2) / 12, m * (3 * radius**2 + h**2) / 12, m * radius**2 / 2])
        out += [(m, np.array([x, y, (bottom + top) / 2]), own) for x, y in OUTER]
    return out


def hub_point() -> np.ndarray:
    return np.array([0.0, 0.0, TOWER_HT + TWR2SHFT]) + OVERHANG * _shaft()


def mass_properties() -> tuple[float, np.ndarray, np.ndarray]:
    """Total mass, centre of mass and inertia tensor about it."""
    ps = parts()
    mass = sum(m for m, _, _ in ps)
    cog = sum(m * c for m, c, _ in ps) / mass
    inertia = np.zeros((3, 3))
    for m, c, own in ps:
        r = c - cog
        inertia += own + m * (r @ r * np.eye(3) - np.outer(r, r))
    return mass, cog, inertia


def mooring() -> tuple[np.ndarray, np.ndarray]:
    """The three lines in MoorPy about the undisplaced platform: their wrench and 6x6 stiffness."""
    main_type = MapLineType("main", LINE_D, LINE_MASS, LINE_EA, 0.0)
    line = MapLine(main_type, LINE_LENGTH, ANCHOR, FAIRLEAD)
    system = moorpy_system([MapLine(main_type, LINE_LENGTH, turned(line.anchor_m, angle),
                                    turned(line.fairlead_m, angle)) for angle in (0.0, 240.0, 120.0)],
                           DEPTH, RHO, G)
    system.solveEquilibrium()
    return system.bodyList[0].getForces(lines_only=True), system.getCoupledStiffness(lines_only=True)


def _row(values) -> str:
    return "[" + ", ".join(f"{v:.6g}" for v in values) + "]"


def main() -> None:
    from HydroData.make_hydrodata import hydrostatics_si

    _, volume = hydrostatics_si()
    mass, cog, inertia = mass_properties()
    force, stiffness = mooring()
    stiffness = (stiffness + stiffness.T) / 2
    stiffness[np.abs(stiffness) < 1e-6 * np.abs(stiffness).max()] = 0.0
    force[np.abs(force) < 1e-6 * np.abs(force).max()] = 0.0
    lines = [
        "# OC4-DeepCwind: the semi-submersible of OC4 Phase II under the NREL 5 MW turbine, from the OpenFAST r-test's",
        "# 5MW_OC4Semi_WSt_WavesWN decks (HydroDyn, ElastoDyn, MAP++). Written by oc4_semi/make_platform.py; the",
        "# sources of every number and what differs from OpenFAST's model: oc4_semi/PROVENANCE.md. Axes: x downwind",
        "# (waves at heading 0 travel to +x), z up; the reference point on the centre line at the still-water line.",
        "name: oc4_semi",
        "description: >-",
        "  OC4-DeepCwind semi with the NREL 5 MW turbine (rigid, rotor parked): potential flow of the columns from a",
        "  capytaine BEM (the deck's WAMIT files are not in this package), the pontoons and braces as Morison members,",
        "  the columns' drag as drag-only members (HydroDyn's PropPot), ElastoDyn's mass with HydroDyn's water",
        "  ballast, the three catenaries as their linear stiffness about the undisplaced position (MoorPy).",
        "environment:",
        f"  water_density_kg_m3: {RHO}     # [kg/m^3]",
        f"  gravity_m_s2: {G}           # [m/s^2]",
        f"  water_depth_m: {DEPTH}            # [m]",
        "# The rigid structure (platform, tower, nacelle, hub, generator, blades at azimuths 0/120/240) and the",
        "# ballast water (rigid) about the reference point: make_platform.mass_properties.",
        "mass:",
        f"  mass_kg: {mass:.2f}            # [kg]",
        f"  cog_m: {_row(cog)}  # [m] from the reference point",
        "  inertia_about_cog_kg_m2:        # [kg m^2] about the centre of mass, platform axes",
        f"    ixx: {inertia[0, 0]:.6g}",
        f"    iyy: {inertia[1, 1]:.6g}",
        f"    izz: {inertia[2, 2]:.6g}",
        f"    ixz: {inertia[0, 2]:.6g}             # the tensor's xz element (the rotor's overhang)",
        f"hub_point_m: {_row(hub_point())}  # [m] the rotor apex: hub height 90 m",
        "potential_flow:                   # the columns' first-order hydrodynamics (HydroData/make_hydrodata.py)",
        "  wamit_root: oc4_semi/HydroData/oc4_semi  # relative to this file (.1 .3 .hst)",
        "  wamit_length_m: 1.0             # [m] WAMITULEN",
        f"  displaced_volume_m3: {volume:.4f}  # [m^3] the columns' (the pontoons' is in their members)",
        "  centre_of_buoyancy_xy_m: [0.0, 0.0]  # [m]",
        "  radiation: convolution          # the retardation kernel from B(w), convolved at the model's step",
        "  radiation_tmax_s: 60.0          # [s] the deck's RdtnTMax",
        "# HydroDyn deck's member table: MDivSize 1 m, member-based Cd (MCoefMod 3). Columns: PropPot, drag only;",
        "# base-column bottoms: the joints' AxCd 9.6 (JointAxID 2). Pontoons and braces (D 1.6 m): full Morison",
        "# members here (Ca 1.0, Cp 1.0: not the deck's, which leaves them to WAMIT), drag Cd 0.63 as the deck.",
        "members:",
    ]
    for name, a, b, prop, cd in MEMBERS:
        column = prop != 4
        lines += [f"  - name: {name}", "    section: circular", f"    diameter_m: {DIAMETER[prop]}",
                  f"    end_a_m: {_row(JOINTS[a])}", f"    end_b_m: {_row(JOINTS[b])}", "    strip_length_m: 1.0",
                  f"    zones: [{{name: all, ca: {0.0 if column else 1.0}, cd: {cd}}}]"]
        if column:
            lines.append("    drag_only: true")
        if a in HEAVE_PLATE_JOINTS:
            lines.append("    end_a_plate: {ca: 0.0, cp: 1.0, cd: 9.6}")
    lines += [
        "# The linear mooring: the MAP++ deck's three chains (835.35 m, 113.35 kg/m, EA 7.536e8 N, fairleads 40.87 m",
        "# out at z = -14 m, anchors at 837.6 m radius, 200 m deep) as MoorPy 1.2.1 linearises them about the",
        "# undisplaced platform (lines only; entries below 1e-6 of the largest dropped, symmetrised).",
        "linear_mooring:",
        "  source: MoorPy 1.2.1, NRELOffshrBsline5MW_OC4DeepCwindSemi_MAP.dat lines linearised at rest",
        f"  force_at_rest_n: {_row(force)}  # [N, N m]",
        "  stiffness:                      # [N/m, N/rad, N m/m, N m/rad]",
    ] + [f"    - {_row(row)}" for row in stiffness]
    (HERE.parent / "oc4_semi.yaml").write_text("\n".join(lines) + "\n")
    blade = sum(d * 3.618 for d in BLADE_DENSITY)
    tower = sum(d * 3.88 for d in TOWER_DENSITY)
    print(f"mass {mass:.1f} kg (blade {blade:.1f}, tower {tower:.1f}), cog {cog}, volume {volume:.2f}")


if __name__ == "__main__":
    main()
