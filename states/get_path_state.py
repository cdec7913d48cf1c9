"""GetPathState: asks a GetPath server (the global planner) for a plan to the goal in userdata."""

from __future__ import annotations

from typing import Any

from flex_nav.action_types import action_type
from flex_nav.behavior.userdata import UserDataView, unwrap
from flex_nav.exceptions import ConfigError
from flex_nav.msg import GetPathGoal
from flex_nav_states.action_base import ActionClientBase, ActionServer, GoalOutcomes
from flex_nav_states.messages import describe

GET_PATH = action_type("GetPath")
GET_PATH_OUTCOMES = GoalOutcomes(
    success="planned", failure="failed", code_outcomes={"EMPTY": "empty", "FAILURE": "failed"}
)


class GetPathState(ActionClientBase):
    """Plans a global path from the robot to the goal with a GetPath server; the plan goes to userdata.

    -- action_name       str    GetPath server name, relative to the behavior's namespace.
    -- server_timeout_s  float  [s] Fail if the server is not connected this long after entry.
    -- timeout_s         float  [s] Cancel and fail if no result this long after sending (0: no limit).

    ># goal  PoseStamped  The goal pose (with its frame).
    #> plan  Path         The plan (nav_msgs/Path) when planned; unchanged otherwise.

    <= planned  The server returned a plan (code SUCCESS).
    <= empty    The planner found no path (code EMPTY): unreachable or blocked goal.
    <= failed   Bad request, server error or missing, timeout, or the goal was cancelled; the reason is logged.
    """

    def __init__(self, action_name: str = "get_path_server", server_timeout_s: float = 5.0,
                 timeout_s: float = 30.0) -> None:
        super().__init__(
            ActionServer(type(self).__name__, GET_PATH, action_name, server_timeout_s, timeout_s),
            outcomes=["planned", "empty", "failed"],
            results=GET_PATH_OUTCOMES,
            input_keys=["goal"],
            output_keys=["plan"],
        )

    def make_goal(self, userdata: UserDataView) -> Any:
        pose = unwrap(userdata.goal)
        if not hasattr(pose, "pose") or not hasattr(pose, "header"):
            raise ConfigError(f"userdata goal must be a geometry_msgs/PoseStamped, got {type(pose).__name__}")
        return GetPathGoal(pose=pose)

    def describe_goal(self, goal: Any) -> str:
        return f"plan to {describe(goal.pose)}"

    def on_success(self, userdata: UserDataView, result: Any) -> str:
        if len(result.plan.poses) == 0:  # a server bug, but never hand an empty plan to a follower
            self.log_error(f"{self.action_name}: SUCCESS with an empty plan; treated as empty")
            return "empty"
        userdata.plan = result.plan
        self.log_info(f"{self.action_name}: {describe(result.plan)}")
        return "planned"
