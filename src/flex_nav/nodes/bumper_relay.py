"""``bumper_relay`` node: bumper presses of any robot model -> contact points for the costmaps.

Subscribes one of (``~input``):
  ``state``   ``bumper_state`` (flex_nav/BumperState: every zone by name; the simulator publishes it)
  ``kobuki``  ``events/bumper`` (flex_nav/BumperEvent, kobuki_msgs/BumperEvent layout: bumper 0/1/2, state 0/1)
  ``create``  ``bumper`` (flex_nav/CreateBumper, ca_msgs/Bumper contact fields: is_left_pressed, is_right_pressed)
Publishes ``bumper_hits`` (geometry_msgs/PointStamped in ``~base_frame``) once per new press, at the middle of
the pressed zone just outside the base. Zones come from the robot profile ``~profile`` (sim/robots/NAME.yaml).
In a lockstep simulation (``/lockstep``) with the ``state`` input the relay holds the simulation at each
``bumper_state`` message until its contact points are out (the costmaps mark them before it steps on).
"""

from __future__ import annotations

import threading

import rospy
from geometry_msgs.msg import PointStamped

from flex_nav.msg import BumperEvent, BumperState, CreateBumper
from flex_nav.nav.costmap.bumper_contacts import BumperContacts
from flex_nav.ros.latest_worker import NEXT_STAMP_S
from flex_nav.ros.lockstep import LockstepParticipant
from flex_nav.ros.params import param_str, reject_unknown
from flex_nav_sim.profiles import load_profile

INPUTS = ("state", "kobuki", "create")
KOBUKI_ZONES = {BumperEvent.LEFT: "left", BumperEvent.CENTER: "center", BumperEvent.RIGHT: "right"}
FIRST_HOLD_WAIT_S = 60.0  # [s] wall: longest wait for the simulator to listen before the first hold is sent


class BumperRelay:
    def __init__(self) -> None:
        reject_unknown("~", ("base_frame", "profile", "input"))
        self.base_frame = param_str("~base_frame", "base_footprint")
        self.contacts = BumperContacts(load_profile(param_str("~profile", "kobuki")))
        source = param_str("~input", "state", INPUTS)
        self.publisher = rospy.Publisher("bumper_hits", PointStamped, queue_size=10)
        # lockstep: bumper_state is the simulator's own, stamped; the other inputs are real drivers' messages
        lockstep = LockstepParticipant("bumper") if source == "state" else None
        self._lockstep = lockstep if lockstep is not None and lockstep.enabled else None
        self._hold_lock = threading.Lock()
        self._next_s = 0.0  # [s] the stamp of the next bumper_state the simulation is held at
        if source == "state":
            self.subscriber = rospy.Subscriber("bumper_state", BumperState, self._on_state, queue_size=10)
            if self._lockstep is not None:  # the first press is held for too, once the simulator listens
                threading.Thread(target=self._first_hold, name="bumper_relay first hold", daemon=True).start()
        elif source == "kobuki":
            self.subscriber = rospy.Subscriber("events/bumper", BumperEvent, self._on_kobuki, queue_size=10)
        else:
            self.subscriber = rospy.Subscriber("bumper", CreateBumper, self._on_create, queue_size=10)

    def _first_hold(self) -> None:
        if self._lockstep is not None and self._lockstep.wait_connected(FIRST_HOLD_WAIT_S):
            self._hold_next(0.0)

    def _hold_next(self, after_s: float) -> None:
        """Hold the simulation at the first bumper_state stamped ``after_s`` [s] or later (never an earlier one)."""
        assert self._lockstep is not None
        with self._hold_lock:
            self._next_s = max(self._next_s, after_s)
            self._lockstep.hold_topic(self.subscriber.resolved_name, self._next_s)

    def _on_state(self, msg: BumperState) -> None:
        try:
            self._publish(self.contacts.update_lists(list(msg.zones), list(msg.pressed)), msg.header.stamp)
        finally:
            if self._lockstep is not None:
                self._hold_next(msg.header.stamp.to_sec() + NEXT_STAMP_S)

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
