"""Benchmark: windmoor12 in LC5.3 (3 hours by default), offline, no ROS, with the constant-Cd
and the filtered (frequency-dependent) drag model.

Prints, per drag model:
- the time loop: ``PlatformModel.run`` with the wave kinematics already in memory (the whole
  period's table, built once before and shared): the kernel alone, on one core; its
  real-time factor is the issue's target (3,000x filtered);
- the whole run as a user makes it (the default: kinematics synthesised in blocks as the run
  goes, each next block made ahead in a worker thread), with the wall seconds it waited for
  blocks, and the cost of one block made on one thread (ms per simulated second): what a
  single core would add to the time loop;
- the filtered model's cost per simulated second relative to the constant model's (target:
  at most 1.3).
Times are the best of ``--repeats`` runs, alternating the models, to be robust to a busy
machine. Then where a right-hand side's time goes (each part of ``dynamics.applied_loads``
called alone in a compiled loop, at the model's state after the run), and the arithmetic
bound: the floating-point operations the filtered step needs (counted from the kernels:
``FLOPS_PER_WET_STRIP_RHS`` and the rest below) x steps per simulated second, against this
core's rate measured with a compiled loop of independent multiply-adds.
Run: python benchmarks/platform_model.py [--duration S] [--repeats N]
The numba kernels are compiled (or loaded from cache) by a short warm-up run first.
"""
from __future__ import annotations

import argparse
import os
import resource
import time

import numpy as np
from numba import njit, objmode

from fowt_hydro_sim.physics.config import DRAG_MODELS, load_case, load_platform
from fowt_hydro_sim.physics.drag_filters import band_velocities, filter_inputs, filter_rates
from fowt_hydro_sim.physics.dynamics import N_BODY_STATES, derivative
from fowt_hydro_sim.physics.loads import component_loads
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.morison import (
    added_mass_from_moments,
    centripetal_from_moments,
    end_plate_loads,
    lever_arms,
    relative_velocities,
    rotated_moments,
    strip_loads,
)
from fowt_hydro_sim.physics.rigid_body import rotation_matrix
from fowt_hydro_sim.physics.tables import interpolate_into
from fowt_hydro_sim.physics.waves.components import repeat_period, synthesize
from fowt_hydro_sim.physics.waves.kinematics import KinematicsTable

# floating-point operations per right-hand side of the filtered model (2 bands, 6 filter
# states, 10 non-zero A entries, 2 non-zero C entries), counted from the kernels (sqrt as one):
# per strip wetted at rest (the others never load: strips wetted as at rest, the default)
FLOPS_PER_WET_STRIP_RHS = {
    "lever arm R c (morison.lever_arms)": 15,
    "relative velocity and fluid acceleration (morison.relative_velocities)": 35,  # w x r 9, 6, 4 dots 20
    "drag per length (morison.strip_loads)": 22,  # 2 bands x (|v_b| 4, 2 x 3), wetted length 2
    "fluid inertia (morison.strip_loads)": 6,
    "drag and inertia wrenches (morison.strip_loads)": 48,  # 2 x (forces 9, r x f 9, sums 6)
}
FLOPS_PER_FILTER_COLUMN_RHS = 40  # every filtered strip direction: rates 16 FMAs, band velocities 4 FMAs
FLOPS_MOMENTS_RHS = 1500  # the 6x6 added mass and the centripetal wrench from the moments
FLOPS_ABM_PER_STATE = 18  # predictor and corrector, 9 each, per state and step
RHS_PER_STEP = 2  # ABM4 PECE


@njit(fastmath=True, cache=True)
def _multiply_adds(n: int) -> float:
    """16 independent chains of a = a x + y (the compiler may pack them into SIMD lanes)."""
    acc = np.arange(16) * 1e-3 + 1.0
    for _ in range(n):
        for k in range(16):
            acc[k] = acc[k] * 0.999999999 + 1e-9
    return acc.sum()


@njit(cache=True)
def _clock() -> float:
    with objmode(now="f8"):
        now = time.perf_counter()
    return now


@njit(cache=True)
def _parts(y: np.ndarray, d, w, n: int) -> np.ndarray:
    """Seconds for n calls of: the whole right-hand side, then each part of it alone, as
    ``dynamics.applied_loads`` calls them for the default options (fixed directions, strips
    wetted as at rest)."""
    out = np.empty_like(y)
    s, plates, bank = d.strips, d.plates, d.filters
    rotation = rotation_matrix(y[3], y[4], y[5])
    states = y[N_BODY_STATES:].reshape((bank.b.size, w.v_filtered.size))
    rates = np.empty_like(states)
    eye = np.eye(3)
    times = np.zeros(8)
    start = _clock()
    for k in range(n):
        derivative(k * 1e-3, y, d, w, out)
    times[0] = _clock() - start
    start = _clock()
    for k in range(n):
        interpolate_into(d.waves.values, d.waves.step_s, k * 1e-3, w.kinematics)
    times[1] = _clock() - start
    start = _clock()
    for _ in range(n):
        lever_arms(rotation, s.centre, w.arm)
        relative_velocities(eye, True, y[6:9], y[9:12], w.kinematics, w.arm, s.directions, s.point, s.rest_wet,
                            True, w.v_rel, w.a_fluid)
    times[2] = _clock() - start
    start = _clock()
    for _ in range(n):
        filter_inputs(s.filter_strip, w.v_rel, w.v_filtered)
        band_velocities(states, w.v_filtered, bank.c, bank.c_nonzero, bank.d, w.v_band)
        filter_rates(states, w.v_filtered, bank.a, bank.a_nonzero, bank.b, rates)
    times[3] = _clock() - start
    start = _clock()
    for _ in range(n):
        strip_loads(eye, y[9:12], s.rest_wet, w.v_rel, w.a_fluid, w.v_band, s.filter_column, w.arm, s.directions,
                    s.length, s.inertia, s.added_mass, s.band_drag, s.drag, s.filtered, False, w.body)
    times[4] = _clock() - start
    start = _clock()
    for _ in range(n):
        rotated_moments(rotation, s.rest_moments, w.first, w.half, w.second)
        added_mass_from_moments(s.rest_moments[0], w.first, w.second, w.added_mass)
        centripetal_from_moments(w.first, w.second, (y[9], y[10], y[11]), w.spin)
    times[5] = _clock() - start
    start = _clock()
    for _ in range(n):
        lever_arms(rotation, plates.centre, w.plate_arm)
        end_plate_loads(eye, y[6:9], y[9:12], w.kinematics, w.plate_arm, plates.normal, w.submerged,
                        plates.pressure_area, plates.added_mass, plates.drag, plates.added_mass_6x6,
                        plates.added_mass_3x3, True, plates.point, w.body[0], w.body[1], w.body[2], w.added_mass)
    times[6] = _clock() - start
    start = _clock()
    for k in range(n):
        component_loads(k * 1e-3, y, rotation, d.component_params, d.component_tables, w.loads, w.masses)
    times[7] = _clock() - start
    return times


PARTS = ("whole right-hand side (dynamics.derivative)", "kinematics interpolation (tables)",
         "lever arms + relative velocities (morison)", "filter rates + band velocities (drag_filters)",
         "drag and inertia wrenches (morison.strip_loads)",
         "6x6 added mass + centripetal wrench from moments (morison)", "end plates (morison)",
         "load components (hydrostatics, mooring, drift, ...)")


def profile(model: PlatformModel, n: int = 20_000) -> str:
    """Microseconds per call of each part of the right-hand side, at the model's state."""
    y = model._state.copy()  # noqa: SLF001 (a benchmark reads the model's kernel data)
    d, w = model._data, model._work  # noqa: SLF001
    _parts(y, d, w, 10)
    times = _parts(y, d, w, n)
    lines = [f"  where a right-hand side's time goes ({n} calls each, load average {os.getloadavg()[0]:.1f}):"]
    for name, seconds in zip(PARTS, times):
        lines.append(f"    {name:55s}{1e6 * seconds / n:8.2f} us{seconds / times[0]:7.0%}")
    rest = times[0] - times[1:].sum()
    lines.append(f"    {'the rest (mass matrix, solve, filter rates copy, ...)':55s}{1e6 * rest / n:8.2f} us"
                 f"{rest / times[0]:7.0%}")
    return "\n".join(lines)


def core_rate_gflops(n: int = 20_000_000) -> float:
    """This core's multiply-add rate [Gflop/s], best of 3 (2 flops per multiply-add)."""
    _multiply_adds(10)
    best = float("inf")
    for _ in range(3):
        start = time.perf_counter()
        _multiply_adds(n)
        best = min(best, time.perf_counter() - start)
    return 2 * 16 * n / best / 1e9


def arithmetic_bound(n_filtered: int, n_wet: int, n_states: int, dt_s: float, measured_s_per_s: float) -> str:
    """What the filtered step needs, against the core's rate and the measured time."""
    per_rhs = (sum(FLOPS_PER_WET_STRIP_RHS.values()) * n_wet + FLOPS_PER_FILTER_COLUMN_RHS * 2 * n_filtered
               + FLOPS_MOMENTS_RHS)
    per_step = RHS_PER_STEP * per_rhs + FLOPS_ABM_PER_STATE * n_states
    flops_per_s = per_step / dt_s
    rate = core_rate_gflops()
    bound_s_per_s = flops_per_s / (rate * 1e9)
    lines = [f"  arithmetic bound (filtered): {RHS_PER_STEP} right-hand sides of {per_rhs:,} flops ("
             f"{sum(FLOPS_PER_WET_STRIP_RHS.values())} per strip wetted at rest x {n_wet}, "
             f"{FLOPS_PER_FILTER_COLUMN_RHS} per filtered input x {2 * n_filtered}, {FLOPS_MOMENTS_RHS} for the "
             f"moments) and {FLOPS_ABM_PER_STATE} per state x {n_states} states per step, x {1 / dt_s:g} steps "
             f"per s = {flops_per_s / 1e6:.2f} Mflop per simulated second",
             f"  core multiply-add rate {rate:.1f} Gflop/s -> bound {1e3 * bound_s_per_s:.3f} ms per simulated "
             f"second ({1 / bound_s_per_s:,.0f}x real time); measured {1e3 * measured_s_per_s:.3f} ms "
             f"({1 / measured_s_per_s:,.0f}x), {bound_s_per_s / measured_s_per_s:.0%} of the bound's speed; "
             f"load average {os.getloadavg()[0]:.1f}"]
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=10800.0, help="simulated seconds")
    parser.add_argument("--load-case", default="lc5.3")
    parser.add_argument("--dt", type=float, default=0.05)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()

    platform = load_platform("windmoor12")
    sea = load_case(args.load_case).sea_state
    for drag in DRAG_MODELS:  # compile / load the kernels' cache
        PlatformModel(platform, synthesize(sea, 600.0), dt_s=args.dt, drag_model=drag).run(10.0)

    waves = synthesize(sea, repeat_period(sea, args.duration))
    env = platform.environment
    start = time.perf_counter()
    probe = PlatformModel(platform, waves, dt_s=args.dt)
    table = KinematicsTable.build(waves, probe.geometry.points_m, probe.wave_table_step_s, env.water_depth_m,
                                  env.gravity_m_s2, env.water_density_kg_m3)
    table_s = time.perf_counter() - start
    models = {drag: PlatformModel(platform, waves, dt_s=args.dt, drag_model=drag, kinematics=table)
              for drag in DRAG_MODELS}
    blocked = {drag: PlatformModel(platform, waves, dt_s=args.dt, drag_model=drag) for drag in DRAG_MODELS}
    loop, whole, waited = ({drag: float("inf") for drag in DRAG_MODELS} for _ in range(3))
    results, blocked_results = {}, {}
    for _ in range(args.repeats):
        for drag in DRAG_MODELS:
            models[drag].reset()
            begin = time.perf_counter()
            results[drag] = models[drag].run(args.duration, output_interval_s=0.25)
            loop[drag] = min(loop[drag], time.perf_counter() - begin)
            model = blocked[drag]
            model.reset()
            before = model.wave_block_wait_s
            begin = time.perf_counter()
            blocked_results[drag] = model.run(args.duration, output_interval_s=0.25)
            if time.perf_counter() - begin < whole[drag]:
                whole[drag], waited[drag] = time.perf_counter() - begin, model.wave_block_wait_s - before
    synthesis = probe._blocks.synthesis  # noqa: SLF001 (blocks made on this thread, best of 3)
    block = np.empty((synthesis.block_rows, len(probe.geometry.points_m), 7))
    block_wall = float("inf")
    for k in range(3):
        start = time.perf_counter()
        synthesis.rows(k * synthesis.block_rows, block)
        block_wall = min(block_wall, time.perf_counter() - start)
    block_ms_per_s = 1e3 * block_wall / (synthesis.block_rows * probe.wave_table_step_s)
    model = models["constant"]
    print(f"windmoor12 {args.load_case}, dt {args.dt:g} s, {args.duration:g} s simulated, "
          f"best of {args.repeats} runs, load average {os.getloadavg()[0]:.1f}")
    print(f"  strips {model.n_strips}, kinematics points {len(model.geometry.points_m)}, "
          f"wave components {waves.frequency_hz.size}, wave table step {model.wave_table_step_s:g} s, "
          f"filter states {models['filtered'].filter_bank.n_states} per strip and direction")
    print(f"  {'':12s}{'time loop (kinematics in memory)':>36s}   {'whole run (blocked kinematics)':>44s}")
    print(f"  {'drag model':12s}{'s':>10s}{'real-time x':>13s}{'surge std m':>13s}   {'s':>10s}{'real-time x':>13s}"
          f"{'waited s':>10s}{'surge std m':>13s}")
    for drag in DRAG_MODELS:
        print(f"  {drag:12s}{loop[drag]:10.2f}{args.duration / loop[drag]:13.0f}"
              f"{results[drag].motion[:, 0].std():13.3f}   {whole[drag]:10.2f}{args.duration / whole[drag]:13.0f}"
              f"{waited[drag]:10.2f}{blocked_results[drag].motion[:, 0].std():13.3f}")
    print(f"  filtered / constant time per simulated second (time loop): "
          f"{loop['filtered'] / loop['constant']:.2f} (target <= 1.30)")
    block_s = synthesis.block_rows * probe.wave_table_step_s
    print(f"  kinematics: the whole period's table {table_s:.1f} s ({table.values.nbytes / 2**20:.0f} MB); one block "
          f"of {block_s:.0f} s made on one thread in {block_wall:.2f} s = {block_ms_per_s:.3f} "
          f"ms per simulated second (on one core, the whole run would be the time loop plus this)")
    print(f"  peak memory (max RSS, with the whole table) "
          f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB")
    filtered = models["filtered"]
    print(profile(filtered))
    n_wet = int((filtered._data.strips.rest_wet > 0.0).sum())  # noqa: SLF001
    print(arithmetic_bound(filtered._data.strips.filter_strip.size, n_wet, filtered._state.size,  # noqa: SLF001
                           args.dt, loop["filtered"] / args.duration))


if __name__ == "__main__":
    main()
