"""Shared pytest configuration.

Runs at import time, before any test module imports rclpy: ROS 2 discovery is confined to
this machine (loopback only), and the caller's ROS_DOMAIN_ID is kept; without one, a domain
id is derived from this checkout's path and the test session's process id, so that two
checkouts (or two sessions) testing on one host at once do not see each other's nodes.

Tests that need ROS (rclpy, the message packages and a middleware) are marked ``ros``, or
skip their module with ``pytest.importorskip("rclpy")``: without ROS they are skipped,
unless FOWT_REQUIRE_ROS=1 (set by .ci/run), where a missing rclpy fails the session.
"""
import importlib.util
import os
import subprocess
import zlib
from pathlib import Path

import pytest

os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"  # forced, never overridden


def free_domain_id(key: str) -> int:
    """A ROS domain id for ``key`` (a checkout and a session): 1..101, the ids valid with any
    participant count on Linux, spread by a hash so that different keys get different ids."""
    return 1 + zlib.crc32(key.encode()) % 101


if not os.environ.get("ROS_DOMAIN_ID"):
    os.environ["ROS_DOMAIN_ID"] = str(free_domain_id(f"{Path(__file__).resolve().parent}:{os.getpid()}"))

HAVE_ROS = importlib.util.find_spec("rclpy") is not None
if not HAVE_ROS and os.environ.get("FOWT_REQUIRE_ROS") == "1":
    raise pytest.UsageError("FOWT_REQUIRE_ROS=1 but rclpy cannot be imported: pip install '.[ros]'")


def pytest_configure(config):
    config.addinivalue_line("markers", "ros: needs rclpy and the ROS message packages (skipped without them)")
    # the kernel's literal_unroll over the load registry, on purpose (physics/loads/__init__.py)
    config.addinivalue_line("filterwarnings", "ignore::numba.core.errors.NumbaExperimentalFeatureWarning")
    if config.option.durations is None:  # the suite's time budget: say where it goes
        config.option.durations = 15


def pytest_collection_modifyitems(config, items):
    if HAVE_ROS:
        return
    skip = pytest.mark.skip(reason="rclpy is not installed (pip install '.[ros]')")
    for item in items:
        if item.get_closest_marker("ros"):
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
