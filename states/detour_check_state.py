"""DetourCheckState: after a push, keep the plan through the pushed object when the replan is a long detour.

A push moves a light object by the push's distance; in a passage longer than that (issue 28's h4: a 0.8 m-wide
box in a 1.2 m route 4 m long) it is still in the way, the replan goes round the block, and the robot that pushed
arrives later than one that never tried. The same holds when a push was stopped (a camera frame taken for a
person) and the way was then reported clear. When the replan (``new_plan``, from where the robot stands) is more than
``max_extra_m`` longer than the rest of the plan it replaces (``plan``, through the object), the old plan is kept:
following it meets the object again, which is then classified and pushed on (a person or a heavy object there is
handled as at the first meeting). At most ``max_keeps`` times per goal (counted in userdata ``keeps``, which the
behavior resets with each goal), so an object that moves but never clears the way costs a bounded number of pushes.
"""

from __future__ import annotations

from typing import Any, Optional

import numpy as np
from nav_msgs.msg import Path

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView, unwrap
from flex_nav.nav.path import detour_m
from flex_nav_states import validation


def _points(path: Path) -> np.ndarray:
    """(N, 2) [m]: the path's positions."""
    return np.array([(p.pose.position.x, p.pose.position.y) for p in path.poses], dtype=np.float64).reshape(-1, 2)


class DetourCheckState(State):
    """Takes ``new_plan`` unless it is a detour of more than ``max_extra_m`` against the rest of ``plan``.

    -- max_extra_m  float  [m] A replan longer than the rest of the old plan by more than this is a detour (> 0).
    -- max_keeps    int    The old plan is kept at most this many times per goal (>= 0; 0: never).

    ># plan      Path   The plan followed before (through the pushed object).
    ># new_plan  Path   The replan from where the robot stands.
    ># keeps     float  Old plans kept for this goal so far.
    #> plan      Path   ``new_plan`` (replanned), or unchanged (keep).
    #> keeps     float  One more on keep.

    <= replanned  ``new_plan`` is no such detour, the old plan is missing or empty, or it was kept max_keeps
                  times already: plan = new_plan.
    <= keep       ``new_plan`` is a detour: the old plan is followed again, to push the object on.
    """

    def __init__(self, max_extra_m: float = 3.0, max_keeps: int = 1) -> None:
        super().__init__(outcomes=["replanned", "keep"], input_keys=["plan", "new_plan", "keeps"],
                         output_keys=["plan", "keeps"])
        owner = type(self).__name__
        self._max_extra_m = validation.number(owner, "max_extra_m", max_extra_m, positive=True, unit="[m]")
        self._max_keeps = validation.integer(owner, "max_keeps", max_keeps, minimum=0)

    def execute(self, userdata: UserDataView) -> Optional[str]:
        new_plan: Path = unwrap(userdata.new_plan)
        old_plan: Any = unwrap(userdata.plan)
        keeps = int(userdata.keeps or 0)
        if self._max_keeps == 0 or not isinstance(old_plan, Path) or not old_plan.poses or not new_plan.poses:
            userdata.plan = new_plan
            return "replanned"
        extra_m = detour_m(_points(old_plan), _points(new_plan))
        if extra_m <= self._max_extra_m:
            userdata.plan = new_plan
            return "replanned"
        if keeps >= self._max_keeps:
            self.log_info(f"the replan is {extra_m:.1f} m longer than the way through the pushed object; the old "
                          f"plan was kept {keeps} times for this goal already (max_keeps {self._max_keeps}): "
                          "taking the replan")
            userdata.plan = new_plan
            return "replanned"
        self.log_warn(f"the replan is {extra_m:.1f} m longer than the way through the pushed object "
                      f"(max_extra_m {self._max_extra_m:g}): following the old plan to push it on")
        userdata.keeps = float(keeps + 1)
        return "keep"
