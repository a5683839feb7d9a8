"""Starting rclpy in the package's commands (node, controller, play, record)."""
from __future__ import annotations

import signal

import rclpy
from rclpy.signals import SignalHandlerOptions


def init_ros(args: list[str] | None) -> None:
    """rclpy without its signal handlers: SIGINT and SIGTERM stop the node through
    KeyboardInterrupt in the main thread, so the stepping ends before the context does."""
    rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)
    # SIGINT too: a shell starting the node in the background (`&`) leaves SIGINT ignored
    for stop in (signal.SIGINT, signal.SIGTERM):
        signal.signal(stop, signal.default_int_handler)
