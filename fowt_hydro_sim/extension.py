"""Loads beyond the Morison model, as the compiled kernel takes them: a wrench time series
and linear, quadratic and cubic terms in the platform's velocity and offset, plus a
mass term. The gap diagnosis's effects (effects/) build these; a plain model has none.

All terms act at the reference point in world axes, per DOF (surge, sway, heave, roll,
pitch, yaw): F = f(t) - B1 v - B2 |v| v - K q - K3 q^3 - M_x a.
"""
from __future__ import annotations

from dataclasses import dataclass, field, fields, replace

import numpy as np


def _zeros(*shape: int):
    return field(default_factory=lambda: np.zeros(shape))


@dataclass(frozen=True)
class Extension:
    """The extra terms; every default is zero (no extension)."""

    force_n: np.ndarray = _zeros(4, 6)  # (n, 6) wrench samples, one every force_step_s, periodic
    force_step_s: float = 1.0
    linear_damping: np.ndarray = _zeros(6, 6)  # B1 [N s/m, N m s/rad]
    quadratic_damping: np.ndarray = _zeros(6)  # B2 [N s^2/m^2, N m s^2/rad^2]
    stiffness: np.ndarray = _zeros(6, 6)  # K [N/m, N m/rad]
    cubic_stiffness: np.ndarray = _zeros(6)  # K3 [N/m^3, N m/rad^3]
    mass: np.ndarray = _zeros(6, 6)  # M_x [kg, kg m^2]

    def __post_init__(self) -> None:
        shapes = {"linear_damping": (6, 6), "quadratic_damping": (6,), "stiffness": (6, 6),
                  "cubic_stiffness": (6,), "mass": (6, 6)}
        for name, shape in shapes.items():
            value = np.asarray(getattr(self, name), dtype=float)
            if value.shape != shape or not np.all(np.isfinite(value)):
                raise ValueError(f"extension {name}: need finite values of shape {shape}, got {value.shape}")
        force = np.asarray(self.force_n, dtype=float)
        if force.ndim != 2 or force.shape[1] != 6 or len(force) < 4 or not np.all(np.isfinite(force)):
            raise ValueError(f"extension force: need finite (n >= 4, 6) samples, got {force.shape}")
        if not self.force_step_s > 0:
            raise ValueError(f"extension force step: must be positive, got {self.force_step_s}")

    def plus(self, other: Extension) -> Extension:
        """Both extensions' terms summed; force series must share their time grid (or one be
        absent)."""
        if not other.has_force:
            force, step = self.force_n, self.force_step_s
        elif not self.has_force:
            force, step = other.force_n, other.force_step_s
        elif self.force_n.shape == other.force_n.shape and self.force_step_s == other.force_step_s:
            force, step = self.force_n + other.force_n, self.force_step_s
        else:
            raise ValueError("extension: two force series on different time grids cannot be summed")
        summed = {f.name: getattr(self, f.name) + getattr(other, f.name)
                  for f in fields(self) if f.name not in ("force_n", "force_step_s")}
        return replace(self, force_n=force, force_step_s=step, **summed)

    @property
    def has_force(self) -> bool:
        return bool(np.any(self.force_n))

    def kernel_fields(self) -> dict:
        """The ``extension_*`` fields of dynamics.KernelData."""
        return {"extension_force_table": np.ascontiguousarray(self.force_n, dtype=float)[:, None, :],
                "extension_force_step_s": float(self.force_step_s),
                "extension_linear_damping": np.array(self.linear_damping, dtype=float),
                "extension_quadratic_damping": np.array(self.quadratic_damping, dtype=float),
                "extension_stiffness": np.array(self.stiffness, dtype=float),
                "extension_cubic_stiffness": np.array(self.cubic_stiffness, dtype=float),
                "extension_mass": np.array(self.mass, dtype=float)}
