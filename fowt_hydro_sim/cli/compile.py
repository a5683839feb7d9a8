"""``fowt-sim compile``: compile the model's kernels into the on-disk cache ahead of a first
run (the set-up command runs it), so that a first ``simulate`` or node starts in seconds."""
from __future__ import annotations

import argparse
import importlib
import sys
import time

WARM_UPS = ("physics", "turbine")  # the packages whose warm_up.entry_points() are compiled, in order


def compile_kernels(args: argparse.Namespace) -> int:
    from fowt_hydro_sim.physics import kernel_cache_dir
    from fowt_hydro_sim.physics.warm_up import warm_kernels
    start = time.perf_counter()
    timings: dict[str, float] = {}
    for package in WARM_UPS:
        timings.update(warm_kernels(importlib.import_module(f"fowt_hydro_sim.{package}.warm_up").entry_points()))
    for name, seconds in timings.items():
        sys.stdout.write(f"{name:34s}{seconds:7.1f} s\n")
    sys.stdout.write(f"kernels ready in {time.perf_counter() - start:.1f} s, cached in {kernel_cache_dir()}\n")
    return 0


def add_parsers(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("compile", help="compile the model's kernels into the cache (set-up; first runs start fast)",
                       description="Compile the model's kernels (or load them from the cache) so that the first "
                                   "run of any command need not: the set-up runs this once after installing. The "
                                   "cache is keyed by the physics sources, so it is redone after an update.")
    p.set_defaults(func=compile_kernels)
