"""Synthetic "measured" runs, for checking calibration and diagnosis without basin data:
a bag holding a wave elevation record and the platform motion (contract topics), as a
converted basin test would."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from fowt_hydro_sim.rosbag.writer import BagWriter
from msg_adapters import cdr, topics
from msg_adapters.sim_time import nanoseconds


def write_measured_bag(path: str | Path, elevation_time_s: np.ndarray, elevation_m: np.ndarray,
                       point_xy_m: tuple[float, float], motion_time_s: np.ndarray, motion: np.ndarray,
                       config: dict | None = None, overwrite: bool = False) -> Path:
    """A bag of /waves/elevation (PointStamped at ``point_xy_m``) and /platform/pose (6-DOF
    motion as PoseStamped), log time = stamp."""
    with BagWriter(path, config=config, overwrite=overwrite) as bag:
        wave = bag.add_topic(topics.ELEVATION, topics.POINT_STAMPED)
        pose = bag.add_topic(topics.POSE, topics.POSE_STAMPED)
        rows = [(nanoseconds(t), [(wave, cdr.point(t, *point_xy_m, eta))])
                for t, eta in zip(elevation_time_s.tolist(), elevation_m.tolist())]
        rows += [(nanoseconds(t), [(pose, cdr.pose(t, m))]) for t, m in zip(motion_time_s.tolist(), motion)]
        bag.write_rows(sorted(rows, key=lambda row: row[0]))
    return Path(path)
