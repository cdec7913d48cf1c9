"""ReplanState: plans every period, publishes each plan, gives up after failures in a row, cancels on exit."""

from __future__ import annotations

import pytest
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path
from unit.states.states_testlib import Harness

from flex_nav.behavior import BehaviorStatus, LogLevel
from flex_nav.msg import GetPathAction, GetPathResult
from flex_nav_states.action_base import SERVER_LOST_S
from flex_nav_states.replan_state import ReplanState


def _goal() -> PoseStamped:
    goal = PoseStamped()
    goal.header.frame_id = "map"
    goal.pose.position.x = 3.0
    goal.pose.orientation.w = 1.0
    return goal


def _plan(x_end: float) -> GetPathResult:
    result = GetPathResult(code=GetPathResult.SUCCESS, message="ok")
    result.plan.header.frame_id = "map"  # stamped 0: the planner's stamp is not the publication's
    for x in (0.0, x_end):
        pose = PoseStamped()
        pose.header.frame_id = "map"
        pose.pose.position.x = x
        result.plan.poses.append(pose)
    return result


def test_plans_every_period_and_publishes_each_plan() -> None:
    h = Harness(ReplanState(period_s=1.0, plan_topic="mb/plan"), inputs={"goal": _goal()})
    client = h.proxies.client("get_path_server", GetPathAction)
    for x_end in (3.0, 2.9, 2.8):
        client.respond(GoalStatus.SUCCEEDED, _plan(x_end), delay_s=0.1)
    h.start()
    h.run_for(2.5, step_s=0.05)
    assert len(client.goals) == 3  # at 0, 1 and 2 s
    gaps = [b - a for a, b in zip(client.sent_at, client.sent_at[1:])]
    assert all(1.0 <= gap <= 1.0 + 0.1 + 1e-9 for gap in gaps), gaps  # the period, late by at most one tick
    published = h.proxies.publishers["mb/plan"].messages
    assert [m.poses[-1].pose.position.x for m in published] == [3.0, 2.9, 2.8]
    assert all(isinstance(m, Path) for m in published)
    # each stamped at its publication: a tick that took the answer in (answered 0.1 s after the request)
    for sent_s, plan in zip(client.sent_at, published):
        assert sent_s + 0.1 - 1e-9 <= plan.header.stamp.to_sec() <= sent_s + 0.2 + 1e-9, (sent_s, plan.header)
        assert plan.header.frame_id == "map"


def test_gives_up_after_failures_in_a_row_with_the_reason() -> None:
    h = Harness(ReplanState(period_s=0.5, max_failures=2), inputs={"goal": _goal()})
    client = h.proxies.client("get_path_server", GetPathAction)
    client.respond(GoalStatus.SUCCEEDED, _plan(3.0))
    client.respond(GoalStatus.ABORTED, GetPathResult(code=GetPathResult.EMPTY, message="goal in an obstacle"))
    client.respond(GoalStatus.SUCCEEDED, _plan(3.0))  # a success resets the count
    client.respond(GoalStatus.ABORTED, GetPathResult(code=GetPathResult.EMPTY, message="goal in an obstacle"))
    client.respond(GoalStatus.ABORTED, GetPathResult(code=GetPathResult.FAILURE, message="no transform"))
    result = h.start().run(max_time_s=10.0)
    assert result.status is BehaviorStatus.FINISHED and result.outcome == "failed"
    assert len(client.goals) == 5
    assert any("goal in an obstacle" in t for t in h.texts()) and any("no transform" in t for t in h.texts())


def test_missing_server_fails_in_bounded_time() -> None:
    h = Harness(ReplanState(server_timeout_s=2.0), inputs={"goal": _goal()})
    client = h.proxies.client("get_path_server", GetPathAction)
    client.available_at_s = float("inf")
    result = h.start().run(max_time_s=5.0)
    assert result.outcome == "failed"
    assert h.clock.now() - 1000.0 <= 2.5
    assert any("not available" in t for t in h.texts())


def test_exit_cancels_the_plan_in_flight() -> None:
    h = Harness(ReplanState(), inputs={"goal": _goal()})
    client = h.proxies.client("get_path_server", GetPathAction)
    client.respond(GoalStatus.SUCCEEDED, _plan(3.0), delay_s=5.0)
    h.start()
    h.run_for(0.3)
    assert client.is_active()
    h.executor.preempt("test")
    h.tick()
    assert client.cancels == 1


def test_a_server_that_goes_away_during_a_plan_fails_the_state_in_bounded_time() -> None:
    h = Harness(ReplanState(period_s=1.0, plan_timeout_s=60.0), inputs={"goal": _goal()})
    client = h.proxies.client("get_path_server", GetPathAction)  # no response queued: the request stays out
    h.start().run_for(0.5)
    assert len(client.goals) == 1 and client.is_active()
    client.available_at_s = float("inf")  # get_path_server died mid-plan
    gone_s = h.clock.now()
    result = h.run(max_time_s=10.0)
    assert result.outcome == "failed"
    assert h.clock.now() - gone_s == pytest.approx(SERVER_LOST_S, abs=0.2)
    assert client.cancels == 1
    assert any("went away during a plan" in t for t in h.texts(LogLevel.ERROR)), h.log_text()


def test_an_unanswered_plan_is_cancelled_counted_and_planned_again() -> None:
    h = Harness(ReplanState(period_s=1.0, plan_timeout_s=2.0, max_failures=2), inputs={"goal": _goal()})
    client = h.proxies.client("get_path_server", GetPathAction)  # connected, never answers
    result = h.start().run(max_time_s=20.0)
    assert result.outcome == "failed"
    assert len(client.goals) == 2 and client.cancels == 2
    assert h.clock.now() - 1000.0 == pytest.approx(4.0, abs=0.2)  # two requests of 2 s each
    assert sum("no answer within plan_timeout_s 2 s" in t for t in h.texts()) == 2, h.log_text()


def test_failed_plans_are_spaced_by_a_doubling_back_off() -> None:
    # period 0.5 s, back-off at most 1.5 s: after failures in a row the starts are 0.5, 1.0, 1.5, 1.5 s apart; a
    # success goes back to the period. Without the back-off every gap was the period (fails then).
    h = Harness(ReplanState(period_s=0.5, max_failures=10, backoff_max_s=1.5), inputs={"goal": _goal()})
    client = h.proxies.client("get_path_server", GetPathAction)
    for _ in range(4):
        client.respond(GoalStatus.ABORTED, GetPathResult(code=GetPathResult.FAILURE, message="no pose"))
    client.respond(GoalStatus.SUCCEEDED, _plan(3.0))
    client.respond(GoalStatus.SUCCEEDED, _plan(3.0))
    h.start()
    h.run_for(6.5, step_s=0.05)
    gaps = [b - a for a, b in zip(client.sent_at, client.sent_at[1:])]
    assert len(gaps) >= 5, gaps
    for gap, expected in zip(gaps, [0.5, 1.0, 1.5, 1.5, 0.5]):
        assert expected - 1e-9 <= gap <= expected + 0.16, gaps  # late by at most a tick (10 Hz) and a step


def test_the_back_off_never_goes_below_the_period() -> None:
    h = Harness(ReplanState(period_s=2.0, max_failures=10, backoff_max_s=0.5), inputs={"goal": _goal()})
    client = h.proxies.client("get_path_server", GetPathAction)
    for _ in range(3):
        client.respond(GoalStatus.ABORTED, GetPathResult(code=GetPathResult.FAILURE, message="no pose"))
    h.start()
    h.run_for(5.0, step_s=0.05)
    gaps = [b - a for a, b in zip(client.sent_at, client.sent_at[1:])]
    assert gaps and all(2.0 - 1e-9 <= gap <= 2.11 for gap in gaps), gaps
