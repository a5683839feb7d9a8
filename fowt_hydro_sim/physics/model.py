"""The platform model: composes waves, Morison strips (constant or band-filtered drag),
hydrostatics, mooring, gravity and an external wrench into a 6-DOF time-domain simulation
(no ROS here).

    model = PlatformModel(load_platform("windmoor12"), synthesize(sea, 3600.0))
    result = model.run(600.0)            # batch
    sample = model.step()                # or one dt at a time (a node does this)
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, fields

import numpy as np

from fowt_hydro_sim.physics import dynamics
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
    N_MODULE_COMPONENTS,
    FilterBank,
    HydroFlags,
    KernelData,
    PlateData,
    RigidBody,
    StripData,
    WaveTable,
)
from fowt_hydro_sim.physics.loads import (FIRST_MODULE_ROW, N_LOADS, ROW, ComponentInputs, component_data, external,
                                          params_of)
from fowt_hydro_sim.physics.loads.extension import Extension
from fowt_hydro_sim.physics.loads.hydrostatic import Hydrostatics, hydrostatics
from fowt_hydro_sim.physics.morison import added_mass_about, added_mass_tensors, lever_arms, relative_velocities
from fowt_hydro_sim.physics.rigid_body import rotation_matrix
from fowt_hydro_sim.physics.strips import Discretisation, discretise
from fowt_hydro_sim.physics.tables import interpolate_table
from fowt_hydro_sim.physics.waves.components import WaveComponents
from fowt_hydro_sim.physics.waves.kinematics import KinematicsTable, complex_amplitudes, table_step

log = logging.getLogger(__name__)

DOF_NAMES = ("surge", "sway", "heave", "roll", "pitch", "yaw")


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
        return RunResult(**{f.name: np.concatenate([getattr(parts[0], f.name)] + [getattr(p, f.name)[1:] for p in parts[1:]])
                            for f in fields(RunResult)})


class PlatformModel:
    """A floating platform in waves, stepped with a fixed dt.

    ``waves`` None is still water. Kinematics are taken at the undisplaced strip points
    (HydroDyn's WaveDisp = 0) from a table over the waves' repeat period. ``drag_model``
    ``constant`` uses each direction's constant Cd; ``filtered`` splits the transverse
    relative velocity into the platform's drag bands (drag_filters.py). ``extension`` adds
    loads beyond the Morison model (extension.py; the gap diagnosis's effects).
    ``kinematics``: the table of these waves at this platform's points, built before (replays
    of one run share it). ``options``: how the moving body's hydrodynamics are taken
    (config.HydroOptions; default today's: displaced wetted length, rotating directions,
    linear hydrostatics; config.HYDRODYN is HydroDyn's).
    """

    def __init__(self, platform: Platform, waves: WaveComponents | None = None, *, dt_s: float = 0.05,
                 drag_model: str = "constant", wave_table_dt_s: float | None = None,
                 extension: Extension | None = None, kinematics: KinematicsTable | None = None,
                 options: HydroOptions | None = None):
        if drag_model not in DRAG_MODELS:
            raise ConfigError(f"drag model {drag_model!r}: must be one of {', '.join(DRAG_MODELS)}")
        if drag_model == "filtered" and not platform.drag_bands:
            raise ConfigError(f"drag model 'filtered': platform {platform.name} has no drag_bands")
        self.platform = platform
        self.waves = waves
        self.dt_s = float(dt_s)
        self.drag_model = drag_model
        self.options = options or HydroOptions()
        self.geometry: Discretisation = discretise(platform)
        bands = platform.drag_bands if drag_model == "filtered" else ()
        self.drag_bands = tuple(b.name for b in bands)
        self.filter_bank: StateSpace = bank_state_space(bands)
        self.hydrostatics: Hydrostatics = hydrostatics(platform, self.geometry.strips)
        env = platform.environment
        if waves is None or waves.frequency_hz.size == 0:
            table = np.zeros((4, len(self.geometry.points_m), 7), dtype=np.float32)
            step, self._elevation = 1.0, np.zeros((4, 1, 1))
        else:
            step = wave_table_dt_s or table_step(waves)
            if kinematics is None:
                kinematics = KinematicsTable.build(waves, self.geometry.points_m, step, env.water_depth_m,
                                                   env.gravity_m_s2, env.water_density_kg_m3)
            elif kinematics.step_s != step or not np.array_equal(kinematics.points_m, self.geometry.points_m):
                raise ValueError("kinematics table: built for other points or another step")
            table = kinematics.values
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
                                                        self.extension, self.options, self.waves))
        return KernelData(
            waves=WaveTable(table, step),
            strips=StripData(s.centre_m, s.axis, s.directions, s.length_m, s.inertia_kg_m, s.added_mass_kg_m,
                             strip_3x3, added_mass_about(s.centre_m, strip_3x3), s.drag_kg_m2,
                             s.band_drag_kg_m2 if filtered else np.zeros((len(s.length_m), 0, 2)),
                             s.filtered & filtered, s.kinematics_point.astype(np.int64)),
            plates=PlateData(plates.centre_m, plates.normal, plates.pressure_area_m2, plates.added_mass_kg,
                             plates.drag_kg_m, plate_3x3, added_mass_about(plates.centre_m, plate_3x3),
                             plates.kinematics_point.astype(np.int64)),
            filters=FilterBank(bank.a, nonzero_entries(bank.a), bank.b, bank.c, nonzero_entries(bank.c), bank.d),
            body=RigidBody(mass.mass_kg, np.array(mass.cog_m), np.array(mass.inertia_about_cog_kg_m2)),
            options=HydroFlags(self.options.load_directions == "fixed", self.options.wetted_length == "undisplaced"),
            component_params=params, component_tables=tables)

    @property
    def n_strips(self) -> int:
        return len(self.geometry.strips.length_m)

    def reset(self, motion: np.ndarray | None = None, velocity: np.ndarray | None = None) -> None:
        """Restart at t = 0 from a 6-DOF offset and velocity (default: at rest), with the drag
        filters in steady state."""
        self._state = np.zeros(N_BODY_STATES + self.n_strips * 2 * self.filter_bank.n_states)
        if motion is not None:
            self._state[0:6] = motion
        if velocity is not None:
            self._state[6:12] = velocity
        self._state[N_BODY_STATES:] = self._steady_filter_states().ravel()
        self._step_index = 0
        self._loads = np.zeros((N_LOADS, 6))
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
            velocity = complex_amplitudes(self.waves, self.geometry.points_m, env.water_depth_m,
                                          env.gravity_m_s2, env.water_density_kg_m3)[:, 0:3]
            response = state_response(bank, 2 * np.pi * self.waves.frequency_hz)  # (n_freq, n_states)
            at_points = np.einsum("pcf,fj->pcj", velocity, response).real  # (points, 3, n_states)
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
        frame = self._frame()
        arm = lever_arms(rotation_matrix(*self._state[3:6]), s.centre_m) if self.options.load_directions == "fixed" \
            else s.centre_m
        v_rel, a_fluid = np.empty((self.n_strips, 2)), np.empty((self.n_strips, 2))
        relative_velocities(frame, self._state[6:9], self._state[9:12], kinematics, arm, s.directions,
                            s.kinematics_point, v_rel, a_fluid)
        return v_rel

    def _restart_history(self) -> None:
        """Forget the integrator's past derivatives (after a jump in state)."""
        self._history = np.full((4, self._state.size), np.nan)
        self._newest = np.zeros(1, dtype=np.int64)  # the ring's latest row
        dynamics.derivative(self.time_s, self._state, self._data, self._loads, self._history[0])

    def set_external_wrench(self, wrench: np.ndarray, frame: str = "world") -> None:
        """Hold a wrench [Fx, Fy, Fz, Mx, My, Mz] until the next call.

        ``world``: world axes at the reference point; ``platform``: body axes at the
        reference point; ``hub``: body axes at the hub point.
        """
        external.set_wrench(params_of("external", self._data.component_params), wrench, frame,
                            self.platform.hub_point_m)
        # the derivative at the current time changes with the input
        dynamics.derivative(self.time_s, self._state, self._data, self._loads, self._history[self._newest[0]])

    def use_streamed_waves(self, step_s: float, n_rows: int = 256) -> None:
        """Take the wave kinematics from ``write_waves`` (a stream, e.g. a wave topic) instead of
        the precomputed table: a ring of ``n_rows`` samples every ``step_s``, still water until
        written. Rows from the current time to 2 steps past the next step end must be written
        before stepping; a row is reused ``n_rows`` steps later."""
        if n_rows < 8 or step_s <= 0:
            raise ValueError(f"streamed waves: need step_s > 0 and n_rows >= 8, got {step_s}, {n_rows}")
        table = np.zeros((n_rows, len(self.geometry.points_m), 7), dtype=np.float32)
        self._data = self._data._replace(waves=WaveTable(table, float(step_s)))
        self._elevation = np.zeros((n_rows, 1, 1))
        self.wave_table_step_s = float(step_s)
        self.waves = None
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
        return self._history[self._newest[0], 6:12].copy()

    def strip_velocities(self) -> tuple[np.ndarray, np.ndarray]:
        """Transverse relative velocity of each strip (n_strips, 2: d1, d2, member frame) and
        its band velocities (n_strips, n_bands, 2) at the current time."""
        waves, bank = self._data.waves, self._data.filters
        v_rel = self._relative_velocities(interpolate_table(waves.values, waves.step_s, self.time_s))
        v_band = np.empty((bank.d.size, 2 * self.n_strips))
        states = self._state[N_BODY_STATES:].reshape(self.filter_bank.n_states, 2 * self.n_strips)
        band_velocities(states, v_rel.ravel(), bank.c, bank.c_nonzero, bank.d, v_band)
        return v_rel, v_band.reshape(-1, self.n_strips, 2).transpose(1, 0, 2)

    @property
    def loads(self) -> np.ndarray:
        """(N_LOADS, 6) loads at the current time (load registry order)."""
        return self._loads.copy()

    def wave_elevation(self, time_s: float | np.ndarray) -> np.ndarray:
        """Elevation at the reference point (0, 0), from the model's wave table."""
        t = np.atleast_1d(np.asarray(time_s, dtype=float))
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
        first = (self.time_s, self._state[:N_BODY_STATES].copy(), self.acceleration, self._loads.copy())
        t, y, acc, loads = self._advance(n_steps, every)
        time = np.concatenate([[first[0]], t])
        states = np.vstack([first[1], y])
        return RunResult(time, states[:, 0:6], states[:, 6:12], np.vstack([first[2], acc]),
                         np.concatenate([first[3][None], loads]), self.wave_elevation(time))

    def _advance(self, n_steps: int, every: int) -> tuple[np.ndarray, ...]:
        n_out = n_steps // every
        out_t = np.empty(n_out)
        out_y = np.empty((n_out, N_BODY_STATES))
        out_acc = np.empty((n_out, 6))
        out_loads = np.empty((n_out, N_LOADS, 6))
        dynamics.integrate(self._state, self._step_index, self.dt_s, n_steps, every, self._data,
                           self._history, self._newest, out_t, out_y, out_acc, out_loads)
        self._step_index += n_steps
        if n_out:
            self._loads[:] = out_loads[-1]
        return out_t, out_y, out_acc, out_loads

    # ------------------------------------------------------------------ analysis
    def prescribed_motion_loads(self, time_s: np.ndarray, motion: np.ndarray, velocity: np.ndarray,
                                acceleration: np.ndarray) -> np.ndarray:
        """Loads (n, N_LOADS, 6) for a prescribed 6-DOF motion, like HydroDyn's driver."""
        if self.filter_bank.n_states:
            raise ConfigError("prescribed motion: the filtered drag model's filter states need the "
                              "time loop; use the constant drag model")
        time_s = np.ascontiguousarray(time_s, dtype=float)
        n = time_s.size
        shapes = {"motion": motion, "velocity": velocity, "acceleration": acceleration}
        for name, arr in shapes.items():
            if np.shape(arr) != (n, 6):
                raise ValueError(f"prescribed motion: {name} must have shape ({n}, 6), got {np.shape(arr)}")
        states = np.ascontiguousarray(np.hstack([motion, velocity]), dtype=float)
        out = np.zeros((n, N_LOADS, 6))
        dynamics.prescribed_motion_loads(time_s, states, np.ascontiguousarray(acceleration, dtype=float),
                                         self._data, out)
        return out

    def mass_matrix(self) -> np.ndarray:
        """Rigid-body plus added mass (and any load component's mass) at rest, 6x6 about the
        reference point."""
        loads, masses = np.zeros((N_LOADS, 6)), np.zeros((N_MODULE_COMPONENTS, 6, 6))
        rest = np.zeros_like(self._state)
        added = dynamics.applied_loads(0.0, rest, self._data, loads, masses, np.empty(rest.size - N_BODY_STATES))
        body = self._data.body
        rigid, _ = dynamics.mass_matrix_and_bias(body.mass, body.cog, body.inertia_cog, np.eye(3), np.zeros(3))
        return rigid + added + masses.sum(axis=0)

    def restoring_matrix(self, step: float = 1e-4) -> np.ndarray:
        """Linear restoring matrix (hydrostatics, gravity, mooring) at rest, by central
        differences of the static loads in still water."""
        still = self._data.waves._replace(values=np.zeros_like(self._data.waves.values[:4]))
        data = self._data._replace(waves=still)
        out = np.zeros((6, 6))
        loads, masses = np.zeros((N_LOADS, 6)), np.zeros((N_MODULE_COMPONENTS, 6, 6))
        restoring = [ROW[name] for name in ("hydrostatic", "mooring", "gravity")]
        for j in range(6):
            wrench = []
            for sign in (1.0, -1.0):
                y = np.zeros_like(self._state)
                y[j] = sign * step
                dynamics.applied_loads(0.0, y, data, loads, masses, np.empty(y.size - N_BODY_STATES))
                wrench.append(loads[restoring].sum(axis=0))
            out[:, j] = -(wrench[0] - wrench[1]) / (2 * step)
        return out

    def natural_periods_s(self) -> np.ndarray:
        """Undamped natural periods of the linearised model, longest first."""
        eigenvalues = np.linalg.eigvals(np.linalg.solve(self.mass_matrix(), self.restoring_matrix()))
        return 2 * np.pi / np.sqrt(np.sort(eigenvalues.real))
