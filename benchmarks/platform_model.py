"""Benchmark: windmoor12 in LC5.3 (3 hours by default), offline, no ROS, with the constant-Cd
and the filtered (frequency-dependent) drag model.

Prints, per drag model: set-up time (waves, kinematics table, filter steady state),
integration time, wall time, real-time factor, and the filtered model's cost per simulated
second relative to the constant model's (target: at most 1.3). Integration times are the
best of ``--repeats`` runs, alternating the models, to be robust to a busy machine.
Then where a right-hand side's time goes (each part of ``dynamics.applied_loads`` called
alone in a compiled loop, at the model's state after the run), and the arithmetic bound: the floating-point operations the filtered step needs per strip
(counted from the kernels, ``FLOPS_PER_STRIP``) x strips x steps per simulated second,
against this core's rate measured with a compiled loop of independent multiply-adds.
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
from fowt_hydro_sim.physics.drag_filters import band_velocities, drag_per_length, filter_rates
from fowt_hydro_sim.physics.dynamics import N_BODY_STATES, derivative
from fowt_hydro_sim.physics.loads import N_LOADS, component_loads
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.morison import (add_wet_added_mass, deep_added_mass_about, lever_arms,
                                            relative_velocities, strip_loads, wetted_fractions)
from fowt_hydro_sim.physics.rigid_body import rotation_matrix
from fowt_hydro_sim.physics.tables import interpolate_table
from fowt_hydro_sim.physics.waves.components import repeat_period, synthesize


# floating-point operations per strip and transverse direction pair, per right-hand side of
# the filtered model (2 bands, 6 filter states, 10 non-zero A entries, 2 non-zero C entries),
# counted from the kernels (sqrt counted as one)
FLOPS_PER_STRIP_RHS = {
    "relative velocity (morison.relative_velocities)": 62,  # 2 rotations 15, w x r 9, 3, 2 x 2 dots 5
    "filter rates (drag_filters.filter_rates)": 52,  # 2 x (6 B u + 10 A x FMAs)
    "band velocities (drag_filters.band_velocities)": 12,  # 2 x (2 D u + 2 C x FMAs)
    "drag per length (drag_filters.drag_per_length)": 20,  # |v| 4, 2 bands x (|v_b| 4 + 2 x 2)
    "strip wrenches (morison.strip_loads)": 147,  # w x (w x r) 18, 2 x (10 + 9 + 3 wrenches 15) ...
    "wetted fraction (morison.wetted_fractions)": 17,
}
# the 6x6 added mass about the reference point, only for strips not fully wet at rest (the
# others are summed from precomputed moments: morison.deep_added_mass_about, ~1,500 flops)
FLOPS_WATERLINE_STRIP_RHS = 108  # S A 27, the 6x6 blocks 36 + 27, scaling 18
FLOPS_DEEP_SUM_RHS = 1500
FLOPS_ABM_PER_STATE = 18  # predictor and corrector, 9 each, per filter state and step
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
def _parts(y: np.ndarray, d, masses: np.ndarray, n: int) -> np.ndarray:
    """Seconds for n calls of: the whole right-hand side, then each part of it alone."""
    out, loads = np.empty_like(y), np.zeros((N_LOADS, 6))
    s, bank = d.strips, d.filters
    rotation = rotation_matrix(y[3], y[4], y[5])
    n_strips = s.length.size
    fixed = d.options.fixed_directions
    frame = np.eye(3) if fixed else rotation
    arm = lever_arms(rotation, s.centre) if fixed else s.centre
    wet, v_rel, a_fluid = np.empty(n_strips), np.empty((n_strips, 2)), np.empty((n_strips, 2))
    states = y[N_BODY_STATES:].reshape((bank.b.size, 2 * n_strips))
    rates, v_band = np.empty_like(states), np.empty((bank.d.size, 2 * n_strips))
    drag, body = np.empty((n_strips, 2)), np.zeros((3, 6))
    kinematics = interpolate_table(d.waves.values, d.waves.step_s, 0.0)
    surface = d.still_surface[:n_strips]
    times = np.zeros(8)
    start = _clock()
    for k in range(n):
        derivative(k * 1e-3, y, d, loads, masses, out)
    times[0] = _clock() - start
    start = _clock()
    for k in range(n):
        kinematics = interpolate_table(d.waves.values, d.waves.step_s, k * 1e-3)
    times[1] = _clock() - start
    start = _clock()
    for _ in range(n):
        wetted_fractions(np.eye(3), 0.0, s.centre, s.axis, s.length, surface, wet)
        arm = lever_arms(rotation, s.centre) if fixed else s.centre
        relative_velocities(frame, y[6:9], y[9:12], kinematics, arm, s.directions, s.point, v_rel, a_fluid)
    times[2] = _clock() - start
    start = _clock()
    for _ in range(n):
        band_velocities(states, v_rel.ravel(), bank.c, bank.c_nonzero, bank.d, v_band)
        filter_rates(states, v_rel.ravel(), bank.a, bank.a_nonzero, bank.b, rates)
    times[3] = _clock() - start
    start = _clock()
    for _ in range(n):
        drag_per_length(v_rel, v_band, s.band_drag, s.drag, s.filtered, drag)
    times[4] = _clock() - start
    start = _clock()
    for _ in range(n):
        strip_loads(frame, y[9:12], wet, a_fluid, drag, arm, s.directions, s.length, s.inertia, s.added_mass,
                    body[0], body[1], body[2])
    times[5] = _clock() - start
    start = _clock()
    for _ in range(n):
        added = deep_added_mass_about(rotation, s.deep_moments) if fixed else s.deep_added_mass_6x6.copy()
        add_wet_added_mass(wet, s.length, s.deep, s.added_mass_6x6, arm, s.added_mass_3x3, fixed, added)
    times[6] = _clock() - start
    start = _clock()
    for k in range(n):
        component_loads(k * 1e-3, y, rotation, d.component_params, d.component_tables, loads, masses)
    times[7] = _clock() - start
    return times


PARTS = ("whole right-hand side (dynamics.derivative)", "kinematics interpolation (tables)",
         "wetted fractions + relative velocities (morison)", "filter rates + band velocities (drag_filters)",
         "drag per length (drag_filters)", "strip wrenches (morison.strip_loads)",
         "strip 6x6 added mass (morison)", "load components (hydrostatics, mooring, drift, ...)")


def profile(model: PlatformModel, n: int = 20_000) -> str:
    """Microseconds per call of each part of the right-hand side, at the model's state."""
    y = model._state.copy()  # noqa: SLF001 (a benchmark reads the model's kernel data)
    d, masses = model._data, model._masses  # noqa: SLF001
    _parts(y, d, masses, 10)
    times = _parts(y, d, masses, n)
    lines = [f"  where a right-hand side's time goes ({n} calls each, load average {os.getloadavg()[0]:.1f}):"]
    for name, seconds in zip(PARTS, times):
        lines.append(f"    {name:55s}{1e6 * seconds / n:8.2f} us{seconds / times[0]:7.0%}")
    rest = times[0] - times[1:].sum()
    lines.append(f"    {'the rest (end plates, mass matrix, solve, allocations)':55s}{1e6 * rest / n:8.2f} us"
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


def arithmetic_bound(n_strips: int, n_waterline: int, n_states: int, dt_s: float, measured_s_per_s: float) -> str:
    """What the filtered step needs, against the core's rate and the measured time."""
    per_step = RHS_PER_STEP * sum(FLOPS_PER_STRIP_RHS.values()) + FLOPS_ABM_PER_STATE * 2 * n_states
    flops_per_s = (per_step * n_strips + RHS_PER_STEP * (FLOPS_WATERLINE_STRIP_RHS * n_waterline
                                                          + FLOPS_DEEP_SUM_RHS)) / dt_s
    rate = core_rate_gflops()
    bound_s_per_s = flops_per_s / (rate * 1e9)
    lines = [f"  arithmetic bound (filtered): {per_step} flops per strip per step x {n_strips} strips, plus the "
             f"6x6 added mass of {n_waterline} waterline strips and the deep strips' sum, x {1 / dt_s:g} steps "
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

    start = time.perf_counter()
    waves = synthesize(sea, repeat_period(sea, args.duration))
    synthesis_s = time.perf_counter() - start
    models, set_up = {}, {}
    for drag in DRAG_MODELS:
        begin = time.perf_counter()
        models[drag] = PlatformModel(platform, waves, dt_s=args.dt, drag_model=drag)
        set_up[drag] = time.perf_counter() - begin
    integration = {drag: float("inf") for drag in DRAG_MODELS}
    results = {}
    for _ in range(args.repeats):
        for drag, model in models.items():
            model.reset()
            begin = time.perf_counter()
            results[drag] = model.run(args.duration, output_interval_s=0.25)
            integration[drag] = min(integration[drag], time.perf_counter() - begin)
    model = models["constant"]
    print(f"windmoor12 {args.load_case}, dt {args.dt:g} s, {args.duration:g} s simulated, "
          f"best of {args.repeats} runs")
    print(f"  strips {model.n_strips}, kinematics points {len(model.geometry.points_m)}, "
          f"wave components {waves.frequency_hz.size}, wave table step {model.wave_table_step_s:g} s, "
          f"filter states {models['filtered'].filter_bank.n_states} per strip and direction")
    print(f"  {'drag model':12s}{'set-up s':>10s}{'integration s':>15s}{'wall s':>9s}{'real-time x':>13s}"
          f"{'surge std m':>13s}")
    for drag in DRAG_MODELS:
        wall = set_up[drag] + integration[drag]
        print(f"  {drag:12s}{set_up[drag]:10.2f}{integration[drag]:15.2f}{wall:9.2f}"
              f"{args.duration / integration[drag]:13.0f}{results[drag].motion[:, 0].std():13.3f}")
    print(f"  filtered / constant time per simulated second: "
          f"{integration['filtered'] / integration['constant']:.2f} (target <= 1.30)")
    print(f"  wave synthesis {synthesis_s:.2f} s (shared); peak memory (max RSS) "
          f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB")
    filtered = models["filtered"]
    print(profile(filtered))
    n_waterline = int((~filtered._data.strips.deep).sum())  # noqa: SLF001
    print(arithmetic_bound(filtered.n_strips, n_waterline, filtered.filter_bank.n_states, args.dt,
                           integration["filtered"] / args.duration))


if __name__ == "__main__":
    main()
