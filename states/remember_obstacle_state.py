"""RememberObstacleState: an obstacle that could not be pushed, reported to the global costmap's obstacle memory.

The footprint is the object ahead in the newest scan (:func:`flex_nav.perception.lidar_shape.footprint_ahead`:
its hits and the same hits as deep again as it is wide along their beams; the scan's frame is taken as the
robot's, x forward), published as geometry_msgs/PolygonStamped in the scan's frame with the scan's stamp, so the
costmap node places it with the transform of that time. The costmap side (issue 28's obstacle memory layer,
:mod:`flex_nav.nav.costmap.memory_layer`) remembers it as lethal, forgets it after its memory time, when the
lidar sees through it, or on the operator's clear.
"""

from __future__ import annotations

from typing import List, Optional

from geometry_msgs.msg import Point32, PolygonStamped
from sensor_msgs.msg import LaserScan

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.perception.lidar_shape import footprint_ahead
from flex_nav_states import validation
from flex_nav_states.messages import message_age_s
from flex_nav_states.proxy_types import PublisherLike, SubscriptionLike, proxies_of


class RememberObstacleState(State):
    """Logs ``text`` (a warning) and, with ``publish``, publishes the footprint of the object ahead for the
    obstacle memory; finishes at once either way (a missing footprint is logged, never a failure).

    -- text            str    The message logged when entered.
    -- publish         bool   Publish the footprint; false: only log (as a LogState).
    -- topic           str    geometry_msgs/PolygonStamped topic of the global costmap's obstacle memory.
    -- scan_topic      str    sensor_msgs/LaserScan topic (its frame taken as the robot's, x forward).
    -- scan_max_age_s  float  [s] An older scan gives no footprint.
    -- reach_m         float  [m] The object is the one with the nearest hit this far ahead.
    -- half_width_m    float  [m] Half the width of the corridor ahead searched for it.
    -- depth_m         float  [m] Depth given to the object beyond its visible side (0: as deep as it is wide).

    #> obstacle_footprint  list  [[x, y], ...] [m] in the scan's frame; [] when nothing was published.

    <= done  Logged, and the footprint published if one was found.
    """

    def __init__(
        self,
        text: str = "obstacle cannot be pushed: planning around it",
        publish: bool = True,
        topic: str = "obstacle_memory/mark",
        scan_topic: str = "scan",
        *,
        scan_max_age_s: float = 0.5,
        reach_m: float = 1.5,
        half_width_m: float = 0.3,
        depth_m: float = 0.0,
    ) -> None:
        super().__init__(outcomes=["done"], output_keys=["obstacle_footprint"])
        owner = type(self).__name__
        self._text = validation.text(owner, "text", text)
        self._publish = validation.boolean(owner, "publish", publish)
        self._topic = validation.name(owner, "topic", topic)
        self._scan_topic = validation.name(owner, "scan_topic", scan_topic)
        self._scan_max_age_s = validation.number(owner, "scan_max_age_s", scan_max_age_s, positive=True, unit="[s]")
        self._reach_m = validation.number(owner, "reach_m", reach_m, positive=True, unit="[m]")
        self._half_width_m = validation.number(owner, "half_width_m", half_width_m, positive=True, unit="[m]")
        self._depth_m = validation.number(owner, "depth_m", depth_m, minimum=0.0, unit="[m]")
        self._scan: Optional[SubscriptionLike] = None
        self._pub: Optional[PublisherLike] = None

    def on_start(self) -> None:
        if self._publish:
            self._scan = proxies_of(self).subscription(self._scan_topic, LaserScan)
            self._pub = proxies_of(self).publisher(self._topic, PolygonStamped)

    def on_enter(self, userdata: UserDataView) -> None:
        self.log_warn(self._text)
        userdata.obstacle_footprint = self._report() if self._publish else []

    def execute(self, userdata: UserDataView) -> Optional[str]:
        return "done"

    def _report(self) -> List[List[float]]:
        if self._scan is None or self._pub is None:
            self.on_start()
        assert self._scan is not None and self._pub is not None
        scan = self._scan.last()
        if scan is None or message_age_s(scan, self._scan, self.now_s()) > self._scan_max_age_s:
            self.log_warn(f"obstacle not remembered: no scan on {self._scan_topic} newer than "
                          f"{self._scan_max_age_s:g} s")
            return []
        footprint = footprint_ahead(scan.ranges, scan.angle_min, scan.angle_increment, scan.range_min,
                                    scan.range_max, reach_m=self._reach_m, half_width_m=self._half_width_m,
                                    depth_m=self._depth_m)
        if footprint is None:
            self.log_warn(f"obstacle not remembered: nothing within {self._reach_m:g} m ahead on {self._scan_topic}")
            return []
        msg = PolygonStamped()
        msg.header.stamp = scan.header.stamp
        msg.header.frame_id = scan.header.frame_id
        msg.polygon.points = [Point32(x=float(x), y=float(y), z=0.0) for x, y in footprint]
        self._pub.publish(msg)
        span = footprint.max(axis=0) - footprint.min(axis=0)
        self.log_info(f"obstacle remembered: {len(footprint)} corners, {span[0]:.2f} x {span[1]:.2f} m, "
                      f"on {self._topic}")
        return [[float(x), float(y)] for x, y in footprint]
