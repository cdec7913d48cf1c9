"""``get_path_server``: the GetPath action -- a global plan from the robot's pose in tf to a goal pose.

Serves GetPath under the node's name and ClearCostmap on ``<node>/clear_costmap``; owns the costmap
``~global_costmap/`` (see :mod:`flex_nav.ros.costmap_ros`; its frames default to ``~global_frame``
("map") and ``~robot_base_frame`` ("base_footprint")) and plans with :class:`flex_nav.nav.planning.planner.GridPlanner`
(parameters ``~planner/``, see :func:`flex_nav.ros.nav_params.planner_params`). Publishes each plan on
``~plan`` (nav_msgs/Path, latched).

Result codes (always with a reason in ``message``):

- SUCCESS: ``plan`` holds at least two poses from the robot to the goal, in the costmap's global frame;
- EMPTY: the planner found no path (unreachable goal, goal or start blocked beyond ``goal_tolerance``);
- FAILURE: unusable request -- NaN/inf or unnormalised goal, empty or unknown frame, goal or robot outside
  the map, no transform to the robot, no map within ``~map_timeout`` [s] -- or preempted.

Planning runs on the server's worker thread (:class:`flex_nav.ros.goal_server.GoalServer`) on a copy of the
costs, so goal and cancel callbacks never wait for it.
"""

from __future__ import annotations

import time
from typing import Optional

import numpy as np
import rospy
import tf2_ros
from nav_msgs.msg import Path

from flex_nav.action_types import action_type
from flex_nav.exceptions import ConfigError, NotReadyError
from flex_nav.msg import GetPathFeedback
from flex_nav.nav.costmap.costmap_grid import CostmapGeometry
from flex_nav.nav.planning.planner import GridPlanner, PlanResult, PlanStatus
from flex_nav.ros.conversions import path_msg, pose_of_xy_yaw
from flex_nav.ros.costmap_ros import CostmapROS
from flex_nav.ros.frames import TfSource, goal_in_frame
from flex_nav.ros.goal_server import GoalOutcome, GoalServer, GoalTicket
from flex_nav.ros.lockstep import LockstepParticipant
from flex_nav.ros.nav_params import planner_params
from flex_nav.ros.params import param_float, reject_unknown
from flex_nav.ros.private_ns import private_name, private_namespace

PARAMETERS = ("global_frame", "robot_base_frame", "map_timeout", "transform_timeout", "global_costmap", "planner")

# how each planner status is reported through GetPath
EMPTY_STATUSES = (PlanStatus.NO_PATH, PlanStatus.START_BLOCKED, PlanStatus.GOAL_BLOCKED)


def plan_code(status: PlanStatus) -> str:
    """GetPath result code name for a planner status."""
    if status is PlanStatus.SUCCESS:
        return "SUCCESS"
    if status in EMPTY_STATUSES:
        return "EMPTY"
    return "FAILURE"


def warm_up(planner: GridPlanner) -> None:
    """Run one tiny plan so the compiled search kernels are loaded before the first goal."""
    costs = np.zeros((4, 4), dtype=np.uint8)
    planner.plan(costs, CostmapGeometry(4, 4, 1.0), (0.5, 0.5), (3.5, 3.5))


class GetPathServer:
    def __init__(self, tf_buffer: Optional[tf2_ros.Buffer] = None) -> None:
        """``tf_buffer``: one shared with other components of the process (None: a buffer of its own)."""
        self.name = private_namespace()
        reject_unknown("~", PARAMETERS)
        self.map_timeout_s = param_float("~map_timeout", 1.0, 0.0, 60.0)
        self.transform_timeout_s = param_float("~transform_timeout", 0.2, 0.0, 10.0)
        self.planner = GridPlanner(planner_params())
        warm_up(self.planner)
        self.tf = TfSource(tf_buffer)
        self.tf_buffer = self.tf.buffer
        self.costmap = CostmapROS("global_costmap", self.tf_buffer)
        self.global_frame = self.costmap.global_frame
        self.plan_publisher = rospy.Publisher(private_name("~plan"), Path, queue_size=1, latch=True)
        self.lockstep = LockstepParticipant("planning")  # a lockstep simulation stands while a goal is planned
        self.costmap.serve_clear_costmap(self.name + "/clear_costmap")
        self.server = GoalServer(self.name, action_type("GetPath"), self._run)
        self.server.start()
        rospy.loginfo(f"{self.name}: serving GetPath in frame '{self.global_frame}'")

    def _run(self, ticket: GoalTicket) -> None:
        self.lockstep.hold_clock(rospy.get_time())
        self.server.release_accept(ticket)  # the goal holds on its own now
        try:
            self._answer(ticket)
        finally:
            self.lockstep.release()

    def _answer(self, ticket: GoalTicket) -> None:
        started = time.monotonic()
        code, message, plan = self._plan(ticket)
        if ticket.cancelled.is_set():
            return
        result = self.server.result(code, message, plan=plan if plan is not None else Path())
        if plan is not None:
            self.plan_publisher.publish(plan)
        outcome = GoalOutcome.SUCCEEDED if code == "SUCCESS" else GoalOutcome.ABORTED
        log = rospy.loginfo if code == "SUCCESS" else rospy.logwarn
        log(f"{self.name}: goal #{ticket.number}: {code}: {message} ({1e3 * (time.monotonic() - started):.1f} ms)")
        self.server.finish(ticket, outcome, result)

    def _plan(self, ticket: GoalTicket) -> tuple:
        """(code name, reason, Path or None) for one goal."""
        try:
            goal = goal_in_frame(self.tf_buffer, ticket.goal.pose, self.global_frame, self.transform_timeout_s)
        except (ConfigError, NotReadyError) as err:
            return "FAILURE", str(err), None
        if not self.costmap.wait_for_map(self.map_timeout_s):
            return "FAILURE", (f"no map yet: nothing arrived on {rospy.resolve_name(self.costmap.map_topic)} "
                               f"within {self.map_timeout_s:.1f} s"), None
        try:
            start = self.costmap.robot_pose.pose(timeout_s=self.transform_timeout_s,
                                                 at_s=ticket.stamp_s if self.lockstep.enabled else None)
        except NotReadyError as err:
            return "FAILURE", f"robot pose unknown: {err}", None
        feedback = GetPathFeedback(location=pose_of_xy_yaw(*start), goal=pose_of_xy_yaw(*goal))
        self.server.feedback(ticket, feedback)
        snapshot = self.costmap.snapshot()
        if snapshot is None:
            return "FAILURE", "no costmap yet", None
        costs, geometry = snapshot
        result: PlanResult = self.planner.plan(costs, geometry, start, tuple(float(v) for v in goal))
        code = plan_code(result.status)
        if not result.ok:
            return code, f"{result.status.name}: {result.reason}", None
        message = f"plan of {len(result.path)} poses, cost {result.cost:.0f}"
        if result.reason:
            message += f" ({result.reason})"
        plan = path_msg(result.path[:, :2], self.global_frame, rospy.Time.now(), final_yaw=float(result.path[-1, 2]))
        return code, message, plan
