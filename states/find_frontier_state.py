"""FindFrontierState: the next frontier to explore on the mapper's newest map; MarkFailedGoalState: remember a goal
that could not be reached, so the exploration does not choose its frontier again."""

from __future__ import annotations

from typing import Any, List, Optional, Tuple

import numpy as np
from nav_msgs.msg import OccupancyGrid

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView, unwrap
from flex_nav.exceptions import ConfigError
from flex_nav.mapping.frontiers import FrontierChoice, FrontierParams, FrontierSearch, choose_frontier, find_frontiers
from flex_nav.nav.costmap.grid_map import GridMap
from flex_nav.nav.pose_checks import yaw_of_quaternion
from flex_nav_states import validation
from flex_nav_states.background_work import BackgroundWork
from flex_nav_states.messages import describe
from flex_nav_states.proxy_types import SubscriptionLike, proxies_of
from flex_nav_states.robot_pose_state import RobotPose, RobotPoseReader, planar_pose_stamped


def grid_map_of_message(msg: Any) -> GridMap:
    """The GridMap of a nav_msgs/OccupancyGrid (origin yaw from its quaternion); ConfigError if it is malformed."""
    info = msg.info
    cells = np.asarray(msg.data, dtype=np.int8)
    if cells.size != info.width * info.height:
        raise ConfigError(f"the map has {cells.size} cells, but its info says {info.width} x {info.height}")
    o = info.origin
    q = o.orientation
    yaw = yaw_of_quaternion(q.x, q.y, q.z, q.w) if any((q.x, q.y, q.z, q.w)) else 0.0  # an all-zero one: no yaw
    return GridMap(cells.reshape(info.height, info.width), float(info.resolution), (o.position.x, o.position.y, yaw))


def goal_positions(goals: Any) -> List[Tuple[float, float]]:
    """(x [m], y [m]) of each goal in a sequence of PoseStamped (or Pose, or (x, y)); ConfigError for anything else."""
    found: List[Tuple[float, float]] = []
    for goal in unwrap(goals):
        item = unwrap(goal)
        pose = getattr(item, "pose", item)
        position = getattr(pose, "position", None)
        if position is not None:
            found.append((float(position.x), float(position.y)))
        elif isinstance(item, (tuple, list)) and len(item) == 2:
            found.append((float(item[0]), float(item[1])))
        else:
            raise ConfigError(f"a failed goal must be a PoseStamped or (x, y), got {type(item).__name__}")
    return found


class FindFrontierState(State):
    """Chooses the next frontier to explore on the newest map and writes its goal to userdata.

    A frontier is where known free space meets unknown space; it is reachable when the robot fits on a way there
    through known free cells (:mod:`flex_nav.mapping.frontiers` has the definitions). The cheapest reachable
    frontier by ``path length - size_weight * size`` is chosen, passing over those whose goal lies within
    ``failed_goal_radius_m`` of a goal that failed before (``failed_goals``) or is a shorter path than
    ``min_goal_distance_m`` from the robot (it stands there already, and the frontier is still one). The search runs
    off the behavior's thread (a large map takes a second); the robot pose must be in the map's frame.

    -- map_topic             str    nav_msgs/OccupancyGrid topic of the growing map (latched), relative to the
                                    behavior's namespace.
    -- pose_topic            str    Robot pose topic, in the map's frame.
    -- pose_type             str    Message type on pose_topic: odometry, pose_stamped or pose_with_covariance.
    -- pose_max_age_s        float  [s] Largest accepted age of the robot pose (0: any age; a localizer publishes
                                    only when its filter updates, which it does not while the robot stands).
    -- timeout_s             float  [s] Fail if there is no map or no valid robot pose this long after entry (> 0).
    -- robot_radius_m        float  [m] Clearance from known obstacles on the way to a frontier.
    -- min_frontier_size_m   float  [m] Smaller frontiers are ignored (cell count x resolution).
    -- size_weight           float  [m/m] Metres of path one metre of frontier is worth in the choice.
    -- failed_goal_radius_m  float  [m] Skip a frontier whose goal lies this close to a failed goal.
    -- min_goal_distance_m   float  [m] Skip a frontier whose goal is a shorter path than this from the robot.
    -- view_distance_m       float  [m] Stop this much path short of the frontier, where it is still in sight (the
                                    lidar sees it from there; 0: go to the frontier itself).

    ># failed_goals  list         Goals that failed before (PoseStamped, in the map's frame).
    #> goal          PoseStamped  The frontier's goal in the map's frame, facing the unknown side (when found).
    #> frontier      Frontier     The chosen flex_nav.mapping.frontiers.Frontier: size_m, path_length_m,
                                  cell_count, cost (when found).

    <= found   A reachable frontier was chosen; its goal is in userdata.
    <= done    No reachable frontier is left (or each one left failed before): the map is complete.
    <= failed  No map or robot pose within timeout_s, the pose is in another frame or off the map, the robot is
               walled in, or the map is malformed; the reason is logged.
    """

    def __init__(
        self,
        map_topic: str = "map",
        pose_topic: str = "amcl_pose",
        pose_type: str = "pose_with_covariance",
        pose_max_age_s: float = 0.0,
        timeout_s: float = 10.0,
        *,
        robot_radius_m: float = 0.2,
        min_frontier_size_m: float = 0.3,
        size_weight: float = 1.0,
        failed_goal_radius_m: float = 0.5,
        min_goal_distance_m: float = 0.4,
        view_distance_m: float = 0.0,
    ) -> None:
        super().__init__(outcomes=["found", "done", "failed"], input_keys=["failed_goals"],
                         output_keys=["goal", "frontier"])
        owner = type(self).__name__
        self._map_topic = validation.name(owner, "map_topic", map_topic)
        self._pose = RobotPoseReader(owner, pose_topic, pose_type, pose_max_age_s)
        self._timeout_s = validation.number(owner, "timeout_s", timeout_s, positive=True, unit="[s]")
        try:
            self._params = FrontierParams(robot_radius_m=robot_radius_m, min_frontier_size_m=min_frontier_size_m,
                                          size_weight=size_weight, failed_goal_radius_m=failed_goal_radius_m,
                                          min_goal_distance_m=min_goal_distance_m, view_distance_m=view_distance_m)
        except ConfigError as err:
            raise ConfigError(f"{owner}: {err}") from err
        self._map_sub: Optional[SubscriptionLike] = None
        self._enter_s = 0.0
        self._work: Optional[BackgroundWork[Tuple[FrontierSearch, FrontierChoice]]] = None
        self._frame = ""  # of the map the running search is on

    def on_start(self) -> None:
        self._map_sub = proxies_of(self).subscription(self._map_topic, OccupancyGrid)
        self._pose.start(self)

    def on_enter(self, userdata: UserDataView) -> None:
        self._enter_s = self.now_s()
        self._work = None

    def on_exit(self, userdata: UserDataView) -> None:
        self._work = None  # a search still running ends on its own; its result is dropped

    def execute(self, userdata: UserDataView) -> Optional[str]:
        if self._work is None:
            return self._start_search(userdata)
        if not self._work.done():
            return None
        try:
            search, choice = self._work.result()
        except ConfigError as err:
            self.log_error(f"cannot search the map on {self._map_topic} for frontiers: {err}")
            return "failed"
        finally:
            self._work = None
        if not search.ok:
            self.log_error(f"cannot search the map for frontiers: {search.reason}")
            return "failed"
        summary = (f"{len(search.frontiers)} reachable frontier(s), {search.unreachable} unreachable, "
                   f"{search.too_small} too small, {choice.skipped_failed} failed before, "
                   f"{choice.skipped_near} where the robot stands")
        frontier = choice.frontier
        if frontier is None:
            self.log_info(f"no frontier left to explore ({summary})")
            return "done"
        goal = planar_pose_stamped(*frontier.goal, self._frame, self.now_s())
        userdata.goal = goal
        userdata.frontier = frontier
        self.log_info(f"frontier of {frontier.size_m:.2f} m, {frontier.path_length_m:.2f} m away: goal "
                      f"{describe(goal)} ({summary})")
        return "found"

    def _start_search(self, userdata: UserDataView) -> Optional[str]:
        if self._map_sub is None:
            self._map_sub = proxies_of(self).subscription(self._map_topic, OccupancyGrid)
        msg: Any = self._map_sub.last()
        pose, problem = self._pose.read(self)
        if msg is None or pose is None:
            if self.now_s() - self._enter_s < self._timeout_s:
                return None
            missing = f"no map on {self._map_topic}" if msg is None else problem
            self.log_error(f"cannot look for frontiers: {missing} (waited {self._timeout_s:g} s)")
            return "failed"
        self._frame = str(msg.header.frame_id).lstrip("/")
        if not self._frame:
            self.log_error(f"the map on {self._map_topic} has no frame_id")
            return "failed"
        if pose.frame_id != self._frame:
            self.log_error(f"the robot pose on {self._pose.topic} is in frame '{pose.frame_id}' but the map on "
                           f"{self._map_topic} is in '{self._frame}': set pose_topic to a pose in the map's frame")
            return "failed"
        try:
            failed = goal_positions(userdata.failed_goals)
        except ConfigError as err:
            self.log_error(f"input key failed_goals: {err}")
            return "failed"
        self._work = BackgroundWork("frontier search", lambda: self._search(msg, pose, failed))
        return None

    def _search(self, msg: Any, pose: RobotPose, failed: List[Tuple[float, float]]) -> Tuple[
            FrontierSearch, FrontierChoice]:
        """In the worker thread: reads only its arguments and the (frozen) parameters."""
        search = find_frontiers(grid_map_of_message(msg), (pose.x, pose.y), self._params)
        return search, choose_frontier(search.frontiers, failed, self._params)


class MarkFailedGoalState(State):
    """Adds the goal that could not be reached to the failed goals, so FindFrontierState passes its frontier over.

    ># goal          PoseStamped  The goal that failed.
    ># failed_goals  list         The goals that failed before.
    #> failed_goals  list         The goals that failed before, then this one (a new list).

    <= done  The goal was added.
    """

    def __init__(self) -> None:
        super().__init__(outcomes=["done"], input_keys=["goal", "failed_goals"], output_keys=["failed_goals"])

    def execute(self, userdata: UserDataView) -> Optional[str]:
        goal = unwrap(userdata.goal)
        goals = [*unwrap(userdata.failed_goals), goal]
        userdata.failed_goals = goals
        self.log_info(f"frontier goal {describe(goal)} failed: not chosen again ({len(goals)} failed so far)")
        return "done"


__all__ = ["FindFrontierState", "MarkFailedGoalState", "goal_positions", "grid_map_of_message"]
