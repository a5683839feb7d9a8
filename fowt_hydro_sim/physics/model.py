"""The platform model: composes waves, Morison strips (constant or band-filtered drag),
hydrostatics, mooring, gravity and an external wrench into a 6-DOF time-domain simulation
(no ROS here).

    model = PlatformModel(load_platform("windmoor12"), synthesize(sea, 3600.0))
    result = model.run(600.0)            # batch
    sample = model.step()                # or one dt at a time (a node does this)

A force written in Python, without a load component of its own (docs/contributing.md):

    def mooring_damper(t, position, velocity):      # world axes, about the reference point
        return np.array([-2e5 * velocity[0], 0, 0, 0, 0, 0])

    model = PlatformModel(platform, waves, user_force=mooring_damper)
    model.run(600.0).load("user")        # its wrench, one row per output sample
"""
from __future__ import annotations

import logging
import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass, fields, replace

import numpy as np

from fowt_hydro_sim.errors import InputError
from fowt_hydro_sim.frames import rotation_matrix as rotation_matrices
from fowt_hydro_sim.physics import dynamics
from fowt_hydro_sim.physics import free_surface_hydrostatics as free_surface
from fowt_hydro_sim.physics.config import DRAG_MODELS, ConfigError, HydroOptions, Platform
from fowt_hydro_sim.physics.drag_filters import (
    StateSpace,
    band_velocities,
    bank_state_space,
    nonzero_entries,
    state_response,
)
from fowt_hydro_sim.physics.dynamics import (
    N_BODY_STATES,
    FilterBank,
    HydroFlags,
    KernelData,
    PlateData,
    RigidBody,
    StripData,
    WaveTable,
)
from fowt_hydro_sim.physics.loads import (
    FIRST_MODULE_ROW,
    N_LOADS,
    RESTORING,
    ROW,
    ComponentInputs,
    component_data,
    external,
    mooring,
    params_of,
)
from fowt_hydro_sim.physics.loads.extension import Extension
from fowt_hydro_sim.physics.loads.hydrostatic import Hydrostatics, carried_wrench, hydrostatics
from fowt_hydro_sim.physics.marine_growth import grown_platform, growth_mass
from fowt_hydro_sim.physics.mooring.catenary_tables import MOORPY, SPAN_H_M, SPAN_V_M, line_forces
from fowt_hydro_sim.physics.mooring.moordyn_lines import MoorDynLines
from fowt_hydro_sim.physics.morison import (
    added_mass_about,
    added_mass_moments,
    added_mass_tensors,
    deep_added_mass_about,
    lever_arms,
    relative_velocities,
    wetted_fractions,
)
from fowt_hydro_sim.physics.rigid_body import rotation_matrix
from fowt_hydro_sim.physics.strips import Discretisation, discretise
from fowt_hydro_sim.physics.tables import interpolate_into, interpolate_table
from fowt_hydro_sim.physics.waves.components import WaveComponents
from fowt_hydro_sim.physics.waves.grid import SeaStateGrid
from fowt_hydro_sim.physics.waves.kinematics import (
    BlocksAhead,
    BlockSynthesis,
    KinematicsTable,
    complex_amplitudes,
    extrapolated_kinematics,
    moving_point_kinematics,
    period_table,
    table_step,
)
from fowt_hydro_sim.physics.waves.maccamy_fuchs import point_groups, scaled_waves

log = logging.getLogger(__name__)

DOF_NAMES = ("surge", "sway", "heave", "roll", "pitch", "yaw")
# f(t, position (6), velocity (6)) -> wrench (6): PlatformModel's user_force
UserForce = Callable[[float, np.ndarray, np.ndarray], np.ndarray]
WAVE_BLOCK_S = 600.0  # kinematics synthesised per block of this length (two blocks held)


@dataclass(frozen=True)
class RunResult:
    """Time series of a run, one row per output sample (world axes, reference point)."""

    time_s: np.ndarray  # (n,)
    motion: np.ndarray  # (n, 6) surge, sway, heave [m], roll, pitch, yaw [rad]
    velocity: np.ndarray  # (n, 6) linear [m/s], angular [rad/s], world axes
    acceleration: np.ndarray  # (n, 6)
    loads: np.ndarray  # (n, N_LOADS, 6), rows in the order of the load registry (physics.loads)
    wave_elevation_m: np.ndarray  # (n,) at the reference point (0, 0)

    def load(self, name: str) -> np.ndarray:
        return self.loads[:, ROW[name]]

    @staticmethod
    def joined(parts: list[RunResult]) -> RunResult:
        """Consecutive runs as one: each part after the first starts where the one before
        ended, so its first row is dropped."""
        if not parts:
            raise ValueError("no run to join")
        return RunResult(**{f.name: np.concatenate([getattr(parts[0], f.name)]
                                                   + [getattr(p, f.name)[1:] for p in parts[1:]])
                            for f in fields(RunResult)})


class PlatformModel:
    """A floating platform in waves, stepped with a fixed dt.

    ``waves`` None is still water. Kinematics are taken at the undisplaced strip points
    (HydroDyn's WaveDisp = 0) from a table over the waves' repeat period. ``drag_model``
    ``constant`` uses each direction's constant Cd; ``filtered`` splits the transverse
    relative velocity into the platform's drag bands (drag_filters.py). ``extension`` adds
    loads beyond the Morison model (extension.py; the gap diagnosis's effects).
    ``kinematics``: the table of these waves at this platform's points, built before (replays
    of one run share it); without it the table is synthesised in blocks of ``wave_block_s``
    as the run advances (waves.kinematics.BlockSynthesis: the same rows, two blocks held in
    a ring, so that the memory does not grow with the repeat period; with ``blocks_ahead`` the
    next block is made in a worker thread while the run uses the current ones: the same rows,
    and a run stepped in real time does not pause for them; a repeat period no longer than a
    block is made whole, once). ``options``: how the moving body's hydrodynamics are taken
    (config.HydroOptions; default: undisplaced wetted length, fixed directions, nonlinear
    hydrostatics and Newman's slow drift; config.HYDRODYN is HydroDyn's, without the drift).
    ``user_force``: a Python function ``f(t, position, velocity) -> (6,)`` adding its wrench
    [Fx, Fy, Fz, Mx, My, Mz] (world axes, about the reference point; N, N m) to the equations
    of motion, reported as the load component ``user``. ``position`` is [x, y, z, roll, pitch,
    yaw] (m, rad) and ``velocity`` [v_x, v_y, v_z, w_x, w_y, w_z] (m/s, rad/s, world axes), both
    copies, at time ``t`` [s]; it is called at every evaluation of the equations of motion (two
    per step, four per step over the first three steps) with the state of that evaluation.
    With it the model steps in a Python loop (``dynamics.integrate_stepwise``: a few times
    slower; a force whose value changes between steps without the state changing calls
    ``user_force_changed``); without it the compiled loop runs alone, unchanged. ``mooring_model``: the
    platform's mooring model (``spring``, ``moorpy``, ``moordyn``; "" = the platform's own
    choice). ``moordyn`` steps MoorDyn in Python between the compiled evaluations, as a user
    force does (``physics.mooring.moordyn_lines``). ``wave_grid``: SeaState's grid, with
    ``options.wave_kinematics`` "grid" (prescribed motion only): the kinematics and elevation
    sampled at its nodes and interpolated as HydroDyn does (``physics.waves.grid``).
    """

    def __init__(self, platform: Platform, waves: WaveComponents | None = None, *, dt_s: float = 0.05,
                 drag_model: str = "constant", wave_table_dt_s: float | None = None,
                 extension: Extension | None = None, kinematics: KinematicsTable | None = None,
                 options: HydroOptions | None = None, wave_block_s: float = WAVE_BLOCK_S,
                 blocks_ahead: bool = True, user_force: UserForce | None = None, mooring_model: str = "",
                 wave_grid: SeaStateGrid | None = None):
        if drag_model not in DRAG_MODELS:
            raise ConfigError(f"drag model {drag_model!r}: must be one of {', '.join(DRAG_MODELS)}")
        if drag_model == "filtered" and not platform.drag_bands and platform.members:  # (no members: no drag)
            raise ConfigError(f"drag model 'filtered': platform {platform.name} has no drag_bands")
        if user_force is not None and not callable(user_force):
            raise ConfigError(f"user force: need a function f(t, position, velocity), got {user_force!r}")
        self.user_force = user_force
        # marine growth: the members grown (cut at the table's rows), its mass on the hydrostatic component,
        # as the fill's loads and mass (of the members as given)
        growth = growth_mass(platform)
        filled = platform
        platform = replace(grown_platform(platform), marine_growth=(), fill_groups=(),
                           mooring=platform.mooring.chosen(mooring_model))
        if platform.mooring.model == "linear" and platform.linear_mooring is None:
            raise ConfigError(f"mooring linear: platform {platform.name} has no linear_mooring")
        self.platform = platform
        self.mooring_lines: MoorDynLines | None = None
        if platform.mooring.model == "moordyn":
            self.mooring_lines = MoorDynLines(platform.mooring.file, platform.mooring.moordyn_dt_s)
        self.waves = waves
        self.dt_s = float(dt_s)
        self.drag_model = drag_model
        self.options = options or HydroOptions()
        if (self.options.wave_kinematics == "grid") != (wave_grid is not None):
            raise ConfigError("wave kinematics 'grid' needs a SeaState grid (wave_grid), and a SeaState grid needs "
                              "wave kinematics 'grid'")
        self.wave_grid = wave_grid
        # Wheeler and extrapolation stretching take each point above z = 0 at its own height
        self.geometry: Discretisation = discretise(
            platform, points_above_water=self.options.stretching in ("wheeler", "extrapolation"))
        bands = platform.drag_bands if drag_model == "filtered" else ()
        self.drag_bands = tuple(b.name for b in bands)
        self.filter_bank: StateSpace = bank_state_space(bands)
        self.hydrostatics: Hydrostatics = hydrostatics(platform, self.geometry.strips, growth, filled)
        env = platform.environment
        n_points = len(self.geometry.points_m)
        self._blocks: BlocksAhead | None = None  # the blocked table's blocks
        self._ring_blocks = [None, None]  # the block held in each half of the ring table
        if waves is None or waves.frequency_hz.size == 0 or not waves.periodic:
            # components on no common grid: summed directly by prescribed_motion_loads only
            table = np.zeros((4, n_points, 7))
            step, self._elevation = 1.0, np.zeros((4, 1, 1))
        else:
            step = wave_table_dt_s or table_step(waves)
            scaled_for = self.geometry.maccamy_fuchs_diameter_m
            if kinematics is not None:
                if kinematics.step_s != step or not np.array_equal(kinematics.points_m, self.geometry.points_m):
                    raise ValueError("kinematics table: built for other points or another step")
                if np.any(scaled_for > 0):
                    raise ConfigError("maccamy_fuchs members: their accelerations are not in a precomputed "
                                      "kinematics table")
                table = np.asarray(kinematics.values, dtype=np.float64)  # the kernel's one table type
            else:
                if not wave_block_s > 0:
                    raise InputError(f"wave block: must be > 0 s, got {wave_block_s}")
                block_rows = max(8, int(np.ceil(wave_block_s / step)))
                period_rows = int(round(waves.period_s / step))
                depth = (env.water_depth_m, env.gravity_m_s2, env.water_density_kg_m3)
                whole = abs(period_rows * step - waves.period_s) <= 1e-6 * waves.period_s
                if whole and period_rows <= block_rows and waves.harmonic.max() < period_rows // 2:
                    # a repeat period no longer than a block: its whole table, once, no ring
                    table = period_table(waves, self.geometry.points_m, period_rows, *depth, np.float64, scaled_for)
                else:
                    self._blocks = BlocksAhead(BlockSynthesis(waves, self.geometry.points_m, step, block_rows, *depth,
                                                              scaled_for),
                                               blocks_ahead)
                    table = np.zeros((2 * block_rows, n_points, 7))
            self._elevation = waves.elevation_series(0.0, 0.0, step, env.water_depth_m, env.gravity_m_s2)[:, None, None]
        self.wave_table_step_s = step
        self.extension = extension or Extension()
        self._data = self._kernel_data(table, step)
        self.reset()

    # ------------------------------------------------------------------ set-up
    def _kernel_data(self, table: np.ndarray, step: float) -> KernelData:
        s, plates = self.geometry.strips, self.geometry.plates
        strip_3x3, plate_3x3 = added_mass_tensors(self.geometry)
        filtered = self.drag_model == "filtered"
        bank = self.filter_bank
        mass = self.platform.mass
        params, tables = component_data(ComponentInputs(self.platform, self.geometry, self.hydrostatics,
                                                        self.extension, self.options, self.waves, self.dt_s,
                                                        self.drag_model))
        strip_6x6 = added_mass_about(s.centre_m, strip_3x3)
        wet = np.empty(len(s.length_m))
        wetted_fractions(np.eye(3), 0.0, s.centre_m, s.axis, s.length_m, np.zeros(len(s.length_m)), wet)
        deep = wet == 1.0
        # strips with drag filter states: wetted as at rest, those wet at rest (the others never load)
        filter_strip = np.flatnonzero(wet > 0.0 if self.options.wetted_length == "undisplaced" else wet >= 0.0)
        filter_column = np.full(len(s.length_m), -1, dtype=np.int64)
        filter_column[filter_strip] = np.arange(filter_strip.size)
        moments = added_mass_moments(s.centre_m, strip_3x3, s.length_m * deep)
        rest_moments = added_mass_moments(s.centre_m, strip_3x3, s.length_m * wet)
        return KernelData(
            waves=WaveTable(table, step),
            strips=StripData(s.centre_m, s.axis, s.directions, s.length_m, s.inertia_kg_m, s.added_mass_kg_m,
                             strip_3x3, strip_6x6, s.drag_kg_m2,
                             s.band_drag_kg_m2 if filtered else np.zeros((len(s.length_m), 0, 2)),
                             s.filtered & filtered, s.kinematics_point.astype(np.int64), filter_strip,
                             filter_column, deep,
                             deep_added_mass_about(np.eye(3), moments), moments, wet,
                             deep_added_mass_about(np.eye(3), rest_moments), rest_moments),
            plates=PlateData(plates.centre_m, plates.normal, plates.pressure_area_m2, plates.added_mass_kg,
                             plates.drag_kg_m, plate_3x3, added_mass_about(plates.centre_m, plate_3x3),
                             plates.kinematics_point.astype(np.int64)),
            filters=FilterBank(bank.a, nonzero_entries(bank.a), bank.b, bank.c, nonzero_entries(bank.c), bank.d),
            body=RigidBody(mass.mass_kg, np.array(mass.cog_m), np.array(mass.inertia_about_cog_kg_m2)),
            options=HydroFlags(self.options.load_directions == "fixed", self.options.wetted_length == "undisplaced"),
            component_params=params, component_tables=tables,
            still_surface=np.zeros(len(s.length_m) + len(plates.centre_m)))

    @property
    def n_strips(self) -> int:
        return len(self.geometry.strips.length_m)

    # ------------------------------------------------------------------ blocked wave table
    def _table_row(self, t: float) -> int:
        """The table row at or before time t, as the kernel's interpolation computes it."""
        return math.floor(t / self.wave_table_step_s)

    def _hold_rows(self, first_row: int, last_row: int) -> None:
        """Synthesise into the ring the blocks holding table rows first..last (at most two
        consecutive blocks; block b in half b mod 2). From a block's first row on, the next
        block not in the ring is made ahead: the worker has the whole block's time for it
        (at 20x real time, 5 s of wall time for a 100 s block). No-op for a whole-period
        table."""
        if self._blocks is None:
            return
        m = self._blocks.block_rows
        if last_row // m - first_row // m > 1:
            raise ValueError(f"wave table rows {first_row}..{last_row}: span more than two blocks")
        for block in range(first_row // m, last_row // m + 1):
            half = block % 2
            if self._ring_blocks[half] != block:
                self._ring_blocks[half] = None  # until written whole
                self._blocks.take(block, self._data.waves.values[half * m:(half + 1) * m])
                self._ring_blocks[half] = block
        if first_row >= 0:
            after = last_row // m + 1
            self._blocks.prepare(after + 1 if after in self._ring_blocks else after)

    @property
    def wave_block_wait_s(self) -> float:
        """Wall seconds the stepping spent on wave blocks: making them, or waiting for the
        worker making them ahead (0 for a whole-period or streamed table)."""
        return 0.0 if self._blocks is None else self._blocks.waited_s

    @property
    def wave_blocks_taken(self) -> tuple[int, int]:
        """How many wave blocks the stepping took, and how many of them the worker made ahead."""
        return (0, 0) if self._blocks is None else (self._blocks.taken, self._blocks.made_ahead)

    def _hold_times(self, first_s: float, last_s: float) -> None:
        """The rows the interpolation reads between these times (4 points around each)."""
        self._hold_rows(self._table_row(first_s) - 1, self._table_row(last_s) + 2)

    def _steps_held(self, first_step: int, n_steps: int) -> int:
        """How many of the next n steps from ``first_step`` the ring can hold at once (two
        blocks from the one the current time needs), after synthesising them; all of them
        for a whole-period table. When the run goes on past them, the block after is made
        ahead meanwhile (in the worker: a batch run's next part then finds it made)."""
        if self.waves is not None and self.waves.frequency_hz.size and not self.waves.periodic:
            raise ConfigError("wave components on no common frequency grid are summed directly, for prescribed "
                              "motion only (fowt-sim loads); the time loop needs them on one")
        if self._blocks is None:
            return n_steps
        m = self._blocks.block_rows
        first_row = self._table_row(first_step * self.dt_s) - 1
        last_row = (first_row // m + 2) * m - 1  # the end of the next block
        n = min(n_steps, max(0, int((last_row - 3) * self.wave_table_step_s / self.dt_s) - first_step))
        while n > 0 and self._table_row((first_step + n) * self.dt_s) + 2 > last_row:
            n -= 1
        self._hold_rows(first_row, self._table_row((first_step + n) * self.dt_s) + 2)
        if n < n_steps:
            self._blocks.prepare(last_row // m + 1)
        return n

    def reset(self, motion: np.ndarray | None = None, velocity: np.ndarray | None = None) -> None:
        """Restart at t = 0 from a 6-DOF offset and velocity (default: at rest), with the drag
        filters in steady state."""
        self._state = np.zeros(N_BODY_STATES + self._data.strips.filter_strip.size * 2 * self.filter_bank.n_states)
        if motion is not None:
            self._state[0:6] = motion
        if velocity is not None:
            self._state[6:12] = velocity
        self._state[N_BODY_STATES:] = self._steady_filter_states()[:, self._data.strips.filter_strip].ravel()
        self._step_index = 0
        self._work = dynamics.workspace(self._data)
        mooring.reset_outside(params_of("mooring", self._data.component_params))
        if self.mooring_lines is not None:
            self.mooring_lines.reset(0.0, self._state)
        self._restart_history()

    def _steady_filter_states(self) -> np.ndarray:
        """Filter states (n_states, n_strips, 2) at t = 0 in steady state: the harmonic
        response to the waves' relative velocity (body held at its initial pose) plus the
        response to the body's initial velocity held constant."""
        bank, s = self.filter_bank, self.geometry.strips
        states = np.zeros((bank.n_states, self.n_strips, 2))
        if bank.n_states == 0:
            return states
        v_body = self._relative_velocities(np.zeros((len(self.geometry.points_m), 7)))  # still water
        states += np.linalg.solve(-bank.a, bank.b)[:, None, None] * v_body
        if self.waves is not None and self.waves.frequency_hz.size:
            env = self.platform.environment
            response = state_response(bank, 2 * np.pi * self.waves.frequency_hz)  # (n_freq, n_states)
            at_points = np.empty((len(self.geometry.points_m), 3, bank.n_states))
            for i, point in enumerate(self.geometry.points_m):  # one point at a time bounds the temporaries
                velocity = complex_amplitudes(self.waves, point, env.water_depth_m, env.gravity_m_s2,
                                              env.water_density_kg_m3)[0, 0:3]
                at_points[i] = (velocity @ response).real  # (3, n_states)
            directions = s.directions @ self._frame().T  # world axes
            states += np.einsum("nkc,ncj->jnk", directions, at_points[s.kinematics_point])
        return states

    def _frame(self) -> np.ndarray:
        """The axes the strip loads are taken in at the current state (morison.py)."""
        return np.eye(3) if self.options.load_directions == "fixed" else rotation_matrix(*self._state[3:6])

    def _relative_velocities(self, kinematics: np.ndarray) -> np.ndarray:
        """Transverse relative velocity (n_strips, 2) at the current state in the given point
        kinematics (points, 7)."""
        s = self.geometry.strips
        fixed = self.options.load_directions == "fixed"
        arm = s.centre_m.copy()
        if fixed:
            lever_arms(rotation_matrix(*self._state[3:6]), s.centre_m, arm)
        v_rel, a_fluid = np.empty((self.n_strips, 2)), np.empty((self.n_strips, 2))
        relative_velocities(self._frame(), fixed, self._state[6:9], self._state[9:12], kinematics, arm,
                            s.directions, s.kinematics_point, np.ones(self.n_strips), False, v_rel, a_fluid)
        return v_rel

    def _restart_history(self) -> None:
        """Forget the integrator's past derivatives (after a jump in state)."""
        self._history = np.full((4, self._state.size), np.nan)
        self._newest = np.zeros(1, dtype=np.int64)  # the ring's latest row
        self._input_changed = False
        self._hold_times(self.time_s, self.time_s)
        self._rates(self.time_s, self._state, self._history[0])

    def _rates(self, t: float, y: np.ndarray, out: np.ndarray) -> None:
        """dy/dt at (t, y) into ``out`` and the loads into the workspace; with a user force,
        its wrench at (t, y) first into its component's params."""
        if self.user_force is not None:
            params_of("user", self._data.component_params)[:] = self._user_wrench(t, y)
        if self.mooring_lines is not None:  # the final evaluation of a step is at the model's own state
            params_of("mooring", self._data.component_params)[1:7] = self.mooring_lines.wrench(t, y, y is self._state)
        dynamics.derivative(t, y, self._data, self._work, out)

    def _user_wrench(self, t: float, y: np.ndarray) -> np.ndarray:
        """The user force's wrench at time t and state y, checked."""
        wrench = np.asarray(self.user_force(t, y[0:6].copy(), y[6:12].copy()), dtype=float)
        if wrench.shape != (6,) or not np.all(np.isfinite(wrench)):
            raise InputError(f"user force at t = {t:g} s: must return 6 finite numbers, got {wrench.tolist()!r}")
        return wrench

    def set_external_wrench(self, wrench: np.ndarray, frame: str = "world") -> None:
        """Hold a wrench [Fx, Fy, Fz, Mx, My, Mz] until the next call.

        ``world``: world axes at the reference point; ``platform``: body axes at the
        reference point; ``hub``: body axes at the hub point.
        """
        external.set_wrench(params_of("external", self._data.component_params), wrench, frame,
                            self.platform.hub_point_m)
        self._input_changed = True  # the derivative at the current time changes with it: ``_refresh``

    def user_force_changed(self) -> None:
        """Say that the user force's value at the current time has changed without the state
        changing (a value it holds, set between steps): the acceleration and loads read next,
        and the next step, evaluate it again, as ``set_external_wrench`` does for its wrench."""
        self._input_changed = True

    def _refresh(self) -> None:
        """Evaluate the derivative at the current time again if an input changed since (the
        next step does it inside the kernel's call; the acceleration and loads read before it)."""
        if self._input_changed:
            self._hold_times(self.time_s, self.time_s)
            self._rates(self.time_s, self._state, self._history[self._newest[0]])
            self._input_changed = False

    def use_streamed_waves(self, step_s: float, n_rows: int = 256) -> None:
        """Take the wave kinematics from ``write_waves`` (a stream, e.g. a wave topic) instead of
        the precomputed table: a ring of ``n_rows`` samples every ``step_s``, still water until
        written. Rows from the current time to 2 steps past the next step end must be written
        before stepping; a row is reused ``n_rows`` steps later."""
        if n_rows < 8 or step_s <= 0:
            raise InputError(f"streamed waves: need step_s > 0 and n_rows >= 8, got {step_s}, {n_rows}")
        if np.any(self.geometry.maccamy_fuchs_diameter_m > 0):
            raise ConfigError("maccamy_fuchs members: streamed waves carry no MacCamy-Fuchs accelerations")
        table = np.zeros((n_rows, len(self.geometry.points_m), 7))
        self._data = self._data._replace(waves=WaveTable(table, float(step_s)))
        self._elevation = np.zeros((n_rows, 1, 1))
        self.wave_table_step_s = float(step_s)
        self.waves = None
        self._blocks = None
        tables = list(self._data.component_tables)  # no components: no slow drift series
        tables[ROW["drift"] - FIRST_MODULE_ROW] = np.zeros((4, 2))
        self._data = self._data._replace(component_tables=tuple(tables))
        self._restart_history()  # the derivative at t changes with the table

    def write_waves(self, time_s: float, kinematics: np.ndarray, elevation_m: float) -> None:
        """Streamed kinematics (points, 7) at the model's points and the elevation at the
        reference point, for ``time_s`` (a multiple of the stream's step)."""
        rows = self._data.waves.values.shape[0]
        row = int(round(time_s / self.wave_table_step_s)) % rows
        self._data.waves.values[row] = kinematics
        self._elevation[row, 0, 0] = elevation_m

    # ------------------------------------------------------------------ state
    @property
    def time_s(self) -> float:
        return self._step_index * self.dt_s

    @property
    def motion(self) -> np.ndarray:
        return self._state[0:6].copy()

    @property
    def velocity(self) -> np.ndarray:
        return self._state[6:12].copy()

    @property
    def acceleration(self) -> np.ndarray:
        self._refresh()
        return self._history[self._newest[0], 6:12].copy()

    def strip_velocities(self) -> tuple[np.ndarray, np.ndarray]:
        """Transverse relative velocity of each strip (n_strips, 2: d1, d2, member frame) and
        its band velocities (n_strips, n_bands, 2) at the current time; NaN for a strip
        without drag filter states (dry at rest, wetted as at rest: it never loads)."""
        waves, bank, filtered = self._data.waves, self._data.filters, self._data.strips.filter_strip
        self._hold_times(self.time_s, self.time_s)
        v_rel = self._relative_velocities(interpolate_table(waves.values, waves.step_s, self.time_s))
        v_band = np.empty((bank.d.size, 2 * filtered.size))
        states = self._state[N_BODY_STATES:].reshape(self.filter_bank.n_states, 2 * filtered.size)
        band_velocities(states, v_rel[filtered].ravel(), bank.c, bank.c_nonzero, bank.d, v_band)
        out = np.full((self.n_strips, bank.d.size, 2), np.nan)
        out[filtered] = v_band.reshape(-1, filtered.size, 2).transpose(1, 0, 2)
        return v_rel, out

    @property
    def loads(self) -> np.ndarray:
        """(N_LOADS, 6) loads at the current time (load registry order)."""
        self._refresh()
        return self._work.loads.copy()

    def wave_elevation(self, time_s: float | np.ndarray) -> np.ndarray:
        """Elevation at the reference point (0, 0), from the model's wave table."""
        t = np.atleast_1d(np.asarray(time_s, dtype=float))
        if self.waves is not None and self.waves.frequency_hz.size and not self.waves.periodic:
            env = self.platform.environment
            return self.waves.elevation(0.0, 0.0, t, env.water_depth_m, env.gravity_m_s2)
        return np.array([interpolate_table(self._elevation, self.wave_table_step_s, x)[0, 0]
                         for x in t])

    # ------------------------------------------------------------------ stepping
    def step(self, n_steps: int = 1) -> None:
        """Advance n steps of dt; the state, acceleration and loads are then at the new time."""
        self._advance(n_steps, n_steps)

    def run(self, duration_s: float, output_interval_s: float | None = None) -> RunResult:
        """Advance ``duration_s`` and return the time series, one row every output interval
        (default every step), the current time included as the first row."""
        n_steps = int(round(duration_s / self.dt_s))
        every = max(1, int(round((output_interval_s or self.dt_s) / self.dt_s)))
        first = (self.time_s, self._state[:N_BODY_STATES].copy(), self.acceleration, self.loads)
        t, y, acc, loads = self._advance(n_steps, every)
        time = np.concatenate([[first[0]], t])
        states = np.vstack([first[1], y])
        return RunResult(time, states[:, 0:6], states[:, 6:12], np.vstack([first[2], acc]),
                         np.concatenate([first[3][None], loads]), self.wave_elevation(time))

    def run_parts(self, duration_s: float, output_interval_s: float | None = None,
                  part_s: float = WAVE_BLOCK_S) -> Iterator[RunResult]:
        """``run`` in consecutive parts of about ``part_s`` (whole output intervals), each as
        ``run`` returns it (its first row is the previous part's last): the same numbers,
        bit for bit, with the outputs of one part in memory at a time."""
        n_steps = int(round(duration_s / self.dt_s))
        every = max(1, int(round((output_interval_s or self.dt_s) / self.dt_s)))
        part_steps = max(1, int(round(part_s / self.dt_s)) // every) * every
        for first in range(0, max(n_steps, 1), part_steps):  # a 0 s run: its one row
            yield self.run(min(part_steps, n_steps - first) * self.dt_s, output_interval_s)

    def _advance(self, n_steps: int, every: int) -> tuple[np.ndarray, ...]:
        """Integrate n steps, recording every ``every``-th; with a blocked wave table, in parts
        of whole recording intervals that the ring holds."""
        if self.options.kinematics == "displaced":
            raise ConfigError("kinematics 'displaced': implemented for a prescribed motion only (fowt-sim loads, "
                              "PlatformModel.prescribed_motion_loads), not for time stepping")
        if self.options.hydrostatics == "free_surface":
            raise ConfigError("hydrostatics 'free_surface': implemented for a prescribed motion only (fowt-sim "
                              "loads, PlatformModel.prescribed_motion_loads), not for time stepping")
        if self.options.stretching != "none":
            raise ConfigError(f"stretching {self.options.stretching!r}: implemented for a prescribed motion only "
                              "(fowt-sim loads, PlatformModel.prescribed_motion_loads), not for time stepping")
        if self.wave_grid is not None:
            raise ConfigError("wave kinematics 'grid': implemented for a prescribed motion only (fowt-sim loads, "
                              "PlatformModel.prescribed_motion_loads), not for time stepping")
        if self.mooring_lines is not None:  # MoorDyn's tensions: this advance's steps only
            self.mooring_lines.forget_before(self.time_s)
        n_out = n_steps // every
        out_t = np.empty(n_out)
        out_y = np.empty((n_out, N_BODY_STATES))
        out_acc = np.empty((n_out, 6))
        out_loads = np.empty((n_out, N_LOADS, 6))
        done, written = 0, 0
        while done < n_steps:
            part = self._steps_held(self._step_index, n_steps - done)
            if part < n_steps - done:
                part -= part % every
            if part <= 0:
                raise InputError(f"output interval {every * self.dt_s:g} s: longer than the wave table's "
                                 f"blocks hold; use a longer wave_block_s")
            outputs = (self._history, self._newest, out_t[written:], out_y[written:], out_acc[written:],
                       out_loads[written:])
            if self.user_force is None and self.mooring_lines is None:
                written += dynamics.integrate(self._state, self._step_index, self.dt_s, part, every, self._data,
                                              self._work, self._input_changed, *outputs)
                self._input_changed = False
            else:
                self._refresh()
                written += dynamics.integrate_stepwise(self._rates, self._state, self._step_index, self.dt_s, part,
                                                       every, self._work, *outputs)
            self._step_index += part
            done += part
            outside = mooring.outside_table(params_of("mooring", self._data.component_params))
            if outside is not None:
                raise InputError(f"{self.platform.mooring.file}: line {outside[1] + 1} left the moorpy model's "
                                 f"table (its fairlead more than {SPAN_H_M:g} m horizontally or {SPAN_V_M:g} m "
                                 f"vertically from where it rests) at t = {outside[0]:g} s")
        return out_t, out_y, out_acc, out_loads

    # ------------------------------------------------------------------ analysis
    def prescribed_motion_loads(self, time_s: np.ndarray, motion: np.ndarray, velocity: np.ndarray,
                                acceleration: np.ndarray) -> np.ndarray:
        """Loads (n, N_LOADS, 6) for a prescribed 6-DOF motion, like HydroDyn's driver."""
        if self.mooring_lines is not None:
            raise ConfigError("prescribed motion: the moordyn mooring needs the time loop; use the moorpy or "
                              "spring mooring")
        if self.filter_bank.n_states:
            raise ConfigError("prescribed motion: the filtered drag model's filter states need the "
                              "time loop; use the constant drag model")
        time_s = np.ascontiguousarray(time_s, dtype=float)
        n = time_s.size
        shapes = {"motion": motion, "velocity": velocity, "acceleration": acceleration}
        for name, arr in shapes.items():
            if np.shape(arr) != (n, 6):
                raise InputError(f"prescribed motion: {name} must have shape ({n}, 6), got {np.shape(arr)}")
        states = np.ascontiguousarray(np.hstack([motion, velocity]), dtype=float)
        acceleration = np.ascontiguousarray(acceleration, dtype=float)
        motion = np.asarray(motion, dtype=float)
        surfaces = self._surfaces(time_s, motion)
        out = np.zeros((n, N_LOADS, 6))
        params_of("user", self._data.component_params)[:] = 0.0  # its row: below
        per_time = (self.options.kinematics == "displaced" or self.options.stretching in ("wheeler", "extrapolation")
                    or self.wave_grid is not None
                    or (self.waves is not None and not self.waves.periodic))  # summed directly at each time
        if per_time and self.waves is not None and self.waves.frequency_hz.size:
            data = self._data._replace(waves=self._moving_table(time_s, motion))
            dynamics.prescribed_motion_loads(time_s, states, acceleration, data, surfaces, out)
        else:
            for part in self._held_parts(time_s):
                self._hold_times(time_s[part].min(), time_s[part].max())
                dynamics.prescribed_motion_loads(time_s[part], states[part], acceleration[part], self._data,
                                                 surfaces[part], out[part])
        if self.options.hydrostatics == "free_surface":
            env = self.platform.environment
            eta = free_surface.wave_elevation(self.waves, env.water_depth_m, env.gravity_m_s2)
            if self.wave_grid is not None:
                eta = self.wave_grid.elevation_function(self.waves, env.water_depth_m, env.gravity_m_s2)
            elif self.options.surface_grid_m is not None:
                eta = free_surface.on_grid(eta, self.options.surface_grid_m, self.options.surface_grid_m)
            out[:, ROW["hydrostatic"]] = free_surface.prescribed_motion_wrenches(
                free_surface.platform_members(self.platform), eta, time_s, motion,
                env.water_density_kg_m3, env.gravity_m_s2)
            if self.hydrostatics.growth[0] > 0 or len(self.hydrostatics.fill_records):
                # the kernel's row also held the growth's weight, the fill's end-cap loads and their inertia
                out[:, ROW["hydrostatic"]] += self._carried_loads(time_s, states, acceleration)
        if self.user_force is not None:
            out[:, ROW["user"]] = [self._user_wrench(t, y) for t, y in zip(time_s, states)]
        return out

    def _carried_loads(self, time_s: np.ndarray, states: np.ndarray, acceleration: np.ndarray) -> np.ndarray:
        """(n, 6): the marine growth's weight, the fill's end-cap loads and their inertial
        reaction along the motion, as the hydrostatic component's kernel adds them."""
        params = params_of("hydrostatic", self._data.component_params)
        out = np.zeros((time_s.size, 6))
        mass = np.zeros((6, 6))
        for i, y in enumerate(states):
            rotation = rotation_matrix(y[3], y[4], y[5])
            mass[:] = 0.0
            carried_wrench(y, rotation, params, out[i], mass)
            out[i] -= mass @ acceleration[i]
        return out

    def _held_parts(self, time_s: np.ndarray) -> list[slice]:
        """Consecutive runs of times whose table rows the ring holds at once (all of them
        for a whole-period table)."""
        if self._blocks is None or time_s.size == 0:
            return [slice(0, time_s.size)]
        m = self._blocks.block_rows
        rows = np.floor(time_s / self.wave_table_step_s).astype(np.int64)
        parts, start = [], 0
        low = high = rows[0]
        for i in range(1, rows.size):
            low, high = min(low, rows[i]), max(high, rows[i])
            if (high + 2) // m - (low - 1) // m > 1:
                parts.append(slice(start, i))
                start, low, high = i, rows[i], rows[i]
        parts.append(slice(start, rows.size))
        return parts

    def _surfaces(self, time_s: np.ndarray, motion: np.ndarray) -> np.ndarray:
        """(n, n_strips + n_plates): the water surface height each strip and end plate is wetted
        up to: 0, or with vertical stretching the elevation at its x, y (displaced or undisplaced,
        as the wetted length)."""
        centres = np.vstack([self.geometry.strips.centre_m, self.geometry.plates.centre_m])
        surfaces = np.zeros((time_s.size, len(centres)))
        if self.options.stretching == "none" or self.waves is None or not self.waves.frequency_hz.size:
            return surfaces
        for i, t in enumerate(time_s):
            xy = centres[:, 0:2]
            if self.options.wetted_length == "displaced":
                xy = motion[i, 0:2] + centres @ rotation_matrices(*motion[i, 3:6])[0:2].T
            surfaces[i] = self._elevation_at(xy, t)
        return surfaces

    def _elevation_at(self, xy: np.ndarray, t: float) -> np.ndarray:
        """The elevation at points (p, 2) at time t: exact, or interpolated on the SeaState grid."""
        env = self.platform.environment
        if self.wave_grid is not None:
            return self.wave_grid.elevation(self.waves, xy, np.full(len(xy), t), env.water_depth_m, env.gravity_m_s2)
        return self.waves.elevation_at(xy, t, env.water_depth_m, env.gravity_m_s2)

    def _moving_table(self, time_s: np.ndarray, motion: np.ndarray) -> WaveTable:
        """A kinematics table whose row i holds, at time t_i = i dt, the kinematics at the
        points' positions at t_i: what the kernel's table look-up then returns at t_i. The
        points are displaced (x + R p; WaveDisp 1; its z only with stretching, as HydroDyn's
        Morison.f90 takes it) or not, as ``options.kinematics`` says; a point's z is at most 0
        or, with Wheeler stretching, at most the elevation eta over it and taken at
        d (z - eta) / (d + eta), or, with extrapolation stretching, at most max(eta, 0) and
        above z = 0 extrapolated from there. The times must be multiples of one step."""
        step = float(time_s[1] - time_s[0]) if time_s.size > 1 else 1.0
        rows = np.round(time_s / step).astype(np.int64)
        if time_s.size < 2 or step <= 0 or np.max(np.abs(rows * step - time_s)) > 1e-6 * step or rows[0] < 0:
            raise ConfigError("prescribed motion with displaced or gridded kinematics or Wheeler or extrapolation "
                              "stretching: the times must be multiples of one constant step from t >= 0")
        points = self.geometry.points_m
        if self.options.kinematics == "displaced":
            rotation = rotation_matrices(motion[:, 3], motion[:, 4], motion[:, 5])  # (3, 3, n)
            world = motion[:, None, 0:3] + np.einsum("ijn,pj->npi", rotation, points)
            if self.options.stretching == "none":  # HydroDyn: the undisplaced z without stretching
                world[:, :, 2] = points[None, :, 2]
        else:
            world = np.repeat(points[None], time_s.size, axis=0)
        env = self.platform.environment
        kinematics = moving_point_kinematics
        if self.options.stretching in ("wheeler", "extrapolation"):
            depth = env.water_depth_m
            eta = np.stack([self._elevation_at(world[i, :, 0:2], t) for i, t in enumerate(time_s)])
            if self.options.stretching == "wheeler":
                world[:, :, 2] = depth * (np.minimum(world[:, :, 2], eta) - eta) / (depth + eta)
            else:  # extrapolated above z = 0, up to eta at most
                world[:, :, 2] = np.minimum(world[:, :, 2], np.maximum(eta, 0.0))
                kinematics = extrapolated_kinematics
        else:
            world[:, :, 2] = np.minimum(world[:, :, 2], 0.0)  # no kinematics above the water line
        if self.wave_grid is not None:
            kinematics = self.wave_grid.interpolate_kinematics(kinematics)
        values = kinematics(self.waves, world.reshape(-1, 3), np.repeat(time_s, len(points)),
                            env.water_depth_m, env.gravity_m_s2, env.water_density_kg_m3)
        table = np.zeros((rows[-1] + 3, len(points), 7))
        table[rows] = values.reshape(time_s.size, len(points), 7)
        for diameter, index in point_groups(self.geometry.maccamy_fuchs_diameter_m):
            scaled = kinematics(scaled_waves(self.waves, diameter, env.water_depth_m, env.gravity_m_s2),
                                world[:, index].reshape(-1, 3), np.repeat(time_s, index.size), env.water_depth_m,
                                env.gravity_m_s2, env.water_density_kg_m3)
            table[rows[:, None], index[None, :], 3:6] = scaled.reshape(time_s.size, index.size, 7)[:, :, 3:6]
        return WaveTable(table, step)

    @property
    def n_mooring_lines(self) -> int:
        """How many mooring lines the model's mooring has."""
        params = params_of("mooring", self._data.component_params)
        if self.mooring_lines is not None:
            return self.mooring_lines.n_lines
        return int(params[1]) if params[0] == MOORPY else len(self.platform.mooring.lines)

    def mooring_tensions(self, time_s: np.ndarray, motion: np.ndarray) -> np.ndarray:
        """(n, lines, 2): each mooring line's fairlead and anchor tension [N] at the times and
        platform positions (n, 6) of a run of this model: the springs' T0 + k (L - L0) (both
        ends), the moorpy lines' quasi-static tensions, or MoorDyn's at its committed steps
        (the times of the latest ``run`` or ``step``, its start included; NaN for others)."""
        time_s, motion = np.atleast_1d(np.asarray(time_s, dtype=float)), np.atleast_2d(motion)
        params = params_of("mooring", self._data.component_params)
        if self.mooring_lines is not None:
            return self.mooring_lines.tensions_at(time_s)
        if params[0] == MOORPY:
            forces = line_forces(params, self._data.component_tables[ROW["mooring"] - FIRST_MODULE_ROW], motion)
            return np.stack([np.hypot(forces[..., 0], forces[..., 1]), np.hypot(forces[..., 2], forces[..., 3])],
                            axis=-1)
        m = self.platform.mooring
        if not m.lines:  # a linear mooring (a matrix) has no lines to report
            return np.zeros((len(time_s), 0, 2))
        fairleads = np.array([line.fairlead_m for line in m.lines])
        anchors = np.array([line.anchor_m for line in m.lines])
        rotations = rotation_matrices(motion[:, 3], motion[:, 4], motion[:, 5])  # (3, 3, n)
        world = motion[:, None, 0:3] + np.einsum("ijn,lj->nli", rotations, fairleads)
        tension = m.pretension_n + m.stiffness_n_m * (np.linalg.norm(anchors[None] - world, axis=-1)
                                                      - m.unstretched_length_m)
        return np.stack([tension, tension], axis=-1)

    def mass_matrix(self) -> np.ndarray:
        """Rigid-body plus added mass (and any load component's mass) at rest, 6x6 about the
        reference point."""
        work = dynamics.workspace(self._data)
        rest = np.zeros_like(self._state)
        self._hold_times(0.0, 0.0)
        interpolate_into(self._data.waves.values, self._data.waves.step_s, 0.0, work.kinematics)
        dynamics.applied_loads(0.0, rest, self._data, work, np.empty(rest.size - N_BODY_STATES),
                               self._data.still_surface, False)
        body = self._data.body
        rigid, bias = np.empty((6, 6)), np.empty(6)
        dynamics.mass_matrix_and_bias(body.mass, body.cog, body.inertia_cog, np.eye(3), np.zeros(3), rigid, bias)
        return rigid + work.world_added_mass + work.masses.sum(axis=0)

    def restoring_matrix(self, step: float = 1e-4) -> np.ndarray:
        """Linear restoring matrix at rest, by central differences in still water of the static
        restoring loads (the registry's ``restoring`` components: hydrostatics, gravity,
        mooring, a potential-flow hull's .hst and AddCLin)."""
        still = self._data.waves._replace(values=np.zeros_like(self._data.waves.values[:4]))
        data = self._data._replace(waves=still)
        out = np.zeros((6, 6))
        work = dynamics.workspace(data)
        restoring = [ROW[name] for name in RESTORING]
        for j in range(6):
            wrench = []
            for sign in (1.0, -1.0):
                y = np.zeros_like(self._state)
                y[j] = sign * step
                dynamics.applied_loads(0.0, y, data, work, np.empty(y.size - N_BODY_STATES), data.still_surface, False)
                wrench.append(work.loads[restoring].sum(axis=0))
            out[:, j] = -(wrench[0] - wrench[1]) / (2 * step)
        return out

    def natural_periods_s(self) -> np.ndarray:
        """Undamped natural periods of the linearised model, longest first."""
        eigenvalues = np.linalg.eigvals(np.linalg.solve(self.mass_matrix(), self.restoring_matrix()))
        return 2 * np.pi / np.sqrt(np.sort(eigenvalues.real))
