"""The package layout's import rules (README, "Module map"): what each package may import,
read from every module's import statements, and checked in a fresh interpreter for what an
import really loads (numba, rclpy)."""
from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

from fowt_hydro_sim.testing import REPO

ROS_PACKAGES = ("rclpy", "rcl_interfaces", "geometry_msgs", "nav_msgs", "rosgraph_msgs", "std_msgs",
                "builtin_interfaces")
# package -> the imports it must not make (prefixes of module names)
FORBIDDEN = {
    "fowt_hydro_sim/physics": ("fowt_hydro_sim.ros", "fowt_hydro_sim.rosbag", "fowt_hydro_sim.studies",
                               "fowt_hydro_sim.cli", "fowt_hydro_sim.testing", "msg_adapters", "mcap", "dask",
                               *ROS_PACKAGES),
    "fowt_hydro_sim/turbine": ("fowt_hydro_sim.ros", "fowt_hydro_sim.rosbag", "fowt_hydro_sim.studies",
                               "fowt_hydro_sim.cli", "fowt_hydro_sim.testing", "msg_adapters", "mcap", "dask",
                               *ROS_PACKAGES),
    "msg_adapters": ("fowt_hydro_sim.physics", "fowt_hydro_sim.ros", "fowt_hydro_sim.rosbag",
                     "fowt_hydro_sim.studies", "fowt_hydro_sim.cli", "numba"),
    "fowt_hydro_sim/rosbag": ("fowt_hydro_sim.physics", "fowt_hydro_sim.ros", "fowt_hydro_sim.studies",
                              "fowt_hydro_sim.cli", "numba", *ROS_PACKAGES),
    "fowt_hydro_sim/studies": ("fowt_hydro_sim.ros", "fowt_hydro_sim.cli", *ROS_PACKAGES),
    "fowt_hydro_sim/ros": ("fowt_hydro_sim.studies", "fowt_hydro_sim.cli"),
    "fowt_hydro_sim/frames.py": ("fowt_hydro_sim.", "msg_adapters", "numba", *ROS_PACKAGES),
    "fowt_hydro_sim/settings.py": ("fowt_hydro_sim.", "msg_adapters", "numba", *ROS_PACKAGES),
    "fowt_hydro_sim/files.py": ("fowt_hydro_sim.", "msg_adapters", "numba", *ROS_PACKAGES),
}


def imports(path: Path) -> set[str]:
    """Every module a file imports (absolute names; relative imports resolved)."""
    package = ".".join(path.relative_to(REPO).with_suffix("").parts[:-1])
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = package.split(".")
                base = ".".join(parts[:len(parts) - node.level + 1] + ([base] if base else []))
            found.add(base)
            found.update(f"{base}.{alias.name}" for alias in node.names)
    return found


@pytest.mark.parametrize("where", sorted(FORBIDDEN))
def test_each_package_imports_only_what_it_may(where: str):
    root = REPO / where
    files = [root] if root.suffix == ".py" else sorted(root.rglob("*.py"))
    assert files, where
    broken = [f"{f.relative_to(REPO)} imports {name}" for f in files for name in sorted(imports(f))
              if any(name == bad.rstrip(".") or name.startswith(bad if bad.endswith(".") else bad + ".")
                     for bad in FORBIDDEN[where])]
    assert not broken, "\n".join(broken)


def loaded_by(statement: str) -> set[str]:
    """The top-level packages loaded by ``statement`` in a fresh interpreter."""
    code = f"import sys; {statement}; print(' '.join(sorted(sys.modules)))"
    done = subprocess.run([sys.executable, "-c", code], cwd=REPO, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return set(done.stdout.split())


def test_the_message_adapters_and_bags_load_no_physics_and_no_numba():
    modules = loaded_by("import msg_adapters.cdr, msg_adapters.topics, fowt_hydro_sim.rosbag.reader, "
                        "fowt_hydro_sim.rosbag.writer")
    assert "numba" not in modules and "fowt_hydro_sim.physics" not in modules


def test_the_physics_loads_no_ros_and_no_bags():
    modules = loaded_by("import fowt_hydro_sim.physics.model, fowt_hydro_sim.physics.wave_feed")
    assert not {"rclpy", "mcap", "msg_adapters", "dask"} & modules


@pytest.mark.ros
def test_the_bag_tools_and_the_controller_start_rclpy_without_the_model():
    modules = loaded_by("import fowt_hydro_sim.ros.player, fowt_hydro_sim.ros.recorder, "
                        "fowt_hydro_sim.ros.thrust_controller, fowt_hydro_sim.ros.startup")
    assert "numba" not in modules and "fowt_hydro_sim.physics.model" not in modules
