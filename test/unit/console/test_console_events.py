"""The runner's messages become small JSON events for the page; the runner's answers find the page's commands."""

from __future__ import annotations

import json

import genpy
import pytest
from unit.console.console_testlib import structure

from flex_nav.console.events import (
    LOG_LEVELS,
    MAX_TEXT_CHARS,
    STATUS_NAMES,
    CommandTracker,
    activity_event,
    feedback_event,
    known_ref,
    log_event,
    robots_event,
    status_event,
    structure_event,
    transition_event,
)
from flex_nav.console.graph import svg_id
from flex_nav.msg import (
    BehaviorActivity,
    BehaviorCommandFeedback,
    BehaviorLog,
    BehaviorStatus,
    BehaviorTransition,
    OutcomeRequest,
)

ROBOT = "/robot1/behavior_runner"


def stamped(msg):
    msg.header.stamp = genpy.Time(12, 250_000_000)
    return msg


def test_status_names_and_log_levels_are_the_messages() -> None:
    assert [getattr(BehaviorStatus, name) for name in STATUS_NAMES] == list(range(len(STATUS_NAMES)))
    assert {getattr(BehaviorLog, name): name for name in ("INFO", "WARN", "HINT", "ERROR", "DEBUG")} == LOG_LEVELS


def test_status() -> None:
    msg = stamped(BehaviorStatus(behavior="flex_planner", code=BehaviorStatus.FAILED, outcome="", reason="x" * 3000,
                                 autonomy=1))
    event = status_event(ROBOT, msg)
    assert {k: v for k, v in event.items() if k != "reason"} == {
        "type": "status", "robot": ROBOT, "behavior": "flex_planner", "code": 5, "status": "FAILED", "outcome": "",
        "autonomy": 1, "stamp": 12.25}
    assert event["reason"].startswith("x" * MAX_TEXT_CHARS) and event["reason"].endswith("(3000 characters)")
    assert status_event(ROBOT, stamped(BehaviorStatus(code=9)))["status"] == "UNKNOWN(9)"


def test_activity_with_a_request() -> None:
    msg = stamped(BehaviorActivity(behavior="flex_planner", autonomy=1, active_paths=["/ApprovePlan"], requests=[
        OutcomeRequest(path="/ApprovePlan", outcome="execute", required=2, reason="autonomy")]))
    assert activity_event(ROBOT, msg) == {
        "type": "activity", "robot": ROBOT, "behavior": "flex_planner", "autonomy": 1, "active": ["/ApprovePlan"],
        "requests": [{"path": "/ApprovePlan", "outcome": "execute", "required": 2, "reason": "autonomy"}],
        "stamp": 12.25}


def test_transition_and_log() -> None:
    msg = stamped(BehaviorTransition(behavior="b", path="/GetPath", outcome="planned", target="ApprovePlan",
                                     required=0, forced=True))
    assert transition_event(ROBOT, msg) == {
        "type": "transition", "robot": ROBOT, "behavior": "b", "path": "/GetPath", "outcome": "planned",
        "target": "ApprovePlan", "required": 0, "forced": True, "stamp": 12.25}
    log = log_event(ROBOT, stamped(BehaviorLog(behavior="b", level=BehaviorLog.WARN, path="/X", text="careful")))
    assert (log["type"], log["level"], log["path"], log["text"]) == ("log", "WARN", "/X", "careful")
    assert log_event(ROBOT, stamped(BehaviorLog(level=7)))["level"] == "7"


def test_feedback_carries_the_refs_and_cuts_long_arguments() -> None:
    msg = BehaviorCommandFeedback(command="start", args=["flex_planner", "goal=" + "1" * 500], ok=True,
                                  message="loading", pending=True)
    event = feedback_event(ROBOT, msg, ["1:7"])
    assert (event["ok"], event["pending"], event["refs"], event["message"]) == (True, True, ["1:7"], "loading")
    assert event["args"][0] == "flex_planner" and event["args"][1].endswith("(505 characters)")
    json.dumps(event)  # every event is JSON


def test_structure_event_gives_each_state_its_svg_id_and_the_start_forms() -> None:
    event = structure_event(ROBOT, structure("flex_planner"), "<svg/>")
    states = {s["path"]: s for s in event["states"]}
    assert states["/Navigate/Navigate/Bumper"]["id"] == svg_id("/Navigate/Navigate/Bumper")
    assert states["/ApprovePlan"]["autonomy"] == {"execute": 2, "replan": 3, "abort": 3}
    assert states["/Navigate"]["kind"] == "sub_behavior" and states["/Navigate"]["behavior"] == "flex_navigate"
    forms = {b["name"]: b for b in event["startable"]}
    speed = next(p for p in forms["explore"]["parameters"] if p["name"] == "stuck_window_s")
    assert speed == {"name": "stuck_window_s", "type": "float", "default": 20.0, "has_default": True, "min": 1.0,
                     "max": None, "choices": None, "description": "[s] no progress this long = stuck"}
    assert (event["svg"], event["error"]) == ("<svg/>", "")
    json.dumps(event)


def test_robots_are_sorted() -> None:
    assert robots_event(["/b/behavior_runner", "/a/behavior_runner"]) == {
        "type": "robots", "robots": ["/a/behavior_runner", "/b/behavior_runner"]}


def test_answers_find_their_commands_in_order_until_the_final_one() -> None:
    tracker = CommandTracker(max_pending=3)
    tracker.sent(ROBOT, "start", ["explore"], "1:1")
    tracker.sent(ROBOT, "pause", [], "2:5")
    tracker.sent(ROBOT, "pause", [], "1:2")
    assert tracker.answered(ROBOT, "start", ["explore"], pending=True) == ["1:1"]  # "loading ...": kept
    assert tracker.answered(ROBOT, "start", ["explore"], pending=False) == ["1:1"]  # final: forgotten
    assert tracker.answered(ROBOT, "start", ["explore"], pending=False) == []
    assert tracker.answered(ROBOT, "pause", [], pending=False) == ["2:5"]  # identical ones in the order sent
    assert tracker.answered("/other/behavior_runner", "pause", [], pending=False) == []
    assert tracker.answered(ROBOT, "pause", [], pending=False) == ["1:2"]
    assert len(tracker) == 0


def test_the_tracker_is_bounded_and_forgets_a_runner_that_went_away() -> None:
    tracker = CommandTracker(max_pending=2)
    for index in range(3):
        tracker.sent(ROBOT, "stop", [], f"1:{index}")
    assert len(tracker) == 2 and tracker.answered(ROBOT, "stop", [], False) == ["1:1"]  # the oldest was dropped
    tracker.sent("/other", "stop", [], "1:9")
    tracker.forget(ROBOT)
    assert len(tracker) == 1 and tracker.answered("/other", "stop", [], False) == ["1:9"]


@pytest.mark.parametrize(("given", "kept"), [(7, "7"), ("a-1", "a-1"), (True, None), (None, None), ([1], None),
                                             ("", None), ("x" * 65, None)])
def test_page_command_ids(given: object, kept: object) -> None:
    assert known_ref(given) == kept
