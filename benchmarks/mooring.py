"""Benchmark and figures of the mooring models, on windmoor12's hull moored by the VolturnUS-S
lines (the packaged OpenFAST MoorDyn file) in 200 m of water.

Prints:
- speed: real-time factor of ``spring``, ``moorpy`` and ``moordyn`` runs (load case lc5.3,
  dt 0.05 s, constant Cd; the time loop only, the model already made), the best of
  ``--repeats``; for ``moordyn`` the wall seconds inside MoorDyn's own steps, and the real-time
  factor without them (ours: the stepwise loop, the coupling and the compiled model);
- moorpy's tabulation against MoorPy solving each line directly, at random offsets;
- MoorDyn's coupling against a smaller step: a free surge decay from 10 m in still water at
  dt 0.05 s against dt 0.0125 s (the largest surge difference over 120 s, relative to 10 m);
- the lines' damping: free surge decays from 10 m with ``moorpy`` (quasi-static: no line
  damping) and ``moordyn`` (line drag and inertia), each fitted over its first cycles
  (``studies.simulate.fit_free_decay``), and the difference in % of critical.
- ``--moordyn``: MoorDyn's cost on VolturnUS-S (its own hull and the lines of its deck), for
  the deck's ``dtM`` and ``NumSegs`` and coarser ones: (a) MoorDyn-C's own ``Step`` calls
  alone, replaying the fairlead motion of (c) through a bare MoorDyn system; (b) our coupling
  (the stepwise loop, the compiled model, the kinematics and ctypes calls: (c) less MoorDyn's
  steps inside it); (c) the whole model with ``moordyn`` (lc5.3, dt 0.05 s), each as x real
  time on CPU time of one core, with the load average; then each coarser deck's accuracy
  against the deck's on a free surge decay from 10 m (largest surge and fairlead tension
  differences, fitted damping).
Run: python benchmarks/mooring.py [--duration S] [--repeats N] [--moordyn]
"""
from __future__ import annotations

import argparse
import dataclasses
import os
import re
import tempfile
import time
from pathlib import Path

import numpy as np

from fowt_hydro_sim.physics.config import load_case, load_platform
from fowt_hydro_sim.physics.model import PlatformModel
from fowt_hydro_sim.physics.waves.components import synthesize
from fowt_hydro_sim.studies.simulate import fit_free_decay

LINES = (Path(__file__).resolve().parents[1] / "fowt_hydro_sim" / "physics" / "data" / "platforms" / "volturnus_s"
         / "IEA-15-240-RWT-UMaineSemi_MoorDyn.dat")


def platform():
    """windmoor12's hull with its springs and the VolturnUS-S lines, in 200 m of water."""
    p = load_platform("windmoor12")
    return dataclasses.replace(p, environment=dataclasses.replace(p.environment, water_depth_m=200.0),
                               mooring=dataclasses.replace(p.mooring, file=str(LINES)))


def speed(duration_s: float, repeats: int) -> None:
    waves = synthesize(load_case("lc5.3").sea_state, 3600.0)
    for model_name in ("spring", "moorpy", "moordyn"):
        best, inside, cpu, cpu_inside = np.inf, 0.0, np.inf, 0.0
        for _ in range(repeats):
            model = PlatformModel(platform(), waves, mooring_model=model_name)
            model.run(1.0)  # compiled, blocks made
            lines = model.mooring_lines
            start, start_cpu = time.perf_counter(), time.process_time()
            before = (lines.moordyn_s, lines.moordyn_cpu_s) if lines else (0.0, 0.0)
            model.run(duration_s, 0.25)
            wall, used = time.perf_counter() - start, time.process_time() - start_cpu
            if wall < best:
                best = wall
                inside = (lines.moordyn_s - before[0]) if lines else 0.0
            if used < cpu:
                cpu = used
                cpu_inside = (lines.moordyn_cpu_s - before[1]) if lines else 0.0
        line = (f"{model_name:8s} {duration_s / best:8.0f}x real time ({best:.2f} s wall for {duration_s:g} s; "
                f"{duration_s / cpu:.0f}x on CPU time)")
        if inside:
            line += (f"; MoorDyn's own steps {inside:.2f} s wall ({duration_s / inside:.0f}x), the rest "
                     f"{best - inside:.2f} s ({duration_s / (best - inside):.0f}x); on CPU time MoorDyn "
                     f"{cpu_inside:.2f} s, the rest {cpu - cpu_inside:.2f} s ({duration_s / (cpu - cpu_inside):.0f}x)")
        print(line, flush=True)


def tabulation(n: int = 200) -> None:
    from fowt_hydro_sim.physics.mooring.catenary_tables import solve
    from fowt_hydro_sim.physics.mooring.moordyn_file import read_lines
    model = PlatformModel(platform(), None, mooring_model="moorpy")
    lines = read_lines(LINES, 200.0)
    rng = np.random.default_rng(1)
    motion = np.column_stack([rng.uniform(-30, 30, (n, 2)), rng.uniform(-9, 9, n), rng.uniform(-0.1, 0.1, (n, 3))])
    ours = model.mooring_tensions(np.zeros(n), motion)
    from fowt_hydro_sim.frames import rotation_matrix
    worst = 0.0
    for k, m in enumerate(motion):
        r = rotation_matrix(*m[3:6])
        for i, line in enumerate(lines):
            fairlead = m[0:3] + r @ np.array(line.fairlead_m)
            h = np.hypot(*(np.array(line.anchor_m[:2]) - fairlead[:2]))
            v = fairlead[2] - line.anchor_m[2]
            f_h, f_v, _, _ = solve(line, 200.0, h, v)
            worst = max(worst, abs(ours[k, i, 0] - np.hypot(f_h, f_v)) / np.hypot(f_h, f_v))
    print(f"moorpy table: largest fairlead tension error {100 * worst:.4f} % over {n} random offsets "
          "(surge, sway +-30 m, heave +-9 m, angles +-0.1 rad)")


def decay(model_name: str, dt_s: float, duration_s: float) -> tuple[np.ndarray, np.ndarray]:
    """Time and surge of a free surge decay from 10 m in still water, every 0.05 s."""
    model = PlatformModel(platform(), None, dt_s=dt_s, mooring_model=model_name)
    model.reset(motion=np.array([10.0, 0, 0, 0, 0, 0]))
    result = model.run(duration_s, 0.05)
    return result.time_s, result.motion[:, 0]


def coupling_and_damping(duration_s: float) -> None:
    _, coarse = decay("moordyn", 0.05, 120.0)
    _, fine = decay("moordyn", 0.0125, 120.0)
    print(f"moordyn dt 0.05 s against 0.0125 s: largest surge difference {np.abs(coarse - fine).max():.4f} m "
          f"over 120 s of a decay from 10 m")
    fits = {}
    for model_name in ("moorpy", "moordyn"):
        t, x = decay(model_name, 0.05, duration_s)
        fits[model_name] = fit_free_decay(t, x)
        print(f"{model_name:8s} surge decay from 10 m: period {fits[model_name]['period_s']:.1f} s, damping "
              f"{100 * fits[model_name]['damping_ratio']:.2f} % of critical over {fits[model_name]['cycles']} cycles")
    extra = fits["moordyn"]["damping_ratio"] - fits["moorpy"]["damping_ratio"]
    print(f"the lines' own damping (moordyn - moorpy): {100 * extra:.2f} % of critical")


def deck_variant(folder: Path, dt_m: float, segments: int) -> Path:
    """The VolturnUS-S deck with MoorDyn's time step ``dt_m`` and each line's ``segments``."""
    text = LINES.read_text()
    text = re.sub(r"^\S+(\s+dtM\b)", f"{dt_m:g}\\1", text, flags=re.M)
    text = re.sub(r"^(\d+\s+main\s+\d+\s+\d+\s+\S+\s+)\d+", rf"\g<1>{segments}", text, flags=re.M)
    path = folder / f"lines_dtM{dt_m:g}_segs{segments}.dat"
    path.write_text(text)
    return path


def volturnus(file: Path):
    """VolturnUS-S moored by the lines of ``file``."""
    p = load_platform("volturnus_s")
    return dataclasses.replace(p, mooring=dataclasses.replace(p.mooring, file=str(file)))


def moordyn_alone(file: Path, fairleads: np.ndarray, time_s: np.ndarray, motion: np.ndarray) -> float:
    """CPU seconds of MoorDyn-C's own Step calls (fairleads (n, 3) in the body frame) replaying
    the platform motion (n, 6) at
    ``time_s`` (the fairleads on a straight line between rows, as the coupling moves them)."""
    import moordyn

    from fowt_hydro_sim.physics.mooring.moordyn_file import without_outputs
    from fowt_hydro_sim.physics.mooring.moordyn_lines import _fairlead_kinematics, _redirected

    n = len(fairleads)
    x, v, arms = np.empty((len(motion), 3 * n)), np.empty(3 * n), np.empty((n, 3))
    for k, m in enumerate(motion):
        _fairlead_kinematics(np.concatenate([m, np.zeros(6)]), fairleads, x[k], v, arms)
    x_list = x.tolist()
    v_list = (np.diff(x, axis=0) / np.diff(time_s)[:, None]).tolist()
    dt = np.diff(time_s).tolist()
    with tempfile.TemporaryDirectory() as folder:
        copy = Path(folder) / file.name
        copy.write_text(file.read_text())
        without_outputs(copy)
        null = os.open(os.devnull, os.O_WRONLY)
        try:
            with _redirected(null, null):
                system = moordyn.Create(str(copy))
                moordyn.SetVerbosity(system, moordyn.LEVEL_ERR)
                moordyn.Init(system, x_list[0], [0.0] * (3 * n))
                start = time.process_time()
                for k in range(len(dt)):
                    moordyn.Step(system, x_list[k], v_list[k], float(time_s[k]), dt[k])
                used = time.process_time() - start
                moordyn.Close(system)
        finally:
            os.close(null)
    return used


def moordyn_cost(duration_s: float, decks: list[tuple[float, int]]) -> None:
    """(a) MoorDyn alone, (b) our coupling, (c) the whole model, per deck variant."""
    waves = synthesize(load_case("lc5.3").sea_state, 3600.0)
    with tempfile.TemporaryDirectory() as folder:
        for dt_m, segments in decks:
            file = deck_variant(Path(folder), dt_m, segments)
            model = PlatformModel(volturnus(file), waves, mooring_model="moordyn")
            model.run(1.0)  # compiled, blocks made
            lines = model.mooring_lines
            inside = lines.moordyn_cpu_s
            start = time.process_time()
            result = model.run(duration_s, 0.05)
            whole = time.process_time() - start
            inside = lines.moordyn_cpu_s - inside
            alone = moordyn_alone(file, lines.fairleads_m, result.time_s, result.motion)
            load = os.getloadavg()[0]
            print(f"moordyn dtM {dt_m:g} s, {segments} segments/line: (a) MoorDyn alone {duration_s / alone:5.1f}x "
                  f"({alone:.2f} s CPU for {duration_s:g} s); (b) our coupling {duration_s / (whole - inside):5.0f}x "
                  f"({whole - inside:.2f} s); (c) whole model {duration_s / whole:5.1f}x ({whole:.2f} s; MoorDyn "
                  f"inside it {inside:.2f} s); load average {load:.2f} on {os.cpu_count()} cores", flush=True)


def moordyn_accuracy(decks: list[tuple[float, int]], duration_s: float = 420.0) -> None:
    """Free surge decays from 10 m on each deck variant against the first (the deck's own)."""
    runs = {}
    with tempfile.TemporaryDirectory() as folder:
        for dt_m, segments in decks:
            model = PlatformModel(volturnus(deck_variant(Path(folder), dt_m, segments)), None,
                                  mooring_model="moordyn")
            model.reset(motion=np.array([10.0, 0, 0, 0, 0, 0]))
            result = model.run(duration_s, 0.05)
            runs[(dt_m, segments)] = (result.time_s, result.motion[:, 0],
                                      model.mooring_tensions(result.time_s, result.motion)[:, :, 0])
    t, x0, tension0 = runs[decks[0]]
    for (dt_m, segments), (_, x, tension) in runs.items():
        fit = fit_free_decay(t, x)
        print(f"decay from 10 m, dtM {dt_m:g} s, {segments} segments/line: period {fit['period_s']:.2f} s, damping "
              f"{100 * fit['damping_ratio']:.3f} % of critical; against dtM {decks[0][0]:g} s, {decks[0][1]} "
              f"segments: largest surge difference {np.abs(x - x0).max():.4f} m, largest fairlead tension "
              f"difference {np.nanmax(np.abs(tension - tension0)) / 1e3:.2f} kN "
              f"({100 * np.nanmax(np.abs(tension - tension0) / tension0):.3f} %)", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=600.0, help="simulated seconds of the speed runs")
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--moordyn", action="store_true",
                        help="only MoorDyn's cost on VolturnUS-S over dtM and segments, and their accuracy")
    args = parser.parse_args()
    if args.moordyn:
        decks = [(0.001, 50), (0.002, 50), (0.004, 50), (0.001, 25)]
        moordyn_cost(args.duration, decks)
        moordyn_accuracy(decks)
        return
    speed(args.duration, args.repeats)
    tabulation()
    coupling_and_damping(600.0)


if __name__ == "__main__":
    main()
