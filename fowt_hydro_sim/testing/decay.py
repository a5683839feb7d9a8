"""Free decays for the physics tests: a platform's still-water equilibrium and the periods of
its surge, heave and pitch decays about it."""
from __future__ import annotations

import numpy as np

from fowt_hydro_sim.physics.config import Platform
from fowt_hydro_sim.physics.model import PlatformModel

# DOF name -> (index, initial offset from the equilibrium [m or rad])
OFFSETS = {"surge": (0, 5.0), "heave": (2, 1.0), "pitch": (4, float(np.radians(2.0)))}


def equilibrium(model: PlatformModel) -> np.ndarray:
    """The still-water pose where the model's loads balance (Newton on its prescribed-motion loads)."""
    q, zero = np.zeros(6), np.zeros((1, 6))

    def total(pose: np.ndarray) -> np.ndarray:
        return model.prescribed_motion_loads(np.zeros(1), pose[None], zero, zero)[0].sum(axis=0)

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


def free_decay_periods(platform: Platform, durations_s: dict[str, float]) -> dict[str, float]:
    """Free-decay periods in still water (no rotor) of the DOFs of ``durations_s`` (surge from
    +5 m, heave from +1 m, pitch from +2 deg, each run that long), about the model's own
    equilibrium."""
    model = PlatformModel(platform, None, dt_s=0.05)
    rest = equilibrium(model)
    periods = {}
    for name, duration in durations_s.items():
        dof, offset = OFFSETS[name]
        start = rest.copy()
        start[dof] += offset
        model.reset(motion=start)
        result = model.run(duration)
        periods[name] = decay_period(result.time_s, result.motion[:, dof] - rest[dof])
    return periods
