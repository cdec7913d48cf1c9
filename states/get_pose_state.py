"""GetPoseState: waits for a goal pose on a geometry_msgs/PoseStamped topic (e.g. RViz's 2D Nav Goal)."""

from __future__ import annotations

from typing import Any, List, Optional

from geometry_msgs.msg import PoseStamped

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.nav.pose_checks import pose_problem
from flex_nav_states import validation
from flex_nav_states.messages import FUTURE_STAMP_TOLERANCE_S, describe, message_age_s, stamp_s
from flex_nav_states.proxy_types import SubscriptionLike, proxies_of

BUFFER_SIZE = 10  # goals kept between two ticks (more than anyone clicks in 0.1 s)


class GetPoseState(State):
    """Waits for a goal pose on a topic and writes it to userdata; stale and malformed messages are dropped.

    A message counts only if it is fresh when the state looks at it: a stamped message must be at most
    ``max_age_s`` old (so a goal left over from an earlier run or latched long ago is ignored) and at most
    ``max_age_s`` ahead of the behavior's clock (dropped with the offset: a sender's clock far ahead, or a goal of
    the timeline before a restarted simulation; one ahead by less is taken with a warning naming the offset); an
    unstamped message (stamp 0) must have arrived after the state was entered. Messages with an empty
    frame_id, non-finite values or an unnormalised orientation are dropped with a warning. Goals are taken
    in arrival order (a goal that came while the state was inactive and is still fresh is used first).

    -- topic      str    geometry_msgs/PoseStamped topic, relative to the behavior's namespace.
    -- max_age_s  float  [s] Largest accepted age of a stamped message (> 0).
    -- timeout_s  float  [s] Give up this long after entry (0: wait until a goal arrives or the state is left).

    #> goal  PoseStamped  The received goal.

    <= received  A fresh, valid goal was written to userdata.
    <= timeout   No valid goal within timeout_s.
    """

    def __init__(self, topic: str = "move_base_simple/goal", max_age_s: float = 1.0, timeout_s: float = 0.0) -> None:
        super().__init__(outcomes=["received", "timeout"], output_keys=["goal"])
        owner = type(self).__name__
        self._topic = validation.name(owner, "topic", topic)
        self._max_age_s = validation.number(owner, "max_age_s", max_age_s, positive=True, unit="[s]")
        self._timeout_s = validation.number(owner, "timeout_s", timeout_s, minimum=0.0, unit="[s]")
        self._sub: Optional[SubscriptionLike] = None
        self._enter_s = 0.0
        self._backlog: List[Any] = []  # stamped messages from before entry, still to be judged

    def on_start(self) -> None:
        self._subscription()

    def on_enter(self, userdata: UserDataView) -> None:
        self._enter_s = self.now_s()
        sub = self._subscription()
        # Messages from before entry: stamped ones are judged by age in execute; unstamped ones cannot be dated.
        kept: List[Any] = []
        while True:
            msg = sub.pop_buffered()
            if msg is None:
                break
            if stamp_s(msg) > 0.0:
                kept.append(msg)
            else:
                self.log_warn(f"dropped an unstamped goal on {self._topic} that arrived before this state was entered")
        self._backlog = kept

    def execute(self, userdata: UserDataView) -> Optional[str]:
        sub = self._subscription()
        now = self.now_s()
        while self._backlog or sub.has_buffered():
            msg = self._backlog.pop(0) if self._backlog else sub.pop_buffered()
            if msg is not None and self._accept(msg, sub, now):
                userdata.goal = msg
                self.log_info(f"goal received on {self._topic}: {describe(msg)}")
                return "received"
        if self._timeout_s > 0.0 and now - self._enter_s >= self._timeout_s:
            self.log_warn(f"no goal on {self._topic} within {self._timeout_s:g} s")
            return "timeout"
        return None

    def _accept(self, msg: Any, sub: SubscriptionLike, now: float) -> bool:
        ahead_s = stamp_s(msg) - now
        if stamp_s(msg) > 0.0 and ahead_s > self._max_age_s:
            self.log_warn(f"dropped a goal on {self._topic} stamped {ahead_s:.2f} s ahead of the behavior's clock "
                          f"(more than max_age_s {self._max_age_s:g} s: the sender's clock is ahead, or the goal is "
                          "from before a restarted simulation)")
            return False
        if stamp_s(msg) > 0.0 and ahead_s > FUTURE_STAMP_TOLERANCE_S:
            self.log_warn(f"goal on {self._topic} stamped {ahead_s:.2f} s ahead of the behavior's clock: are the "
                          "clocks of the two computers synchronised? (its age is taken from its arrival)")
        if stamp_s(msg) > 0.0:
            age = message_age_s(msg, sub, now)
            if abs(age) > self._max_age_s:
                self.log_warn(
                    f"dropped a stale goal on {self._topic}: {age:.2f} s old (max_age_s {self._max_age_s:g} s)"
                )
                return False
        if not msg.header.frame_id:
            self.log_warn(f"dropped a goal on {self._topic} without frame_id: {describe(msg)}")
            return False
        p, q = msg.pose.position, msg.pose.orientation
        problem = pose_problem((p.x, p.y, p.z), (q.x, q.y, q.z, q.w))
        if problem is not None:
            self.log_warn(f"dropped a goal on {self._topic}: {problem}")
            return False
        return True

    def _subscription(self) -> SubscriptionLike:
        if self._sub is None:
            self._sub = proxies_of(self).subscription(self._topic, PoseStamped, buffer_size=BUFFER_SIZE)
        return self._sub
