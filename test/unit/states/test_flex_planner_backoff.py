"""behaviors/flex_planner.yaml: replans of one goal are spaced by the back-off, so a fault lasting a few seconds
does not use every replan up at once (before: five replans within about a second, then the goal given up)."""

from __future__ import annotations

from pathlib import Path

from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped
from unit.states.states_testlib import Harness, path, pose_stamped

from flex_nav.behavior.autonomy import Autonomy
from flex_nav.behavior.yaml_loader import load_behavior
from flex_nav.msg import ClearCostmapAction, ClearCostmapResult, GetPathAction, GetPathResult

REPO = Path(__file__).resolve().parents[3]
STEP_S = 0.05  # [s]


def test_replans_are_spaced_by_a_doubling_back_off_before_the_goal_is_given_up() -> None:
    behavior = load_behavior(REPO / "behaviors" / "flex_planner.yaml", parameters={"navigate": "navigate_fails"},
                             search_path=[REPO / "test" / "data" / "behaviors", REPO / "behaviors"])
    h = Harness(behavior.root, autonomy=Autonomy.FULL)
    for name in ("get_path_server/clear_costmap", "follow_path_server/clear_costmap",
                 "pure_pursuit_topic/clear_costmap"):
        h.proxies.client(name, ClearCostmapAction).respond(
            GoalStatus.SUCCEEDED, ClearCostmapResult(code=ClearCostmapResult.SUCCESS))
    planner = h.proxies.client("get_path_server", GetPathAction)
    for _ in range(8):
        planner.respond(GoalStatus.SUCCEEDED, GetPathResult(code=GetPathResult.SUCCESS, plan=path([(0, 0), (3, 0)])))
    h.start()
    h.proxies.subscription("move_base_simple/goal", PoseStamped).inject(pose_stamped(3.0, 0.0, stamp_s=h.clock.now()))
    end_s = h.clock.now() + 30.0
    while h.clock.now() < end_s and not any("giving up this goal" in t for t in h.texts()):
        assert not h.tick(), h.log_text()
        h.advance(STEP_S)
    assert any("giving up this goal" in t for t in h.texts()), h.log_text()
    gaps = [b - a for a, b in zip(planner.sent_at, planner.sent_at[1:])]
    assert len(planner.sent_at) == 6, gaps  # the first plan and max_replans (5) replans
    for gap, backoff_s in zip(gaps, [0.5, 1.0, 2.0, 4.0, 4.0]):
        assert backoff_s <= gap <= backoff_s + 0.5, gaps  # the back-off, plus the few ticks of the states between
    assert planner.sent_at[-1] - planner.sent_at[0] >= 11.5
