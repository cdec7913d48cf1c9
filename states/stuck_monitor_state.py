"""StuckMonitorState: report when the robot makes no progress (neither moves nor turns) for a while."""

from __future__ import annotations

import math
from typing import Optional

from nav_msgs.msg import Odometry
from std_msgs.msg import Bool

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.nav.angles import wrap_angle
from flex_nav_states import validation
from flex_nav_states.messages import OdomSample, message_age_s, odom_sample, sample_is_finite
from flex_nav_states.proxy_types import SubscriptionLike, proxies_of


class StuckMonitorState(State):
    """Returns ``stuck`` when the robot neither moved nor turned enough within a time window.

    Progress is measured on odometry against an anchor pose: once the robot is ``min_distance_m`` away from
    it or has turned ``min_rotation_rad`` from its heading (net, so dithering in place does not count), the
    anchor moves to the current pose. If the anchor is older than ``window_s`` the robot is stuck.
    Paused time restarts the window, and so does time the controller reports waiting on purpose (a fresh
    ``True`` on ``waiting_topic``, e.g. a controller giving way to a person walking across its path).

    -- window_s          float  [s] Longest time without progress (> 0).
    -- min_distance_m    float  [m] Displacement that counts as progress (> 0).
    -- min_rotation_rad  float  [rad] Net rotation that counts as progress (> 0).
    -- odom_topic        str    nav_msgs/Odometry topic.
    -- odom_timeout_s    float  [s] Fail when no fresh odometry for this long.
    -- waiting_topic     str    std_msgs/Bool: True while the robot waits on purpose ("" = none); a message
                                older than odom_timeout_s does not count.

    <= stuck   No progress within window_s.
    <= failed  No fresh odometry within odom_timeout_s (the robot's progress cannot be watched).
    """

    def __init__(
        self,
        window_s: float = 10.0,
        min_distance_m: float = 0.1,
        min_rotation_rad: float = 0.3,
        odom_topic: str = "odom",
        odom_timeout_s: float = 1.0,
        *,
        waiting_topic: str = "",
    ) -> None:
        super().__init__(outcomes=["stuck", "failed"])
        owner = type(self).__name__
        self._window_s = validation.number(owner, "window_s", window_s, positive=True, unit="[s]")
        self._min_distance_m = validation.number(owner, "min_distance_m", min_distance_m, positive=True, unit="[m]")
        self._min_rotation_rad = validation.number(owner, "min_rotation_rad", min_rotation_rad, positive=True,
                                                   unit="[rad]")
        self._odom_topic = validation.name(owner, "odom_topic", odom_topic)
        self._odom_timeout_s = validation.number(owner, "odom_timeout_s", odom_timeout_s, positive=True, unit="[s]")
        self._waiting_topic = validation.name(owner, "waiting_topic", waiting_topic) if waiting_topic else ""
        self._waiting_sub: Optional[SubscriptionLike] = None
        self._sub: Optional[SubscriptionLike] = None
        self._anchor: Optional[OdomSample] = None
        self._anchor_s = 0.0
        self._last_fresh_s = 0.0

    def on_start(self) -> None:
        self._sub = proxies_of(self).subscription(self._odom_topic, Odometry)
        if self._waiting_topic:
            self._waiting_sub = proxies_of(self).subscription(self._waiting_topic, Bool)

    def on_enter(self, userdata: UserDataView) -> None:
        self._anchor = None
        self._last_fresh_s = self.now_s()

    def on_resume(self, userdata: UserDataView) -> None:
        self._anchor = None
        self._last_fresh_s = self.now_s()

    def execute(self, userdata: UserDataView) -> Optional[str]:
        now = self.now_s()
        sample = self._fresh_sample(now)
        if sample is None:
            if now - self._last_fresh_s > self._odom_timeout_s:
                self.log_error(f"no fresh odometry on {self._odom_topic} for {self._odom_timeout_s:g} s")
                return "failed"
            return None
        self._last_fresh_s = now
        anchor = self._anchor
        if anchor is None:
            self._anchor, self._anchor_s = sample, now
            return None
        moved = math.hypot(sample.x - anchor.x, sample.y - anchor.y)
        turned = abs(wrap_angle(sample.yaw - anchor.yaw))
        if moved >= self._min_distance_m or turned >= self._min_rotation_rad or self._waiting(now):
            self._anchor, self._anchor_s = sample, now
            return None
        if now - self._anchor_s > self._window_s:
            self.log_warn(
                f"robot stuck: moved {moved:.3f} m and turned {math.degrees(turned):.1f} deg in {self._window_s:g} s "
                f"(needs {self._min_distance_m:g} m or {math.degrees(self._min_rotation_rad):.1f} deg)"
            )
            return "stuck"
        return None

    def _waiting(self, now: float) -> bool:
        """True while a fresh message on ``waiting_topic`` says the robot waits on purpose."""
        sub = self._waiting_sub
        if sub is None:
            return False
        msg = sub.last()
        return msg is not None and bool(msg.data) and message_age_s(msg, sub, now) <= self._odom_timeout_s

    def _fresh_sample(self, now: float) -> Optional[OdomSample]:
        sub = self._sub
        if sub is None:
            sub = self._sub = proxies_of(self).subscription(self._odom_topic, Odometry)
        msg = sub.last()
        if msg is None or message_age_s(msg, sub, now) > self._odom_timeout_s:
            return None
        sample = odom_sample(msg)
        return sample if sample_is_finite(sample) else None
