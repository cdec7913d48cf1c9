"""behaviors/explore.yaml on fake servers and a scripted map: frontier -> plan -> drive -> the map grows -> no
frontier left -> save -> back to the start; a frontier that cannot be reached is marked and not retried; a map that
is not saved still brings the robot back but fails the behavior; a stale robot pose stops it; at autonomy Low the
operator approves each frontier. Its structure reuses flex_planner's parts (the Navigate sub-behavior,
simple_recovery)."""

from __future__ import annotations

from pathlib import Path
from typing import Any, List

import numpy as np
import pytest
from actionlib_msgs.msg import GoalStatus
from unit.behavior.behavior_testlib import child
from unit.mapping.test_frontiers import RES, room
from unit.states.states_testlib import Harness, KinematicRobot, path
from unit.states.test_states_exploration import occupancy_grid, robot_pose

from flex_nav.behavior.autonomy import Autonomy
from flex_nav.behavior.container import Container
from flex_nav.behavior.yaml_loader import load_behavior
from flex_nav.msg import FollowPathAction, FollowPathResult, GetPathAction, GetPathResult
from flex_nav.srv import MapFile, MapFileResponse

REPO = Path(__file__).resolve().parents[3]
BEHAVIORS = REPO / "behaviors"
STEP_S = 0.05  # [s]
START = (1.0, 1.5)  # [m] where the robot starts, in the half-known room

# A Navigate sub-behavior on one fake FollowPath server (explore passes what it passes to flex_navigate).
NAVIGATE = """
behavior: follow_only
description: Follow the plan with one FollowPath server.
parameters:
  profile: {type: str, default: kobuki, description: unused}
  stuck_window_s: {type: float, default: 20.0, description: "[s] unused"}
  final_heading: {type: bool, default: true, description: the last pose's yaw is a goal}
input_keys: [plan]
outcomes: [arrived, failed, bumper, stuck]
states:
  Follow:
    class: flex_nav_states.follow_path_state.FollowPathState
    parameters: {action_name: follower, final_heading: $final_heading}
    transitions: {done: arrived, failed: failed, preempted: failed}
"""


class Scene:
    """explore with the fake planner, follower and save service; the map and the robot pose injected."""

    def __init__(self, tmp_path: Path, occ: np.ndarray, follow: List[int], saved: bool = True,
                 autonomy: Autonomy = Autonomy.FULL, robot: bool = False, **parameters: Any) -> None:
        """``robot``: a kinematic robot answers the turn at the start with odometry (the other tests skip the
        turn: ``look_around`` skip unless given)."""
        (tmp_path / "follow_only.yaml").write_text(NAVIGATE)
        behavior = load_behavior(BEHAVIORS / "explore.yaml", search_path=[tmp_path, BEHAVIORS],
                                 parameters={"navigate": "follow_only", "map_path": "/maps/building",
                                             "look_around": "skip", **parameters})
        self.h = Harness(behavior.root, autonomy=autonomy)
        self.robot = KinematicRobot(self.h, yaw=0.3) if robot else None
        self.planner = self.h.proxies.client("get_path_server", GetPathAction)
        for _ in range(len(follow)):
            self.planner.respond(GoalStatus.SUCCEEDED, GetPathResult(code=GetPathResult.SUCCESS,
                                                                     plan=path([START, (2.0, 1.5)])), delay_s=0.1)
        self.follower = self.h.proxies.client("follower", FollowPathAction)
        for status in follow:
            code = FollowPathResult.SUCCESS if status == GoalStatus.SUCCEEDED else FollowPathResult.FAILURE
            self.follower.respond(status, FollowPathResult(code=code, message="scripted"), delay_s=1.0)
        self.saver = self.h.proxies.service("mapper/save_map", MapFile)
        self.saver.respond(MapFileResponse(ok=saved, message="wrote /maps/building.yaml" if saved else "disk full"))
        self.h.start()
        self.map = self.h.proxies.sub("/map")
        self.map.inject(occupancy_grid(occ))
        self.pose = self.h.proxies.sub("pose")
        self.mapper_alive = True  # False: the mapper publishes no pose any more
        self.step(0.0)

    def step(self, dt_s: float = STEP_S) -> None:
        """Time moves on; the mapper publishes the robot's pose at every scan (the robot stays where it started:
        the follower is faked)."""
        self.h.advance(dt_s)
        if self.mapper_alive:
            self.pose.inject(robot_pose(*START, stamp_s=self.h.clock.now()))

    def run(self, max_time_s: float = 60.0, explored_after: int = 0) -> Any:
        """Tick until the behavior ends; the whole room is known once the follower has ended ``explored_after``
        goals (0: never)."""
        end_s = self.h.clock.now() + max_time_s
        while self.h.clock.now() < end_s:
            if self.h.tick():
                return self.h.executor.result()
            self.step()
            if explored_after and len(self.follower.goals) >= explored_after and not self.follower.is_active():
                self.map.inject(occupancy_grid(room()))
                explored_after = 0
        raise AssertionError(f"explore still running after {max_time_s} s:\n{self.h.log_text()}")

    def plan_goals(self) -> List[tuple]:
        return [(g.pose.pose.position.x, g.pose.pose.position.y) for g in self.planner.goals]


def test_explores_the_frontier_saves_the_map_and_drives_back_to_the_start(tmp_path):
    scene = Scene(tmp_path, room(40), follow=[GoalStatus.SUCCEEDED] * 2)
    result = scene.run(explored_after=1)
    assert result.outcome == "finished", scene.h.log_text()
    frontier, home = scene.plan_goals()
    assert 40 * RES - 2 * RES <= frontier[0] < 40 * RES  # the boundary of the known half
    assert home == pytest.approx(START)
    assert [r.path for r in scene.saver.requests] == ["/maps/building"]
    texts = scene.h.texts()
    saved_at = next(i for i, t in enumerate(texts) if "wrote /maps/building.yaml" in t)
    planned_home_at = max(i for i, t in enumerate(texts) if "goal sent" in t and "get_path_server" in t)
    assert saved_at < planned_home_at  # saved before driving back
    assert [g.ignore_final_heading for g in scene.follower.goals] == [True, True]  # explore's final_heading: false


def test_a_frontier_that_cannot_be_reached_is_marked_failed_and_not_tried_again(tmp_path):
    failed = GoalStatus.ABORTED
    scene = Scene(tmp_path, room(40), follow=[failed, failed, GoalStatus.SUCCEEDED], max_tries=1.0)
    result = scene.run()
    assert result.outcome == "finished", scene.h.log_text()
    goals = scene.plan_goals()
    assert len(goals) == 3  # the frontier, once more after the back-off, then home
    assert goals[0] == goals[1] and goals[2] == pytest.approx(START)
    texts = scene.h.texts()
    assert any("1 failed so far" in t for t in texts)
    assert any("no frontier left" in t and "1 failed before" in t for t in texts)


def test_the_turn_at_the_start_looks_around_before_the_first_frontier(tmp_path):
    scene = Scene(tmp_path, room(40), follow=[GoalStatus.SUCCEEDED] * 2, robot=True, look_around="turn")
    result = scene.run(explored_after=1)
    assert result.outcome == "finished", scene.h.log_text()
    texts = scene.h.texts()
    turned_at = next(i for i, t in enumerate(texts) if t.startswith("turned +3"))
    first_plan_at = next(i for i, t in enumerate(texts) if "goal sent" in t and "get_path_server" in t)
    assert turned_at < first_plan_at, scene.h.log_text()
    rates = [m.twist.angular.z for m in scene.h.proxies.pub("cmd_vel_stamped").messages]
    assert max(rates) == pytest.approx(1.5)  # look_around_speed_radps
    assert scene.robot is not None and scene.robot.yaw == pytest.approx(0.3, abs=0.05)  # a full turn, back
    assert scene.robot.traveled_m == pytest.approx(0.0)


def test_a_turn_that_fails_is_logged_and_exploring_goes_on(tmp_path):
    scene = Scene(tmp_path, room(40), follow=[GoalStatus.SUCCEEDED] * 2, look_around="turn")  # no odometry
    result = scene.run(explored_after=1)
    assert result.outcome == "finished", scene.h.log_text()
    assert any("the turn at the start failed" in t for t in scene.h.texts())
    assert len(scene.plan_goals()) == 2


@pytest.mark.parametrize(("home_max_tries", "outcome"), [(10.0, "finished"), (3.0, "failed")])
def test_the_way_home_gets_its_own_tries(tmp_path, home_max_tries, outcome):
    """Four failed drives home (late scans on a loaded machine abort the controller): the default ten tries
    bring the robot home; the frontiers' three would leave it where it stands."""
    aborted = GoalStatus.ABORTED
    scene = Scene(tmp_path, room(40), follow=[GoalStatus.SUCCEEDED, aborted, aborted, aborted, aborted,
                                              GoalStatus.SUCCEEDED], home_max_tries=home_max_tries)
    result = scene.run(explored_after=1)
    assert result.outcome == outcome, scene.h.log_text()
    homeward = scene.plan_goals()[1:]
    assert all(g == pytest.approx(START) for g in homeward)
    assert len(homeward) == (5 if outcome == "finished" else 4)  # max_tries failed retries after the first try


def test_a_map_that_is_not_saved_still_brings_the_robot_back_but_fails(tmp_path):
    scene = Scene(tmp_path, room(), follow=[GoalStatus.SUCCEEDED], saved=False)
    result = scene.run()
    assert result.outcome == "failed", scene.h.log_text()
    assert scene.plan_goals() == [pytest.approx(START)]  # no frontier: straight to saving and home
    assert any("disk full" in t for t in scene.h.texts())


def test_a_silent_mapper_pose_fails_the_exploration_before_anything_moves(tmp_path):
    scene = Scene(tmp_path, room(40), follow=[GoalStatus.SUCCEEDED], map_timeout_s=2.0)
    scene.mapper_alive = False
    scene.pose.inject(robot_pose(*START, stamp_s=scene.h.clock.now() - 5.0))  # its last pose, 5 s ago
    result = scene.run()
    assert result.outcome == "failed"
    assert scene.planner.goals == []
    assert any("s old (pose_max_age_s 1 s)" in t for t in scene.h.texts()), scene.h.log_text()


def test_at_autonomy_low_the_operator_approves_each_frontier(tmp_path):
    scene = Scene(tmp_path, room(40), follow=[GoalStatus.SUCCEEDED] * 2, autonomy=Autonomy.LOW)
    for _ in range(100):
        scene.h.tick()
        scene.step()
    requests = scene.h.executor.requested_outcomes()
    assert [(r.path, r.outcome) for r in requests] == [("/ApproveFrontier", "explore")]
    assert scene.planner.goals == []  # nothing planned before the approval
    scene.h.executor.approve("/ApproveFrontier")
    for _ in range(20):
        scene.h.tick()
        scene.step()
    assert len(scene.planner.goals) == 1


@pytest.mark.parametrize("navigate", ["flex_navigate", "multi_level_navigate", "create_navigate"])
def test_explore_drives_with_flex_planners_navigate_and_bumper_recovery(navigate):
    root = load_behavior("explore", parameters={"navigate": navigate}, search_path=[BEHAVIORS]).root
    for goal_state in ("GoToFrontier", "GoHome"):
        concurrency = child(root, goal_state, "Navigate", "Navigate")
        assert isinstance(concurrency, Container) and "Bumper" in concurrency.children
        recovery = child(root, goal_state, "Recovery")
        assert isinstance(recovery, Container)
        assert set(recovery.children) == {"Stop", "BackUp", "BackUpFailed", "Clear"}
    flex_planner = load_behavior("flex_planner", parameters={"navigate": navigate}, search_path=[BEHAVIORS]).root
    planner_concurrency = child(flex_planner, "Navigate", "Navigate")
    assert isinstance(planner_concurrency, Container) and isinstance(concurrency, Container)
    assert set(planner_concurrency.children) == set(concurrency.children)
