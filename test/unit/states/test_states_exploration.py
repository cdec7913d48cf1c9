"""The exploration states on fake proxies: FindFrontierState (found, done, failed, failed goals skipped),
MarkFailedGoalState, RobotPoseState and SaveMapState (saved, service missing, not ok, no answer)."""

from __future__ import annotations

import math
import threading
from typing import Any, Dict, Optional

import genpy
import numpy as np
import pytest
from geometry_msgs.msg import PoseWithCovarianceStamped
from nav_msgs.msg import OccupancyGrid
from unit.mapping.test_frontiers import RES, ROWS, room
from unit.states.states_testlib import Harness, odometry, pose_stamped

from flex_nav.behavior import BehaviorStatus, LogLevel
from flex_nav.exceptions import ConfigError, NotReadyError
from flex_nav.mapping.frontiers import Frontier
from flex_nav.nav.costmap.grid_map import UNKNOWN
from flex_nav.nav.pose_checks import quaternion_of_yaw, yaw_of_quaternion
from flex_nav.srv import MapFile, MapFileResponse
from flex_nav_states.find_frontier_state import FindFrontierState, MarkFailedGoalState, grid_map_of_message
from flex_nav_states.robot_pose_state import RobotPoseState
from flex_nav_states.save_map_state import SaveMapState

ROBOT = (1.0, 1.5)  # [m] in the rooms of unit.mapping.test_frontiers


def occupancy_grid(occ: np.ndarray, frame: str = "map", origin=(0.0, 0.0, 0.0)) -> OccupancyGrid:
    msg = OccupancyGrid()
    msg.header.frame_id = frame
    msg.info.resolution = RES
    msg.info.height, msg.info.width = occ.shape
    msg.info.origin.position.x, msg.info.origin.position.y = origin[0], origin[1]
    o = msg.info.origin.orientation
    o.x, o.y, o.z, o.w = quaternion_of_yaw(origin[2])
    msg.data = occ.reshape(-1).tolist()
    return msg


def robot_pose(x: float, y: float, stamp_s: float, frame: str = "map", yaw: float = 0.0) -> PoseWithCovarianceStamped:
    msg = PoseWithCovarianceStamped()
    msg.header.stamp = genpy.Time.from_sec(stamp_s)
    msg.header.frame_id = frame
    msg.pose.pose.position.x, msg.pose.pose.position.y = x, y
    o = msg.pose.pose.orientation
    o.x, o.y, o.z, o.w = quaternion_of_yaw(yaw)
    return msg


def finder(occ: Optional[np.ndarray], pose: Optional[tuple] = ROBOT, failed_goals=(), pose_frame: str = "map",
           **params: Any) -> Harness:
    """A started FindFrontierState with the map and the robot pose injected (None: not published)."""
    h = Harness(FindFrontierState(**params), inputs={"failed_goals": list(failed_goals)}).start()
    if occ is not None:
        h.proxies.sub("map").inject(occupancy_grid(occ))
    if pose is not None:
        h.proxies.sub("amcl_pose").inject(robot_pose(pose[0], pose[1], stamp_s=h.clock.now(), frame=pose_frame))
    return h


def errors(h: Harness) -> str:
    return "\n".join(h.texts(min_level=int(LogLevel.ERROR)))


# --- FindFrontierState ------------------------------------------------------------------------------------------


def test_found_writes_the_goal_in_the_map_frame_and_the_frontier():
    h = finder(room(40))
    result = h.run(max_time_s=5.0)
    assert result.outcome == "found", h.log_text()
    goal = result.outputs["goal"]
    assert goal.header.frame_id == "map"
    assert 40 * RES - 2 * RES <= goal.pose.position.x < 40 * RES  # on the boundary of the known half
    q = goal.pose.orientation
    assert abs(yaw_of_quaternion(q.x, q.y, q.z, q.w)) < math.radians(10)  # facing the unknown (+x)
    frontier = result.outputs["frontier"]
    assert isinstance(frontier, Frontier)
    assert frontier.size_m == pytest.approx((ROWS - 2) * RES)
    assert (frontier.goal[0], frontier.goal[1]) == pytest.approx((goal.pose.position.x, goal.pose.position.y))
    assert any("1 reachable frontier(s)" in t for t in h.texts())


def test_a_map_with_an_origin_and_the_message_conversion_agree():
    occ = room(40)
    grid = grid_map_of_message(occupancy_grid(occ, origin=(-2.0, 3.0, 0.3)))
    assert grid.origin == pytest.approx((-2.0, 3.0, 0.3))
    assert np.array_equal(grid.occupancy, occ) and grid.resolution == pytest.approx(RES)
    bad = occupancy_grid(occ)
    bad.data = bad.data[:-1]
    with pytest.raises(ConfigError, match="cells"):
        grid_map_of_message(bad)


def test_done_when_the_map_has_no_frontier_left():
    h = finder(room())
    result = h.run(max_time_s=5.0)
    assert result.outcome == "done", h.log_text()
    assert "goal" not in result.outputs
    assert any("no frontier left" in t for t in h.texts())


def test_a_map_that_comes_within_the_timeout_is_used():
    h = finder(None, timeout_s=3.0)
    h.run_for(1.0)
    h.proxies.sub("map").inject(occupancy_grid(room(40)))
    assert h.run(max_time_s=3.0).outcome == "found", h.log_text()


@pytest.mark.parametrize(
    ("occ", "pose", "frame", "reason"),
    [
        (None, ROBOT, "map", "no map on map"),
        (room(40), None, "map", "no robot pose on amcl_pose"),
        (room(40), ROBOT, "odom", "in frame 'odom'"),
        (room(40), (-1.0, 1.5), "map", "outside the map"),
    ],
    ids=["no map", "no pose", "other frame", "off the map"],
)
def test_failed_without_map_or_pose_within_the_timeout_or_with_a_pose_off_the_map(occ, pose, frame, reason):
    h = finder(occ, pose, pose_frame=frame, timeout_s=2.0)
    start_s = h.clock.now()
    result = h.run(max_time_s=5.0)
    assert result.outcome == "failed", h.log_text()
    assert reason in errors(h)
    if occ is None or pose is None:
        assert 2.0 <= h.clock.now() - start_s <= 2.5  # waited the timeout, no longer


def test_a_stale_pose_is_refused_when_pose_max_age_s_is_set():
    h = Harness(FindFrontierState(pose_max_age_s=1.0, timeout_s=1.0), inputs={"failed_goals": []}).start()
    h.proxies.sub("map").inject(occupancy_grid(room(40)))
    h.proxies.sub("amcl_pose").inject(robot_pose(*ROBOT, stamp_s=h.clock.now() - 5.0))
    assert h.run(max_time_s=3.0).outcome == "failed"
    assert "s old (pose_max_age_s 1 s)" in errors(h)


def two_frontier_room() -> np.ndarray:
    occ = room(70)  # the unknown east part: a long frontier far away
    occ[25:35, 0] = UNKNOWN  # a short one in the west wall, near the robot
    return occ


def test_frontiers_whose_goal_failed_before_are_skipped_until_none_is_left():
    params: Dict[str, Any] = {"size_weight": 0.0, "robot_radius_m": 0.1}
    first = finder(two_frontier_room(), pose=(0.6, 1.5), **params).run(max_time_s=5.0)
    assert first.outcome == "found"
    goal_a = first.outputs["goal"]
    assert goal_a.pose.position.x < 0.5  # the near one first (size does not count)
    h = finder(two_frontier_room(), pose=(0.6, 1.5), failed_goals=[goal_a], **params)
    second = h.run(max_time_s=5.0)
    assert second.outcome == "found"
    goal_b = second.outputs["goal"]
    assert goal_b.pose.position.x > 3.0  # the far one
    assert any("1 failed before" in t for t in h.texts())
    third = finder(two_frontier_room(), pose=(0.6, 1.5), failed_goals=[goal_a, goal_b], **params)
    assert third.run(max_time_s=5.0).outcome == "done"


def test_mark_failed_goal_appends_to_a_new_list():
    before = [pose_stamped(5.0, 5.0)]
    goal = pose_stamped(1.0, 2.0)
    h = Harness(MarkFailedGoalState(), inputs={"goal": goal, "failed_goals": before})
    result = h.start().run(max_time_s=1.0)
    assert result.outcome == "done"
    assert [g.pose.position.x for g in result.outputs["failed_goals"]] == [5.0, 1.0]
    assert len(before) == 1  # the caller's list is not changed


@pytest.mark.parametrize(
    ("params", "match"),
    [({"robot_radius_m": -0.1}, "FindFrontierState: .*robot_radius_m"), ({"pose_type": "pose"}, "pose_with_covariance"),
     ({"timeout_s": 0.0}, "timeout_s must be > 0"), ({"map_topic": "a b"}, "map_topic"),
     ({"size_weight": math.nan}, "size_weight")],
)
def test_find_frontier_parameters_are_checked_when_built(params, match):
    with pytest.raises(ConfigError, match=match):
        FindFrontierState(**params)


# --- RobotPoseState ---------------------------------------------------------------------------------------------


def test_robot_pose_writes_a_pose_stamped_in_the_pose_frame():
    h = Harness(RobotPoseState()).start()
    h.proxies.sub("amcl_pose").inject(robot_pose(2.0, -1.0, stamp_s=h.clock.now(), yaw=0.7))
    result = h.run(max_time_s=2.0)
    assert result.outcome == "done"
    pose = result.outputs["pose"]
    assert (pose.header.frame_id, pose.pose.position.x, pose.pose.position.y) == ("map", 2.0, -1.0)
    q = pose.pose.orientation
    assert yaw_of_quaternion(q.x, q.y, q.z, q.w) == pytest.approx(0.7)


def test_robot_pose_from_odometry_and_failed_without_a_valid_pose():
    h = Harness(RobotPoseState(pose_topic="odom", pose_type="odometry")).start()
    h.proxies.sub("odom").inject(odometry(0.5, 0.25, 0.0, 0.0, 0.0, h.clock.now(), frame="odom"))
    assert h.run(max_time_s=2.0).outputs["pose"].header.frame_id == "odom"
    h = Harness(RobotPoseState(timeout_s=1.5)).start()
    bad = robot_pose(1.0, 1.0, stamp_s=h.clock.now())
    bad.pose.pose.orientation.w = 0.0  # not a rotation
    h.proxies.sub("amcl_pose").inject(bad)
    start_s = h.clock.now()
    assert h.run(max_time_s=3.0).outcome == "failed"
    assert 1.5 <= h.clock.now() - start_s <= 2.0
    assert "not usable" in errors(h)


# --- SaveMapState -----------------------------------------------------------------------------------------------


def saver(answer: Any = None, available: bool = True, **params: Any) -> Harness:
    h = Harness(SaveMapState(**params))
    service = h.proxies.service(params.get("service", "mapper/save_map"), MapFile)
    if not available:
        service.available_at_s = math.inf
    if answer is not None:
        service.respond(answer)
    return h.start()


def test_save_map_saved_sends_the_path_and_logs_the_files():
    h = saver(MapFileResponse(ok=True, message="wrote /tmp/lab.yaml and /tmp/lab.pgm"), path="/tmp/lab")
    result = h.run(max_time_s=5.0)
    assert result.status is BehaviorStatus.FINISHED and result.outcome == "saved", h.log_text()
    assert [r.path for r in h.proxies.service("mapper/save_map", MapFile).requests] == ["/tmp/lab"]
    assert any("wrote /tmp/lab.yaml and /tmp/lab.pgm" in t for t in h.texts())


def test_save_map_fails_when_the_service_is_missing():
    h = saver(available=False, service="slam/save_map", server_timeout_s=1.0)
    assert h.run(max_time_s=5.0).outcome == "failed"
    assert "slam/save_map is not available" in errors(h)


def test_save_map_fails_and_logs_the_reason_when_the_mapper_says_not_ok():
    h = saver(MapFileResponse(ok=False, message="directory /nope does not exist"), path="/nope/map")
    assert h.run(max_time_s=5.0).outcome == "failed"
    assert "directory /nope does not exist" in errors(h)


class SilentService:
    """A MapFile service that is there but answers only when released (bounded, so its thread always ends)."""

    srv_type = MapFile

    def __init__(self) -> None:
        self.release = threading.Event()

    def is_available(self, timeout_s: float = 0.0) -> bool:
        return True

    def call(self, request: Any, timeout_s: float = 5.0) -> Any:
        if not self.release.wait(10.0):
            raise NotReadyError("never released")
        return MapFileResponse(ok=True, message="too late")


def test_save_map_fails_when_no_answer_comes_in_time_and_the_late_answer_is_dropped():
    h = Harness(SaveMapState(server_timeout_s=1.0, timeout_s=2.0))
    silent = SilentService()
    h.proxies.services["mapper/save_map"] = silent  # type: ignore[assignment]
    start_s = h.start().clock.now()
    result = h.run(max_time_s=10.0)
    silent.release.set()
    assert result.outcome == "failed"
    assert 3.0 <= h.clock.now() - start_s <= 3.5
    assert "did not answer within 3 s" in errors(h)
    assert not any("too late" in t for t in h.texts())


@pytest.mark.parametrize(
    ("params", "match"),
    [({"path": ""}, "path must not be empty"), ({"path": 3}, "path must be a string"),
     ({"service": ""}, "service"), ({"timeout_s": -1.0}, "timeout_s")],
)
def test_save_map_parameters_are_checked_when_built(params, match):
    with pytest.raises(ConfigError, match=match):
        SaveMapState(**params)

