"""Action-client states: result codes -> outcomes, server reasons logged, missing server, timeout, cancel on exit."""

from __future__ import annotations

import pytest
from actionlib_msgs.msg import GoalStatus
from nav_msgs.msg import Path
from unit.states.states_testlib import Harness, path, pose_stamped

from flex_nav.behavior import BehaviorStatus, ConcurrencyContainer, LogLevel, State
from flex_nav.exceptions import ConfigError
from flex_nav.msg import (
    ClearCostmapAction,
    ClearCostmapResult,
    FollowPathAction,
    FollowPathResult,
    FollowTopicAction,
    FollowTopicResult,
    GetPathAction,
    GetPathResult,
)
from flex_nav_states.action_base import SEND_WAIT_S, SERVER_LOST_S
from flex_nav_states.clear_costmaps_state import ClearCostmapsState
from flex_nav_states.follow_path_state import FollowPathState, FollowPlannerState
from flex_nav_states.follow_topic_state import FollowTopicState
from flex_nav_states.follow_until_blocked_state import FollowUntilBlockedState
from flex_nav_states.get_path_state import GetPathState

SUCCEEDED, ABORTED, PREEMPTED = GoalStatus.SUCCEEDED, GoalStatus.ABORTED, GoalStatus.PREEMPTED


def get_path_result(code: int, message: str, points=((0.0, 0.0), (1.0, 0.0))) -> GetPathResult:
    result = GetPathResult(code=code, message=message)
    if code == GetPathResult.SUCCESS:
        result.plan = path(list(points))
    return result


def get_path_harness(**params) -> Harness:
    state = GetPathState(**params)
    return Harness(state, inputs={"goal": pose_stamped(2.0, 1.0, 0.5, stamp_s=1000.0)})


# --- GetPath ------------------------------------------------------------------------------------------------


def test_get_path_planned_writes_the_plan_and_logs_the_reason():
    h = get_path_harness(action_name="planner")
    client = h.proxies.client("planner", GetPathAction)
    client.respond(SUCCEEDED, get_path_result(GetPathResult.SUCCESS, "plan of 2 poses"), delay_s=0.3)
    result = h.start().run(max_time_s=5.0)
    assert result.status is BehaviorStatus.FINISHED
    assert result.outcome == "planned"
    assert len(client.goals) == 1
    assert client.goals[0].pose.pose.position.x == 2.0
    assert client.goals[0].pose.header.frame_id == "map"
    assert [p.pose.position.x for p in result.outputs["plan"].poses] == [0.0, 1.0]
    assert any("plan of 2 poses" in t for t in h.texts())
    assert client.availability_checks and max(client.availability_checks) <= SEND_WAIT_S  # never waits long


@pytest.mark.parametrize(
    ("status", "code", "outcome", "level"),
    [
        (ABORTED, GetPathResult.EMPTY, "empty", LogLevel.WARN),
        (ABORTED, GetPathResult.FAILURE, "failed", LogLevel.ERROR),
        (SUCCEEDED, GetPathResult.FAILURE, "failed", LogLevel.ERROR),
        (ABORTED, GetPathResult.SUCCESS, "failed", LogLevel.ERROR),  # a success code with a failed status
        (PREEMPTED, GetPathResult.SUCCESS, "failed", LogLevel.WARN),  # cancelled elsewhere: default code 0
    ],
)
def test_get_path_maps_codes_and_logs_the_server_reason(status, code, outcome, level):
    h = get_path_harness()
    client = h.proxies.client("get_path_server", GetPathAction)
    client.respond(status, GetPathResult(code=code, message="goal in an obstacle at (2.00, 1.00)"))
    result = h.start().run(max_time_s=5.0)
    assert result.outcome == outcome
    reasons = [e for e in h.logs if "goal in an obstacle at (2.00, 1.00)" in e.message]
    assert reasons, h.log_text()
    assert reasons[-1].level == level


def test_get_path_without_result_message_fails_and_says_so():
    h = get_path_harness()
    client = h.proxies.client("get_path_server", GetPathAction)
    client.respond(ABORTED, None)
    assert h.start().run(max_time_s=5.0).outcome == "failed"
    assert any("no result" in t for t in h.texts(LogLevel.ERROR))


def test_get_path_success_with_empty_plan_is_not_planned():
    h = get_path_harness()
    client = h.proxies.client("get_path_server", GetPathAction)
    client.respond(SUCCEEDED, GetPathResult(code=GetPathResult.SUCCESS, message="ok"))
    result = h.start().run(max_time_s=5.0)
    assert result.outcome == "empty"
    assert "plan" not in result.outputs


def test_get_path_server_missing_fails_after_the_bound():
    h = get_path_harness(server_timeout_s=2.0)
    client = h.proxies.client("get_path_server", GetPathAction)
    client.available_at_s = float("inf")
    start = h.clock.now()
    result = h.start().run(max_time_s=10.0)
    assert result.outcome == "failed"
    assert 2.0 <= h.clock.now() - start <= 2.2
    assert client.goals == []
    assert any("get_path_server" in t and "not available" in t for t in h.texts(LogLevel.ERROR))


def test_get_path_server_connecting_late_within_the_bound_is_used():
    h = get_path_harness(server_timeout_s=2.0)
    client = h.proxies.client("get_path_server", GetPathAction)
    client.available_at_s = h.clock.now() + 1.5
    client.respond(SUCCEEDED, get_path_result(GetPathResult.SUCCESS, "ok"))
    assert h.start().run(max_time_s=10.0).outcome == "planned"
    assert client.sent_at[0] >= client.available_at_s


def test_get_path_timeout_cancels_the_goal():
    h = get_path_harness(timeout_s=1.0)
    client = h.proxies.client("get_path_server", GetPathAction)  # no response: the goal stays active
    client.preempt_on_cancel = False
    result = h.start().run(max_time_s=5.0)
    assert result.outcome == "failed"
    assert client.cancels == 1
    assert any("timeout_s" in t for t in h.texts(LogLevel.ERROR))


def test_get_path_preempt_cancels_the_active_goal():
    h = get_path_harness()
    client = h.proxies.client("get_path_server", GetPathAction)
    h.start()
    h.run_for(0.5)
    assert client.is_active()
    h.executor.preempt()
    assert h.tick()
    assert h.executor.status is BehaviorStatus.PREEMPTED
    assert client.cancels == 1
    assert not client.is_active()


def test_get_path_rejects_a_goal_that_is_not_a_pose():
    h = Harness(GetPathState(), inputs={"goal": "kitchen"})
    client = h.proxies.client("get_path_server", GetPathAction)
    assert h.start().run(max_time_s=2.0).outcome == "failed"
    assert client.goals == []
    assert any("PoseStamped" in t for t in h.texts(LogLevel.ERROR))


@pytest.mark.parametrize(
    "params",
    [{"action_name": ""}, {"action_name": "a b"}, {"server_timeout_s": 0.0}, {"timeout_s": -1.0},
     {"timeout_s": float("nan")}],
)
def test_get_path_parameters_are_validated(params):
    with pytest.raises(ConfigError, match=next(iter(params))):
        GetPathState(**params)


# --- FollowPath / FollowPlanner / FollowTopic --------------------------------------------------------------


@pytest.mark.parametrize(
    ("status", "code", "outcome"),
    [
        (SUCCEEDED, FollowPathResult.SUCCESS, "done"),
        (ABORTED, FollowPathResult.FAILURE, "failed"),
        (PREEMPTED, FollowPathResult.PREEMPT, "preempted"),
        (PREEMPTED, FollowPathResult.SUCCESS, "preempted"),
        (ABORTED, FollowPathResult.PREEMPT, "preempted"),
    ],
)
@pytest.mark.parametrize("cls", [FollowPathState, FollowPlannerState])
def test_follow_path_maps_codes(cls, status, code, outcome):
    state = cls(action_name="follower")
    h = Harness(state, inputs={"plan": path([(0, 0), (1, 0), (2, 0)])})
    client = h.proxies.client("follower", FollowPathAction)
    client.respond(status, FollowPathResult(code=code, message="path blocked for 5.0 s"), delay_s=1.0)
    assert h.start().run(max_time_s=5.0).outcome == outcome
    assert len(client.goals[0].path.poses) == 3
    assert any("path blocked for 5.0 s" in t for t in h.texts())


def test_follow_defaults_point_at_the_shipped_servers():
    assert FollowPathState().action_name == "pure_pursuit_path"
    assert FollowPlannerState().action_name == "follow_path_server"
    assert FollowTopicState().action_name == "pure_pursuit_topic"
    assert GetPathState().action_name == "get_path_server"


def test_follow_path_refuses_an_empty_plan_without_sending():
    h = Harness(FollowPathState(), inputs={"plan": path([])})
    client = h.proxies.client("pure_pursuit_path", FollowPathAction)
    assert h.start().run(max_time_s=2.0).outcome == "failed"
    assert client.goals == []
    assert any("empty" in t for t in h.texts(LogLevel.ERROR))


class Bumper(State):
    """Test monitor: returns ``hit`` at a given time."""

    def __init__(self, at_s: float) -> None:
        super().__init__(outcomes=["hit"])
        self.at_s = at_s

    def execute(self, userdata):
        return "hit" if self.now_s() >= self.at_s else None


def test_follow_path_goal_is_cancelled_when_a_monitor_ends_the_concurrency():
    cc = ConcurrencyContainer(
        outcomes=["arrived", "bumped", "failed"],
        conditions=[("bumped", [("Monitor", "hit")]), ("arrived", [("Follow", "done")]),
                    ("failed", [("Follow", "failed")]), ("failed", [("Follow", "preempted")])],
        input_keys=["plan"],
    )
    cc.add("Follow", FollowPathState())
    cc.add("Monitor", Bumper(at_s=1002.0))
    h = Harness(cc, inputs={"plan": path([(0, 0), (5, 0)])})
    client = h.proxies.client("pure_pursuit_path", FollowPathAction)
    result = h.start().run(max_time_s=10.0)
    assert result.outcome == "bumped"
    assert client.cancels == 1
    assert any("cancelled" in t for t in h.texts())


def test_follow_path_pause_cancels_and_resume_sends_again():
    h = Harness(FollowPathState(), inputs={"plan": path([(0, 0), (5, 0)])})
    client = h.proxies.client("pure_pursuit_path", FollowPathAction)
    h.start()
    h.run_for(0.5)
    assert len(client.goals) == 1
    h.executor.pause()
    h.tick()
    assert client.cancels == 1
    assert not client.is_active()
    h.advance(3.0)
    h.executor.resume()
    h.tick()
    h.run_for(0.2)
    assert len(client.goals) == 2
    assert client.is_active()
    client.finish(SUCCEEDED, FollowPathResult(code=FollowPathResult.SUCCESS, message="arrived"))
    assert h.run(max_time_s=2.0).outcome == "done"


def test_follow_path_result_before_exit_is_not_cancelled():
    h = Harness(FollowPathState(), inputs={"plan": path([(0, 0), (1, 0)])})
    client = h.proxies.client("pure_pursuit_path", FollowPathAction)
    client.respond(SUCCEEDED, FollowPathResult(code=FollowPathResult.SUCCESS, message="arrived"))
    assert h.start().run(max_time_s=2.0).outcome == "done"
    assert client.cancels == 0


@pytest.mark.parametrize("final_heading", [True, False])
@pytest.mark.parametrize("cls", [FollowPathState, FollowPlannerState, FollowUntilBlockedState])
def test_follow_path_goal_says_whether_the_final_heading_counts(cls, final_heading):
    h = Harness(cls(final_heading=final_heading), inputs={"plan": path([(0, 0), (1, 0)])})
    client = h.proxies.client(cls().action_name, FollowPathAction)
    client.respond(SUCCEEDED, FollowPathResult(code=FollowPathResult.SUCCESS, message="arrived"))
    assert h.start().run(max_time_s=2.0).outcome == "done"
    assert client.goals[0].ignore_final_heading is (not final_heading)
    assert any(("to its final heading" in t) is final_heading for t in h.texts())


@pytest.mark.parametrize("final_heading", [True, False])
def test_follow_topic_goal_says_whether_the_final_heading_counts(final_heading):
    h = Harness(FollowTopicState(path_topic="mid/plan", action_name="ctrl", final_heading=final_heading))
    client = h.proxies.client("ctrl", FollowTopicAction)
    client.respond(SUCCEEDED, FollowTopicResult(code=FollowTopicResult.SUCCESS, message="arrived"))
    assert h.start().run(max_time_s=2.0).outcome == "done"
    assert client.goals[0].ignore_final_heading is (not final_heading)


@pytest.mark.parametrize("cls", [FollowPathState, FollowTopicState])
@pytest.mark.parametrize("value", [1, "true", None])
def test_final_heading_must_be_a_boolean(cls, value):
    with pytest.raises(ConfigError, match="final_heading must be true or false"):
        cls(final_heading=value)


def test_follow_topic_sends_the_topic_and_maps_failure():
    h = Harness(FollowTopicState(path_topic="mid/plan", action_name="ctrl"))
    client = h.proxies.client("ctrl", FollowTopicAction)
    client.respond(ABORTED, FollowTopicResult(code=FollowTopicResult.FAILURE, message="no path on mid/plan"))
    assert h.start().run(max_time_s=2.0).outcome == "failed"
    assert client.goals[0].topic.data == "mid/plan"
    assert any("no path on mid/plan" in t for t in h.texts(LogLevel.ERROR))


def test_follow_topic_with_fresh_path_never_sends_for_the_previous_goals_plan():
    """move_base_like's latched plan topic still holds the previous goal's plan; the first replans fail."""
    h = Harness(FollowTopicState(path_topic="mb/plan", fresh_path_s=3.0))
    client = h.proxies.client("pure_pursuit_topic", FollowTopicAction)
    h.proxies.subscription("mb/plan", Path).inject(path([(0, 0), (5, 0)], stamp_s=h.clock.now() - 10.0))
    start = h.clock.now()
    result = h.start().run(max_time_s=10.0)
    assert result.outcome == "failed" and client.goals == []
    assert h.clock.now() - start == pytest.approx(3.0, abs=0.15)
    assert any("no path on mb/plan newer than this goal within fresh_path_s 3 s" in t
               for t in h.texts(LogLevel.ERROR)), h.log_text()


def test_follow_topic_with_fresh_path_sends_once_a_new_plan_comes():
    h = Harness(FollowTopicState(path_topic="mb/plan", fresh_path_s=3.0))
    client = h.proxies.client("pure_pursuit_topic", FollowTopicAction)
    plans = h.proxies.subscription("mb/plan", Path)
    plans.inject(path([(0, 0), (5, 0)], stamp_s=h.clock.now() - 10.0))
    h.start().run_for(1.0)
    assert client.goals == []
    plans.inject(path([(0, 0), (2, 0)], stamp_s=h.clock.now()))  # the first plan for this goal
    h.run_for(0.2)
    assert len(client.goals) == 1 and client.goals[0].topic.data == "mb/plan"


def test_follow_topic_goal_says_from_when_a_path_counts_as_fresh():
    """With fresh_path_s (or follow_next_path) the state sends the goal only with a Path stamped since entry, so
    the goal carries the entry time and the server takes that Path without waiting for a newer one; without
    either, newer_than stays 0 and the server counts from the goal's start."""
    h = Harness(FollowTopicState(path_topic="mb/plan", fresh_path_s=3.0))
    client = h.proxies.client("pure_pursuit_topic", FollowTopicAction)
    entered_s = h.clock.now()
    h.start().run_for(0.5)
    h.proxies.subscription("mb/plan", Path).inject(path([(0, 0), (2, 0)], stamp_s=h.clock.now()))
    h.run_for(0.2)
    assert len(client.goals) == 1
    assert client.goals[0].newer_than.to_sec() == pytest.approx(entered_s, abs=1e-6)
    plain = Harness(FollowTopicState(path_topic="mid/plan"))
    plain_client = plain.proxies.client("pure_pursuit_topic", FollowTopicAction)
    plain.start().run_for(0.2)
    assert len(plain_client.goals) == 1 and plain_client.goals[0].newer_than.is_zero()


def test_follow_topic_server_timeout_counts_from_the_fresh_path_not_from_entry():
    """A wait for a fresh path longer than server_timeout_s must not use up the server's grace."""
    h = Harness(FollowTopicState(path_topic="mb/plan", fresh_path_s=10.0, server_timeout_s=1.0))
    client = h.proxies.client("pure_pursuit_topic", FollowTopicAction)
    client.available_at_s = h.clock.now() + 6.5  # the controller restarts while the planner is still planning
    plans = h.proxies.subscription("mb/plan", Path)
    h.start().run_for(6.0)
    plans.inject(path([(0, 0), (2, 0)], stamp_s=h.clock.now()))
    h.run_for(1.0)  # the server is back 0.5 s after the fresh plan, within its 1 s grace: not failed
    assert len(client.goals) == 1, h.log_text()


def test_follow_topic_following_the_next_path_is_never_done_and_resumes_on_a_newer_path():
    """Beside a planner: the local plan ended short of the goal (someone stands on it); the controller must
    follow the planner's next plan, not stay idle until a stuck monitor fires."""
    h = Harness(FollowTopicState(path_topic="mid/plan", follow_next_path=True))
    client = h.proxies.client("pure_pursuit_topic", FollowTopicAction)
    plans = h.proxies.subscription("mid/plan", Path)
    client.respond(GoalStatus.SUCCEEDED, FollowTopicResult(code=FollowTopicResult.SUCCESS, message="goal reached"))
    h.start().run_for(2.0)  # the first goal ends at once; the plan on the topic is not newer: nothing sent
    assert len(client.goals) == 1
    assert any("following the next one" in t for t in h.texts())
    plans.inject(path([(0, 0), (3, 0)], stamp_s=h.clock.now()))  # the planner's next plan
    h.run_for(0.2)
    assert len(client.goals) == 2 and client.is_active()
    h.executor.preempt()  # the planner arrived: the container ends it
    h.tick()
    assert client.cancels == 1


def test_follow_topic_preempt_cancels():
    h = Harness(FollowTopicState())
    client = h.proxies.client("pure_pursuit_topic", FollowTopicAction)
    h.start()
    h.run_for(1.0)
    h.executor.preempt()
    h.tick()
    assert client.cancels == 1


def test_follow_topic_server_missing_fails():
    h = Harness(FollowTopicState(server_timeout_s=1.0))
    h.proxies.client("pure_pursuit_topic", FollowTopicAction).available_at_s = float("inf")
    assert h.start().run(max_time_s=5.0).outcome == "failed"
    assert any("pure_pursuit_topic" in t and "not available" in t for t in h.texts(LogLevel.ERROR))



def test_a_server_that_goes_away_during_the_goal_fails_it_even_without_a_timeout():
    h = Harness(FollowTopicState(timeout_s=0.0))  # no limit on the goal's run time
    client = h.proxies.client("pure_pursuit_topic", FollowTopicAction)
    h.start().run_for(1.0)
    assert len(client.goals) == 1 and client.active_goal is not None
    client.available_at_s = float("inf")  # the controller node died: its connections dropped
    gone_s = h.clock.now()
    result = h.run(max_time_s=10.0)
    assert result.outcome == "failed"
    assert h.clock.now() - gone_s == pytest.approx(SERVER_LOST_S, abs=0.2)
    assert any("went away during the goal" in t for t in h.texts(LogLevel.ERROR)), h.log_text()


def test_a_server_reconnecting_within_the_grace_keeps_the_goal():
    h = Harness(FollowTopicState(timeout_s=0.0))
    client = h.proxies.client("pure_pursuit_topic", FollowTopicAction)
    h.start().run_for(1.0)
    client.available_at_s = float("inf")
    h.run_for(0.5 * SERVER_LOST_S)
    client.available_at_s = h.clock.now()  # back (a dropped connection re-made)
    h.run_for(2.0 * SERVER_LOST_S)  # still running: the lost time starts again from zero next time
    assert len(client.goals) == 1

# --- ClearCostmaps ------------------------------------------------------------------------------------------

NAMES = ["global/clear_costmap", "local/clear_costmap", "mid/clear_costmap"]


def clear_harness(timeout_s: float = 3.0):
    h = Harness(ClearCostmapsState(costmaps=NAMES, timeout_s=timeout_s))
    clients = [h.proxies.client(n, ClearCostmapAction) for n in NAMES]
    return h, clients


def ok(message: str = "cleared") -> ClearCostmapResult:
    return ClearCostmapResult(code=ClearCostmapResult.SUCCESS, message=message)


def test_clear_costmaps_clears_all_concurrently():
    h, clients = clear_harness()
    for client in clients:
        client.respond(SUCCEEDED, ok(), delay_s=1.0)
    start = h.clock.now()
    assert h.start().run(max_time_s=5.0).outcome == "done"
    assert [len(c.goals) for c in clients] == [1, 1, 1]
    assert max(c.sent_at[0] for c in clients) == start  # all sent on the first tick, before any result
    assert h.clock.now() - start < 1.5  # the three 1 s waits overlapped


def test_clear_costmaps_one_failure_fails_and_names_it():
    h, clients = clear_harness()
    clients[0].respond(SUCCEEDED, ok())
    clients[1].respond(ABORTED, ClearCostmapResult(code=ClearCostmapResult.FAILURE, message="local has no map yet"))
    clients[2].respond(SUCCEEDED, ok())
    assert h.start().run(max_time_s=5.0).outcome == "failed"
    errors = h.texts(LogLevel.ERROR)
    assert any("local/clear_costmap" in t and "local has no map yet" in t for t in errors)


def test_clear_costmaps_missing_server_fails_within_the_bound():
    h, clients = clear_harness(timeout_s=2.0)
    clients[0].respond(SUCCEEDED, ok())
    clients[1].available_at_s = float("inf")
    clients[2].respond(SUCCEEDED, ok())
    start = h.clock.now()
    assert h.start().run(max_time_s=10.0).outcome == "failed"
    assert h.clock.now() - start <= 2.2
    assert any("local/clear_costmap" in t and "not available" in t for t in h.texts(LogLevel.ERROR))


def test_clear_costmaps_timeout_cancels_unanswered_goals():
    h, clients = clear_harness(timeout_s=2.0)
    clients[0].respond(SUCCEEDED, ok())
    clients[1].respond(SUCCEEDED, ok())
    assert h.start().run(max_time_s=10.0).outcome == "failed"
    assert clients[2].cancels == 1
    assert clients[0].cancels == clients[1].cancels == 0


def test_clear_costmaps_preempt_cancels_active_goals():
    h, clients = clear_harness()
    clients[0].respond(SUCCEEDED, ok())
    h.start()
    h.run_for(0.5)
    h.executor.preempt()
    h.tick()
    assert [c.cancels for c in clients] == [0, 1, 1]


@pytest.mark.parametrize("costmaps", [[], "global/clear_costmap", ["a", "a"], [""]])
def test_clear_costmaps_validates_the_list(costmaps):
    with pytest.raises(ConfigError, match="costmaps"):
        ClearCostmapsState(costmaps=costmaps)


def test_clear_costmaps_paused_time_does_not_count():
    h, clients = clear_harness(timeout_s=2.0)
    clients[0].respond(SUCCEEDED, ok())
    clients[1].respond(SUCCEEDED, ok())
    h.start()
    h.run_for(1.0)
    h.executor.pause()
    h.tick()
    h.advance(10.0)
    h.executor.resume()
    h.tick()
    h.run_for(0.8)  # 1.8 s of unpaused time: still waiting for the third server
    clients[2].finish(SUCCEEDED, ok())
    assert h.run(max_time_s=1.0).outcome == "done"


@pytest.mark.parametrize("topic", ["..", "a/../b", "plan/", "1plan"])
def test_follow_topic_state_refuses_an_illegal_topic_at_load_time(topic: str) -> None:
    # before: taken as given; the servers waited topic_timeout for a Path on it and failed 2 s later
    with pytest.raises(ConfigError, match="not a legal ROS name"):
        FollowTopicState(path_topic=topic)
