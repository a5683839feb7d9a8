"""The turbine node's state messages: one quantity per topic, stamped, in ``vector.x`` of a
geometry_msgs/Vector3Stamped (y and z zero)."""
from __future__ import annotations

from geometry_msgs.msg import Vector3Stamped

from msg_adapters._common import header


def quantity_msg(time_s: float, value: float, frame_id: str = "hub") -> Vector3Stamped:
    msg = Vector3Stamped(header=header(time_s, frame_id))
    msg.vector.x = float(value)
    return msg
