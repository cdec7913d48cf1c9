"""behaviors/push_or_avoid.yaml on fake servers: blocked -> movable: push and go on; person: back off, wait,
never a forward command; heavy: the push stalls, back off, plan around; the tries are bounded."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import numpy as np
import pytest
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped
from sensor_msgs.msg import LaserScan
from unit.perception.shape_synth import box_corners, ranges_of
from unit.states.states_testlib import Harness, KinematicRobot, path, pose_stamped, twists, wall_scan
from unit.states.test_states_obstacles import Camera

from flex_nav.behavior.yaml_loader import load_behavior
from flex_nav.msg import (
    ClearCostmapAction,
    ClearCostmapResult,
    FollowPathAction,
    FollowPathResult,
    GetPathAction,
    GetPathResult,
)

BEHAVIORS = Path(__file__).resolve().parents[3] / "behaviors"
STEP_S = 0.05  # [s]
BLOCKED = "blocked: obstacle on the path 0.90 m ahead at (2.00, 0.00) for 0.50 s (blocked_distance 1 m)"


class Scene:
    """The behavior with a kinematic robot, a camera and scripted planner / controller / costmap servers."""

    def __init__(self, label, follow_results, plans=6, **parameters) -> None:
        behavior = load_behavior(BEHAVIORS / "push_or_avoid.yaml", parameters=parameters)
        self.h = Harness(behavior.root)
        self.robot = KinematicRobot(self.h)
        self.planner = self.h.proxies.client("get_path_server", GetPathAction)
        for _ in range(plans):
            self.planner.respond(GoalStatus.SUCCEEDED, GetPathResult(code=GetPathResult.SUCCESS,
                                                                     plan=path([(0, 0), (3, 0)])), delay_s=0.1)
        self.follower = self.h.proxies.client("pure_pursuit_path", FollowPathAction)
        for status, code, message in follow_results:
            self.follower.respond(status, FollowPathResult(code=code, message=message), delay_s=0.5)
        for name in ("pure_pursuit_path/clear_costmap", "get_path_server/clear_costmap"):
            clear = self.h.proxies.client(name, ClearCostmapAction)
            for _ in range(6):
                clear.respond(GoalStatus.SUCCEEDED, ClearCostmapResult(code=ClearCostmapResult.SUCCESS))
        self.h.start()
        self.camera = Camera(self.h, label)
        self.lidar = self.h.proxies.subscription("scan", LaserScan)
        self.wall_behind_x: Optional[float] = None  # [m] world x of something behind the robot (None: free all round)
        self.box_ahead_x: Optional[float] = None  # [m] world x of a 0.4 m box's near face ahead (None: no box)
        self.h.proxies.subscription("move_base_simple/goal", PoseStamped).inject(
            pose_stamped(3.0, 0.0, stamp_s=self.h.clock.now()))

    def run_until(self, text: str, max_time_s: float, on_step=None) -> float:
        """Tick until a log line contains ``text``; returns the time it took."""
        start = self.h.clock.now()
        while self.h.clock.now() - start <= max_time_s:
            assert not self.h.tick(), self.h.log_text()
            if any(text in t for t in self.h.texts()):
                return self.h.clock.now() - start
            self.h.advance(STEP_S)
            if on_step is not None:
                on_step()
            self.camera.publish()
            self.lidar.inject(self.scan())
        raise AssertionError(f"no {text!r} within {max_time_s} s:\n{self.h.log_text()}")

    def scan(self) -> LaserScan:
        """The robot's scan: the wall behind (if any) and the box ahead (if any)."""
        scan = wall_scan(self.h.clock.now(), self.robot.x, self.wall_behind_x)
        if self.box_ahead_x is not None:
            angles = scan.angle_min + scan.angle_increment * np.arange(len(scan.ranges))
            face = self.box_ahead_x - self.robot.x
            box = ranges_of((0.0, 0.0), angles, [box_corners(face + 0.2, 0.0, 0.4, 0.4, 0.2)])
            scan.ranges = [float(min(r, b)) for r, b in zip(scan.ranges, box)]
        return scan

    def visited(self) -> list:
        return [t for t in self.h.texts() if t]


BLOCKED_THEN_DONE = [(GoalStatus.ABORTED, FollowPathResult.FAILURE, BLOCKED),
                     (GoalStatus.SUCCEEDED, FollowPathResult.SUCCESS, "goal reached")]


def test_movable_obstacle_is_pushed_and_the_goal_reached():
    # the camera alone (this scene's lidar sees no box: fused, "movable vs nothing" would look again first)
    scene = Scene("movable", BLOCKED_THEN_DONE, push_distance_m=0.8, push_speed_mps=0.2, backoff_m=-0.3,
                  fuse_lidar=False)
    scene.run_until("goal reached", 30.0)
    assert abs(scene.robot.x - 0.5) < 0.05  # pushed the whole distance, then backed off from the box
    assert len(scene.follower.goals) == 2 and len(scene.planner.goals) == 2  # plan, replan after the push
    assert any("pushed 0.8" in t for t in scene.h.texts())


def test_person_is_never_pushed_the_robot_backs_off_waits_and_goes_on():
    scene = Scene(lambda t: "person" if t < 4.0 else "clear", BLOCKED_THEN_DONE, backoff_m=-0.3)
    scene.run_until("goal reached", 30.0)
    assert all(v <= 0.0 for v, _ in twists(scene.h))  # never a forward command (the controller is faked)
    assert abs(scene.robot.x + 0.3) < 0.03
    assert any("path clear" in t for t in scene.h.texts())
    assert len(scene.follower.goals) == 2


def test_backing_off_from_a_person_stops_for_someone_behind_and_the_behavior_goes_on():
    scene = Scene(lambda t: "person" if t < 4.0 else "clear", BLOCKED_THEN_DONE, backoff_m=-0.3)
    scene.wall_behind_x = -0.35  # someone 0.35 m behind the start: 0.18 m behind the robot's back
    scene.run_until("goal reached", 30.0)
    assert any("behind the robot, in the way" in t for t in scene.h.texts()), scene.h.log_text()
    assert -0.2 < scene.robot.x <= 0.0  # stopped short of the 0.3 m back-off
    assert any("path clear" in t for t in scene.h.texts())  # waited for the person as after a full back-off
    assert len(scene.follower.goals) == 2


def test_heavy_obstacle_push_stalls_then_backs_off_and_plans_around():
    scene = Scene("movable", BLOCKED_THEN_DONE, push_distance_m=1.0, push_speed_mps=0.2, backoff_m=-0.3)

    def heavy():
        if scene.robot.x >= 0.3 and scene.robot.v > 0.0:
            scene.robot.blocked = True  # touches the heavy box: no progress any more
        elif scene.robot.blocked and any("stalled" in t for t in scene.h.texts()):
            scene.robot.blocked = False  # it can back off

    scene.run_until("goal reached", 40.0, on_step=heavy)
    texts = scene.h.texts()
    assert any("stalled" in t for t in texts) and any("planning around it" in t for t in texts)
    assert abs(scene.robot.x - 0.0) < 0.05  # 0.3 m pushed, 0.3 m backed off
    assert len(scene.planner.goals) == 2


@pytest.mark.parametrize("camera, look_row, decided, pushed, x_range", [
    # the rule chosen on the validation splits (flex_nav.perception.fusion): a lidar box never beats the camera's
    # clear, it only asks for the looks; two looks back (0.13-0.15 m each), no push
    ("clear", 4, "fused clear (row 8", False, (-0.31, -0.25)),
    # an undecided camera: the box decides after the looks; the 0.5 m push and the 0.3 m back-off
    ("unknown", 3, "fused movable (row 7", True, (-0.15, 0.0))])
def test_with_the_lidar_a_box_is_looked_at_again_then_decided(camera, look_row, decided, pushed, x_range):
    scene = Scene(camera, BLOCKED_THEN_DONE, fuse_lidar=True, max_looks=2, look_again_m=-0.15,
                  push_distance_m=0.5, push_speed_mps=0.2, backoff_m=-0.3)
    scene.box_ahead_x = 0.55
    scene.run_until("goal reached", 40.0)
    texts = scene.h.texts()
    looks = [t for t in texts if f"fused look_again (row {look_row}" in t]
    assert len(looks) == 2, scene.h.log_text()
    assert any(decided in t for t in texts), scene.h.log_text()
    assert any("pushed 0.5" in t for t in texts) == pushed
    assert x_range[0] < scene.robot.x < x_range[1]


def test_with_the_lidar_a_box_the_camera_calls_movable_is_pushed_at_once():
    scene = Scene("movable", BLOCKED_THEN_DONE, fuse_lidar=True, push_distance_m=0.5, backoff_m=-0.3)
    scene.box_ahead_x = 0.55
    scene.run_until("goal reached", 30.0)
    assert not any("look_again" in t for t in scene.h.texts())
    assert any("fused movable (row 6" in t for t in scene.h.texts())


def heavy_box_scene(**parameters: object) -> Scene:
    """A box 0.5 m ahead that stops the robot once it pushes at 0.3 m, until the push gave up."""
    scene = Scene("movable", BLOCKED_THEN_DONE, push_distance_m=1.0, push_speed_mps=0.2, backoff_m=-0.3,
                  **parameters)
    scene.box_ahead_x = 0.5

    def heavy():
        if scene.robot.x >= 0.3 and scene.robot.v > 0.0:
            scene.robot.blocked = True
        elif scene.robot.blocked and any("stalled" in t for t in scene.h.texts()):
            scene.robot.blocked = False

    scene.run_until("goal reached", 40.0, on_step=heavy)
    return scene


def test_a_heavy_obstacle_is_reported_to_the_obstacle_memory_by_default():
    scene = heavy_box_scene()  # remember_heavy: true by default
    (mark,) = scene.h.proxies.pub("obstacle_memory/mark").messages
    xs = [p.x for p in mark.polygon.points]
    assert abs(min(xs) - (0.5 - scene.robot.x)) < 0.05  # the box's face, seen from where the robot backed off to
    assert any(t.startswith("obstacle remembered") for t in scene.h.texts())


def test_without_remember_heavy_nothing_is_sent_to_the_memory():
    scene = heavy_box_scene(remember_heavy=False)
    assert any("stalled" in t for t in scene.h.texts())
    assert "obstacle_memory/mark" not in scene.h.proxies.publishers  # not even advertised
    assert not any(t.startswith("obstacle remembered") for t in scene.h.texts())


def test_tries_are_bounded_then_the_recovery_chain_runs():
    always_blocked = [(GoalStatus.ABORTED, FollowPathResult.FAILURE, BLOCKED)] * 8
    scene = Scene("clear", always_blocked, plans=8, max_tries=2.0)
    scene.run_until("aborting the goal", 60.0)
    texts = scene.h.texts()
    assert len(scene.follower.goals) == 4  # 3 tries + the last one after the recovery chain
    chain = [next(i for i, t in enumerate(texts) if t.startswith(prefix))
             for prefix in ("cleared 2 costmap(s)", "turned +", "moved -0.2")]
    assert chain == sorted(chain), scene.h.log_text()  # clear both, spin, (wait), back up


def test_a_follow_failure_that_is_not_blocked_is_not_classified_and_nothing_is_pushed():
    stale = [(GoalStatus.ABORTED, FollowPathResult.FAILURE, "robot pose unknown: no odometry received yet"),
             (GoalStatus.SUCCEEDED, FollowPathResult.SUCCESS, "goal reached")]
    scene = Scene("movable", stale)
    scene.run_until("goal reached", 30.0)
    assert all(v == 0.0 for v, _ in twists(scene.h))  # no push: only the (faked) controller drives
    assert not any("obstacle class" in t for t in scene.h.texts())
    assert len(scene.follower.goals) == 2


def test_following_without_progress_ends_as_stuck_and_is_replanned_not_classified():
    scene = Scene("movable", [])  # the controller never answers and the robot does not move
    took = scene.run_until("goal sent: plan to", 1.0)
    assert took < 1.0
    scene.run_until("robot stuck", 15.0)
    scene.follower.respond(GoalStatus.SUCCEEDED, FollowPathResult(code=FollowPathResult.SUCCESS, message="ok"))
    scene.run_until("goal reached", 10.0)
    assert scene.follower.cancels == 1  # the stuck attempt's goal was cancelled
    assert len(scene.follower.goals) == 2 and len(scene.planner.goals) == 2
    assert all(v == 0.0 for v, _ in twists(scene.h))  # nothing pushed


def test_no_new_plan_after_a_failure_follows_the_plan_it_had_to_the_obstacle_and_pushes_it():
    """S1, seed 0 of the evaluation: a stale scan ended following; the replan found no path (the box in the
    door had reached the global costmap), and the robot waited for the way to clear from afar. Now it follows
    the plan it had, is blocked at the box, classifies it and pushes."""
    failures = [(GoalStatus.ABORTED, FollowPathResult.FAILURE, "stale scan: no message for 0.54 s"),
                *BLOCKED_THEN_DONE]
    scene = Scene("movable", failures, plans=0, push_distance_m=0.8, push_speed_mps=0.2, backoff_m=-0.3)
    ok = GetPathResult(code=GetPathResult.SUCCESS, plan=path([(0, 0), (3, 0)]))
    scene.planner.respond(GoalStatus.SUCCEEDED, ok, delay_s=0.1)  # the first plan
    scene.planner.respond(GoalStatus.ABORTED, GetPathResult(code=GetPathResult.EMPTY, message="NO_PATH"),
                          delay_s=0.1)  # the replan after the stale scan
    scene.planner.respond(GoalStatus.SUCCEEDED, ok, delay_s=0.1)  # the replan after the push
    took = scene.run_until("goal reached", 30.0)
    assert took < 20.0  # no waiting for the way to clear (patience 45 s)
    follows = scene.follower.goals
    assert len(follows) == 3 and follows[1].path.poses == follows[0].path.poses  # the plan it had
    assert any("pushed 0.8" in t for t in scene.h.texts())


def scripted_planner(scene: Scene, answers: str) -> None:
    """The planner's answers in order: "p" a plan, "e" no path (EMPTY)."""
    for answer in answers:
        if answer == "p":
            scene.planner.respond(GoalStatus.SUCCEEDED, GetPathResult(code=GetPathResult.SUCCESS,
                                                                      plan=path([(0, 0), (3, 0)])), delay_s=0.1)
        else:
            scene.planner.respond(GoalStatus.ABORTED, GetPathResult(code=GetPathResult.EMPTY, message="NO_PATH"),
                                  delay_s=0.1)


def test_an_object_the_camera_calls_clear_that_closes_the_way_is_waited_for_by_planning_again():
    """A hidden variant of S2 (a grey 60 kg box in a 0.9 m door, removed at 40 s): the camera called it clear, so
    the class-based wait ended at once and every loop spent tries until the goal was given up at 40.7 s. Now,
    after the way was reported clear, the planner is asked again every no_path_wait_s while it finds no path."""
    scene = Scene("clear", BLOCKED_THEN_DONE, plans=0, no_path_wait_s=2.0, no_path_waits=20.0)
    scripted_planner(scene, "pe" + "eeee" + "p")  # plan; around: none; 4 more without a path; then the way is free
    elapsed = scene.run_until("goal reached", 60.0)
    texts = scene.h.texts()
    assert len(scene.planner.goals) == 7 and len(scene.follower.goals) == 2, scene.h.log_text()
    assert not any("aborting the goal" in t for t in texts)
    assert elapsed > 4 * 2.0  # it waited between the plans


def test_planning_again_after_the_wait_is_bounded():
    """No path ever again: the plans after the wait end after no_path_waits (3) and the behavior goes on as
    before (follows the plan it had, meets the object, and after max_tries the recovery chain gives up)."""
    scene = Scene("clear", BLOCKED_THEN_DONE[:1] * 8, plans=0, no_path_wait_s=1.0, no_path_waits=3.0)
    scripted_planner(scene, "p" + "e" * 30)
    scene.run_until("aborting the goal", 120.0)
    # the first plan, around (none), 1 + 3 after the wait, then each further blocked episode's around and after-wait
    # plan, and the recovery chain's last plan: bounded well below the 31 answers scripted
    assert 6 <= len(scene.planner.goals) <= 16, scene.h.log_text()


def test_after_a_push_a_long_detour_is_refused_once_and_the_object_pushed_on():
    """Issue 28's h4: the box pushed along a passage longer than the push is still in the way, and the replan goes
    round the block. The old plan is followed again (push_on_max 1): blocked at the box, pushed on; the next
    detour is taken."""
    blocked_twice = [(GoalStatus.ABORTED, FollowPathResult.FAILURE, BLOCKED)] * 2 + [
        (GoalStatus.SUCCEEDED, FollowPathResult.SUCCESS, "goal reached")]
    scene = Scene("movable", blocked_twice, plans=0, push_distance_m=0.5, push_speed_mps=0.2, backoff_m=-0.3,
                  push_on_max=1)
    through = GetPathResult(code=GetPathResult.SUCCESS, plan=path([(0, 0), (3, 0)]))
    around = GetPathResult(code=GetPathResult.SUCCESS, plan=path([(0.2, 0), (0.2, 4), (3, 4), (3, 0)]))
    scene.planner.respond(GoalStatus.SUCCEEDED, through, delay_s=0.1)  # the first plan
    scene.planner.respond(GoalStatus.SUCCEEDED, around, delay_s=0.1)  # after the first push: 8.2 m vs 2.8 m
    scene.planner.respond(GoalStatus.SUCCEEDED, around, delay_s=0.1)  # after the second: taken
    scene.run_until("goal reached", 40.0)
    texts = scene.h.texts()
    assert sum("pushed 0.5" in t for t in texts) == 2, scene.h.log_text()
    assert any("following the old plan to push it on" in t for t in texts)
    assert any("kept 1 times for this goal already" in t for t in texts)
    follows = scene.follower.goals
    assert len(follows) == 3 and follows[1].path.poses == follows[0].path.poses  # the old plan again
    assert len(follows[2].path.poses) == len(around.plan.poses)  # then the detour


def test_by_default_the_detour_after_a_push_is_taken_at_once():
    scene = Scene("movable", BLOCKED_THEN_DONE, plans=0, push_distance_m=0.5)  # push_on_max 0
    scene.planner.respond(GoalStatus.SUCCEEDED, GetPathResult(code=GetPathResult.SUCCESS, plan=path([(0, 0), (3, 0)])),
                          delay_s=0.1)
    around = GetPathResult(code=GetPathResult.SUCCESS, plan=path([(0.2, 0), (0.2, 4), (3, 4), (3, 0)]))
    scene.planner.respond(GoalStatus.SUCCEEDED, around, delay_s=0.1)
    scene.run_until("goal reached", 30.0)
    assert len(scene.follower.goals) == 2 and len(scene.follower.goals[1].path.poses) == len(around.plan.poses)
    assert not any("push it on" in t for t in scene.h.texts())


def test_after_the_old_plan_was_kept_an_object_the_camera_calls_clear_is_pushed_on():
    """h4 seeds 3-4 with push_on_max 1: after the push the box lay further along the passage and, up close, the
    camera called its face clear; planning around it used up the tries and the goal was given up. Once the plan
    through a pushed object was kept for the goal, "clear" is pushed as well."""
    blocked_thrice = [(GoalStatus.ABORTED, FollowPathResult.FAILURE, BLOCKED)] * 3 + [
        (GoalStatus.SUCCEEDED, FollowPathResult.SUCCESS, "goal reached")]
    scene = Scene(lambda t: "movable" if t < 6.0 else "clear", blocked_thrice, plans=0, push_distance_m=0.5,
                  push_speed_mps=0.2, backoff_m=-0.3, push_on_max=1)
    through = GetPathResult(code=GetPathResult.SUCCESS, plan=path([(0, 0), (3, 0)]))
    around = GetPathResult(code=GetPathResult.SUCCESS, plan=path([(0.2, 0), (0.2, 4), (3, 4), (3, 0)]))
    for plan in (through, around, through, through):  # first; after push 1 (kept); after push 2; after push 3
        scene.planner.respond(GoalStatus.SUCCEEDED, plan, delay_s=0.1)
    scene.run_until("goal reached", 60.0)
    texts = scene.h.texts()
    assert sum("pushed 0.5" in t for t in texts) == 3, scene.h.log_text()
    # what followed each class: the pushes after "clear" are the new rule's
    after_clear = [texts[i + 1] for i, t in enumerate(texts) if t == "obstacle class: clear (camera only)"]
    assert len(after_clear) == 2 and all(t.startswith("pushed 0.5") for t in after_clear), scene.h.log_text()
    assert len(scene.follower.goals) == 4


def test_without_a_kept_plan_an_object_the_camera_calls_clear_is_planned_around_not_pushed():
    scene = Scene("clear", BLOCKED_THEN_DONE, plans=0, push_on_max=1)
    scene.planner.respond(GoalStatus.SUCCEEDED, GetPathResult(code=GetPathResult.SUCCESS, plan=path([(0, 0), (3, 0)])),
                          delay_s=0.1)
    around = GetPathResult(code=GetPathResult.SUCCESS, plan=path([(0.2, 0), (0.2, 4), (3, 4), (3, 0)]))
    scene.planner.respond(GoalStatus.SUCCEEDED, around, delay_s=0.1)
    scene.run_until("goal reached", 30.0)
    assert not any("pushed" in t for t in scene.h.texts()), scene.h.log_text()
    assert len(scene.follower.goals[1].path.poses) == len(around.plan.poses)
