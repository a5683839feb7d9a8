"""Basin test files (CSV/TSV, HDF5, MATLAB .mat) read into full-scale measured runs, checked
(``studies.basin_import`` writes them as bags: ``fowt-sim measured import``).

A YAML column map says what each channel of the file is (quantity, unit, sign, offset),
where the wave probes stand, where the motion was measured, the model's scale and the sea
state. Each run is checked at model scale before it is scaled: samples out of order, clock
gaps, dropouts (non-finite samples) and, with two or more probes, a probe whose clock is
offset from the first probe's (from the waves' travel between them). Each problem is
reported in one line; a short one is interpolated (or corrected), a long one refuses the
run. The values are then converted to SI units, Froude-scaled (``io.scaling``) and the
motion moved from its measured point to the platform's reference point.
"""
from __future__ import annotations

import csv
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import scipy.optimize
import yaml

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.frames import rotation_matrix
from fowt_hydro_sim.io.scaling import froude_factor
from fowt_hydro_sim.physics.config import ConfigError, _Fields
from fowt_hydro_sim.physics.waves.components import wavenumber

GRAVITY_M_S2 = 9.80665
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
ACCELERATIONS = ("accel_x", "accel_y", "accel_z", "angular_accel_x", "angular_accel_y", "angular_accel_z")
# each quantity a channel may hold, and its kind (for units and Froude scaling)
QUANTITIES = {"elevation": "length", "surge": "length", "sway": "length", "heave": "length", "roll": "angle",
              "pitch": "angle", "yaw": "angle", "accel_x": "acceleration", "accel_y": "acceleration",
              "accel_z": "acceleration", "angular_accel_x": "angular_acceleration",
              "angular_accel_y": "angular_acceleration", "angular_accel_z": "angular_acceleration",
              "tension": "force", "thrust": "force", "wind_speed": "velocity"}
# units each kind may be given in, and their factors to SI
UNITS = {"length": {"m": 1.0, "cm": 0.01, "mm": 0.001},
         "angle": {"rad": 1.0, "deg": math.pi / 180.0},
         "time": {"s": 1.0, "ms": 0.001},
         "acceleration": {"m/s^2": 1.0, "g": GRAVITY_M_S2},
         "angular_acceleration": {"rad/s^2": 1.0, "deg/s^2": math.pi / 180.0},
         "force": {"N": 1.0, "kN": 1000.0},
         "velocity": {"m/s": 1.0, "cm/s": 0.01, "mm/s": 0.001}}
MAX_GAP_S = 1.0  # full scale: longer gaps and dropouts refuse the run
GAP_STEP_SHARE = 1.5  # a clock step longer than this x the median step is a gap
CLOCK_TOLERANCE_S = 0.1  # full scale: a probe clock offset below this is not reported
MAX_CLOCK_OFFSET_S = 10.0  # full scale: a larger probe clock offset refuses the run
SUFFIXES = {".csv": "csv", ".tsv": "tsv", ".txt": "tsv", ".h5": "hdf5", ".hdf5": "hdf5", ".hdf": "hdf5",
            ".mat": "mat"}


@dataclass(frozen=True)
class Channel:
    """One channel of the file: quantity = sign x (raw - offset), in ``unit`` at model scale.
    ``position_m``: a probe's x, y (model scale, m, world axes, origin at the platform's
    reference point at rest); ``line``: a tension's mooring line."""

    name: str
    quantity: str
    unit: str
    sign: float = 1.0
    offset: float = 0.0
    position_m: tuple[float, float] | None = None
    line: str | None = None

    @property
    def kind(self) -> str:
        """The quantity's kind (length, angle, force...: its units and Froude scaling)."""
        return QUANTITIES[self.quantity]

    def to_si(self, raw: np.ndarray) -> np.ndarray:
        """The channel's values in SI units, still at model scale."""
        return self.sign * (raw - self.offset) * UNITS[self.kind][self.unit]


@dataclass(frozen=True)
class ColumnMap:
    """A column map (YAML): see docs/guide/measured.md for its fields."""

    channels: tuple[Channel, ...]
    scale: float = 1.0
    density_ratio: float | None = None
    time_channel: str | None = None
    time_unit: str = "s"
    sample_rate_hz: float | None = None
    run_channel: str | None = None
    skip_rows: int = 0
    motion_point_m: tuple[float, float, float] = (0.0, 0.0, 0.0)
    sea_state: dict = field(default_factory=dict)
    water_depth_m: float | None = None
    source: dict = field(default_factory=dict)
    free_decay: str | None = None  # the DOF of free decays in calm water (no probe needed)

    @property
    def probes(self) -> list[Channel]:
        """The wave probes, in the map's order (the first is the replays' record)."""
        return [c for c in self.channels if c.quantity == "elevation"]

    @property
    def heading_deg(self) -> float:
        """The waves' direction of travel [deg] (the map's sea state; default 0)."""
        return float(self.sea_state.get("heading_deg", 0.0))

    def needed(self) -> list[str]:
        """The file's channels the map reads."""
        names = [c.name for c in self.channels]
        return ([self.time_channel] if self.time_channel else []) + names


def load_column_map(path: str | Path) -> ColumnMap:
    """Read and check a column map; ``ConfigError`` names the field at fault."""
    path = Path(path)
    try:
        data = yaml.safe_load(path.read_text())
    except OSError as exc:
        raise ConfigError(f"{path}: cannot read ({exc.strerror})") from None
    except yaml.YAMLError as exc:
        raise ConfigError(f"{path}: not YAML ({str(exc).splitlines()[0]})") from None
    return column_map(data, str(path))


def column_map(data: object, where: str = "column map") -> ColumnMap:
    """A column map from its parsed YAML (a mapping)."""
    f = _Fields(data, where)
    scale = f.number("scale", 1.0, positive=True)
    density_ratio = f.optional_number("density_ratio", positive=True)
    time = f.sub("time")
    time_channel = str(time.data["channel"]) if time.data.get("channel") is not None else None
    time.used.add("channel")
    time_unit = time.text("unit", "s", tuple(UNITS["time"]))
    rate = time.optional_number("sample_rate_hz", positive=True)
    time.finish()
    if (time_channel is None) == (rate is None):
        raise ConfigError(f"{where}: time: give either channel (a clock channel) or sample_rate_hz")
    run_channel = f.data.get("run_channel")
    f.used.add("run_channel")
    skip_rows = int(f.number("skip_rows", 0.0, non_negative=True))
    free_decay = f.text("free_decay", None, DOFS) if f.data.get("free_decay") is not None else None
    f.used.add("free_decay")
    motion_point = f.vector("motion_point_m", 3, (0.0, 0.0, 0.0))
    sea = f.sub("sea_state", {})
    sea_state = {name: sea.number(name) for name in ("hs_m", "tp_s", "gamma", "heading_deg") if name in sea.data}
    sea.used.update(sea_state)
    sea.finish()
    depth = f.optional_number("water_depth_m", positive=True)
    channels = []
    raw_channels = f._raw("channels", None)
    if not isinstance(raw_channels, dict) or not raw_channels:
        raise ConfigError(f"{f.at('channels')}: must be a mapping of channel name -> quantity, unit ...")
    for name, spec in raw_channels.items():
        c = _Fields(spec, f"{f.at('channels')}.{name}", False)
        quantity = c.text("quantity", None, tuple(QUANTITIES))
        unit = c.text("unit", None, tuple(UNITS[QUANTITIES[quantity]]))
        position = c.vector("position_m", 2) if quantity == "elevation" else None
        line = c.text("line") if quantity == "tension" else None
        channels.append(Channel(str(name), quantity, unit, c.number("sign", 1.0), c.number("offset", 0.0),
                                position, line))
        if channels[-1].sign not in (1.0, -1.0):
            raise ConfigError(f"{c.at('sign')}: must be 1 or -1, got {channels[-1].sign:g}")
        c.finish()
    f.finish()
    quantities = [c.quantity for c in channels]
    twice = sorted({q for q in quantities if quantities.count(q) > 1 and q not in ("elevation", "tension")})
    if twice:
        raise ConfigError(f"{where}: channels: {', '.join(twice)} mapped from more than one channel")
    lines = [c.line for c in channels if c.line]
    if len(set(lines)) < len(lines):
        raise ConfigError(f"{where}: channels: a mooring line has two tension channels")
    if "elevation" not in quantities and free_decay is None:
        raise ConfigError(f"{where}: channels: no wave probe (quantity elevation); the replays need one (free "
                          "decays in calm water need none: free_decay: DOF)")
    if free_decay is not None and free_decay not in quantities:
        raise ConfigError(f"{where}: free_decay: {free_decay} is not a channel's quantity")
    if scale != 1.0 and density_ratio is None and any(QUANTITIES[q] == "force" for q in quantities):
        raise ConfigError(f"{where}: density_ratio: needed to scale forces (sea water / basin water, e.g. 1.025)")
    return ColumnMap(tuple(channels), scale, density_ratio, time_channel, time_unit, rate,
                     str(run_channel) if run_channel is not None else None, skip_rows, motion_point, sea_state,
                     depth, dict(data), free_decay)


# ------------------------------------------------------------------------------------------- reading files
@dataclass
class RawRun:
    """One run as the file holds it: model-scale channels by their file names."""

    name: str
    channels: dict[str, np.ndarray]


def file_format(path: Path) -> str:
    """csv, tsv, hdf5 or mat, from the file's suffix."""
    kind = SUFFIXES.get(path.suffix.lower())
    if kind is None:
        raise InputError(f"{path}: unknown file type {path.suffix!r} (read: {', '.join(sorted(SUFFIXES))})")
    return kind


def read_runs(path: str | Path, mapping: ColumnMap) -> list[RawRun]:
    """The runs of a basin file: one, or several (a run column in a table; groups of an HDF5
    file; structs of a .mat file)."""
    path = Path(path)
    if not path.is_file():
        raise InputError(f"{path}: no such file")
    kind = file_format(path)
    if kind in ("csv", "tsv"):
        runs = _read_table(path, mapping, "," if kind == "csv" else "\t")
    elif kind == "hdf5":
        runs = _read_hdf5(path, mapping)
    else:
        runs = _read_mat(path, mapping)
    for run in runs:
        missing = [name for name in mapping.needed() if name not in run.channels]
        if missing:
            raise InputError(f"{path}: run {run.name}: no channel(s) {', '.join(missing)} "
                             f"(has: {', '.join(sorted(run.channels)) or 'none'})")
    return runs


def _number(text: str, path: Path, line: int, column: str) -> float:
    text = text.strip()
    if text == "" or text.lower() in ("nan", "na", "n/a"):
        return math.nan
    try:
        return float(text)
    except ValueError:
        hint = " (a units row? skip_rows: 1 in the column map skips it)" if line == 2 else ""
        raise InputError(f"{path}: line {line}, column {column}: not a number: {text!r}{hint}") from None


def _read_table(path: Path, mapping: ColumnMap, delimiter: str) -> list[RawRun]:
    with open(path, newline="") as stream:
        rows = csv.reader(stream, delimiter=delimiter)
        header = [h.strip() for h in next(rows, [])]
        if not header:
            raise InputError(f"{path}: empty file")
        wanted = {name: header.index(name) for name in mapping.needed() if name in header}
        if len(wanted) < len(set(mapping.needed())):
            missing = [n for n in mapping.needed() if n not in header]
            raise InputError(f"{path}: no column(s) {', '.join(missing)} in the header (has: {', '.join(header)})")
        run_index = None
        if mapping.run_channel:
            if mapping.run_channel not in header:
                raise InputError(f"{path}: no run column {mapping.run_channel!r} in the header")
            run_index = header.index(mapping.run_channel)
        runs: dict[str, dict[str, list[float]]] = {}
        for number, row in enumerate(rows, start=2):
            if number - 1 <= mapping.skip_rows or not any(cell.strip() for cell in row):
                continue
            if len(row) < len(header):
                row = row + [""] * (len(header) - len(row))
            run = row[run_index].strip() if run_index is not None else path.stem
            values = runs.setdefault(run, {name: [] for name in wanted})
            for name, index in wanted.items():
                values[name].append(_number(row[index], path, number, name))
    if not runs:
        raise InputError(f"{path}: no data rows")
    single = len(runs) == 1 and run_index is None
    return [RawRun(path.stem if single else f"{path.stem}_{run}", {k: np.asarray(v) for k, v in values.items()})
            for run, values in runs.items()]


def _vector(value: object) -> np.ndarray | None:
    """A numeric 1-D array of a stored value (MATLAB's (n, 1) or (1, n) too), or None."""
    array = np.asarray(value)
    if array.dtype.kind not in "fiu" or array.size < 2:
        return None
    return array.astype(float).ravel() if sum(s > 1 for s in array.shape) == 1 else None


def _read_hdf5(path: Path, mapping: ColumnMap) -> list[RawRun]:
    try:
        import h5py
    except ImportError:
        raise InputError(f"{path}: reading HDF5 files needs h5py: pip install 'fowt_hydro_sim[basin]'") from None
    try:
        stream = h5py.File(path, "r")
    except OSError as exc:
        raise InputError(f"{path}: not an HDF5 file ({exc})") from None
    groups: list[tuple[str, dict[str, np.ndarray]]] = []
    with stream:
        def visit(name: str, item: object) -> None:
            if isinstance(item, h5py.Group):
                vectors = {key: v for key, member in item.items() if isinstance(member, h5py.Dataset)
                           and (v := _vector(member[()])) is not None}
                if all(n in vectors for n in mapping.needed()):
                    groups.append((name, vectors))
        visit("", stream)
        stream.visititems(visit)
    return _runs_found(path, groups, mapping)


def _read_mat(path: Path, mapping: ColumnMap) -> list[RawRun]:
    import scipy.io
    try:
        data = scipy.io.loadmat(path, simplify_cells=True)
    except NotImplementedError:  # MATLAB v7.3 files are HDF5
        return _read_hdf5(path, mapping)
    except (ValueError, OSError, TypeError) as exc:
        raise InputError(f"{path}: not a MATLAB file ({exc})") from None
    data = {k: v for k, v in data.items() if not k.startswith("__")}
    groups: list[tuple[str, dict[str, np.ndarray]]] = []

    def visit(name: str, value: object) -> None:
        if isinstance(value, dict):
            vectors = {k: v for k, item in value.items() if (v := _vector(item)) is not None}
            if all(n in vectors for n in mapping.needed()):
                groups.append((name, vectors))
            for key, item in value.items():
                visit(f"{name}/{key}" if name else key, item)
        elif isinstance(value, (list, np.ndarray)) and all(isinstance(v, dict) for v in value) and len(value):
            for i, item in enumerate(value):
                visit(f"{name}[{i}]", item)
    visit("", data)
    return _runs_found(path, groups, mapping)


def _runs_found(path: Path, groups: list[tuple[str, dict[str, np.ndarray]]], mapping: ColumnMap) -> list[RawRun]:
    if not groups:
        raise InputError(f"{path}: no group or struct holds the map's channels ({', '.join(mapping.needed())})")
    names = [re.sub(r"[^A-Za-z0-9_.-]+", "_", name).strip("_") for name, _ in groups]
    return [RawRun(f"{path.stem}_{name}" if name and len(groups) > 1 else path.stem, vectors)
            for name, (_, vectors) in zip(names, groups)]


# ------------------------------------------------------------------------------------ checks and handling
@dataclass
class BasinRun:
    """A run checked, in SI units at full scale: time, each probe's elevation (with its
    clock corrected), the platform's 6-DOF motion at its reference point and the other
    measured channels by quantity (``tension:LINE`` for a mooring line)."""

    name: str
    source: str
    time_s: np.ndarray
    probes: dict[str, tuple[tuple[float, float], np.ndarray, float]]  # name -> (x, y), elevation, clock shift
    motion: np.ndarray
    unmeasured_dofs: tuple[str, ...]
    others: dict[str, np.ndarray]
    notes: list[str]


class RunRefused(InputError):
    """A run whose clock or channels have a problem too long to interpolate."""


def _runs_of(mask: np.ndarray) -> list[tuple[int, int]]:
    """(start, stop) index ranges where ``mask`` is True."""
    edges = np.diff(np.concatenate([[0], mask.astype(np.int8), [0]]))
    return list(zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)))


def checked_clock(label: str, time_s: np.ndarray, values: np.ndarray, max_gap_s: float,
                  notes: list[str]) -> tuple[np.ndarray, np.ndarray]:
    """A clock (model scale) and its samples (n, k): non-finite stamps dropped, samples out of
    order sorted, repeated stamps dropped (the first kept), gaps filled with NaN samples at
    the median step; ``max_gap_s`` (model scale) is the longest gap or backward jump
    accepted. One note per kind of problem."""
    finite = np.isfinite(time_s)
    if not finite.all():
        notes.append(f"{label}: {int((~finite).sum())} samples without a time stamp: dropped")
        time_s, values = time_s[finite], values[finite]
    if time_s.size < 3:
        raise RunRefused(f"{label}: fewer than 3 time-stamped samples")
    running = np.maximum.accumulate(time_s)
    back = float(np.max(running - time_s))
    if back > max_gap_s:
        at = float(time_s[int(np.argmax(running - time_s))])
        raise RunRefused(f"{label}: the clock jumps back by {back:.4g} s to t = {at:.6g} s (model scale), more "
                         f"than the {max_gap_s:.4g} s accepted: refused")
    order = np.argsort(time_s, kind="stable")
    unordered = int(np.count_nonzero(order != np.arange(order.size)))
    time_s, values = time_s[order], values[order]
    repeated = np.concatenate([[False], np.diff(time_s) <= 0])
    if unordered or repeated.any():
        first = float(time_s[np.flatnonzero(order != np.arange(order.size))[0]] if unordered
                      else time_s[np.flatnonzero(repeated)[0]])
        notes.append(f"{label}: clock not monotonic: {unordered} samples out of order (sorted), "
                     f"{int(repeated.sum())} repeated stamps (dropped; the first kept); first at t = {first:.6g} s, "
                     f"at most {back:.3g} s back (model scale)")
        time_s, values = time_s[~repeated], values[~repeated]
    steps = np.diff(time_s)
    step = float(np.median(steps))
    gaps = np.flatnonzero(steps > GAP_STEP_SHARE * step)
    if gaps.size:
        longest = float(steps[gaps].max() - step)
        if longest > max_gap_s:
            at = float(time_s[gaps[np.argmax(steps[gaps])]])
            raise RunRefused(f"{label}: a clock gap of {longest:.4g} s at t = {at:.6g} s (model scale), longer "
                             f"than the {max_gap_s:.4g} s accepted: refused")
        first_gap = float(time_s[gaps[0]])
        pieces_t, pieces_v, last = [], [], 0
        for i in gaps:
            missing = int(round(steps[i] / step)) - 1
            inserted = time_s[i] + step * np.arange(1, missing + 1) if missing > 0 else np.empty(0)
            inserted = inserted[inserted < time_s[i + 1] - 0.5 * step]
            pieces_t += [time_s[last:i + 1], inserted]
            pieces_v += [values[last:i + 1], np.full((inserted.size, values.shape[1]), np.nan)]
            last = i + 1
        time_s = np.concatenate(pieces_t + [time_s[last:]])
        values = np.concatenate(pieces_v + [values[last:]])
        notes.append(f"{label}: {gaps.size} clock gap(s), the longest {longest:.3g} s (first at t = {first_gap:.6g} s, "
                     f"model scale): interpolated")
    return time_s, values


def filled(label: str, time_s: np.ndarray, values: np.ndarray, names: list[str], max_gap_s: float,
           notes: list[str], inserted: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Dropouts (non-finite samples) of each channel interpolated linearly when at most
    ``max_gap_s`` long (model scale), the run refused when longer; samples at the record's
    ends that some channel lacks are cut off. ``inserted``: rows a clock gap added (not
    reported again as dropouts)."""
    good = np.isfinite(values)
    rows = good.all(axis=1)
    if not rows.any():
        raise RunRefused(f"{label}: no sample where every channel has a value")
    first, last = int(np.argmax(rows)), len(rows) - int(np.argmax(rows[::-1]))
    if first > 0 or last < len(rows):
        notes.append(f"{label}: {first} samples at the start and {len(rows) - last} at the end lack a channel: cut")
        time_s, values, good, inserted = time_s[first:last], values[first:last], good[first:last], inserted[first:last]
    values = values.copy()
    for j, name in enumerate(names):
        spans = [(a, b) for a, b in _runs_of(~good[:, j]) if not inserted[a:b].all()]
        if spans:
            longest = max(float(time_s[b] - time_s[a - 1]) for a, b in spans)
            if longest > max_gap_s:
                a = max(spans, key=lambda s: time_s[s[1]] - time_s[s[0] - 1])[0]
                raise RunRefused(f"{label}: channel {name}: a dropout of {longest:.4g} s at t = {time_s[a]:.6g} s "
                                 f"(model scale), longer than the {max_gap_s:.4g} s accepted: refused")
            notes.append(f"{label}: channel {name}: {len(spans)} dropout(s), the longest {longest:.3g} s (first at "
                         f"t = {time_s[spans[0][0]]:.6g} s, model scale): interpolated")
        bad = ~good[:, j]
        if bad.any():
            values[bad, j] = np.interp(time_s[bad], time_s[~bad], values[~bad, j])
    return time_s, values


def probe_clock_offset(time_s: np.ndarray, reference: np.ndarray, other: np.ndarray, distance_m: float,
                       water_depth_m: float | None, gravity_m_s2: float = GRAVITY_M_S2) -> float:
    """How late [s] the clock of a probe ``distance_m`` down-wave of the reference probe runs
    (both records on the uniform clock ``time_s``, full scale): the reference record is
    propagated to the other probe (linear waves: each component's phase advanced by its
    wavenumber x the distance) and the lag of the other's record behind it is the
    cross-correlation's peak (Hann-windowed), refined between samples by the delay that
    maximises the cross-spectrum's real part."""
    n = time_s.size
    step = float(time_s[1] - time_s[0])
    spectrum = np.fft.rfft(reference - reference.mean())
    omega = 2 * np.pi * np.fft.rfftfreq(n, step)
    k = omega**2 / gravity_m_s2 if water_depth_m is None else wavenumber(omega, water_depth_m, gravity_m_s2)
    predicted = np.fft.irfft(spectrum * np.exp(-1j * k * distance_m), n)
    window = np.hanning(n)
    cross = np.fft.rfft((other - other.mean()) * window, 2 * n) * np.conj(np.fft.rfft(predicted * window, 2 * n))
    correlation = np.fft.irfft(cross, 2 * n)
    i = int(np.argmax(correlation))
    coarse = (i if i < n else i - 2 * n) * step
    omega_padded = 2 * np.pi * np.fft.rfftfreq(2 * n, step)
    fit = scipy.optimize.minimize_scalar(lambda d: -float(np.real(np.sum(cross * np.exp(1j * omega_padded * d)))),
                                         bounds=(coarse - step, coarse + step), method="bounded",
                                         options={"xatol": 1e-6 * step})
    return float(fit.x)


def condition(raw: RawRun, mapping: ColumnMap, source: str, max_gap_s: float = MAX_GAP_S) -> BasinRun:
    """A run read from a file: checked and handled at model scale, then in SI units at full
    scale with the motion at the platform's reference point (``BasinRun``). ``max_gap_s``:
    the longest gap or dropout interpolated, full scale."""
    label = f"{source}: run {raw.name}"
    notes: list[str] = []
    lam, rho = mapping.scale, mapping.density_ratio or 1.0
    model_gap_s = max_gap_s / froude_factor("time", lam)
    names = [c.name for c in mapping.channels]
    values = np.column_stack([raw.channels[n] for n in names])
    if mapping.time_channel:
        clock = raw.channels[mapping.time_channel] * UNITS["time"][mapping.time_unit]
    else:
        clock = np.arange(values.shape[0]) / mapping.sample_rate_hz
    marked = np.column_stack([values, np.zeros(len(clock))])
    clock, marked = checked_clock(label, clock, marked, model_gap_s, notes)
    inserted = np.isnan(marked[:, -1])
    clock, values = filled(label, clock, marked[:, :-1], names, model_gap_s, notes, inserted)
    time_s = clock * froude_factor("time", lam)
    full = {c.name: c.to_si(values[:, j]) * froude_factor(c.kind, lam, rho) for j, c in enumerate(mapping.channels)}
    by_quantity = {c.quantity: full[c.name] for c in mapping.channels if c.quantity not in ("elevation", "tension")}
    motion = np.column_stack([by_quantity.get(dof, np.zeros(time_s.size)) for dof in DOFS])
    unmeasured = tuple(dof for dof in DOFS if dof not in by_quantity)
    point = np.asarray(mapping.motion_point_m) * froude_factor("length", lam)
    if point.any():
        rotations = rotation_matrix(motion[:, 3], motion[:, 4], motion[:, 5])  # (3, 3, n)
        motion[:, :3] -= np.einsum("ijn,j->ni", rotations, point)
    probes = {}
    reference = mapping.probes[0] if mapping.probes else None
    heading = math.radians(mapping.heading_deg)
    for probe in mapping.probes:
        xy = (probe.position_m[0] * lam, probe.position_m[1] * lam)
        shift = 0.0
        if probe is not reference:
            distance = ((xy[0] - reference.position_m[0] * lam) * math.cos(heading)
                        + (xy[1] - reference.position_m[1] * lam) * math.sin(heading))
            offset = probe_clock_offset(time_s, full[reference.name], full[probe.name], distance,
                                        mapping.water_depth_m)
            if abs(offset) > MAX_CLOCK_OFFSET_S:
                raise RunRefused(f"{label}: probe {probe.name}: its clock seems {offset:+.3g} s off probe "
                                 f"{reference.name}'s (full scale), more than {MAX_CLOCK_OFFSET_S:g} s: refused")
            if abs(offset) > CLOCK_TOLERANCE_S:
                shift = -offset
                notes.append(f"{label}: probe {probe.name}: clock {offset:+.3f} s off probe {reference.name}'s "
                             f"(full scale, from the waves' travel between them): corrected (samples moved before "
                             f"the record's start dropped)")
        probes[probe.name] = (xy, full[probe.name], shift)
    if time_s[0] < 0:  # ROS stamps are not negative
        notes.append(f"{label}: the clock starts at {time_s[0]:.6g} s (full scale): all stamps moved "
                     f"{-time_s[0]:.6g} s later so that none is negative")
        time_s = time_s - time_s[0]
    others = {(f"tension:{c.line}" if c.quantity == "tension" else c.quantity): full[c.name]
              for c in mapping.channels if c.quantity not in ("elevation", *DOFS)}
    return BasinRun(raw.name, source, time_s, probes, motion, unmeasured, others, notes)
