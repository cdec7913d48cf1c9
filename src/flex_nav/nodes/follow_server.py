"""``follow_path_server`` / ``follow_topic_server``: mid-level planners that follow a path by replanning.

``follow_path_server`` serves FollowPath (the path is in the goal); ``follow_topic_server`` serves
FollowTopic (it follows the newest nav_msgs/Path on the topic named in the goal, waiting at most
``~topic_timeout`` [s] for the first one). Neither drives the robot: at ``~planner_frequency`` [Hz] each
looks ``~lookahead_distance`` [m] ahead along the goal path (arc length from the robot's closest point,
tracked monotonically; see :class:`flex_nav.nav.control.progress.PathProgress`), plans from the robot to that
point on its own costmap ``~local_costmap/`` (rolling window with the static map and ``scan`` by default)
and publishes the plan on ``~plan`` -- the path a ``pure_pursuit_topic`` controller follows. The lookahead
point backs off along the path until it lies on the costmap on a passable cell.

The goal succeeds within ``~goal_tolerance`` [m] of the path's end facing the yaw of its last pose within
``~yaw_goal_tolerance`` [rad] (0.25; move_base's goal check; a goal with ``ignore_final_heading`` needs the
position alone). Near the end the local plan ends at the path's last pose with its yaw, and it is
republished while the robot turns there, so the controller (``use_final_heading``) turns in place to it;
keep the controller's ``yaw_goal_tolerance`` below this one, or it may stop turning before this check
passes. It aborts with the reason on a bad
path (empty, NaN, unknown frame), when no plan could be made for ``~failure_timeout`` [s] of ROS time (blocked path,
no robot pose, no map) or when the node that sent it is gone for ``~client_timeout`` [s] (2.0; 0: off), and it
is preempted by a cancel or replaced by a newer goal. Replanning is paced on ROS time: while ROS time stands
still (a paused simulation) nothing is replanned; when it moves backwards (a restarted simulation) the goal
aborts with the reason. A FollowTopic goal naming an illegal topic (empty, ``..``, blanks) aborts at once. Keep
``lookahead_distance`` well above (controller speed / planner_frequency), or the controller reaches the
end of a local plan before the next one arrives.

Other parameters: ``global_frame`` ("map"), ``robot_base_frame`` ("base_footprint"),
``transform_timeout`` [s] (0.2), ``planner/*`` (:func:`flex_nav.ros.nav_params.planner_params`; a local
planner usually takes ``lethal_cost: 254`` so that a robot inside the inscribed zone can still plan out).
"""

from __future__ import annotations

import math
import time
from typing import Optional, Tuple

import numpy as np
import rospy
import tf2_ros
from nav_msgs.msg import Path

from flex_nav.exceptions import ConfigError, NotReadyError
from flex_nav.nav.control.clock_watch import ClockChange, ClockWatch
from flex_nav.nav.control.progress import PathProgress, Progress
from flex_nav.nav.costmap.costmap_grid import FREE
from flex_nav.nav.planning.planner import GridPlanner
from flex_nav.nodes.follow_base import FollowNode, GoalPath, GoalSource, Pose2D, bad_path
from flex_nav.nodes.get_path_server import warm_up
from flex_nav.ros.conversions import path_msg
from flex_nav.ros.costmap_ros import CostmapROS
from flex_nav.ros.frames import TfSource, path_in_frame
from flex_nav.ros.goal_server import GoalOutcome, GoalTicket
from flex_nav.ros.lockstep import LockstepParticipant
from flex_nav.ros.nav_params import planner_params
from flex_nav.ros.params import param_float
from flex_nav.ros.private_ns import private_name
from flex_nav.ros.ros_clock import RosClock
from flex_nav.ros.topic_path import TopicPath, TopicPaths

PARAMETERS = (
    "global_frame", "robot_base_frame", "lookahead_distance", "planner_frequency", "goal_tolerance",
    "failure_timeout", "topic_timeout", "transform_timeout", "local_costmap", "planner", "client_timeout",
    "yaw_goal_tolerance",
)
CLOCK_POLL_S = 0.01  # [s] wall: on simulated time, how often the replanning loop reads ROS time


class FollowServer(FollowNode):
    """One follow server node, serving FollowPath or FollowTopic as ``source`` says."""

    def __init__(self, source: GoalSource, tf_buffer: Optional[tf2_ros.Buffer] = None) -> None:
        """``tf_buffer``: one shared with other components of the process (None: a buffer of its own)."""
        super().__init__(source, PARAMETERS)
        self.lookahead_distance = param_float("~lookahead_distance", 1.5, 0.05, 1000.0)
        self.period_s = 1.0 / param_float("~planner_frequency", 2.0, 0.05, 100.0)
        self.goal_tolerance = param_float("~goal_tolerance", 0.25, 0.001, 100.0)
        self.yaw_goal_tolerance = param_float("~yaw_goal_tolerance", 0.25, 0.001, 3.15)  # [rad]
        self.failure_timeout_s = param_float("~failure_timeout", 3.0, 0.0, 3600.0)
        self.topic_timeout_s = param_float("~topic_timeout", 2.0, 0.0, 600.0)
        self.transform_timeout_s = param_float("~transform_timeout", 0.2, 0.0, 10.0)
        self.planner = GridPlanner(planner_params())
        warm_up(self.planner)
        PathProgress([[0.0, 0.0], [1.0, 0.0]], 0.5, 0.1).update(0.2, 0.1)  # load its compiled kernel now
        self.tf = TfSource(tf_buffer)
        self.tf_buffer = self.tf.buffer
        self.costmap = CostmapROS("local_costmap", self.tf_buffer, rolling_default=True, static_default=True)
        self.global_frame = self.costmap.global_frame
        self.clock = RosClock(poll_s=CLOCK_POLL_S)
        self.lockstep = LockstepParticipant("replanning")  # a goal's replanning ticks hold a lockstep simulation
        self._topics = TopicPaths(self._wake, self.clock, LockstepParticipant("paths"))  # reports each Path taken in
        # not latched: a stale local plan must not steer the controller of a new goal
        self.plan_publisher = rospy.Publisher(private_name("~plan"), Path, queue_size=1)
        self.costmap.serve_clear_costmap(self.name + "/clear_costmap")
        spec = self._serve()
        rospy.loginfo(f"{self.name}: {spec.name}, lookahead {self.lookahead_distance:.2f} m, "
                      f"replanning at {1.0 / self.period_s:.1f} Hz in '{self.global_frame}'")

    # ------------------------------------------------------------------ goals
    def _progress_of(self, msg: Path, final_heading: bool) -> PathProgress:
        poses = path_in_frame(self.tf_buffer, msg, self.global_frame, self.transform_timeout_s)
        return PathProgress(poses, self.lookahead_distance, self.goal_tolerance,
                            self.yaw_goal_tolerance if final_heading else None)

    def _pursue(self, ticket: GoalTicket, first: GoalPath) -> None:
        try:
            progress = self._progress_of(first.msg, not ticket.goal.ignore_final_heading)
        except (ConfigError, NotReadyError) as err:
            self._end(ticket, GoalOutcome.ABORTED, bad_path(first.topic, err))
            return
        try:
            self._follow(ticket, progress, first.topic, first.count)
        finally:
            self.lockstep.release()

    def _follow(self, ticket: GoalTicket, progress: PathProgress, source: Optional[TopicPath], used: int) -> None:
        last_plan_s = self.clock.now()  # replanning is paced and failure_timeout counted on ROS time
        next_due_s = last_plan_s
        watch = ClockWatch(stall_timeout_s=0.0)  # a stopped clock just stops the replanning; a jump back ends it
        watch.observe(last_plan_s, time.monotonic())
        pose: Optional[Pose2D] = None
        self.lockstep.hold_clock(next_due_s)
        self.server.release_accept(ticket)  # the goal holds on its own now
        while True:
            self.lockstep.hold_clock(next_due_s)
            with self._wake:
                while not ticket.cancelled.is_set() and not rospy.is_shutdown():
                    now_s = self.clock.now()
                    if watch.observe(now_s, time.monotonic()) is ClockChange.JUMPED_BACK:
                        self._end(ticket, GoalOutcome.ABORTED, f"ROS time moved backwards by {watch.jump_s:.2f} s "
                                  "(a restarted simulation or a looped bag): goal dropped", pose)
                        return
                    if now_s >= next_due_s:
                        break
                    self._wake.wait(self.clock.wall_wait_s(next_due_s, now_s))
            if ticket.cancelled.is_set() or rospy.is_shutdown():
                return
            next_due_s = max(next_due_s + self.period_s, self.clock.now())
            if source is not None and source.new_for_tick(used, self.clock.now(), self.lockstep.enabled):
                used = source.count
                try:
                    progress = self._progress_of(source.msg, not ticket.goal.ignore_final_heading)
                except (ConfigError, NotReadyError) as err:
                    self._end(ticket, GoalOutcome.ABORTED, bad_path(source, err), pose)
                    return
            try:
                pose = self.costmap.robot_pose.pose(timeout_s=self.transform_timeout_s,
                                                    at_s=self.clock.now() if self.lockstep.enabled else None)
                state, problem = self._replan(ticket, progress, pose, source)
            except NotReadyError as err:
                state, problem = None, f"robot pose unknown: {err}"
            if state is not None and state.done:
                heading = (f", heading {math.degrees(-state.heading_error):+.1f} deg from its yaw"  # robot - path
                           if math.isfinite(state.heading_error) else "")
                self._end(ticket, GoalOutcome.SUCCEEDED,
                          f"reached the end of the path ({state.distance_to_end:.3f} m from it{heading})", pose)
                return
            now_s = self.clock.now()
            if problem is None:
                last_plan_s = now_s
            elif now_s - last_plan_s >= self.failure_timeout_s:
                reason = f"no local plan for {now_s - last_plan_s:.1f} s: {problem}"
                self._end(ticket, GoalOutcome.ABORTED, reason, pose)
                return
            else:
                rospy.logwarn_throttle(1.0, f"{self.name}: {problem}")

    def _replan(
        self, ticket: GoalTicket, progress: PathProgress, pose: Pose2D, source: Optional[TopicPath]
    ) -> Tuple[Optional[Progress], Optional[str]]:
        """Plan to the lookahead point and publish it; (progress, None) or (progress or None, why not)."""
        snapshot = self.costmap.snapshot()
        if snapshot is None:
            return None, "no costmap yet (waiting for the map)"
        costs, geometry = snapshot
        def usable(x: float, y: float) -> bool:  # on the costmap and passable
            cell = geometry.world_to_cell(x, y)
            return geometry.in_bounds(cell) and self.planner.passable(int(costs[cell]))

        state = progress.update(pose[0], pose[1], inside=usable, yaw=pose[2])
        self._feedback(ticket, pose, source)
        if state.done:
            return state, None
        start_cell = geometry.world_to_cell(pose[0], pose[1])
        if geometry.in_bounds(start_cell):
            costs[start_cell] = FREE  # the robot's own cell (navfn's clearRobotCell): sensors may mark it
        # the path's end carries its yaw only when it is a goal heading; otherwise the plan ends facing along itself
        heading_counts = progress.yaw_goal_tolerance is not None
        target = state.target if heading_counts or not state.target_is_end else state.target[:2]
        result = self.planner.plan(costs, geometry, pose, target)
        if not result.ok:
            return state, f"{result.status.name}: {result.reason}"
        if ticket.cancelled.is_set():
            return state, None
        self.plan_publisher.publish(path_msg(np.asarray(result.path[:, :2]), self.global_frame, rospy.Time.now(),
                                             final_yaw=float(result.path[-1, 2])))
        return state, None
