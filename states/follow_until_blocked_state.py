"""FollowUntilBlockedState: FollowPath, with the controller's "blocked" abort as its own outcome."""

from __future__ import annotations

from typing import Any

from actionlib_msgs.msg import GoalStatus

from flex_nav.behavior.userdata import UserDataView, unwrap
from flex_nav.exceptions import ConfigError
from flex_nav.msg import FollowPathGoal
from flex_nav_states.action_base import ActionClientBase
from flex_nav_states.follow_path_state import FOLLOW_PATH
from flex_nav_states.messages import describe

BLOCKED_PREFIX = "blocked"  # reason prefix of flex_nav.follow.blocked's abort


class FollowUntilBlockedState(ActionClientBase):
    """Sends the plan to a FollowPath controller and waits; a path blocked by an obstacle is ``blocked``.

    The controller must run blocked-path detection (``pure_pursuit_path`` with ``~blocked_distance`` > 0):
    it aborts with a reason starting ``blocked`` when an obstacle sits on the path within that distance.

    -- action_name       str    FollowPath server name, relative to the behavior's namespace.
    -- server_timeout_s  float  [s] Fail if the server is not connected this long after entry.
    -- timeout_s         float  [s] Cancel and fail if no result this long after sending (0: no limit).

    ># plan  Path  The path to follow (nav_msgs/Path, at least one pose).

    <= done       The server reached the end of the path.
    <= blocked    The server stopped because an obstacle sits on the path ahead.
    <= failed     Any other failure (lost, bad path, missing server, timeout); the reason is logged.
    <= preempted  The server stopped the goal for someone else.
    """

    def __init__(self, action_name: str = "pure_pursuit_path", server_timeout_s: float = 5.0,
                 timeout_s: float = 0.0) -> None:
        super().__init__(
            spec=FOLLOW_PATH,
            action_name=action_name,
            server_timeout_s=server_timeout_s,
            timeout_s=timeout_s,
            outcomes=["done", "blocked", "failed", "preempted"],
            success="done",
            failure="failed",
            cancelled="preempted",
            code_outcomes={"FAILURE": "failed", "PREEMPT": "preempted"},
            input_keys=["plan"],
        )

    def make_goal(self, userdata: UserDataView) -> Any:
        path = unwrap(userdata.plan)
        if getattr(path, "poses", None) is None or not hasattr(path, "header"):
            raise ConfigError(f"userdata plan must be a nav_msgs/Path, got {type(path).__name__}")
        if len(path.poses) == 0:
            raise ConfigError("userdata plan is empty")
        return FollowPathGoal(path=path)

    def describe_goal(self, goal: Any) -> str:
        return f"follow {describe(goal.path)}"

    def map_result(self, userdata: UserDataView, status: int, result: Any) -> str:
        message = str(getattr(result, "message", "") or "") if result is not None else ""
        if status == GoalStatus.ABORTED and message.startswith(BLOCKED_PREFIX):
            self.log_warn(f"{self.action_name}: {message}")
            return "blocked"
        return super().map_result(userdata, status, result)
