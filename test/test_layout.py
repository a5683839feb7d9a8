"""The package layout's import rules (README, "Module map"), as an allow-list: for every
package and top-level module of fowt_hydro_sim, msg_adapters and benchmarks/, the project
packages it may import and where the heavy third-party packages may be imported, read from
every module's import statements (function-level imports included); the import graph has no
cycle, between packages or between modules; and fresh interpreters show what an import
really loads (numba, rclpy)."""
from __future__ import annotations

import ast
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from fowt_hydro_sim.testing import REPO

ROOT = "fowt_hydro_sim"  # the package's own __init__ (its public names are loaded lazily)
BASICS = {ROOT, "errors", "frames", "files", "settings"}  # the top-level modules
# each unit (a package or top-level module of fowt_hydro_sim, by its name under it; msg_adapters;
# benchmarks) -> the units it may import
MAY_IMPORT: dict[str, set[str]] = {
    ROOT: set(),
    "errors": set(),
    "frames": set(),
    "files": set(),
    "settings": {"errors"},
    "msg_adapters": {"frames"},
    "physics": BASICS,
    "turbine": BASICS | {"physics", "io"},  # (the field's turbine files: AeroDyn's tower table)
    "io": BASICS | {"physics"},
    "rosbag": BASICS | {"msg_adapters"},
    "studies": BASICS | {"physics", "turbine", "rosbag", "io", "msg_adapters"},
    "ros": BASICS | {"physics", "turbine", "rosbag", "msg_adapters"},
    "testing": BASICS | {"physics", "turbine", "rosbag", "io", "ros", "msg_adapters", "cli"},  # (suites run the CLI)
    "cli": BASICS | {"physics", "turbine", "rosbag", "io", "studies", "ros", "msg_adapters"},
    "benchmarks": BASICS | {"physics", "turbine", "rosbag", "io", "studies", "ros", "msg_adapters", "testing",
                            "cli"},
}
ROS_PACKAGES = ("rcl_interfaces", "geometry_msgs", "nav_msgs", "rosgraph_msgs", "std_msgs", "builtin_interfaces")
# heavy or optional third-party packages -> the only units that may import them
THIRD_PARTY: dict[str, set[str]] = {
    "rclpy": {"ros", "cli", "testing", "benchmarks"},
    **{name: {"ros", "cli", "testing", "benchmarks", "msg_adapters"} for name in ROS_PACKAGES},
    "numba": {"physics", "turbine", "studies", "benchmarks"},
    "mcap": {"rosbag", "ros", "testing", "benchmarks"},
    "zstandard": {"rosbag", "ros", "testing", "benchmarks"},
    "dask": {"studies", "benchmarks"},
    "matplotlib": {"studies", "benchmarks"},
    "openfast_io": {"io", "testing", "benchmarks"},
    "rosco": {"turbine", "testing", "benchmarks"},
    "moordyn": {"physics", "testing", "benchmarks"},
    "moorpy": {"physics", "studies", "testing", "benchmarks"},
}


def source_files() -> dict[str, Path]:
    """Every module of the project: dotted name -> file (benchmarks as ``benchmarks.name``)."""
    files = sorted((REPO / ROOT).rglob("*.py")) + sorted((REPO / "msg_adapters").rglob("*.py")) \
        + sorted((REPO / "benchmarks").glob("*.py"))
    modules = {}
    for path in files:
        parts = path.relative_to(REPO).with_suffix("").parts
        modules[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return modules


MODULES = source_files()


def unit_of(module: str) -> str | None:
    """The unit of a project module (``physics``, ``frames``, ``msg_adapters``...), else None."""
    parts = module.split(".")
    if parts[0] == ROOT:
        return ROOT if len(parts) == 1 else parts[1]
    return parts[0] if parts[0] in ("msg_adapters", "benchmarks") else None


def imported_names(module: str) -> Iterator[str]:
    """The absolute names a module imports (relative imports resolved; ``from p import m``
    names the module ``p.m`` when m is a module, else ``p``)."""
    path = MODULES[module]
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            yield from (alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = package.split(".")
                base = ".".join(parts[:len(parts) - node.level + 1] + ([base] if base else []))
            for alias in node.names:
                yield f"{base}.{alias.name}" if f"{base}.{alias.name}" in MODULES else base


def project_module(name: str) -> str | None:
    """The project module an imported name loads (its longest known prefix), else None."""
    while name and name not in MODULES:
        name = name.rpartition(".")[0]
    return name or None


def module_graph() -> dict[str, set[str]]:
    return {m: {t for t in map(project_module, imported_names(m)) if t and t != m} for m in MODULES}


def unit_graph() -> dict[str, set[str]]:
    graph: dict[str, set[str]] = {}
    for module, targets in module_graph().items():
        graph.setdefault(unit_of(module), set()).update(unit_of(t) for t in targets if unit_of(t) != unit_of(module))
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """One cycle through each back edge of a depth-first search (none if the graph is acyclic)."""
    found, state, path = [], {}, []

    def visit(node: str) -> None:
        state[node] = "open"
        path.append(node)
        for after in sorted(graph.get(node, ())):
            if state.get(after) == "open":
                found.append(path[path.index(after):] + [after])
            elif after not in state:
                visit(after)
        path.pop()
        state[node] = "done"

    for node in sorted(graph):
        if node not in state:
            visit(node)
    return found


def test_every_unit_has_rules():
    assert {unit_of(m) for m in MODULES} == set(MAY_IMPORT)


@pytest.mark.parametrize("unit", sorted(MAY_IMPORT))
def test_each_unit_imports_only_what_it_may(unit: str):
    broken = []
    for module in (m for m in MODULES if unit_of(m) == unit):
        for name in sorted(set(imported_names(module))):
            target = project_module(name)
            if target is not None and unit_of(target) != unit and unit_of(target) not in MAY_IMPORT[unit]:
                broken.append(f"{MODULES[module].relative_to(REPO)} imports {name}")
            top = name.split(".")[0]
            if target is None and top in THIRD_PARTY and unit not in THIRD_PARTY[top]:
                broken.append(f"{MODULES[module].relative_to(REPO)} imports {name} (only in "
                              f"{', '.join(sorted(THIRD_PARTY[top]))})")
    assert not broken, "\n".join(broken)


def test_the_rules_catch_a_forbidden_import():
    """The checker itself: a physics -> turbine import, and numba in the bags, are refused."""
    assert "turbine" not in MAY_IMPORT["physics"] and "rosbag" not in THIRD_PARTY["numba"]
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == [["a", "b", "c", "a"]]
    assert cycles({"a": {"b", "c"}, "b": {"c"}, "c": set()}) == []


def test_the_packages_import_each_other_without_a_cycle():
    assert not cycles(unit_graph()), cycles(unit_graph())


def test_the_modules_import_each_other_without_a_cycle():
    found = cycles(module_graph())
    assert not found, "\n".join(" -> ".join(cycle) for cycle in found)


def loaded_by(statement: str) -> set[str]:
    """The modules loaded by ``statement`` in a fresh interpreter."""
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


def test_the_package_and_its_errors_load_nothing_heavy():
    modules = loaded_by("import fowt_hydro_sim, fowt_hydro_sim.errors, fowt_hydro_sim.settings")
    assert not {"numba", "rclpy", "numpy", "fowt_hydro_sim.physics"} & modules


@pytest.mark.ros
def test_the_bag_tools_and_the_controller_start_rclpy_without_the_model():
    modules = loaded_by("import fowt_hydro_sim.ros.player, fowt_hydro_sim.ros.recorder, "
                        "fowt_hydro_sim.ros.thrust_controller, fowt_hydro_sim.ros.startup")
    assert "numba" not in modules and "fowt_hydro_sim.physics.model" not in modules
