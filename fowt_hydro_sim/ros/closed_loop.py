"""``fowt-sim closed-loop``: the platform node and the turbine node (ROSCO) in lockstep, and
one bag recording both (``fowt-sim record``), as three child processes on the caller's ROS
domain. Returns when the platform node has stepped its duration (or stopped), after
stopping the turbine and closing the bag."""
from __future__ import annotations

import logging
import os
import re
import signal
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

log = logging.getLogger("fowt_hydro_sim.closed_loop")


@dataclass(frozen=True)
class ClosedLoopResult:
    simulated_s: float
    wall_s: float
    returncodes: dict[str, int]
    logs: dict[str, str]

    @property
    def speed(self) -> float:
        """Simulated seconds per wall second of the platform's stepping."""
        return self.simulated_s / self.wall_s if self.wall_s > 0 else 0.0


def _command(command: str, parameters: dict[str, Any]) -> list[str]:
    args = [sys.executable, "-m", "fowt_hydro_sim.cli", command, "--ros-args"]
    for name, value in parameters.items():
        if value is None or value == "":  # not given: the node's default
            continue
        text = str(value).lower() if isinstance(value, bool) else str(value)
        args += ["-p", f"{name}:={text}"]
    return args


def _start(args: list[str], log_path: Path) -> subprocess.Popen:
    with open(log_path, "w") as out:  # the child keeps its own descriptor
        return subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=out, stderr=subprocess.STDOUT,
                                cwd=os.getcwd())


def _stop(process: subprocess.Popen, timeout_s: float = 20.0) -> int:
    if process.poll() is None:
        process.send_signal(signal.SIGINT)
    try:
        return process.wait(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        process.kill()
        return process.wait()


def run(bag: str | Path, node: dict[str, Any], turbine: dict[str, Any], overwrite: bool = False,
        timeout_s: float = 3600.0) -> ClosedLoopResult:
    """Run the loop: ``node`` and ``turbine`` are the two nodes' parameters (the node's
    lockstep is set); the bag and the nodes' logs (``<bag>.logs/``) are written."""
    bag = Path(bag)
    logs = Path(f"{bag}.logs")
    logs.mkdir(parents=True, exist_ok=True)
    record = [sys.executable, "-m", "fowt_hydro_sim.cli", "record", "-o", str(bag)] + (["--overwrite"] if overwrite
                                                                                       else [])
    processes = {"record": _start(record, logs / "record.log")}
    processes["node"] = _start(_command("node", {**node, "lockstep": True}), logs / "node.log")
    processes["turbine"] = _start(_command("turbine", turbine), logs / "turbine.log")
    codes: dict[str, int] = {}
    try:
        deadline = time.monotonic() + timeout_s
        while processes["node"].poll() is None and time.monotonic() < deadline:
            if processes["record"].poll() is not None or processes["turbine"].poll() is not None:
                break  # no bag (e.g. it exists) or no turbine (bad parameters, ROSCO failed to start)
            time.sleep(0.2)
    finally:
        for name in ("node", "turbine", "record"):
            codes[name] = _stop(processes[name])
    texts = {name: (logs / f"{name}.log").read_text() for name in processes}
    done = re.search(r"([\d.]+) s simulated in ([\d.]+) s of wall time", texts["node"])
    simulated, wall = map(float, done.groups()) if done else (0.0, 0.0)
    return ClosedLoopResult(simulated, wall, codes, texts)
