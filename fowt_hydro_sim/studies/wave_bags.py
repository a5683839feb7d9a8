"""``fowt-sim waves``: a bag of ``/waves/elevation`` samples for a sea state or load case,
as a wave probe would record it (for ``fowt-sim play`` or the node's ``wave_source bag``)."""
from __future__ import annotations

from dataclasses import asdict
from pathlib import Path

import numpy as np

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.physics.config import Environment, SeaState
from fowt_hydro_sim.physics.waves.components import repeat_period, synthesize
from fowt_hydro_sim.rosbag.writer import BagWriter, qos_profiles
from msg_adapters import cdr, topics
from msg_adapters.sim_time import nanoseconds


def write_wave_bag(path: str | Path, sea: SeaState, duration_s: float, environment: Environment,
                   sample_dt_s: float = 0.1, point_xy_m: tuple[float, float] = (0.0, 0.0),
                   frame_id: str = "world", overwrite: bool = False, load_case: str | None = None) -> int:
    """Write ``duration_s`` of elevation at ``point_xy_m`` every ``sample_dt_s`` (log time =
    sample time); returns the number of samples."""
    if duration_s <= 0 or sample_dt_s <= 0:
        raise InputError(f"waves: duration and sample step must be positive, got {duration_s}, {sample_dt_s}")
    period_s = repeat_period(sea, duration_s)
    eta = synthesize(sea, period_s).elevation_series(*point_xy_m, sample_dt_s, environment.water_depth_m,
                                                      environment.gravity_m_s2)
    n = int(np.floor(duration_s / sample_dt_s + 1e-9)) + 1
    config = {"waves": {"load_case": load_case, "sea_state": asdict(sea), "repeat_period_s": period_s,
                        "duration_s": duration_s, "sample_dt_s": sample_dt_s, "point_xy_m": list(point_xy_m),
                        "water_depth_m": environment.water_depth_m, "frame_id": frame_id}}
    with BagWriter(path, config=config, overwrite=overwrite) as bag:
        channel = bag.add_topic(topics.ELEVATION, topics.POINT_STAMPED, qos_profiles())
        for i in range(n):
            t = i * sample_dt_s
            bag.write(channel, nanoseconds(t), cdr.point(t, *point_xy_m, float(eta[i % len(eta)]), frame_id))
    return n
