"""``fowt-sim closed-loop``: the platform node and the turbine node (ROSCO) in lockstep, and
one bag recording both (``fowt-sim record``, given the run's configuration: both nodes'
parameters, the platform and the sea state), as three child processes on the caller's ROS
domain. Returns when the platform node has stepped its duration (or stopped, or lost its
controller as its controller_lost says), after stopping the turbine and closing the bag;
Ctrl-C stops all three cleanly."""
from __future__ import annotations

import logging
import math
import os
import re
import signal
import subprocess
import sys
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

log = logging.getLogger("fowt_hydro_sim.closed_loop")
INTERRUPTED_GRACE_S = 10.0  # after Ctrl-C: wall seconds for each process to end on its own SIGINT
RECORDER_READY_S = 120.0  # wall seconds at most for the recorder to see the platform node (its start compiles)


@dataclass(frozen=True)
class ClosedLoopResult:
    simulated_s: float
    wall_s: float
    returncodes: dict[str, int]
    logs: dict[str, str]
    interrupted: bool = False  # stopped by Ctrl-C

    @property
    def speed(self) -> float:
        """Simulated seconds per wall second of the platform's stepping."""
        return self.simulated_s / self.wall_s if self.wall_s > 0 else 0.0


def parameter_text(value: Any) -> str:
    """A parameter value as ``-p name:=TEXT`` takes it (YAML): booleans in lower case, a
    list or tuple as a YAML sequence of its items, floats written back exactly."""
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(parameter_text(v) for v in value) + "]"
    if isinstance(value, float):
        return repr(value)
    return str(value)


def _command(command: str, parameters: dict[str, Any]) -> list[str]:
    args = [sys.executable, "-m", "fowt_hydro_sim.cli", command, "--ros-args"]
    for name, value in parameters.items():
        if value is None or value == "":  # not given: the node's default
            continue
        args += ["-p", f"{name}:={parameter_text(value)}"]
    return args


def _start(args: list[str], log_path: Path) -> subprocess.Popen:
    with open(log_path, "w") as out:  # the child keeps its own descriptor
        return subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=out, stderr=subprocess.STDOUT,
                                cwd=os.getcwd())


def _stop(process: subprocess.Popen, timeout_s: float = 20.0, grace_s: float = 0.0) -> int:
    """Its exit code, after ``grace_s`` wall seconds to end by itself, then SIGINT, then
    (``timeout_s`` later) SIGKILL."""
    try:
        process.wait(timeout=grace_s)
    except subprocess.TimeoutExpired:
        pass
    if process.poll() is None:
        process.send_signal(signal.SIGINT)
    try:
        return process.wait(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        process.kill()
        return process.wait()


def static_offset(node: dict[str, Any], turbine: dict[str, Any]) -> tuple[float, ...]:
    """The platform's offset K^-1 (F0 + F) under the turbine's steady thrust F in the initial
    wind (K, F0: the platform's restoring matrix and wrench at rest with its mooring,
    ``turbine.coupled.restoring``), where a closed loop starts without a start-up swing (as
    the offline coupled run does)."""
    import numpy as np

    from fowt_hydro_sim.physics.config import load_platform
    from fowt_hydro_sim.physics.model import PlatformModel
    from fowt_hydro_sim.ros.turbine_node import TurbineSettings
    from fowt_hydro_sim.turbine.coupled import restoring, steady_wind_wrench
    from fowt_hydro_sim.turbine.description import load_turbine
    from fowt_hydro_sim.turbine.performance import RotorCoefficients, read_table

    settings = TurbineSettings(**{k: v for k, v in turbine.items() if v is not None})
    description = load_turbine(settings.turbine)
    coefficients = RotorCoefficients(read_table(description.performance_path))
    platform = load_platform(node.get("platform") or "windmoor12")
    point = np.array(platform.hub_point_m)
    if settings.hub_height_m:
        point[2] = settings.hub_height_m
    wrench = steady_wind_wrench(description, coefficients, settings.make_wind().at(0.0), point)
    at_rest, stiffness = restoring(PlatformModel(platform, None, mooring_model=node.get("mooring") or ""))
    return tuple(float(v) for v in np.linalg.solve(stiffness, at_rest + wrench))


def with_systems(node: dict[str, Any], turbine: dict[str, Any]) -> tuple[dict[str, Any], dict[str, Any]]:
    """The two nodes' parameters with the named system (``system``, given to either) filled
    in: the platform and mooring of the platform node, the platform and turbine of the
    turbine node; ConfigError if one was given otherwise than the system says."""
    from fowt_hydro_sim.ros.node import NodeSettings
    from fowt_hydro_sim.ros.turbine_node import TurbineSettings
    from fowt_hydro_sim.turbine.system import filled

    system = node.get("system") or turbine.get("system")
    if not system:
        return node, turbine
    return filled(NodeSettings, {**node, "system": system}), filled(TurbineSettings, {**turbine, "system": system})


def _wait_for_recording(record_log: Path, processes: dict[str, subprocess.Popen], timeout_s: float) -> None:
    """Until the recorder subscribes to the platform's odometry (or a process ends, or the
    timeout: the run goes on, the bag may miss its first messages)."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline and all(p.poll() is None for p in processes.values()):
        if "recording /platform/odom" in record_log.read_text():
            return
        time.sleep(0.1)


def run_configuration(node: dict[str, Any], turbine: dict[str, Any]) -> dict:
    """The closed loop's configuration as its bag stores it: the platform node's full
    configuration (``run_config``: its parameters, platform and sea state) and the turbine
    node's parameters (``turbine_parameters``), so that ``fowt-sim info --params-file``
    writes the file that reruns it."""
    from dataclasses import asdict

    from fowt_hydro_sim.physics.config import platform_path
    from fowt_hydro_sim.ros import parameters
    from fowt_hydro_sim.ros.node import NodeSettings
    from fowt_hydro_sim.ros.run_config import run_config
    from fowt_hydro_sim.ros.turbine_node import TurbineSettings

    node_settings = NodeSettings(**{k: v for k, v in node.items() if v is not None})
    turbine_settings = TurbineSettings(**{k: v for k, v in turbine.items() if v is not None})
    config = run_config(parameters.values(node_settings), platform_path(node_settings.platform).read_text(),
                        asdict(node_settings.sea_state))
    config["turbine_parameters"] = {k: list(v) if isinstance(v, (list, tuple)) else v
                                    for k, v in parameters.values(turbine_settings).items()}
    return config


def read_params_file(path: str | Path) -> tuple[dict[str, Any], dict[str, Any]]:
    """The platform node's and the turbine node's parameters in a ROS parameter file (the
    sections ``fowt_hydro_sim`` and ``fowt_turbine``, as ``fowt-sim info --params-file``
    writes them), each checked against its settings; ConfigError names a bad one."""
    import yaml

    from fowt_hydro_sim.physics.config import ConfigError
    from fowt_hydro_sim.ros.node import NodeSettings
    from fowt_hydro_sim.ros.turbine_node import TurbineSettings
    from fowt_hydro_sim.settings import SettingError, check, described

    try:
        document = yaml.safe_load(Path(path).read_text())
    except OSError as exc:
        raise ConfigError(f"--params-file {path}: cannot be read ({exc.strerror or exc})") from None
    except yaml.YAMLError as exc:
        raise ConfigError(f"--params-file {path}: not YAML ({str(exc).splitlines()[0]})") from None
    out = []
    for section, cls in (("fowt_hydro_sim", NodeSettings), ("fowt_turbine", TurbineSettings)):
        given = ((document or {}).get(section) or {}).get("ros__parameters") if isinstance(document, dict) else None
        if not isinstance(given, dict):
            raise ConfigError(f"--params-file {path}: no {section}: ros__parameters: section")
        known = described(cls)
        values = {}
        for name, value in given.items():
            if name not in known:
                raise ConfigError(f"--params-file {path}: {section} has no parameter {name}")
            try:
                values[name] = check(known[name], tuple(value) if isinstance(value, list) else value)
            except SettingError as exc:
                raise ConfigError(f"--params-file {path}: {section} parameter {name}: {exc}") from None
        out.append(values)
    return out[0], out[1]


def run(bag: str | Path, node: dict[str, Any], turbine: dict[str, Any], overwrite: bool = False,
        timeout_s: float | None = None) -> ClosedLoopResult:
    """Run the loop: ``node`` and ``turbine`` are the two nodes' parameters (the node's
    lockstep is set; without an ``initial_state`` the platform starts at its static offset
    under the initial thrust); the bag (with the run's configuration, ``run_configuration``)
    and the nodes' logs (``<bag>.logs/``, with ROSCO's debug files in ``rosco/`` when
    ``rosco_logging`` is given) are written. It lasts until the platform node
    ends (its duration stepped, or stopped), with no wall-clock limit unless ``timeout_s``
    is given. Ctrl-C (KeyboardInterrupt) stops the three processes, closes the bag and
    returns the result with ``interrupted`` set."""
    import yaml

    bag = Path(bag)
    node, turbine = with_systems(node, turbine)
    if node.get("initial_state") is None:
        node = {**node, "initial_state": list(static_offset(node, turbine))}
        log.info(f"the platform starts at its static offset under the initial thrust: "
                 f"{', '.join(f'{v:.4g}' for v in node['initial_state'])}")
    node = {**node, "lockstep": True}
    if node.get("platform") and not turbine.get("platform"):  # the rotor on the platform's own hub point
        turbine = {**turbine, "platform": node["platform"]}
    # the turbine answers the platform only once the recorder subscribes to its topics: no sample missed
    turbine = {**turbine, "wait_for_subscribers": turbine.get("wait_for_subscribers") or 1}
    logs = Path(f"{bag}.logs")
    if turbine.get("rosco_logging") and not turbine.get("rosco_debug_dir"):
        turbine["rosco_debug_dir"] = str(logs / "rosco")  # ROSCO's debug files beside the nodes' logs
    logs.mkdir(parents=True, exist_ok=True)
    config_path = logs / "run_config.yaml"
    config_path.write_text(yaml.safe_dump(run_configuration(node, turbine), sort_keys=False))
    record = [sys.executable, "-m", "fowt_hydro_sim.cli", "record", "-o", str(bag), "--config", str(config_path)]
    processes = {"record": _start(record + (["--overwrite"] if overwrite else []), logs / "record.log")}
    codes: dict[str, int] = {}
    interrupted = False
    try:
        processes["node"] = _start(_command("node", node), logs / "node.log")
        _wait_for_recording(logs / "record.log", processes, RECORDER_READY_S)  # the run's first messages too
        processes["turbine"] = _start(_command("turbine", turbine), logs / "turbine.log")
        deadline = time.monotonic() + timeout_s if timeout_s else math.inf
        while processes["node"].poll() is None and time.monotonic() < deadline:
            # no bag (e.g. it exists), or no turbine at all (bad parameters, ROSCO failed to start: exit 2);
            # a turbine lost mid-run is the node's to handle (its controller_lost)
            if processes["record"].poll() is not None or processes["turbine"].poll() == 2:
                break
            time.sleep(0.2)
    except KeyboardInterrupt:
        interrupted = True
    finally:
        main = threading.current_thread() is threading.main_thread()
        stops: list[int] = []  # a Ctrl-C from here on: noted, no effect on the clean-up
        previous = signal.signal(signal.SIGINT, lambda signum, _: stops.append(signum)) if main else None
        time.sleep(0.05)  # a Ctrl-C already pending (its children may end first) is taken here: noted
        interrupted = interrupted or bool(stops)
        try:
            for name in ("node", "turbine", "record"):
                if name in processes:
                    # after Ctrl-C at a terminal each child has its own SIGINT: a second one would cut its clean-up
                    codes[name] = _stop(processes[name], grace_s=INTERRUPTED_GRACE_S if interrupted else 0.0)
        finally:
            if main:
                signal.signal(signal.SIGINT, previous)
    texts = {name: (logs / f"{name}.log").read_text() for name in processes}
    done = re.search(r"([\d.]+) s simulated in ([\d.]+) s of wall time", texts.get("node", ""))
    simulated, wall = map(float, done.groups()) if done else (0.0, 0.0)
    return ClosedLoopResult(simulated, wall, codes, texts, interrupted)
