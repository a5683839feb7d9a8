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
RECORDER_READY_S = 120.0  # wall seconds at most for the recorder to see the platform node (its start compiles)


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


def static_offset(node: dict[str, Any], turbine: dict[str, Any]) -> tuple[float, ...]:
    """The platform's offset K^-1 F under the turbine's steady thrust in the initial wind (K:
    the platform's restoring matrix at rest), where a closed loop starts without a start-up
    swing."""
    import numpy as np

    from fowt_hydro_sim.physics.config import load_platform
    from fowt_hydro_sim.physics.model import PlatformModel
    from fowt_hydro_sim.ros.turbine_node import TurbineSettings
    from fowt_hydro_sim.turbine.description import load_turbine
    from fowt_hydro_sim.turbine.performance import RotorCoefficients, read_table
    from fowt_hydro_sim.turbine.rotor import aero_loads, steady_operating_point

    settings = TurbineSettings(**{k: v for k, v in turbine.items() if v is not None})
    description = load_turbine(settings.turbine)
    coefficients = RotorCoefficients(read_table(description.performance_path))
    wind = settings.make_wind().at(0.0)
    speed, pitch, _ = steady_operating_point(description, coefficients, wind)
    thrust, _ = aero_loads(description, coefficients, wind, speed, pitch)
    platform = load_platform(node.get("platform") or "windmoor12")
    hub = np.array(platform.hub_point_m)
    if settings.hub_height_m:
        hub[2] = settings.hub_height_m
    force = np.array([thrust, 0.0, 0.0])
    stiffness = PlatformModel(platform, None).restoring_matrix()
    return tuple(float(v) for v in np.linalg.solve(stiffness, np.concatenate([force, np.cross(hub, force)])))


def _wait_for_recording(record_log: Path, processes: dict[str, subprocess.Popen], timeout_s: float) -> None:
    """Until the recorder subscribes to the platform's odometry (or a process ends, or the
    timeout: the run goes on, the bag may miss its first messages)."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline and all(p.poll() is None for p in processes.values()):
        if "recording /platform/odom" in record_log.read_text():
            return
        time.sleep(0.1)


def run(bag: str | Path, node: dict[str, Any], turbine: dict[str, Any], overwrite: bool = False,
        timeout_s: float = 3600.0) -> ClosedLoopResult:
    """Run the loop: ``node`` and ``turbine`` are the two nodes' parameters (the node's
    lockstep is set; without an ``initial_state`` the platform starts at its static offset
    under the initial thrust); the bag and the nodes' logs (``<bag>.logs/``) are written."""
    bag = Path(bag)
    if node.get("initial_state") is None:
        node = {**node, "initial_state": list(static_offset(node, turbine))}
        log.info(f"the platform starts at its static offset under the initial thrust: "
                 f"{', '.join(f'{v:.4g}' for v in node['initial_state'])}")
    logs = Path(f"{bag}.logs")
    logs.mkdir(parents=True, exist_ok=True)
    record = [sys.executable, "-m", "fowt_hydro_sim.cli", "record", "-o", str(bag)] + (["--overwrite"] if overwrite
                                                                                       else [])
    processes = {"record": _start(record, logs / "record.log")}
    processes["node"] = _start(_command("node", {**node, "lockstep": True}), logs / "node.log")
    _wait_for_recording(logs / "record.log", processes, RECORDER_READY_S)  # the run's first messages too
    # the turbine answers the platform only once the recorder subscribes to its topics: no sample missed
    turbine = {**turbine, "wait_for_subscribers": turbine.get("wait_for_subscribers") or 1}
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
