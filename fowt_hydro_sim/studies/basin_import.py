"""``fowt-sim measured import``: basin files read and checked (``io.basin``), each run
written as a measured bag of the project's contract with its import stored as the run's
configuration."""
from __future__ import annotations

import datetime
import logging
import platform as host
import re
from pathlib import Path

import numpy as np
import scipy

from fowt_hydro_sim import __version__
from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.frames import quaternion_from_euler
from fowt_hydro_sim.io.basin import ACCELERATIONS, MAX_GAP_S, BasinRun, ColumnMap, condition, read_runs
from fowt_hydro_sim.rosbag.writer import BagWriter, qos_profiles
from msg_adapters import cdr, topics
from msg_adapters.sim_time import nanoseconds_array

log = logging.getLogger(__name__)

PROBE_TOPIC_PREFIX = topics.ELEVATION + "/"
TENSION_TOPIC_PREFIX = "/mooring/tension/"
WIND_SPEED_TOPIC = "/turbine/wind_speed"
THRUST_TOPIC = "/turbine/thrust"
BATCH = 20000  # samples per batch of messages written


def _topic_name(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_]", "_", name)


def run_configuration(run: BasinRun, mapping: ColumnMap) -> dict:
    """What a measured bag stores as its run configuration: software, sea state, and the
    import (source file, run, scale, densities, column map, probes, checks)."""
    return {
        "software": {"fowt_hydro_sim": __version__, "python": host.python_version(), "numpy": np.__version__,
                     "scipy": scipy.__version__},
        "started_utc": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "sea_state": dict(mapping.sea_state),
        "measured": {"source_file": run.source, "run": run.name, "scale": mapping.scale,
                     "density_ratio": mapping.density_ratio, "froude_scaled": mapping.scale != 1.0,
                     "probes": {name: list(xy) for name, (xy, _, _) in run.probes.items()},
                     "replay_probe": mapping.probes[0].name if mapping.probes else None,
                     "free_decay": mapping.free_decay,
                     "probe_clock_shifts_s": {name: shift for name, (_, _, shift) in run.probes.items() if shift},
                     "unmeasured_dofs": list(run.unmeasured_dofs), "checks": list(run.notes),
                     "column_map": mapping.source},
    }


def write_basin_bag(path: str | Path, run: BasinRun, mapping: ColumnMap, overwrite: bool = False) -> Path:
    """The run as a bag: /waves/elevation (the map's first probe; none in a free decay mapped
    without one), /waves/elevation/NAME (the others, their clocks corrected; samples moved
    before 0 s dropped), /platform/pose
    (unmeasured DOFs 0), and when measured /platform/accel (missing components NaN),
    /mooring/tension/LINE, /turbine/wind_speed, /turbine/thrust. Messages are built as
    arrays and written in batches of ``BATCH`` samples (the channels on the run's clock in
    one batch, each shifted probe in its own)."""
    t = run.time_s
    zeros = np.zeros(6)
    pose_t, six_t, point_t = cdr.pose(0.0, zeros), cdr.six(0.0, zeros), cdr.point(0.0, 0.0, 0.0, 0.0)
    poses = np.hstack([run.motion[:, :3], quaternion_from_euler(run.motion[:, 3], run.motion[:, 4],
                                                                run.motion[:, 5])])
    with BagWriter(path, config=run_configuration(run, mapping), overwrite=overwrite) as bag:
        common: list[tuple[int, bytes, int, np.ndarray]] = []  # channel, template, offset, values (n, k)
        shifted: list[tuple[int, float, np.ndarray]] = []  # channel, shift, values (n, 3)
        for i, (name, ((x, y), eta, shift)) in enumerate(run.probes.items()):
            topic = topics.ELEVATION if i == 0 else PROBE_TOPIC_PREFIX + _topic_name(name)
            channel = bag.add_topic(topic, topics.POINT_STAMPED, qos_profiles())
            points = np.column_stack([np.full(t.size, x), np.full(t.size, y), eta])
            if shift:
                shifted.append((channel, shift, points))
            else:
                common.append((channel, point_t, len(point_t) - 24, points))
        common.append((bag.add_topic(topics.POSE, topics.POSE_STAMPED, qos_profiles()), pose_t, len(pose_t) - 56,
                       poses))
        if any(q in run.others for q in ACCELERATIONS):
            accel = np.column_stack([run.others.get(q, np.full(t.size, np.nan)) for q in ACCELERATIONS])
            common.append((bag.add_topic(topics.MOTION["accel"][0], topics.ACCEL_STAMPED, qos_profiles()), six_t,
                           len(six_t) - 48, accel))
        scalars = {f"{TENSION_TOPIC_PREFIX}{_topic_name(q.split(':', 1)[1])}": v
                   for q, v in run.others.items() if q.startswith("tension:")}
        scalars.update({topic: run.others[q] for q, topic in (("wind_speed", WIND_SPEED_TOPIC),
                                                              ("thrust", THRUST_TOPIC)) if q in run.others})
        for topic, values in scalars.items():
            vectors = np.column_stack([values, np.zeros(t.size), np.zeros(t.size)])
            common.append((bag.add_topic(topic, topics.VECTOR3_STAMPED, qos_profiles()), point_t,
                           len(point_t) - 24, vectors))
        for start in range(0, t.size, BATCH):
            rows = slice(start, start + BATCH)
            stamps = cdr.stamps(t[rows])
            bag.write_blocks(nanoseconds_array(t[rows]), [c for c, *_ in common],
                             [cdr.block(template, stamps, [(offset, values[rows])])
                              for _, template, offset, values in common])
            for channel, shift, values in shifted:
                moved = t[rows] + shift
                keep = moved >= 0
                block = cdr.block(point_t, cdr.stamps(moved[keep]), [(len(point_t) - 24, values[rows][keep])])
                bag.write_blocks(nanoseconds_array(moved[keep]), [channel], [block])
    return Path(path)


def import_files(paths: list[str | Path], mapping: ColumnMap, output: str | Path, max_gap_s: float = MAX_GAP_S,
                 overwrite: bool = False) -> list[tuple[Path, BasinRun]]:
    """Every run of the files checked, then each written as a bag OUTPUT/RUN (no bag is
    written if a run is refused); each problem found is logged in one line."""
    runs: list[BasinRun] = []
    for path in paths:
        for raw in read_runs(path, mapping):
            runs.append(condition(raw, mapping, Path(path).name, max_gap_s))
    names = [run.name for run in runs]
    if len(set(names)) < len(names):
        twice = sorted({n for n in names if names.count(n) > 1})
        raise InputError(f"two runs would be written to the same bag: {', '.join(twice)} (rename a file)")
    existing = [str(Path(output) / run.name) for run in runs if (Path(output) / run.name).exists()]
    if existing and not overwrite:
        raise InputError(f"{', '.join(existing)}: exists (pass --overwrite to replace it)")
    written = []
    for run in runs:
        for note in run.notes:
            log.warning(note)
        written.append((write_basin_bag(Path(output) / run.name, run, mapping, overwrite), run))
    return written
