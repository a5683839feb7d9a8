"""Shared pytest configuration.

Runs at import time, before any test module imports rclpy: ROS 2 discovery is confined to
this machine (loopback only), and the caller's ROS_DOMAIN_ID is kept; without one, a domain
id is derived from this checkout's path and the test session's process id, so that two
checkouts (or two sessions) testing on one host at once do not see each other's nodes.
Under pytest-xdist (``pytest -n 2``) each worker gets a domain of its own: the caller's id
for the first worker, the next ids for the others.

Test tiers are markers (pyproject.toml): the default run leaves out ``slow``. Tests that
need ROS (rclpy, the message packages and a middleware) are marked ``ros``, those that need
ROSCO's Python toolbox ``rosco``: without them installed they are skipped, unless
FOWT_REQUIRE_ROS=1 (set by .ci/run), where a missing rclpy or toolbox fails the session.
"""
import collections
import importlib.util
import os
import signal
import subprocess
import zlib
from pathlib import Path

import pytest

os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"  # forced, never overridden

# A test run started in the background of a non-interactive shell (`bash .ci/run &`) inherits
# SIGINT ignored, and so would every command it starts: the tests that send Ctrl-C to a
# command need it to have the default handling, as at a terminal.
if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)


def free_domain_id(key: str) -> int:
    """A ROS domain id for ``key`` (a checkout and a session): 1..101, the ids valid with any
    participant count on Linux, spread by a hash so that different keys get different ids."""
    return 1 + zlib.crc32(key.encode()) % 101


if not os.environ.get("ROS_DOMAIN_ID"):  # (each xdist worker is a process of its own)
    os.environ["ROS_DOMAIN_ID"] = str(free_domain_id(f"{Path(__file__).resolve().parent}:{os.getpid()}"))
elif os.environ.get("PYTEST_XDIST_WORKER", "gw0") != "gw0":
    worker = int(os.environ["PYTEST_XDIST_WORKER"].removeprefix("gw"))
    os.environ["ROS_DOMAIN_ID"] = str(1 + (int(os.environ["ROS_DOMAIN_ID"]) - 1 + worker) % 101)

# marker -> (installed?, what to install)
NEEDS = {
    "ros": (importlib.util.find_spec("rclpy") is not None, "pip install '.[ros]'"),
    "rosco": (all(importlib.util.find_spec(m) is not None for m in ("rosco", "wisdem")), "pip install '.[rosco]'"),
}
missing = [f"{marker} ({install})" for marker, (present, install) in NEEDS.items() if not present]
if missing and os.environ.get("FOWT_REQUIRE_ROS") == "1":
    raise pytest.UsageError(f"FOWT_REQUIRE_ROS=1 but not installed: {', '.join(missing)}")


def pytest_configure(config):
    # the kernel's literal_unroll over the load registry, on purpose (physics/loads/__init__.py)
    config.addinivalue_line("filterwarnings", "ignore::numba.core.errors.NumbaExperimentalFeatureWarning")
    if config.option.durations is None:  # the suite's time budget: say where it goes
        config.option.durations = 15


def pytest_collection_modifyitems(config, items):
    # The files with the most slow tests first (a stable sort: each file's tests stay in order):
    # with --no-loadscope-reorder, pytest-xdist hands whole files to its processes in this order,
    # so the minutes-long files start early and the last ones are quick, which keeps both
    # processes busy to the end (xdist's own order, by number of tests, left a long file last).
    slow = collections.Counter(item.path for item in items if item.get_closest_marker("slow"))
    items.sort(key=lambda item: -slow[item.path])
    for marker, (present, install) in NEEDS.items():
        if present:
            continue
        skip = pytest.mark.skip(reason=f"not installed: {install}")
        for item in items:
            if item.get_closest_marker(marker):
                item.add_marker(skip)


@pytest.fixture
def small_disk(tmp_path):
    """A 1 MiB tmpfs: a disk that fills up within seconds of recording (mounting needs root)."""
    if os.geteuid() != 0:
        pytest.skip("mounting a small tmpfs needs root")
    disk = tmp_path / "disk"
    disk.mkdir()
    subprocess.run(["mount", "-t", "tmpfs", "-o", "size=1m", "tmpfs", str(disk)], check=True)
    try:
        yield disk
    finally:
        subprocess.run(["umount", str(disk)], check=True)
