"""Shared pytest configuration.

Runs at import time, before any test module imports rclpy: ROS 2 discovery is
confined to this machine (loopback only) and a fixed domain id is used unless
the caller chose one.
"""
import os

os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"  # forced, never overridden
os.environ.setdefault("ROS_DOMAIN_ID", "42")
