"""GoalListState: hand out the goals of a fixed list one by one (the paper's intermediate goals, in a loop)."""

from __future__ import annotations

import math
from typing import Any, List, Optional, Sequence, Tuple

from geometry_msgs.msg import PoseStamped

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import ConfigError
from flex_nav.nav.pose_checks import quaternion_of_yaw
from flex_nav_states import validation
from flex_nav_states.messages import describe, to_stamp


class GoalListState(State):
    """Writes the next goal of a fixed list to userdata each time it is entered; after the last, starts over.

    Goals are stamped with the behavior's clock when handed out. The position in the list belongs to this
    state in this run of the behavior (it starts at the first goal whenever the behavior starts).

    -- goals     list  Goals as [x, y, yaw_deg]: [m], [m], [deg] in frame_id (at least one).
    -- frame_id  str   Frame of the goals (e.g. map).
    -- loops     int   How many times to go through the list (0: forever).

    #> goal        PoseStamped  The next goal.
    #> goal_index  int          Number of this goal in the run, from 1.

    <= next  A goal was written.
    <= done  The list was gone through loops times; no goal was written.
    """

    def __init__(self, goals: Sequence[Sequence[float]] = ((1.0, 0.0, 0.0),), frame_id: str = "map",
                 loops: int = 1) -> None:
        super().__init__(outcomes=["next", "done"], output_keys=["goal", "goal_index"])
        owner = type(self).__name__
        # goals come from YAML, not from type-checked code: a string is a sequence mypy cannot rule out here
        if isinstance(goals, str) or not isinstance(goals, (list, tuple)) or not goals:  # type: ignore[unreachable]
            raise ConfigError(f"{owner}: goals must be a non-empty list of [x, y, yaw_deg], got {goals!r}")
        self._goals: List[Tuple[float, float, float]] = []
        for index, goal in enumerate(goals):
            if isinstance(goal, str) or not isinstance(goal, (list, tuple)) or len(goal) != 3:
                raise ConfigError(f"{owner}: goals[{index}] must be [x, y, yaw_deg], got {goal!r}")
            x, y, yaw_deg = (validation.number(owner, f"goals[{index}][{i}]", v) for i, v in enumerate(goal))
            self._goals.append((x, y, math.radians(yaw_deg)))
        self._frame_id = validation.name(owner, "frame_id", frame_id)
        if isinstance(loops, bool) or not isinstance(loops, int) or loops < 0:
            raise ConfigError(f"{owner}: loops must be an integer >= 0 (0: forever), got {loops!r}")
        self._loops = loops
        self._handed_out = 0

    def on_start(self) -> None:
        self._handed_out = 0

    def execute(self, userdata: UserDataView) -> Optional[str]:
        if self._loops and self._handed_out >= self._loops * len(self._goals):
            self.log_info(f"all {self._handed_out} goals handed out")
            return "done"
        x, y, yaw = self._goals[self._handed_out % len(self._goals)]
        self._handed_out += 1
        goal = self._pose(x, y, yaw)
        userdata.goal = goal
        userdata.goal_index = self._handed_out
        total = f"/{self._loops * len(self._goals)}" if self._loops else ""
        self.log_info(f"goal {self._handed_out}{total}: {describe(goal)}")
        return "next"

    def _pose(self, x: float, y: float, yaw: float) -> Any:
        msg = PoseStamped()
        msg.header.stamp = to_stamp(self.now_s())
        msg.header.frame_id = self._frame_id
        msg.pose.position.x, msg.pose.position.y = x, y
        q = msg.pose.orientation
        q.x, q.y, q.z, q.w = quaternion_of_yaw(yaw)
        return msg
