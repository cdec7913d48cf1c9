"""The console reads a runner's ~structure strictly: the shipped behaviors round-trip, anything off-schema is
refused naming the field; runners are found by their status topics."""

from __future__ import annotations

import copy
import json
from typing import Any, Callable, Dict

import pytest
from unit.console.console_testlib import structure, structure_text

from flex_nav.console.errors import StructureError
from flex_nav.console.model import BehaviorStructure, runner_names


def test_flex_planner_round_trips_with_kinds_ancestors_and_startable_forms() -> None:
    planner = structure("flex_planner")
    assert planner.loaded and planner.behavior == "flex_planner"
    approve = planner.state("/ApprovePlan")
    assert approve is not None and approve.autonomy["execute"] == 2 and not approve.is_container
    bumper = planner.state("/Navigate/Navigate/Bumper")
    assert bumper is not None and bumper.class_name.endswith("BumperMonitorState")
    assert planner.ancestors("/Navigate/Navigate/Bumper") == ["/Navigate/Navigate", "/Navigate", "/"]
    assert planner.ancestors("/nowhere") == []
    concurrency = planner.state("/Navigate/Navigate")
    assert concurrency is not None and ("stuck", (("Stuck", "stuck"),)) in concurrency.conditions
    explore = planner.startable["explore"]
    assert explore.error == ""
    info = explore.parameter("stuck_window_s")
    assert info is not None and (info.type, info.minimum, info.default) == ("float", 1.0, 20.0)
    assert explore.parameter("nothing") is None
    assert {p.name for p in planner.parameters} >= {"navigate", "max_replans"}
    assert planner.values["navigate"] == "flex_navigate"


def test_no_behavior_loaded() -> None:
    idle = structure("")
    assert not idle.loaded and idle.behavior == "" and "explore" in idle.startable
    assert not BehaviorStructure.empty().loaded


def _data() -> Dict[str, Any]:
    return copy.deepcopy(json.loads(structure_text("simple_recovery")))


def _set(path: str, value: Any) -> Callable[[Dict[str, Any]], None]:
    def change(data: Dict[str, Any]) -> None:
        *where, last = path.split(".")
        target: Any = data
        for key in where:
            target = target[int(key)] if key.isdigit() else target[key]
        target[int(last) if last.isdigit() else last] = value
    return change


@pytest.mark.parametrize(("change", "reason"), [
    (_set("schema", "other"), "schema 'other' version 1 is not 'flex_nav/behavior_structure'"),
    (_set("version", 2), "version 2"),
    (_set("states.1.kind", "blob"), r"states\[1\]\.kind 'blob' is not one of state, state_machine"),
    (_set("states.1.path", "Stop"), r"states\[1\]\.path 'Stop' must start with '/'"),
    (_set("states.1.path", "/"), "state path '/' is listed twice"),
    (_set("states.1.parent", "/Later"), "comes before its parent '/Later'"),
    (_set("states.1.autonomy", {"done": 7}), r"autonomy: 'done': 7 is not a level 0\.\.3"),
    (_set("states.1.autonomy", {"vanished": 1}), "'vanished': 1 is not a level 0..3 of an outcome"),
    (_set("states.1.autonomy", {"done": True}), r"autonomy\['done'\] must be int"),
    (_set("states.1.outcomes", ["done", 3]), r"states\[1\]\.outcomes must be a list of names"),
    (_set("states.1.transitions", {"done": 1}), r"transitions\['done'\] must be str"),
    (_set("states.1.conditions", [{"outcome": "x", "when": [["A"]]}]), r"when must be a list of \[state, outcome\]"),
    (_set("states", {}), "structure.states must be list, got dict"),
    (_set("startable.0.parameters.0.type", "complex"), r"startable\[0\]\.parameters\[0\]\.type 'complex'"),
    (_set("startable.0.parameters.0.min", "0"), "min must be a number or null"),
    (_set("startable.0.parameters.0.choices", "ab"), "choices must be a list or null"),
    (_set("startable.0", []), r"startable\[0\] must be an object, got list"),
    (lambda data: data.pop("behavior"), "structure has no 'behavior'"),
])
def test_an_off_schema_structure_is_refused_naming_the_field(change: Callable[[Dict[str, Any]], None],
                                                              reason: str) -> None:
    data = _data()
    change(data)
    with pytest.raises(StructureError, match=reason):
        BehaviorStructure.from_json(json.dumps(data))


def test_text_that_is_not_json_or_too_long_is_refused() -> None:
    with pytest.raises(StructureError, match="not JSON"):
        BehaviorStructure.from_json("{")
    with pytest.raises(StructureError, match="must be an object, got list"):
        BehaviorStructure.from_json("[]")
    with pytest.raises(StructureError, match="more than the 10 accepted"):
        BehaviorStructure.from_json(structure_text("simple_recovery"), max_chars=10)


def test_runners_are_found_by_their_status_topics() -> None:
    topics = [
        ("/robot1/behavior_runner/status", "flex_nav/BehaviorStatus"),
        ("/robot1/behavior_runner/log", "flex_nav/BehaviorLog"),
        ("/behavior_runner/status", "flex_nav/BehaviorStatus"),
        ("/robot2/driver/status", "std_msgs/String"),  # another status topic of another type
        ("/status", "flex_nav/BehaviorStatus"),  # a runner needs a name
        ("/robot1/behavior_runner/status", "flex_nav/BehaviorStatus"),
    ]
    assert runner_names(topics) == ["/behavior_runner", "/robot1/behavior_runner"]
    assert runner_names([]) == []
