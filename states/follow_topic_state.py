"""FollowTopicState: a FollowTopic server (a controller) follows the newest path on a topic."""

from __future__ import annotations

from typing import Any

from std_msgs.msg import String

from flex_nav.action_types import action_type
from flex_nav.behavior.userdata import UserDataView
from flex_nav.msg import FollowTopicGoal
from flex_nav_states import validation
from flex_nav_states.action_base import ActionClientBase

FOLLOW_TOPIC = action_type("FollowTopic")


class FollowTopicState(ActionClientBase):
    """Asks a FollowTopic server (e.g. pure_pursuit_topic) to follow the paths published on a topic.

    Typically runs beside FollowPlannerState in a concurrency container: the mid-level planner publishes
    its local plan on ``path_topic`` and the controller drives along the newest one.

    -- path_topic        str    nav_msgs/Path topic the server follows (e.g. follow_path_server/plan).
    -- action_name       str    FollowTopic server name, relative to the behavior's namespace.
    -- server_timeout_s  float  [s] Fail if the server is not connected this long after entry.
    -- timeout_s         float  [s] Cancel and fail if no result this long after sending (0: no limit).

    <= done       The server reached the end of the path (code SUCCESS).
    <= failed     The server failed (no path on the topic, blocked, stale sensors), is missing, or timed out.
    <= preempted  The server stopped the goal for someone else.
    """

    def __init__(self, path_topic: str = "follow_path_server/plan", action_name: str = "pure_pursuit_topic",
                 server_timeout_s: float = 5.0, timeout_s: float = 0.0) -> None:
        super().__init__(
            spec=FOLLOW_TOPIC,
            action_name=action_name,
            server_timeout_s=server_timeout_s,
            timeout_s=timeout_s,
            outcomes=["done", "failed", "preempted"],
            success="done",
            failure="failed",
            cancelled="preempted",
            code_outcomes={"FAILURE": "failed", "PREEMPT": "preempted"},
        )
        self._path_topic = validation.name(type(self).__name__, "path_topic", path_topic)

    def make_goal(self, userdata: UserDataView) -> Any:
        return FollowTopicGoal(topic=String(data=self._path_topic))

    def describe_goal(self, goal: Any) -> str:
        return f"follow the paths on {self._path_topic}"
