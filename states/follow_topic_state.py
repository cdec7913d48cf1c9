"""FollowTopicState: a FollowTopic server (a controller) follows the newest path on a topic."""

from __future__ import annotations

from typing import Any, Optional

import genpy
from nav_msgs.msg import Path
from std_msgs.msg import String

from flex_nav.action_types import action_type
from flex_nav.behavior.userdata import UserDataView
from flex_nav.msg import FollowTopicGoal
from flex_nav_states import validation
from flex_nav_states.action_base import ActionClientBase, ActionServer
from flex_nav_states.follow_path_state import FOLLOW_OUTCOMES
from flex_nav_states.messages import stamp_s
from flex_nav_states.proxy_types import SubscriptionLike, proxies_of

FOLLOW_TOPIC = action_type("FollowTopic")


class FollowTopicState(ActionClientBase):
    """Asks a FollowTopic server (e.g. pure_pursuit_topic) to follow the paths published on a topic.

    Typically runs beside FollowPlannerState in a concurrency container: the mid-level planner publishes
    its local plan on ``path_topic`` and the controller drives along the newest one.

    -- path_topic        str    nav_msgs/Path topic the server follows (e.g. follow_path_server/plan).
    -- action_name       str    FollowTopic server name, relative to the behavior's namespace.
    -- server_timeout_s  float  [s] Fail if the server is not connected this long after entry.
    -- timeout_s         float  [s] Cancel and fail if no result this long after sending (0: no limit).
    -- fresh_path_s      float  [s] > 0: send the goal only once path_topic carries a Path stamped after entry,
                                and fail after this long without one, so that a latched plan for the previous
                                goal is never followed (the goal's newer_than is the entry time: the server
                                takes that Path at once); 0: send at once (the server takes a Path older than
                                the goal when no newer one comes within a second: a one-shot publisher).
    -- follow_next_path  bool   True: at the end of a path, wait for a Path stamped after it and follow that
                                one (at most fresh_path_s, when > 0), never done: for a controller beside a
                                planner that decides arrival (a local plan that stops short of the goal, e.g.
                                before a person standing on it, must not leave the controller idle).
    -- final_heading     bool   True: at a path's end the server turns the robot to the last pose's yaw (within
                                its yaw_goal_tolerance); False: reaching the position is enough.

    <= done       The server reached the end of the path (code SUCCESS; not with follow_next_path).
    <= failed     The server failed (no path on the topic, blocked, stale sensors), is missing, or timed out;
                  or no fresh path came within fresh_path_s.
    <= preempted  The server stopped the goal for someone else.
    """

    def __init__(self, path_topic: str = "follow_path_server/plan", action_name: str = "pure_pursuit_topic",
                 server_timeout_s: float = 5.0, timeout_s: float = 0.0, *, fresh_path_s: float = 0.0,
                 follow_next_path: bool = False, final_heading: bool = True) -> None:
        super().__init__(
            ActionServer(type(self).__name__, FOLLOW_TOPIC, action_name, server_timeout_s, timeout_s),
            outcomes=["done", "failed", "preempted"],
            results=FOLLOW_OUTCOMES,
        )
        owner = type(self).__name__
        self._path_topic = validation.name(owner, "path_topic", path_topic)
        self._fresh_path_s = validation.number(owner, "fresh_path_s", fresh_path_s, minimum=0.0, unit="[s]")
        self._follow_next_path = bool(follow_next_path)
        self._final_heading = validation.boolean(owner, "final_heading", final_heading)
        self._paths: Optional[SubscriptionLike] = None
        self._entered_s = 0.0
        self._path_is_fresh = True

    def on_start(self) -> None:
        super().on_start()
        if self._fresh_path_s > 0.0 or self._follow_next_path:
            self._paths = proxies_of(self).subscription(self._path_topic, Path)

    def on_enter(self, userdata: UserDataView) -> None:
        super().on_enter(userdata)
        self._entered_s = self.now_s()
        self._path_is_fresh = self._fresh_path_s == 0.0

    def execute(self, userdata: UserDataView) -> Optional[str]:
        if not self._path_is_fresh:
            if self._paths is None:
                self._paths = proxies_of(self).subscription(self._path_topic, Path)
            newest = self._paths.last()
            if newest is not None and stamp_s(newest) >= self._entered_s:
                self._path_is_fresh = True
                self._wait_start_s = self.now_s()  # server_timeout_s counts from here, not from entry
            elif self._fresh_path_s > 0.0 and self.now_s() - self._entered_s >= self._fresh_path_s:
                self.log_error(f"{self.action_name}: no path on {self._path_topic} newer than this goal within "
                               f"fresh_path_s {self._fresh_path_s:g} s; not following an older one")
                return "failed"
            else:
                return None
        outcome = super().execute(userdata)
        if outcome == "done" and self._follow_next_path:
            self.log_info(f"{self.action_name}: end of the path on {self._path_topic}; following the next one")
            self.on_enter(userdata)  # a new goal once a newer Path comes
            self._path_is_fresh = False
            return None
        return outcome

    def make_goal(self, userdata: UserDataView) -> Any:
        goal = FollowTopicGoal(topic=String(data=self._path_topic), ignore_final_heading=not self._final_heading)
        if self._fresh_path_s > 0.0 or self._follow_next_path:
            # Paths count from entry (or the re-arm): where the state first waits for one stamped since, the server
            # takes it at once instead of waiting up to 1 s for one newer than the goal; where it sends at once
            # (follow_next_path's first entry) this is the goal's start, as with 0
            goal.newer_than = genpy.Time.from_sec(self.now_s())
        return goal

    def describe_goal(self, goal: Any) -> str:
        return f"follow the paths on {self._path_topic}"
