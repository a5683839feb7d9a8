"""Starting rclpy in the package's commands (node, controller, turbine, play, record; the
closed loop's three processes each start here too).

A user without ROS_DOMAIN_ID gets a ROS domain of their own (``own_domain``): two users of
one host do not see each other's nodes, while every command of one user shares the domain.
"""
from __future__ import annotations

import logging
import os
import signal

log = logging.getLogger("fowt_hydro_sim.startup")

DOMAIN_IDS = 101  # ids 1..101: valid whatever the number of participants on a Linux host


def domain_id_of(uid: int) -> int:
    """The ROS domain id of the user ``uid``: 1..101, distinct for up to 101 consecutive uids."""
    return 1 + uid % DOMAIN_IDS


def own_domain(environ: os._Environ | dict = os.environ) -> None:
    """Without ROS_DOMAIN_ID: discovery on this host only (ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST,
    unless set) in the user's own domain (``domain_id_of`` the user id), said once. An explicit
    ROS_DOMAIN_ID is kept, and nothing is changed. Called before rclpy starts (rcl reads both
    variables when it is initialised)."""
    if environ.get("ROS_DOMAIN_ID", "").strip():
        return
    environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    environ["ROS_DOMAIN_ID"] = str(domain_id_of(os.getuid()))
    log.info(f"ROS_DOMAIN_ID not set: using {environ['ROS_DOMAIN_ID']} (from user id {os.getuid()}), discovery "
             f"range {environ['ROS_AUTOMATIC_DISCOVERY_RANGE']}; set ROS_DOMAIN_ID to choose another")


def init_ros(args: list[str] | None) -> None:
    """rclpy without its signal handlers: SIGINT and SIGTERM stop the node through
    KeyboardInterrupt in the main thread, so the stepping ends before the context does."""
    own_domain()
    import rclpy
    from rclpy.signals import SignalHandlerOptions

    rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)
    # SIGINT too: a shell starting the node in the background (`&`) leaves SIGINT ignored
    for stop in (signal.SIGINT, signal.SIGTERM):
        signal.signal(stop, signal.default_int_handler)


def ignore_stop_signals() -> None:
    """SIGINT and SIGTERM ignored from here on: a node's clean-up after it was stopped (its
    threads joined, its bag closed, each with a timeout) is not cut by a second signal, such
    as the one a terminal's Ctrl-C sends to a whole process group and its parent then
    forwards."""
    for stop in (signal.SIGINT, signal.SIGTERM):
        signal.signal(stop, signal.SIG_IGN)
