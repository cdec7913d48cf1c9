"""FollowPathState and FollowPlannerState: send the plan in userdata to a FollowPath server and wait."""

from __future__ import annotations

from typing import Any, Tuple

from flex_nav.action_types import action_type
from flex_nav.behavior.userdata import UserDataView, unwrap
from flex_nav.exceptions import ConfigError
from flex_nav.msg import FollowPathGoal
from flex_nav_states import validation
from flex_nav_states.action_base import ActionClientBase, ActionServer, GoalOutcomes
from flex_nav_states.messages import describe

FOLLOW_PATH = action_type("FollowPath")
FOLLOW_OUTCOMES = GoalOutcomes(  # of the states that have a server follow a path (FollowPath, FollowTopic)
    success="done", failure="failed", code_outcomes={"FAILURE": "failed", "PREEMPT": "preempted"}, cancelled="preempted"
)


class FollowPathState(ActionClientBase):
    """Sends the plan to a FollowPath server (a path-following controller, e.g. pure_pursuit_path) and waits.

    -- action_name       str    FollowPath server name, relative to the behavior's namespace.
    -- server_timeout_s  float  [s] Fail if the server is not connected this long after entry.
    -- timeout_s         float  [s] Cancel and fail if no result this long after sending (0: no limit).
    -- final_heading     bool   True: the path's last yaw is the goal heading (the server turns the robot to it,
                                within its yaw_goal_tolerance); False: reaching the position is enough.

    ># plan  Path  The path to follow (nav_msgs/Path, at least one pose).

    <= done       The server reached the end of the path (code SUCCESS).
    <= failed     The server failed (blocked, lost, bad path), is missing, or timed out; the reason is logged.
    <= preempted  The server stopped the goal for someone else (code PREEMPT or cancelled by another client).
    """

    OUTCOMES: Tuple[str, ...] = ("done", "failed", "preempted")  # subclasses may add their own

    def __init__(self, action_name: str = "pure_pursuit_path", server_timeout_s: float = 5.0,
                 timeout_s: float = 0.0, *, final_heading: bool = True) -> None:
        super().__init__(
            ActionServer(type(self).__name__, FOLLOW_PATH, action_name, server_timeout_s, timeout_s),
            outcomes=list(self.OUTCOMES),
            results=FOLLOW_OUTCOMES,
            input_keys=["plan"],
        )
        self._final_heading = validation.boolean(type(self).__name__, "final_heading", final_heading)

    def make_goal(self, userdata: UserDataView) -> Any:
        path = unwrap(userdata.plan)
        poses = getattr(path, "poses", None)
        if poses is None or not hasattr(path, "header"):
            raise ConfigError(f"userdata plan must be a nav_msgs/Path, got {type(path).__name__}")
        if len(poses) == 0:
            raise ConfigError("userdata plan is empty")
        return FollowPathGoal(path=path, ignore_final_heading=not self._final_heading)

    def describe_goal(self, goal: Any) -> str:
        heading = "" if goal.ignore_final_heading else " to its final heading"
        return f"follow {describe(goal.path)}{heading}"


class FollowPlannerState(FollowPathState):
    """Sends the plan to a mid-level planner (a FollowPath server such as follow_path_server) and waits.

    The mid-level planner replans locally along the plan and publishes the local plan that a controller
    (e.g. FollowTopicState with pure_pursuit_topic) drives along; run the two in one concurrency container.

    -- action_name       str    FollowPath server name of the mid-level planner.
    -- server_timeout_s  float  [s] Fail if the server is not connected this long after entry.
    -- timeout_s         float  [s] Cancel and fail if no result this long after sending (0: no limit).
    -- final_heading     bool   True: done only once the robot faces the plan's last yaw (within the planner's
                                yaw_goal_tolerance); give the controller beside it the same value.

    ># plan  Path  The global plan to follow (nav_msgs/Path, at least one pose).

    <= done       The planner reached the end of the plan (code SUCCESS).
    <= failed     The planner failed (no local plan, bad path), is missing, or timed out; the reason is logged.
    <= preempted  The planner stopped the goal for someone else.
    """

    def __init__(self, action_name: str = "follow_path_server", server_timeout_s: float = 5.0,
                 timeout_s: float = 0.0, *, final_heading: bool = True) -> None:
        super().__init__(action_name=action_name, server_timeout_s=server_timeout_s, timeout_s=timeout_s,
                         final_heading=final_heading)
