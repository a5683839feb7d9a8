"""Wrenches [Fx, Fy, Fz, Mx, My, Mz] to and from geometry_msgs/WrenchStamped."""
from __future__ import annotations

import numpy as np
from geometry_msgs.msg import WrenchStamped

from msg_adapters._common import components, header, vector, vector3
from msg_adapters.stamps import seconds


def wrench_msg(time_s: float, wrench, frame_id: str = "world") -> WrenchStamped:
    """WrenchStamped of a wrench [F, M], axes as given."""
    wrench = vector(wrench, 6, "wrench")
    msg = WrenchStamped(header=header(time_s, frame_id))
    msg.wrench.force, msg.wrench.torque = vector3(wrench[:3]), vector3(wrench[3:])
    return msg


def wrench_from_msg(msg: WrenchStamped) -> tuple[float, np.ndarray, str]:
    """(time, wrench, frame_id) of a WrenchStamped."""
    return seconds(msg.header.stamp), components(msg.wrench.force, msg.wrench.torque), msg.header.frame_id
