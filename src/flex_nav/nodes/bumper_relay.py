"""``bumper_relay`` node: bumper presses of any robot model -> contact points for the costmaps.

Subscribes one of (``~input``):
  ``state``   ``bumper_state`` (flex_nav/BumperState: every zone by name; the simulator publishes it)
  ``kobuki``  ``events/bumper`` (flex_nav/BumperEvent, kobuki_msgs/BumperEvent layout: bumper 0/1/2, state 0/1)
  ``create``  ``bumper`` (flex_nav/CreateBumper, ca_msgs/Bumper contact fields: is_left_pressed, is_right_pressed)
Publishes ``bumper_hits`` (geometry_msgs/PointStamped in ``~base_frame``) once per new press, at the middle of
the pressed zone just outside the base. Zones come from the robot profile ``~profile`` (sim/robots/NAME.yaml).
"""

from __future__ import annotations

import rospy
from geometry_msgs.msg import PointStamped

from flex_nav.msg import BumperEvent, BumperState, CreateBumper
from flex_nav.nav.costmap.bumper_contacts import BumperContacts
from flex_nav.ros.params import param_str, reject_unknown
from flex_nav_sim.profiles import load_profile

INPUTS = ("state", "kobuki", "create")
KOBUKI_ZONES = {BumperEvent.LEFT: "left", BumperEvent.CENTER: "center", BumperEvent.RIGHT: "right"}


class BumperRelay:
    def __init__(self) -> None:
        reject_unknown("~", ("base_frame", "profile", "input"))
        self.base_frame = param_str("~base_frame", "base_footprint")
        self.contacts = BumperContacts(load_profile(param_str("~profile", "kobuki")))
        source = param_str("~input", "state", INPUTS)
        self.publisher = rospy.Publisher("bumper_hits", PointStamped, queue_size=10)
        if source == "state":
            self.subscriber = rospy.Subscriber("bumper_state", BumperState, self._on_state, queue_size=10)
        elif source == "kobuki":
            self.subscriber = rospy.Subscriber("events/bumper", BumperEvent, self._on_kobuki, queue_size=10)
        else:
            self.subscriber = rospy.Subscriber("bumper", CreateBumper, self._on_create, queue_size=10)

    def _on_state(self, msg: BumperState) -> None:
        self._publish(self.contacts.update_lists(list(msg.zones), list(msg.pressed)), msg.header.stamp)

    def _on_kobuki(self, msg: BumperEvent) -> None:
        zone = KOBUKI_ZONES.get(msg.bumper)
        if zone is None:
            rospy.logwarn_throttle(5.0, f"bumper_relay: unknown kobuki bumper {msg.bumper}")
            return
        self._publish(self.contacts.update({zone: msg.state == BumperEvent.PRESSED}), rospy.Time(0))

    def _on_create(self, msg: CreateBumper) -> None:
        self._publish(self.contacts.update({"left": msg.is_left_pressed, "right": msg.is_right_pressed}),
                      msg.header.stamp)

    def _publish(self, touched: list[tuple[str, float, float]], stamp: rospy.Time) -> None:
        for zone, x, y in touched:
            point = PointStamped()
            point.header.frame_id = self.base_frame
            point.header.stamp = stamp
            point.point.x, point.point.y = x, y
            self.publisher.publish(point)
            rospy.loginfo(f"bumper_relay: {zone} bumper pressed; contact at ({x:.2f}, {y:.2f}) in {self.base_frame}")
