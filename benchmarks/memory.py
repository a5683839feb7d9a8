"""Benchmark of memory against record length: ``fowt-sim simulate`` of LC5.3 for 1, 3, 6 and
24 hours, each in a new process (kernels already compiled: ``fowt-sim compile`` first).

Prints, per record length: the whole process's wall time, the time loop's real-time factor
and the peak resident memory of the run (``summary.json``, ru_maxrss at the end of the run)
and of the whole process (written files included), with the load average beside them.

    python benchmarks/memory.py [--hours 1 3 6 24] [--drag constant]
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from fowt_hydro_sim.testing import REPO

# the child's own peak RSS, whatever ran before it in this process
PEAK = "import resource, sys, runpy; sys.argv = ['fowt-sim', *sys.argv[1:]]\n" \
       "try:\n    runpy.run_module('fowt_hydro_sim.cli', run_name='__main__')\nfinally:\n" \
       "    print('peak_rss_mb', resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, file=sys.stderr)"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--hours", type=float, nargs="+", default=[1.0, 3.0, 6.0, 24.0])
    parser.add_argument("--drag", default="constant")
    args = parser.parse_args()
    subprocess.run([sys.executable, "-m", "fowt_hydro_sim.cli", "compile"], check=True, cwd=REPO, capture_output=True)
    print(f"simulate lc5.3, drag {args.drag}, output every 0.25 s; {os.cpu_count()} cores, "
          f"{os.sysconf('SC_PHYS_PAGES') * os.sysconf('SC_PAGE_SIZE') / 2**30:.0f} GiB")
    print(f"{'hours':>6s}{'wall [s]':>10s}{'x real':>8s}{'run peak [MB]':>15s}{'process peak [MB]':>19s}{'load':>7s}")
    with tempfile.TemporaryDirectory() as folder:
        for hours in args.hours:
            out = Path(folder) / f"h{hours:g}"
            start = time.perf_counter()
            done = subprocess.run([sys.executable, "-c", PEAK, "simulate", "--drag", args.drag, "--duration",
                                   str(3600.0 * hours), "-o", str(out)], check=True, cwd=REPO, capture_output=True,
                                  text=True)
            wall = time.perf_counter() - start
            perf = json.loads((out / "summary.json").read_text())["performance"]
            process_mb = float(done.stderr.rsplit("peak_rss_mb", 1)[1])
            print(f"{hours:6g}{wall:10.1f}{perf['real_time_factor']:8.0f}{perf['peak_memory_mb']:15.0f}"
                  f"{process_mb:19.0f}{os.getloadavg()[0]:7.1f}", flush=True)
            for f in out.iterdir():
                f.unlink()


if __name__ == "__main__":
    main()
