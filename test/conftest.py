"""Shared pytest configuration.

Runs at import time, before any test module imports rclpy: ROS 2 discovery is confined to
this machine (loopback only) and a fixed domain id is used unless the caller chose one.

Tests that need ROS (rclpy, the message packages and a middleware) are marked ``ros``, or
skip their module with ``pytest.importorskip("rclpy")``: without ROS they are skipped,
unless FOWT_REQUIRE_ROS=1 (set by .ci/run), where a missing rclpy fails the session.
"""
import importlib.util
import os

import pytest

os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"  # forced, never overridden
os.environ.setdefault("ROS_DOMAIN_ID", "42")

HAVE_ROS = importlib.util.find_spec("rclpy") is not None
if not HAVE_ROS and os.environ.get("FOWT_REQUIRE_ROS") == "1":
    raise pytest.UsageError("FOWT_REQUIRE_ROS=1 but rclpy cannot be imported: pip install '.[ros]'")


def pytest_configure(config):
    config.addinivalue_line("markers", "ros: needs rclpy and the ROS message packages (skipped without them)")


def pytest_collection_modifyitems(config, items):
    if HAVE_ROS:
        return
    skip = pytest.mark.skip(reason="rclpy is not installed (pip install '.[ros]')")
    for item in items:
        if item.get_closest_marker("ros"):
            item.add_marker(skip)
