"""Loads for a prescribed platform motion: the HydroDyn driver's job, so that a user with an
OpenFAST model can compare channel for channel.

The motion file is the driver's PRP input (PRPInputsMod 2): 19 columns without a header,
``t | x y z | roll pitch yaw | their first | their second time derivatives``, of the platform
reference point in global axes. Columns 11-13 and 17-19 are derivatives of the angles; they
are converted to angular velocity and acceleration as the driver does
(``frames.angular_velocity_from_euler_rates``).
"""
from __future__ import annotations

import io
import logging
from pathlib import Path
from typing import NamedTuple

import numpy as np

from fowt_hydro_sim.frames import angular_acceleration_from_euler_rates, angular_velocity_from_euler_rates
from fowt_hydro_sim.physics.config import ConfigError, HydroOptions, Platform
from fowt_hydro_sim.physics.loads import NAMES, ROW
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import WaveComponents
from fowt_hydro_sim.physics.waves.grid import SeaStateGrid

log = logging.getLogger(__name__)

CHANNELS = ("HydroFxi", "HydroFyi", "HydroFzi", "HydroMxi", "HydroMyi", "HydroMzi")
HYDRO_COMPONENTS = ("drag", "inertia", "added_mass", "hydrostatic")  # HydroDyn's total (no weight, no mooring)
_AXES = ("Fx", "Fy", "Fz", "Mx", "My", "Mz")


class PrescribedMotion(NamedTuple):
    time_s: np.ndarray  # (n,)
    motion: np.ndarray  # (n, 6) x, y, z [m], roll, pitch, yaw [rad]
    velocity: np.ndarray  # (n, 6) linear [m/s], angular velocity [rad/s], global axes
    acceleration: np.ndarray  # (n, 6)


def motion_from_columns(data: np.ndarray) -> PrescribedMotion:
    """The motion of the driver's 19 columns (angle rates converted to angular velocity)."""
    angles, rates, rate_derivatives = data[:, 4:7], data[:, 10:13], data[:, 16:19]
    velocity = np.hstack([data[:, 7:10], angular_velocity_from_euler_rates(angles, rates)])
    acceleration = np.hstack([data[:, 13:16], angular_acceleration_from_euler_rates(angles, rates, rate_derivatives)])
    return PrescribedMotion(data[:, 0].copy(), data[:, 1:7].copy(), velocity, acceleration)


def read_prp_motion(path: str | Path) -> PrescribedMotion:
    """A HydroDyn driver PRP motion file (values separated by blanks or commas, as the
    driver's list-directed read takes them); ConfigError naming the problem."""
    path = Path(path)
    try:
        data = np.loadtxt(io.StringIO(path.read_text().replace(",", " ")), ndmin=2)
    except (OSError, ValueError, UnicodeDecodeError) as exc:
        raise ConfigError(f"{path}: cannot be read as a HydroDyn PRP motion file ({exc})") from None
    if data.shape[1] != 19:
        raise ConfigError(f"{path}: expected 19 columns (t, 6 positions, 6 rates, 6 second derivatives), "
                          f"got {data.shape[1]}")
    if len(data) < 2 or not np.all(np.isfinite(data)) or np.any(np.diff(data[:, 0]) <= 0):
        raise ConfigError(f"{path}: need at least two rows of finite numbers with increasing time")
    return motion_from_columns(data)


def prescribed_loads(platform: Platform, waves: WaveComponents | None, motion: PrescribedMotion,
                     options: HydroOptions, wave_table_dt_s: float | None = None,
                     wave_grid: SeaStateGrid | None = None) -> np.ndarray:
    """Every load component (n, N_LOADS, 6; global axes, about the displaced reference point)
    along the motion, with the constant drag model (``wave_grid``: SeaState's grid, for
    ``options.wave_kinematics`` "grid")."""
    return prescribed_run(platform, waves, motion, options, wave_table_dt_s, wave_grid=wave_grid)[0]


def prescribed_run(platform: Platform, waves: WaveComponents | None, motion: PrescribedMotion,
                   options: HydroOptions, wave_table_dt_s: float | None = None,
                   mooring_model: str = "", wave_grid: SeaStateGrid | None = None) -> tuple[np.ndarray, np.ndarray]:
    """``prescribed_loads`` with the mooring model ``mooring_model`` ("" = the platform's; not
    moordyn, which needs the time loop), and each mooring line's fairlead and anchor tension
    along the motion (n, lines, 2) [N]."""
    model = PlatformModel(platform, waves, options=options, wave_table_dt_s=wave_table_dt_s,
                          mooring_model=mooring_model, wave_grid=wave_grid)
    loads = model.prescribed_motion_loads(motion.time_s, motion.motion, motion.velocity, motion.acceleration)
    return loads, model.mooring_tensions(motion.time_s, motion.motion)


def hydro_channels(loads: np.ndarray) -> np.ndarray:
    """HydroDyn's HydroFxi .. HydroMzi (n, 6): the hydrodynamic and hydrostatic components."""
    return loads[:, [ROW[name] for name in HYDRO_COMPONENTS]].sum(axis=1)


def write_loads_csv(path: str | Path, time_s: np.ndarray, loads: np.ndarray,
                    tensions: np.ndarray | None = None) -> Path:
    """``Time``, the HydroDyn channels, then ``<component>_<Fx..Mz>`` for every load component,
    then, with ``tensions`` (n, lines, 2), ``lineN_fairlead_tension_n`` and
    ``lineN_anchor_tension_n`` for each mooring line."""
    path = Path(path)
    tensions = np.zeros((len(time_s), 0, 2)) if tensions is None else tensions
    header = ["Time", *CHANNELS, *(f"{name}_{axis}" for name in NAMES for axis in _AXES),
              *(f"line{i + 1}_{end}_tension_n" for i in range(tensions.shape[1]) for end in ("fairlead", "anchor"))]
    table = np.column_stack([time_s, hydro_channels(loads), loads.reshape(len(time_s), -1),
                             tensions.reshape(len(time_s), -1)])
    np.savetxt(path, table, delimiter=",", header=",".join(header), comments="", fmt="%.9g")
    log.info("wrote %s (%d rows)", path, len(time_s))
    return path
