"""Loads beyond the Morison model, as the compiled kernel takes them: a wrench time series
and linear, quadratic and cubic terms in the platform's velocity and offset, plus a
mass term. The gap diagnosis's effects (effects/) build these; a plain model has none.

All terms act at the reference point in world axes, per DOF (surge, sway, heave, roll,
pitch, yaw): F = f(t) - B1 v - B2 |v| v - K q - K2 q^2 - K3 q^3 - M_x a. K2 is an
asymmetric restoring: stiffer on the side of positive offset, softer on the other.
"""
from __future__ import annotations

from dataclasses import dataclass, field, fields, replace

import numpy as np

from fowt_hydro_sim.physics.jit import step_loop
from fowt_hydro_sim.physics.tables import interpolate_series


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
    quadratic_stiffness: np.ndarray = _zeros(6)  # K2 [N/m^2, N m/rad^2]

    def __post_init__(self) -> None:
        shapes = {"linear_damping": (6, 6), "quadratic_damping": (6,), "stiffness": (6, 6),
                  "cubic_stiffness": (6,), "mass": (6, 6), "quadratic_stiffness": (6,)}
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

    def delayed(self, delay_s: float) -> Extension:
        """The same terms with the force series arriving ``delay_s`` later (periodic)."""
        if not self.has_force or delay_s == 0.0:
            return self
        n = len(self.force_n)
        spectrum = np.fft.rfft(self.force_n, axis=0)
        frequency_hz = np.fft.rfftfreq(n, self.force_step_s)
        shifted = np.fft.irfft(spectrum * np.exp(-2j * np.pi * frequency_hz * delay_s)[:, None], n, axis=0)
        return replace(self, force_n=shifted)

    @property
    def has_force(self) -> bool:
        return bool(np.any(self.force_n))


def parameters(inputs) -> tuple[np.ndarray, np.ndarray]:
    """[force step, B1 (36), B2 (6), K (36), K3 (6), M_x (36), K2 (6)] and the force samples (n, 6)."""
    x = inputs.extension
    return np.concatenate([[x.force_step_s], np.ravel(x.linear_damping), x.quadratic_damping, np.ravel(x.stiffness),
                           x.cubic_stiffness, np.ravel(x.mass), x.quadratic_stiffness]), x.force_n


@step_loop
def wrench(t: float, y: np.ndarray, rotation: np.ndarray, params: np.ndarray, table: np.ndarray,
           out: np.ndarray, mass: np.ndarray) -> None:
    """f(t) - B1 v - B2 |v| v - K q - K2 q^2 - K3 q^3, and M_x on the left-hand side."""
    for i in range(6):  # written out: no temporaries in the step loop
        q, v = y[i], y[6 + i]
        acc = (interpolate_series(table, params[0], t, i) - params[37 + i] * abs(v) * v
               - (params[121 + i] + params[79 + i] * q) * q * q)
        for j in range(6):
            acc -= params[1 + 6 * i + j] * y[6 + j] + params[43 + 6 * i + j] * y[j]
            mass[i, j] += params[85 + 6 * i + j]
        out[i] += acc
