"""Wave kinematics sampled on SeaState's grid and interpolated as HydroDyn reads them.

SeaState computes the incident-wave kinematics and elevation at the nodes of a grid, and
HydroDyn interpolates between them (``SeaState_Interp.f90``, ``SeaSt_WaveField.f90``):

- x: 2 NX - 1 nodes from -X_HalfWidth to +X_HalfWidth, spacing dX = X_HalfWidth / (NX - 1);
  y likewise (Y_HalfWidth, NY);
- z: NZ nodes z_k = -(1 - cos((NZ - 1 - k) dtheta)) Z_Depth, k = 0 .. NZ - 1, dtheta =
  pi / (2 (NZ - 1)): from -Z_Depth to 0, closer together near the surface (Z_Depth "default":
  the water depth);
- t: every WaveDT from 0.

A value at (t, x, y, z) is the multilinear interpolation of its 16 neighbouring nodes, linear
in t, x, y and in the angle theta = acos(1 + z / Z_Depth) (not in z); a point outside the grid
takes the value at the grid's boundary (SeaState clamps the interpolation coordinate). The
elevation is interpolated likewise in t, x and y. A point above z = 0 (extrapolation
stretching) is interpolated in t, x and y only, at its own height (HydroDyn: the value at z = 0
plus z times its vertical gradient there, each from its own t, x, y grid). The grid's nodal
values here are the exact kinematics; SeaState's come from its inverse FFT in single precision.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.config import ConfigError
from fowt_hydro_sim.physics.waves.components import WaveComponents, wavenumber
from fowt_hydro_sim.physics.waves.seastate import read_seastate

# (waves, points (n, 3), times (n,), depth, gravity, density) -> kinematics (n, 7)
Kinematics = Callable[[WaveComponents, np.ndarray, np.ndarray, float, float, float], np.ndarray]


@dataclass(frozen=True)
class SeaStateGrid:
    """SeaState's kinematics grid: its input file's X_HalfWidth, Y_HalfWidth, Z_Depth (None:
    "default", the water depth), NX, NY, NZ and WaveDT."""

    x_half_width_m: float
    y_half_width_m: float
    z_depth_m: float | None
    nx: int
    ny: int
    nz: int
    dt_s: float

    def __post_init__(self) -> None:
        if not (self.x_half_width_m > 0 and self.y_half_width_m > 0 and self.dt_s > 0):
            raise ConfigError(f"SeaState grid: X_HalfWidth, Y_HalfWidth and WaveDT must be > 0, got "
                              f"{self.x_half_width_m:g}, {self.y_half_width_m:g}, {self.dt_s:g}")
        if min(self.nx, self.ny, self.nz) < 2:
            raise ConfigError(f"SeaState grid: NX, NY and NZ must be at least 2, got {self.nx}, {self.ny}, {self.nz}")
        if self.z_depth_m is not None and not self.z_depth_m > 0:
            raise ConfigError(f"SeaState grid: Z_Depth must be > 0, got {self.z_depth_m:g}")

    @classmethod
    def from_seastate_file(cls, path: str | Path) -> SeaStateGrid:
        """The grid of a SeaState input file; ConfigError naming the field it cannot read."""
        sea = read_seastate(path)
        z_depth = None if sea.text("Z_Depth").upper() == "DEFAULT" else sea.number("Z_Depth")
        return cls(sea.number("X_HalfWidth"), sea.number("Y_HalfWidth"), z_depth, sea.integer("NX"),
                   sea.integer("NY"), sea.integer("NZ"), sea.number("WaveDT"))

    @property
    def dx_m(self) -> float:
        return self.x_half_width_m / (self.nx - 1)

    @property
    def dy_m(self) -> float:
        return self.y_half_width_m / (self.ny - 1)

    @property
    def dtheta(self) -> float:
        return math.pi / (2 * (self.nz - 1))

    def z_nodes(self, water_depth_m: float) -> np.ndarray:
        """The NZ node heights, deepest first (m)."""
        k = np.arange(self.nz)
        return -(1.0 - np.cos((self.nz - 1 - k) * self.dtheta)) * self.depth(water_depth_m)

    def depth(self, water_depth_m: float) -> float:
        """Z_Depth, or the water depth for "default"."""
        return water_depth_m if self.z_depth_m is None else self.z_depth_m

    def interpolate_kinematics(self, evaluate: Kinematics) -> Kinematics:
        """``evaluate`` (exact kinematics at points, each at its own time) sampled at this grid's
        nodes and interpolated to the points as HydroDyn does."""

        def gridded(waves: WaveComponents, points_m: np.ndarray, t_s: np.ndarray, depth_m: float,
                    gravity_m_s2: float, density_kg_m3: float) -> np.ndarray:
            nodes, times, weights = self._corners(np.atleast_2d(points_m), np.asarray(t_s, dtype=float), depth_m)
            # each distinct node and time with a weight evaluated once (a point on a node or a
            # time on WaveDT needs fewer than 16; neighbouring points share theirs)
            used = weights.ravel() != 0.0
            keys = np.column_stack([nodes.reshape(-1, 3), times.ravel()])[used]
            unique, inverse = np.unique(keys, axis=0, return_inverse=True)
            values = evaluate(waves, unique[:, 0:3], unique[:, 3], depth_m, gravity_m_s2, density_kg_m3)
            n_points = weights.shape[0]
            owner = np.repeat(np.arange(n_points), weights.shape[1])[used]
            out = np.zeros((n_points, values.shape[1]))
            np.add.at(out, owner, weights.ravel()[used, None] * values[inverse.ravel()])
            return out

        return gridded

    def elevation(self, waves: WaveComponents | None, xy_m: np.ndarray, t_s: np.ndarray, depth_m: float,
                  gravity_m_s2: float) -> np.ndarray:
        """The elevation at points (n, 2), each at its own time (n,), interpolated in t, x, y
        between the grid's nodes."""
        xy = np.atleast_2d(np.asarray(xy_m, dtype=float))
        t = np.broadcast_to(np.asarray(t_s, dtype=float), (xy.shape[0],))
        if waves is None or waves.frequency_hz.size == 0:
            return np.zeros(xy.shape[0])
        (tx, wt), (ix, wx), (iy, wy) = self._time_axis(t), self._x_axis(xy[:, 0]), self._y_axis(xy[:, 1])
        corner_t, corner_x, corner_y, weights = [], [], [], []
        for a in (0, 1):
            for b in (0, 1):
                for c in (0, 1):
                    corner_t.append((tx + a) * self.dt_s)
                    corner_x.append(-self.x_half_width_m + (ix + b) * self.dx_m)
                    corner_y.append(-self.y_half_width_m + (iy + c) * self.dy_m)
                    weights.append((wt if a else 1 - wt) * (wx if b else 1 - wx) * (wy if c else 1 - wy))
        values = elevation_at_times(waves, np.column_stack([np.concatenate(corner_x), np.concatenate(corner_y)]),
                                    np.concatenate(corner_t), depth_m, gravity_m_s2)
        return np.sum(np.array(weights) * values.reshape(8, -1), axis=0)

    def elevation_function(self, waves: WaveComponents | None, depth_m: float,
                           gravity_m_s2: float) -> Callable[[float, float, float], float]:
        """eta(t, x, y) interpolated on the grid (the free-surface hydrostatics' form)."""
        return lambda t, x, y: float(self.elevation(waves, np.array([[x, y]]), np.array([t]), depth_m,
                                                    gravity_m_s2)[0])

    # ------------------------------------------------------------------ interpolation
    def _time_axis(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        s = t / self.dt_s
        low = np.floor(s)
        return low.astype(np.int64), s - low

    def _x_axis(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return _uniform_axis((x + self.x_half_width_m) / self.dx_m, 2 * self.nx - 1)

    def _y_axis(self, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return _uniform_axis((y + self.y_half_width_m) / self.dy_m, 2 * self.ny - 1)

    def _z_axis(self, z: np.ndarray, water_depth_m: float) -> tuple[np.ndarray, np.ndarray]:
        """Node index below and weight of the one above along the angle theta (deeper than
        -Z_Depth: the deepest node)."""
        ratio = np.clip(1.0 + z / self.depth(water_depth_m), 0.0, 1.0)
        return _uniform_axis((self.nz - 1) - np.arccos(ratio) / self.dtheta, self.nz)

    def _corners(self, points: np.ndarray, t: np.ndarray, water_depth_m: float
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The 16 grid nodes around each point (n, 16, 3), their times (n, 16) and weights
        (n, 16). A point above z = 0 keeps its own height at every corner."""
        n = points.shape[0]
        t = np.broadcast_to(t, (n,))
        (it, wt), (ix, wx), (iy, wy) = self._time_axis(t), self._x_axis(points[:, 0]), self._y_axis(points[:, 1])
        iz, wz = self._z_axis(np.minimum(points[:, 2], 0.0), water_depth_m)
        above = points[:, 2] > 0.0
        z_nodes = self.z_nodes(water_depth_m)
        nodes, times, weights = np.empty((n, 16, 3)), np.empty((n, 16)), np.empty((n, 16))
        corner = 0
        for a in (0, 1):
            for b in (0, 1):
                for c in (0, 1):
                    for d in (0, 1):
                        times[:, corner] = (it + a) * self.dt_s
                        nodes[:, corner, 0] = -self.x_half_width_m + (ix + b) * self.dx_m
                        nodes[:, corner, 1] = -self.y_half_width_m + (iy + c) * self.dy_m
                        nodes[:, corner, 2] = np.where(above, points[:, 2], z_nodes[iz + d])
                        weights[:, corner] = ((wt if a else 1 - wt) * (wx if b else 1 - wx)
                                              * (wy if c else 1 - wy) * (wz if d else 1 - wz))
                        corner += 1
        return nodes, times, weights


def _uniform_axis(s: np.ndarray, n_nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """Node index below (0 .. n_nodes - 2) and the weight (0 .. 1) of the node above for
    coordinates ``s`` in node units, clamped to the axis's ends."""
    s = np.clip(s, 0.0, n_nodes - 1.0)
    low = np.minimum(np.floor(s), n_nodes - 2).astype(np.int64)
    return low, s - low


def elevation_at_times(waves: WaveComponents, xy_m: np.ndarray, t_s: np.ndarray, depth_m: float,
                       gravity_m_s2: float) -> np.ndarray:
    """Exact elevation at points (n, 2), each at its own time (n,), by direct summation."""
    omega = 2 * np.pi * waves.frequency_hz
    k = wavenumber(omega, depth_m, gravity_m_s2)
    s = np.outer(xy_m[:, 0], np.cos(waves.direction_rad)) + np.outer(xy_m[:, 1], np.sin(waves.direction_rad))
    return np.cos(np.outer(t_s, omega) - k * s + waves.phase_rad) @ waves.amplitude_m
