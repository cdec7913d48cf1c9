"""FollowUntilBlockedState: FollowPathState, with the controller's "blocked" abort as its own outcome."""

from __future__ import annotations

from typing import Any

from actionlib_msgs.msg import GoalStatus

from flex_nav.behavior.userdata import UserDataView
from flex_nav_states.follow_path_state import FollowPathState

BLOCKED_PREFIX = "blocked"  # reason prefix of flex_nav.nav.control.blocked's abort


class FollowUntilBlockedState(FollowPathState):
    """Sends the plan to a FollowPath controller and waits; a path blocked by an obstacle is ``blocked``.

    The controller must run blocked-path detection (``pure_pursuit_path`` with ``~blocked_distance`` > 0):
    it aborts with a reason starting ``blocked`` when an obstacle sits on the path within that distance.

    -- action_name       str    FollowPath server name, relative to the behavior's namespace.
    -- server_timeout_s  float  [s] Fail if the server is not connected this long after entry.
    -- timeout_s         float  [s] Cancel and fail if no result this long after sending (0: no limit).
    -- final_heading     bool   True: the path's last yaw is the goal heading; False: the position is enough.

    ># plan  Path  The path to follow (nav_msgs/Path, at least one pose).

    <= done       The server reached the end of the path.
    <= blocked    The server stopped because an obstacle sits on the path ahead.
    <= failed     Any other failure (lost, bad path, missing server, timeout); the reason is logged.
    <= preempted  The server stopped the goal for someone else.
    """

    OUTCOMES = ("done", "blocked", "failed", "preempted")

    def map_result(self, userdata: UserDataView, status: int, result: Any) -> str:
        message = str(getattr(result, "message", "") or "") if result is not None else ""
        if status == GoalStatus.ABORTED and message.startswith(BLOCKED_PREFIX):
            self.log_warn(f"{self.action_name}: {message}")
            return "blocked"
        return super().map_result(userdata, status, result)
