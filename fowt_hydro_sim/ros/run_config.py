"""A run's full configuration, stored in its bag, and the node parameter file that
reproduces the run from it (``fowt-sim info BAG --params-file F``)."""
from __future__ import annotations

import datetime
import platform as host
from pathlib import Path

import numpy as np
import scipy
import yaml

from fowt_hydro_sim import __version__
from fowt_hydro_sim.errors import InputError


def run_config(parameters: dict, platform_yaml: str, sea_state: dict) -> dict:
    """Software versions, the node's parameters, the platform definition and the sea state."""
    return {
        "software": {"fowt_hydro_sim": __version__, "python": host.python_version(), "numpy": np.__version__,
                     "scipy": scipy.__version__},
        "started_utc": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "parameters": {k: list(v) if isinstance(v, (list, tuple)) else v for k, v in parameters.items()},
        "sea_state": sea_state,
        "platform_yaml": platform_yaml,
    }


def write_params_file(config: dict, path: str | Path) -> Path:
    """A ROS parameter file for ``fowt-sim node --ros-args --params-file`` that reruns the
    recorded run (not recording again), with its platform written beside it. A closed loop's
    configuration (with ``turbine_parameters``) adds the turbine node's section
    (``fowt_turbine``, its platform the same file): ``fowt-sim closed-loop --params-file``
    reruns it."""
    path = Path(path)
    if "parameters" not in config or "platform_yaml" not in config:
        raise InputError("the bag's configuration has no node parameters (not recorded by fowt-sim node)")
    platform_file = path.with_name(path.stem + "_platform.yaml")
    platform_file.write_text(config["platform_yaml"])
    parameters = {**config["parameters"], "platform": str(platform_file.resolve()), "record": "",
                  "record_overwrite": False}
    document = {"fowt_hydro_sim": {"ros__parameters": parameters}}
    if "turbine_parameters" in config:
        document["fowt_turbine"] = {"ros__parameters": {**config["turbine_parameters"],
                                                        "platform": str(platform_file.resolve()),
                                                        "wait_for_subscribers": 0, "rosco_debug_dir": ""}}
    path.write_text(yaml.safe_dump(document, sort_keys=False))
    return path

