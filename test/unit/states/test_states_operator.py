"""Operator states: the decision's suggestion gated by autonomy and answered by the operator; log; wait."""

from __future__ import annotations

import pytest
from unit.states.states_testlib import Harness, path, pose_stamped

from flex_nav.behavior import Autonomy, BehaviorStatus, LogLevel, StateMachine
from flex_nav.exceptions import ConfigError
from flex_nav_states.goal_list_state import GoalListState
from flex_nav_states.log_state import LogState
from flex_nav_states.operator_decision_state import OperatorDecisionState
from flex_nav_states.wait_state import WaitState


def decision_machine(suggestion: str = "yes") -> StateMachine:
    sm = StateMachine(outcomes=["approved", "rejected", "replan"])
    sm.add(
        "Approve",
        OperatorDecisionState(outcomes=["yes", "no", "replan"], hint="Execute this plan?", suggestion=suggestion),
        transitions={"yes": "approved", "no": "rejected", "replan": "replan"},
        autonomy={"yes": "low", "no": "full", "replan": "full"},
    )
    return sm


def test_decision_fires_its_suggestion_at_full_autonomy():
    h = Harness(decision_machine(), autonomy=Autonomy.FULL)
    assert h.start().run(max_time_s=2.0).outcome == "approved"
    hints = [e.message for e in h.logs if e.level == LogLevel.HINT]
    assert hints == ["Execute this plan? [yes, no, replan]; suggested: yes"]


def test_decision_at_low_autonomy_waits_for_the_operator_approval():
    h = Harness(decision_machine(), autonomy=Autonomy.LOW)
    h.start()
    h.run_for(5.0)  # requested, not fired
    requests = h.executor.requested_outcomes()
    assert [(r.path, r.outcome) for r in requests] == [("/Approve", "yes")]
    h.executor.approve("/Approve")
    assert h.run(max_time_s=1.0).outcome == "approved"


def test_decision_operator_can_choose_another_outcome():
    h = Harness(decision_machine(), autonomy=Autonomy.LOW)
    h.start()
    h.run_for(1.0)
    h.executor.force_transition("/Approve", "replan")
    assert h.run(max_time_s=1.0).outcome == "replan"


def test_decision_without_suggestion_waits_even_at_full_autonomy():
    h = Harness(decision_machine(suggestion=""), autonomy=Autonomy.FULL)
    h.start()
    h.run_for(5.0)
    assert h.executor.status is BehaviorStatus.RUNNING
    assert h.executor.requested_outcomes() == []
    assert any("no suggestion" in e.message for e in h.logs)
    h.executor.force_transition("/Approve", "no")
    assert h.run(max_time_s=1.0).outcome == "rejected"


@pytest.mark.parametrize(
    ("params", "match"),
    [({"outcomes": []}, "outcomes"), ({"outcomes": "yes"}, "outcomes"), ({"suggestion": "maybe"}, "maybe"),
     ({"outcomes": ["yes", "yes"]}, "repeats")],
)
def test_decision_parameters_are_validated(params, match):
    with pytest.raises(ConfigError, match=match):
        OperatorDecisionState(**params)


def test_log_fills_in_userdata_values():
    state = LogState(text="reached {goal} along {plan}", severity="warn", keys=["goal", "plan"])
    assert state.input_keys == ("goal", "plan")
    h = Harness(state, inputs={"goal": pose_stamped(1.0, 2.0, 0.0), "plan": path([(0, 0), (3, 4)])})
    assert h.start().run(max_time_s=1.0).outcome == "done"
    warned = [e.message for e in h.logs if e.level == LogLevel.WARN]
    assert warned == ["reached (1.00, 2.00, 0 deg) in map along path of 2 poses, 5.00 m in map"]


def test_log_plain_text_and_braces_that_are_not_placeholders():
    h = Harness(LogState(text="Flex Planner {v2} ready", keys=["v2"]), inputs={"v2": 0.5})
    h.start().run(max_time_s=1.0)
    assert any(e.message == "Flex Planner 0.5 ready" for e in h.logs)


@pytest.mark.parametrize(
    ("params", "match"),
    [({"text": "at {goal}"}, "goal"), ({"text": "x", "severity": "fatal"}, "severity"), ({"text": 3}, "text"),
     ({"text": "x", "keys": "goal"}, "keys")],
)
def test_log_parameters_are_validated(params, match):
    with pytest.raises(ConfigError, match=match):
        LogState(**params)


def test_wait_waits_on_the_behavior_clock():
    h = Harness(WaitState(wait_time_s=2.5))
    start = h.clock.now()
    assert h.start().run(max_time_s=5.0).outcome == "done"
    assert 2.5 <= h.clock.now() - start <= 2.6


def goal_loop(loops: int) -> StateMachine:
    sm = StateMachine(outcomes=["finished"], output_keys=["goal", "goal_index"])
    sm.add("Next", GoalListState(goals=[[1.0, 2.0, 90.0], [3.0, 4.0, -90.0]], frame_id="map", loops=loops),
           transitions={"next": "Drive", "done": "finished"})
    sm.add("Drive", WaitState(wait_time_s=1.0), transitions={"done": "Next"})
    return sm


def test_goal_list_hands_out_the_goals_in_order_then_done():
    h = Harness(goal_loop(loops=2))
    result = h.start().run(max_time_s=20.0)
    assert result.outcome == "finished"
    logged = [e.message for e in h.logs if e.message.startswith("goal ")]
    assert logged == [
        "goal 1/4: (1.00, 2.00, 90 deg) in map",
        "goal 2/4: (3.00, 4.00, -90 deg) in map",
        "goal 3/4: (1.00, 2.00, 90 deg) in map",
        "goal 4/4: (3.00, 4.00, -90 deg) in map",
    ]
    assert result.outputs["goal_index"] == 4
    goal = result.outputs["goal"]
    assert goal.header.frame_id == "map"
    handed_out_s = next(e.time_s for e in h.logs if e.message.startswith("goal 4/4"))
    assert goal.header.stamp.to_sec() == pytest.approx(handed_out_s)  # stamped when handed out
    assert handed_out_s >= 1003.0  # after three 1 s drives


def test_goal_list_forever():
    h = Harness(goal_loop(loops=0))
    h.start()
    h.run_for(30.0)
    assert sum(e.message.startswith("goal ") for e in h.logs) >= 14


@pytest.mark.parametrize(
    ("params", "match"),
    [({"goals": []}, "goals"), ({"goals": [[1.0, 2.0]]}, "goals\\[0\\]"), ({"goals": [[1.0, "a", 0.0]]}, "goals"),
     ({"loops": -1}, "loops"), ({"loops": 1.5}, "loops"), ({"frame_id": ""}, "frame_id")],
)
def test_goal_list_parameters_are_validated(params, match):
    with pytest.raises(ConfigError, match=match):
        GoalListState(**params)
