"""Every command from the browser is checked against the loaded behavior before it reaches a runner; each refusal
says what was wrong and what is valid. Start parameters reach the runner as the values that were checked."""

from __future__ import annotations

import math
import re
from typing import Any, Dict, Optional, Sequence

import pytest
from unit.console.console_testlib import structure

from flex_nav.behavior.behavior import ParameterInfo
from flex_nav.console.commands import COMMANDS, RunnerCommand, check_parameter, to_yaml, validate_command
from flex_nav.console.errors import CommandRefused
from flex_nav.console.model import BehaviorStructure, StartableInfo
from flex_nav.nodes.behavior_runner import BehaviorRunner, parse_assignments

PLANNER = structure("flex_planner")
IDLE = structure("")


def ok(request: Dict[str, Any], loaded: BehaviorStructure = PLANNER,
       active: Optional[Sequence[str]] = None) -> RunnerCommand:
    return validate_command(request, loaded, active)


def refused(request: Dict[str, Any], loaded: BehaviorStructure = PLANNER,
            active: Optional[Sequence[str]] = None) -> CommandRefused:
    with pytest.raises(CommandRefused) as caught:
        validate_command(request, loaded, active)
    return caught.value


def test_the_commands_are_the_runners() -> None:
    assert set(COMMANDS) == set(BehaviorRunner.COMMANDS) and "force" in COMMANDS


def test_accepted_commands_become_the_runners_arguments() -> None:
    assert ok({"command": "approve", "path": "/ApprovePlan"}) == RunnerCommand("approve", ("/ApprovePlan",))
    assert ok({"command": "approve", "path": "/ApprovePlan", "outcome": "execute", "type": "command", "id": 3,
               "robot": "/r"}) == RunnerCommand("approve", ("/ApprovePlan", "execute"))
    assert ok({"command": "force", "path": "/GetPath", "outcome": "empty"}, active=["/GetPath"]) == RunnerCommand(
        "force", ("/GetPath", "empty"))
    assert ok({"command": "force", "path": "/Navigate", "outcome": "stuck"},
              active=["/Navigate/Navigate/Bumper", "/Navigate/Navigate/Stuck"]).args == ("/Navigate", "stuck")
    assert ok({"command": "force", "path": "/GetPath", "outcome": "empty"}).args == ("/GetPath", "empty")  # unknown
    assert ok({"command": "lock", "path": "/Navigate"}) == RunnerCommand("lock", ("/Navigate",))
    assert ok({"command": "unlock", "path": "/Navigate/Navigate/Bumper"}).args == ("/Navigate/Navigate/Bumper",)
    for command in ("pause", "resume", "preempt", "stop"):
        assert ok({"command": command}, IDLE) == RunnerCommand(command)
    assert ok({"command": "autonomy", "level": "High"}).args == ("high",)
    assert ok({"command": "autonomy", "level": 0}).args == ("off",)


@pytest.mark.parametrize(("request_", "reason", "field"), [
    ({"command": "fly"}, r"command 'fly' is not valid \(valid: approve, force, autonomy, pause, resume, preempt, stop,"
                         r" lock, unlock, start\)", "command"),
    ({"command": 3}, "command 3 is not valid", "command"),
    ({}, "command None is not valid", "command"),
    ({"command": "pause", "path": "/GetPath"}, r"pause: field 'path' is not valid \(valid: none\)", "path"),
    ({"command": "force", "path": "/GetPath", "outcome": "planned", "eval": "1"},
     r"force: field 'eval' is not valid \(valid: path, outcome\)", "eval"),
    ({"command": "force", "path": "/GetPath"}, "force needs outcome", "outcome"),
    ({"command": "approve", "path": ""}, "approve: path must be a non-empty string, got ''", "path"),
    ({"command": "approve", "path": ["/GetPath"]}, r"approve: path must be a non-empty string, got \['/GetPath'\]",
     "path"),
    ({"command": "lock", "path": "/" + "x" * 600}, "lock: path is 601 characters long", "path"),
    ({"command": "approve", "path": "/Nowhere"},
     r"approve: state path '/Nowhere' is not valid \(valid: /, /ClearCostmaps, /ClearFailed, .*and \d+ more\)", "path"),
    ({"command": "approve", "path": "/ApprovePlan", "outcome": "go"},
     r"approve: outcome of /ApprovePlan 'go' is not valid \(valid: execute, replan, abort\)", "outcome"),
    ({"command": "force", "path": "/GetPath", "outcome": "planned!"},
     r"outcome of /GetPath 'planned!' is not valid \(valid: planned, empty, failed\)", "outcome"),
    ({"command": "autonomy", "level": "max"}, r"autonomy level 'max' is not valid \(valid: off, low, high, full, 0,",
     "level"),
    ({"command": "autonomy", "level": 4}, "autonomy level 4 is not valid", "level"),
    ({"command": "autonomy", "level": True}, "autonomy level True is not valid", "level"),
])
def test_refusals_name_the_bad_value_and_the_valid_ones(request_: Dict[str, Any], reason: str, field: str) -> None:
    err = refused(request_)
    assert err.field == field
    assert err.args[0] and re.search(reason, str(err)), str(err)


def test_forcing_a_state_that_is_not_active_is_refused_with_the_active_ones() -> None:
    err = refused({"command": "force", "path": "/GetPath", "outcome": "empty"}, active=["/ReceiveGoal"])
    assert str(err) == "force: state '/GetPath' is not active (active: /ReceiveGoal)"
    assert err.choices == ("/ReceiveGoal",)


def test_state_commands_need_a_loaded_behavior() -> None:
    err = refused({"command": "lock", "path": "/GetPath"}, IDLE)
    assert "no behavior is loaded on this runner" in str(err)


# --- start ---------------------------------------------------------------------------------------------------------
def start(parameters: Any = None, behavior: str = "flex_planner", **more: Any) -> Dict[str, Any]:
    request: Dict[str, Any] = {"command": "start", "behavior": behavior, **more}
    if parameters is not None:
        request["parameters"] = parameters
    return request


def test_a_start_carries_autonomy_and_the_parameters_as_the_runner_reads_them() -> None:
    command = ok(start({"max_replans": 2, "navigate": "create_navigate", "goal_topic": "true"}, autonomy="low"),
                 IDLE)
    assert command.command == "start" and command.args[:2] == ("flex_planner", "autonomy=low")
    assert parse_assignments(list(command.args[1:])) == {
        "autonomy": "low", "max_replans": 2.0, "navigate": "create_navigate", "goal_topic": "true"}
    assert ok(start(), IDLE) == RunnerCommand("start", ("flex_planner",))


@pytest.mark.parametrize("value", [1e-05, 1e20, -0.0, 0.1, 3.0])
def test_floats_round_trip_through_the_runners_yaml(value: float) -> None:
    info = ParameterInfo("x", "float", 1.0, True)
    text = to_yaml(info, check_parameter(info, value))
    parsed = parse_assignments([f"x={text}"])["x"]
    assert parsed == value and isinstance(parsed, float)


@pytest.mark.parametrize("value", ["", "yes", "1.5", "[1, 2]", "a: b", "#x", "x=y", "ünïcode ✓ 🚀", "line\nbreak",
                                   "'quoted'", "$navigate", "null", "~"])
def test_strings_reach_the_runner_as_strings(value: str) -> None:
    info = ParameterInfo("s", "str", "", True)
    assert parse_assignments([f"s={to_yaml(info, value)}"])["s"] == value


def test_lists_and_dicts_round_trip() -> None:
    for kind, value in (("list", [1, 2.5, "a", None, True]), ("dict", {"a": [1, {"b": "yes"}], "c": 0.5})):
        info = ParameterInfo("v", kind, None, False)
        assert parse_assignments([f"v={to_yaml(info, value)}"])["v"] == value


def _idle_with(parameters: Sequence[ParameterInfo], error: str = "") -> BehaviorStructure:
    return BehaviorStructure("", "", (), {}, {}, {"b": StartableInfo("b", tuple(parameters), error)})


SPEED = ParameterInfo("speed", "float", 0.2, True, minimum=0.0, maximum=1.0, description="[m/s]")
COUNT = ParameterInfo("count", "int", 1, True)
MODE = ParameterInfo("mode", "str", "a", True, choices=("a", "b"))
GOAL = ParameterInfo("goal", "list", None, False)
FLAG = ParameterInfo("flag", "bool", False, True)
FORM = _idle_with([SPEED, COUNT, MODE, GOAL, FLAG])


@pytest.mark.parametrize(("parameters", "reason", "field"), [
    ("speed=1", r"start: parameters must be an object \{name: value\}, got 'speed=1'", "parameters"),
    ({"sped": 0.1, "goal": []}, r"start b: parameter 'sped' is not valid \(valid: speed, count, mode, goal, flag\)",
     "parameters.sped"),
    ({"speed": "fast", "goal": []}, "parameter 'speed' must be float, got str 'fast'", "parameters.speed"),
    ({"speed": True, "goal": []}, "parameter 'speed' must be float, got bool True", "parameters.speed"),
    ({"count": 1.5, "goal": []}, "parameter 'count' must be int, got float 1.5", "parameters.count"),
    ({"flag": 1, "goal": []}, "parameter 'flag' must be bool, got int 1", "parameters.flag"),
    ({"goal": "[1, 2]"}, "parameter 'goal' must be list, got str", "parameters.goal"),
    ({"speed": math.inf, "goal": []}, "parameter 'speed' must be finite, got inf", "parameters.speed"),
    ({"speed": -0.5, "goal": []}, "parameter 'speed' = -0.5 is below its minimum 0.0", "parameters.speed"),
    ({"speed": 2, "goal": []}, "parameter 'speed' = 2.0 is above its maximum 1.0", "parameters.speed"),
    ({"mode": "c", "goal": []}, r"parameter 'mode' value 'c' is not valid \(valid: a, b\)", "parameters.mode"),
    ({}, r"start b: parameter\(s\) goal have no default: give a value", "parameters.goal"),
    ({"goal": ["x" * 20000]}, r"parameter 'goal': the value is \d+ characters long as YAML \(at most 16384\)",
     "parameters.goal"),
])
def test_start_parameters_are_checked_against_the_schema(parameters: Any, reason: str, field: str) -> None:
    err = refused(start(parameters, behavior="b"), FORM)
    assert err.field == field
    assert re.search(reason, str(err)), str(err)


def test_start_refuses_unknown_behaviors_and_unreadable_schemas() -> None:
    err = refused(start(behavior="../etc/passwd"), IDLE)
    assert err.field == "behavior"
    assert "start: behavior '../etc/passwd' is not valid (valid: count_try, create_flex_planner," in str(err)
    err = refused(start(behavior="b"), _idle_with([], error="b.yaml:3: YAML syntax error"))
    assert str(err) == "start: the parameters of 'b' cannot be read: b.yaml:3: YAML syntax error"
    err = refused(start(behavior="b", autonomy="most"), FORM)
    assert err.field == "autonomy" and "autonomy level 'most' is not valid" in str(err)


def test_a_value_that_would_not_round_trip_is_refused() -> None:
    info = ParameterInfo("t", "list", None, False)
    with pytest.raises(CommandRefused, match="would reach the runner as"):
        to_yaml(info, [1, (2, 3)])  # a tuple (never from JSON) comes back a list
