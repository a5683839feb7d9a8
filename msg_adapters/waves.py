"""Wave elevation samples to and from geometry_msgs/PointStamped (x, y where measured; z elevation)."""
from __future__ import annotations

from geometry_msgs.msg import Point, PointStamped

from msg_adapters._common import header
from msg_adapters.stamps import seconds


def elevation_msg(time_s: float, x_m: float, y_m: float, elevation_m: float,
                  frame_id: str = "world") -> PointStamped:
    """PointStamped of the elevation `elevation_m` measured at (x_m, y_m)."""
    return PointStamped(header=header(time_s, frame_id),
                        point=Point(x=float(x_m), y=float(y_m), z=float(elevation_m)))


def elevation_from_msg(msg: PointStamped) -> tuple[float, float, float, float, str]:
    """(time, x, y, elevation, frame_id) of a PointStamped."""
    p = msg.point
    return seconds(msg.header.stamp), p.x, p.y, p.z, msg.header.frame_id
