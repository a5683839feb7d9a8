"""Benchmark: the time loop of a potential-flow hull (volturnus_s) in an irregular sea against
the Morison hull windmoor12 in the same sea, in one process, alternating, best of
``--repeats``; and, with ``--baseline PATH``, windmoor12 on another checkout of the package
(e.g. the code before potential flow) in a subprocess, alternating with this one's, so that
both speeds are taken at the same machine load (their ratio is the figure).

Printed per case: seconds for the record, real-time factor, surge std (a sanity check that
the run moved), and the ratios. The cases: windmoor12 (the reference), volturnus_s with the
convolution radiation (its default), with the .ss file's state-space radiation, without the
memory, with its AddBQuad split into two first-order bands at 0.05 Hz (the filtered drag
model), and oc4_semi (the columns' potential flow with 25 Morison members: the pontoons and
braces, the columns' drag). With ``--memory-hours H1 H2 ...``, also
``fowt-sim simulate --platform volturnus_s`` of that many hours, each in a new process, with
the process's peak resident memory (flat memory: the same figure for every record length).
The time loop is ``PlatformModel.run`` with the kinematics
already in memory (the kernel alone, on one core), as ``benchmarks/platform_model.py`` times it.
Run: PYTHONPATH=. python benchmarks/potential_flow.py [--duration S] [--repeats N] [--load-case LC]
     [--baseline /path/to/other/checkout] [--memory-hours 1 4]
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.config import DragBand, load_case, load_platform
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import repeat_period, synthesize
from fowt_hydro_sim.physics.waves.kinematics import KinematicsTable, table_step

BASELINE_PROBE = """
import sys, time
from fowt_hydro_sim.physics.config import DragBand, load_case, load_platform
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import repeat_period, synthesize
from fowt_hydro_sim.physics.waves.kinematics import KinematicsTable
duration, case, dt, repeats = float(sys.argv[1]), sys.argv[2], float(sys.argv[3]), int(sys.argv[4])
platform, sea = load_platform("windmoor12"), load_case(case).sea_state
waves = synthesize(sea, repeat_period(sea, duration))
probe = PlatformModel(platform, waves, dt_s=dt)
env = platform.environment
table = KinematicsTable.build(waves, probe.geometry.points_m, probe.wave_table_step_s, env.water_depth_m,
                              env.gravity_m_s2, env.water_density_kg_m3)
model = PlatformModel(platform, waves, dt_s=dt, kinematics=table)
model.run(10.0)
for _ in range(repeats):
    sys.stdin.readline()
    model.reset()
    start = time.perf_counter()
    model.run(duration, output_interval_s=0.25)
    print(time.perf_counter() - start, flush=True)
"""


# the peak resident memory of a ``fowt-sim`` process, whatever ran before it
PEAK = "import resource, sys, runpy; sys.argv = ['fowt-sim', *sys.argv[1:]]\n" \
       "try:\n    runpy.run_module('fowt_hydro_sim.cli', run_name='__main__')\nfinally:\n" \
       "    print('peak_rss_mb', resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, file=sys.stderr)"
SPLIT = (DragBand("low", "lowpass", 1, cutoff_hz=0.05), DragBand("wave", "highpass", 1, cutoff_hz=0.05))


def time_loop_model(name: str, waves, dt: float, radiation: str | None = None, split: bool = False) -> PlatformModel:
    """A model of the packaged platform ``name`` with the waves' kinematics in memory
    (``radiation`` overrides a potential-flow hull's radiation model; ``split``: its AddBQuad in
    the two bands of ``SPLIT``, the filtered drag model)."""
    platform = load_platform(name)
    if radiation is not None:
        platform = dataclasses.replace(platform, potential_flow=dataclasses.replace(platform.potential_flow,
                                                                                    radiation=radiation))
    if split:
        matrix = tuple(map(tuple, np.array(platform.potential_flow.added_quadratic_damping)))
        flow = dataclasses.replace(platform.potential_flow, added_quadratic_damping_bands=(matrix, matrix))
        platform = dataclasses.replace(platform, drag_bands=SPLIT, potential_flow=flow)
    drag = "filtered" if split else "constant"
    probe = PlatformModel(platform, None, dt_s=dt, drag_model=drag)
    env = platform.environment
    table = KinematicsTable.build(waves, probe.geometry.points_m, table_step(waves), env.water_depth_m,
                                  env.gravity_m_s2, env.water_density_kg_m3)
    return PlatformModel(platform, waves, dt_s=dt, kinematics=table, drag_model=drag)


def memory(hours: list[float], load_case: str) -> None:
    """``fowt-sim simulate --platform volturnus_s`` for each record length in a new process: wall
    time, the run's real-time factor and the process's peak resident memory."""
    print(f"memory: fowt-sim simulate --platform volturnus_s --load-case {load_case}, output every 0.25 s, "
          "each in a new process")
    print(f"{'hours':>6s}{'wall [s]':>10s}{'x real':>8s}{'peak RSS [MB]':>15s}{'load':>7s}")
    with tempfile.TemporaryDirectory() as folder:
        for h in hours:
            out = Path(folder) / f"h{h:g}"
            start = time.perf_counter()
            done = subprocess.run([sys.executable, "-c", PEAK, "simulate", "--platform", "volturnus_s",
                                   "--load-case", load_case, "--duration", str(3600.0 * h), "-o", str(out)],
                                  check=True, capture_output=True, text=True)
            wall = time.perf_counter() - start
            factor = json.loads((out / "summary.json").read_text())["performance"]["real_time_factor"]
            peak = float(done.stderr.rsplit("peak_rss_mb", 1)[1])
            print(f"{h:6g}{wall:10.1f}{factor:8.0f}{peak:15.0f}{os.getloadavg()[0]:7.1f}", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=3600.0, help="simulated seconds")
    parser.add_argument("--load-case", default="lc5.3")
    parser.add_argument("--dt", type=float, default=0.05)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--baseline", help="another checkout's root: its windmoor12 time loop, alternated with ours")
    parser.add_argument("--memory-hours", type=float, nargs="*", default=[],
                        help="record lengths [h] of the memory runs (none by default)")
    args = parser.parse_args()

    sea = load_case(args.load_case).sea_state
    waves = synthesize(sea, repeat_period(sea, args.duration))
    cases = {"windmoor12 (Morison, constant drag)": time_loop_model("windmoor12", waves, args.dt),
             "volturnus_s (potential flow, convolution)": time_loop_model("volturnus_s", waves, args.dt),
             "volturnus_s (potential flow, state space)": time_loop_model("volturnus_s", waves, args.dt,
                                                                          "state_space"),
             "volturnus_s (potential flow, no memory)": time_loop_model("volturnus_s", waves, args.dt, "none"),
             "volturnus_s (AddBQuad in two bands)": time_loop_model("volturnus_s", waves, args.dt, split=True),
             "oc4_semi (potential flow + Morison members)": time_loop_model("oc4_semi", waves, args.dt)}
    for model in cases.values():  # compile / load the kernels' cache
        model.run(10.0)
    baseline = None
    if args.baseline:
        env = {**os.environ, "PYTHONPATH": args.baseline}
        baseline = subprocess.Popen([sys.executable, "-c", BASELINE_PROBE, str(args.duration), args.load_case,
                                     str(args.dt), str(args.repeats)], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                    text=True, env=env, cwd=args.baseline)
    best = {name: float("inf") for name in cases}
    surge = {}
    baseline_best = float("inf")
    for _ in range(args.repeats):
        for name, model in cases.items():
            model.reset()
            start = time.perf_counter()
            surge[name] = model.run(args.duration, output_interval_s=0.25).motion[:, 0].std()
            best[name] = min(best[name], time.perf_counter() - start)
        if baseline is not None:
            baseline.stdin.write("\n")
            baseline.stdin.flush()
            baseline_best = min(baseline_best, float(baseline.stdout.readline()))
    if baseline is not None:
        baseline.wait()
    print(f"{args.load_case} (Hs {sea.hs_m:g} m, Tp {sea.tp_s:g} s, {waves.frequency_hz.size} wave components), "
          f"dt {args.dt:g} s, {args.duration:g} s simulated, time loop, best of {args.repeats}, "
          f"load average {os.getloadavg()[0]:.1f}")
    reference = best["windmoor12 (Morison, constant drag)"]
    for name, seconds in best.items():
        print(f"  {name:45s}{seconds:8.2f} s{args.duration / seconds:9.0f}x real time  "
              f"time / windmoor12's {seconds / reference:5.2f}  surge std {surge[name]:.3f} m")
    convolution = best["volturnus_s (potential flow, convolution)"]
    state_space = best["volturnus_s (potential flow, state space)"]
    no_memory = best["volturnus_s (potential flow, no memory)"]
    print(f"  volturnus_s: convolution time / state space's {convolution / state_space:.2f}; the memory's time "
          f"over no memory: convolution {convolution - no_memory:.2f} s, state space {state_space - no_memory:.2f} s")
    if baseline is not None:
        print(f"  {'windmoor12 on ' + args.baseline:45s}{baseline_best:8.2f} s{args.duration / baseline_best:9.0f}x "
              f"real time  this checkout's windmoor12 time / baseline's {reference / baseline_best:5.2f}")
    if args.memory_hours:
        memory(args.memory_hours, args.load_case)


if __name__ == "__main__":
    main()
