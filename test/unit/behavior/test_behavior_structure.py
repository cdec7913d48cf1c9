"""The JSON structure a behavior_runner publishes on ~structure (flex_nav.behavior.structure), on real behaviors."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any, Dict

import pytest

from flex_nav.behavior.builtin_states import Wait
from flex_nav.behavior.state_machine import StateMachine
from flex_nav.behavior.structure import (
    AUTONOMY_LEVELS,
    KINDS,
    SCHEMA,
    VERSION,
    describe,
    jsonable,
    startable_behaviors,
    structure_json,
)
from flex_nav.behavior.yaml_loader import list_behaviors, load_behavior, parameter_schema
from flex_nav.exceptions import BehaviorLoadError, ConfigError

BEHAVIORS = Path(__file__).resolve().parents[3] / "behaviors"
DATA = Path(__file__).resolve().parent / "data"


def states_of(text: str) -> Dict[str, Dict[str, Any]]:
    return {state["path"]: state for state in json.loads(text)["states"]}


def test_flex_planner_states_kinds_transitions_and_autonomy() -> None:
    text = structure_json(load_behavior("flex_planner", search_path=[BEHAVIORS]), [BEHAVIORS])
    data = json.loads(text)
    assert (data["schema"], data["version"], data["behavior"]) == (SCHEMA, VERSION, "flex_planner")
    assert data["autonomy_levels"] == ["off", "low", "high", "full"] == list(AUTONOMY_LEVELS)
    states = states_of(text)
    root = states["/"]
    assert (root["label"], root["parent"], root["kind"], root["initial"]) == ("flex_planner", None, "state_machine",
                                                                             "ClearCostmaps")
    assert root["transitions"] == {} and root["autonomy"] == {"finished": 0, "failed": 0}
    approve = states["/ApprovePlan"]
    assert approve["kind"] == "state" and approve["parent"] == "/"
    assert approve["class"] == "flex_nav_states.operator_decision_state.OperatorDecisionState"
    assert approve["outcomes"] == ["execute", "replan", "abort"]
    assert approve["transitions"] == {"execute": "Navigate", "replan": "GetPath", "abort": "ReceiveGoal"}
    assert approve["autonomy"] == {"execute": 2, "replan": 3, "abort": 3}  # high, full, full
    assert states["/GetPath"]["autonomy"] == {"planned": 0, "empty": 0, "failed": 0}  # every outcome listed
    navigate = states["/Navigate"]
    assert (navigate["kind"], navigate["behavior"]) == ("sub_behavior", "flex_navigate")
    assert navigate["transitions"]["bumper"] == "Recovery"
    assert (states["/Recovery"]["kind"], states["/Recovery"]["behavior"]) == ("sub_behavior", "simple_recovery")
    assert states["/Recovery/BackUp"]["parent"] == "/Recovery"
    concurrency = states["/Navigate/Navigate"]
    assert concurrency["kind"] == "concurrency" and concurrency["initial"] is None
    assert {"outcome": "stuck", "when": [["Stuck", "stuck"]]} in concurrency["conditions"]
    assert states["/Navigate/Navigate/Bumper"]["transitions"] == {}  # concurrent children have conditions instead
    assert root["children"][:3] == ["ClearCostmaps", "ClearFailed", "ReceiveGoal"]
    assert {s["kind"] for s in states.values()} <= set(KINDS)


def test_every_container_comes_before_its_children_and_every_path_once() -> None:
    text = structure_json(load_behavior("explore", search_path=[BEHAVIORS]))
    listed = json.loads(text)["states"]
    seen = set()
    for state in listed:
        assert state["path"] not in seen
        assert state["parent"] is None or state["parent"] in seen
        seen.add(state["path"])
    states = states_of(text)
    for state in states.values():
        for label in state["children"]:
            assert states[f"{state['path'].rstrip('/')}/{label}"]["parent"] == state["path"]
    # nested sub-behaviors: go_to_goal includes flex_navigate, whose root holds the concurrency Navigate
    assert states["/GoToFrontier"]["behavior"] == "go_to_goal"
    assert states["/GoToFrontier/Navigate"]["behavior"] == "flex_navigate"
    assert states["/GoToFrontier/Navigate/Navigate"]["kind"] == "concurrency"
    assert states["/ApproveFrontier"]["autonomy"]["explore"] == 2


def test_priority_containers_and_the_executors_paths_agree() -> None:
    from flex_nav.behavior.executor import BehaviorExecutor  # noqa: PLC0415

    behavior = load_behavior("guarded_wait", search_path=[DATA])
    states = states_of(json.dumps(describe(behavior)))
    assert states["/Guarded/Guard/Recover"]["kind"] == "priority"
    assert states["/Guarded/Guard/Recover/Announce"]["kind"] == "sub_behavior"
    assert states["/Guarded/Guard"]["kind"] == "state_machine"
    assert set(states) == set(BehaviorExecutor(behavior).state_paths)  # the paths commands take


def test_parameter_schema_and_values() -> None:
    data = describe(load_behavior("flex_planner", {"max_replans": 2.0}, search_path=[BEHAVIORS]))
    params = {p["name"]: p for p in data["parameters"]}
    assert params["max_replans"] == {"name": "max_replans", "type": "float", "default": 5.0, "has_default": True,
                                     "min": 0.0, "max": None, "choices": None,
                                     "description": "replans of one goal before giving it up"}
    assert params["backup_offset_m"]["max"] == -0.01
    assert data["values"]["max_replans"] == 2.0 and data["values"]["navigate"] == "flex_navigate"


def test_parameter_schema_reads_choices_without_defaults_and_names_bad_files(tmp_path: Path) -> None:
    (tmp_path / "b.yaml").write_text(
        "behavior: b\nparameters:\n  mode: {type: str, default: a, choices: [a, b], description: which}\n"
        "  goal: {type: list}\noutcomes: [done]\nstates: {}\n")
    mode, goal = parameter_schema("b", [tmp_path])
    assert (mode.name, mode.choices, mode.description, mode.default) == ("mode", ("a", "b"), "which", "a")
    assert (goal.name, goal.type, goal.has_default) == ("goal", "list", False)
    (tmp_path / "bad.yaml").write_text("behavior: bad\nparameters:\n  x: {type: complex}\n")
    with pytest.raises(BehaviorLoadError, match=r"bad\.yaml:3: .*type of parameter 'x' 'complex' is not valid"):
        parameter_schema("bad", [tmp_path])
    with pytest.raises(ConfigError, match="valid: b, bad"):
        parameter_schema("missing", [tmp_path])


def test_startable_behaviors_list_the_search_path_with_errors_and_a_bound(tmp_path: Path) -> None:
    (tmp_path / "ok.yaml").write_text("behavior: ok\nparameters:\n  n: {type: int, default: 1}\n")
    (tmp_path / "broken.yaml").write_text("behavior: [unclosed\n")
    entries, truncated = startable_behaviors([tmp_path])
    assert not truncated
    assert [e["name"] for e in entries] == ["broken", "ok"]
    assert entries[0]["parameters"] == [] and "broken.yaml" in entries[0]["error"]
    assert entries[1]["error"] == "" and entries[1]["parameters"][0]["default"] == 1
    entries, truncated = startable_behaviors([tmp_path], max_count=1)
    assert truncated and [e["name"] for e in entries] == ["broken"]
    shipped, _ = startable_behaviors([BEHAVIORS])
    assert [e["name"] for e in shipped] == sorted(list_behaviors([BEHAVIORS]))
    assert all(e["error"] == "" for e in shipped)


def test_no_behavior_loaded_is_an_empty_structure_with_the_startable_list() -> None:
    data = json.loads(structure_json(None, [BEHAVIORS]))
    assert data["behavior"] == "" and data["states"] == [] and data["parameters"] == [] and data["values"] == {}
    assert "flex_planner" in [e["name"] for e in data["startable"]]


def test_a_behavior_built_in_code_has_plain_state_machines() -> None:
    from flex_nav.behavior.behavior import Behavior  # noqa: PLC0415

    inner = StateMachine(outcomes=["done"])
    inner.add("Wait", Wait(wait_time_s=0.1), transitions={"done": "done"})
    root = StateMachine(outcomes=["finished"])
    root.add("Inner", inner, transitions={"done": "finished"}, autonomy={"done": "low"})
    states = states_of(json.dumps(describe(Behavior("coded", root))))
    assert states["/Inner"]["kind"] == "state_machine" and states["/Inner"]["behavior"] == ""
    assert states["/Inner"]["autonomy"] == {"done": 1}
    assert states["/Inner/Wait"]["class"] == "flex_nav.behavior.builtin_states.Wait"


def test_values_json_cannot_hold_are_made_plain() -> None:
    import datetime  # noqa: PLC0415

    assert jsonable({"a": [1.5, math.inf, (1, 2)], 3: datetime.date(2024, 1, 2)}) == {
        "a": [1.5, "inf", [1, 2]], "3": "datetime.date(2024, 1, 2)"}
    assert json.loads(json.dumps(jsonable([math.nan]), allow_nan=False)) == ["nan"]
