"""The builtin states: behavior on the manual clock and validation of their parameters."""

from __future__ import annotations

import pytest
from unit.behavior.behavior_testlib import executor, record_events

from flex_nav.behavior import BehaviorStatus, LogLevel, StateMachine
from flex_nav.behavior.builtin_states import Calculation, Compare, Decision, Log, Wait
from flex_nav.exceptions import ConfigError


def run_single(state, outcomes_map):
    sm = StateMachine(outcomes=sorted(set(outcomes_map.values())))
    sm.add("S", state, transitions=outcomes_map)
    ex = executor(sm)
    events = record_events(ex)
    return ex.run(timeout_s=60.0), events


def test_wait_finishes_after_its_time():
    result, events = run_single(Wait(wait_time_s=1.25), {"done": "finished"})
    assert result.status is BehaviorStatus.FINISHED
    assert events["transition"][0].time_s == pytest.approx(1.3)  # first tick at or after 1.25 s at 10 Hz


@pytest.mark.parametrize("bad", [-1.0, float("inf"), "1", True])
def test_wait_rejects_bad_times(bad):
    with pytest.raises(ConfigError, match="wait_time_s"):
        Wait(wait_time_s=bad)


def test_log_logs_once_at_its_severity():
    _, events = run_single(Log("careful", "warn"), {"done": "finished"})
    assert [(e.level, e.message, e.path) for e in events["log"]] == [(LogLevel.WARN, "careful", "/S")]
    with pytest.raises(ConfigError, match=r"severity 'loud' is not valid \(valid: info, warn, hint, error\)"):
        Log("x", "loud")


def test_decision_returns_its_choice():
    result, _ = run_single(Decision(["left", "right"], "right"), {"left": "a", "right": "b"})
    assert result.outcome == "b"


@pytest.mark.parametrize(
    ("operation", "operand", "value", "expected"),
    [
        ("add", 2, 3, 5),
        ("subtract", 2, 3, 1),
        ("multiply", 2, 3, 6),
        ("divide", 2, 3, 1.5),
        ("min", 2, 3, 2),
        ("max", 2, 3, 3),
        ("set", 7, 3, 7),
    ],
)
def test_calculation(operation, operand, value, expected):
    sm = StateMachine(outcomes=["finished"], input_keys=["x"], output_keys=["y"])
    sm.add(
        "C",
        Calculation(operation, operand),
        transitions={"done": "finished"},
        remapping={"input_value": "x", "output_value": "y"},
    )
    assert executor(sm, inputs={"x": value}).run(timeout_s=1.0).outputs == {"y": expected}


def test_calculation_rejects_bad_parameters():
    with pytest.raises(ConfigError, match=r"operation 'pow' is not valid \(valid: add, subtract"):
        Calculation("pow", 2)
    with pytest.raises(ConfigError, match="cannot divide by an operand of 0"):
        Calculation("divide", 0)


@pytest.mark.parametrize(
    ("comparison", "value", "outcome"), [(">=", 1.0, "met"), (">", 1.0, "not_met"), ("!=", 2, "met")]
)
def test_compare(comparison, value, outcome):
    sm = StateMachine(outcomes=["met", "not_met"], input_keys=["value"])
    sm.add("C", Compare(comparison, 1.0), transitions={"met": "met", "not_met": "not_met"})
    assert executor(sm, inputs={"value": value}).run(timeout_s=1.0).outcome == outcome
    with pytest.raises(ConfigError, match=r"comparison '=>' is not valid"):
        Compare("=>", 1.0)
