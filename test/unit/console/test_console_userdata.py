"""The console's reading of a runner's ~userdata (flex_nav.console.userdata): strict, bounded, each value written as
one line of text; and its way through the server to a page (snapshot included). No ROS, no browser."""

from __future__ import annotations

import asyncio
import json
import math
from typing import Any, Dict, List

import pytest
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path
from unit.console.test_console_server import ROBOT, console, page, run, served, until

from flex_nav.behavior.userdata_summary import MISSING, StateUserdata, summarize, userdata_json
from flex_nav.console.errors import UserdataError
from flex_nav.console.userdata import shown, userdata_event, value_text


def goal() -> PoseStamped:
    msg = PoseStamped()
    msg.header.frame_id = "map"
    msg.pose.position.x, msg.pose.position.y = 7.0, 1.0
    msg.pose.orientation.z, msg.pose.orientation.w = math.sin(math.pi / 4), math.cos(math.pi / 4)
    return msg


def runner_text() -> str:
    path = Path()
    path.poses = [goal(), goal()]
    return userdata_json("flex_planner", 12.5, [
        StateUserdata("/ReceiveGoal", (), (("goal", goal()),)),
        StateUserdata("/GetPath", (("goal", goal()), ("tries", MISSING)), (("plan", path),)),
    ])


def test_the_runners_message_becomes_lines_of_text_per_state() -> None:
    event = userdata_event(ROBOT, runner_text())
    assert event["type"] == "userdata" and event["robot"] == ROBOT and event["behavior"] == "flex_planner"
    assert event["stamp"] == 12.5 and event["states_omitted"] == 0
    assert event["states"]["/ReceiveGoal"] == [{"key": "goal", "role": "out", "set": True,
                                               "text": 'geometry_msgs/PoseStamped frame="map" x=7 y=1 yaw_deg=90'}]
    get_path = event["states"]["/GetPath"]
    assert [(k["key"], k["role"], k["set"]) for k in get_path] == [("goal", "in", True), ("tries", "in", False),
                                                                   ("plan", "out", True)]
    assert get_path[1]["text"] == "(no value yet)"
    assert get_path[2]["text"] == 'nav_msgs/Path frame="" poses=2 length_m=0 end=[7, 1]'


def test_values_are_written_as_short_text() -> None:
    assert [value_text(v) for v in (None, True, 2.5, 3, "a\"b")] == ["null", "true", "2.5", "3", '"a\\"b"']
    assert value_text(summarize(list(range(10)))) == "list [0, 1, 2, 3, 4, 5, … (10 items)]"
    assert value_text(summarize({"a": 1})) == 'dict {"a": 1}'
    assert value_text(summarize("x" * 200)) == '"' + "x" * 120 + '"… (200 characters)'
    assert value_text(summarize(float("inf"))) == "inf"
    assert value_text({"type": "some.Class"}) == "some.Class"
    assert len(shown({"type": "list", "len": 9, "items": ["y" * 100] * 9})) == 300
    nested: Any = 1
    for _ in range(30):
        nested = [nested]
    assert "…" in value_text(nested)  # deep nesting written only so far


@pytest.mark.parametrize(("text", "reason"), [
    ("[1]", "userdata must be an object, got list"),
    ("{", "userdata: not JSON"),
    ('{"schema": "flex_nav/userdata", "version": 2, "behavior": "", "states": []}', "version 2 is not"),
    ('{"schema": "flex_nav/userdata", "version": 1, "states": []}', "userdata has no 'behavior'"),
    ('{"schema": "flex_nav/userdata", "version": 1, "behavior": "b", "stamp": NaN, "states": []}', "NaN is not a JSON"),
    ('{"schema": "flex_nav/userdata", "version": 1, "behavior": "b", "states": [{"path": "x", "keys": []}]}',
     "userdata.states[0].path 'x' must start with '/'"),
    ('{"schema": "flex_nav/userdata", "version": 1, "behavior": "b", "states": [{"path": "/x", "keys": '
     '[{"key": "k", "role": "eval", "set": true}]}]}', "userdata.states[0].keys[0].role 'eval' is not one of"),
    ('{"schema": "flex_nav/userdata", "version": 1, "behavior": "b", "states": [{"path": "/x", "keys": '
     '[{"key": "k", "role": "in", "set": 1}]}]}', "userdata.states[0].keys[0].set must be bool, got int"),
])
def test_a_message_off_the_schema_is_refused_naming_the_field(text: str, reason: str) -> None:
    with pytest.raises(UserdataError, match=reason.replace("[", r"\[").replace("]", r"\]").replace(".", r"\.")):
        userdata_event(ROBOT, text)


def test_an_oversized_message_is_refused_before_it_is_parsed() -> None:
    with pytest.raises(UserdataError, match="userdata: 101 characters, more than the 100 accepted"):
        userdata_event(ROBOT, " " * 101, max_chars=100)


def test_a_page_gets_the_userdata_live_and_in_its_snapshot() -> None:
    async def check() -> None:
        made, _ = console(port=0)
        async with served(made) as client:
            ws = await page(client)
            await asyncio.to_thread(made.submit_robots, [ROBOT])
            await asyncio.to_thread(made.submit_userdata, ROBOT, runner_text())
            live = await until(ws, lambda e: e["type"] == "userdata")
            assert "/ReceiveGoal" in live["states"]
            await asyncio.to_thread(made.submit_userdata, ROBOT, json.dumps({"schema": "flex_nav/userdata"}))
            error = await until(ws, lambda e: e["type"] == "error")
            assert error["robot"] == ROBOT and error["message"].startswith("unreadable userdata: userdata: schema")
            later = await client.ws_connect("/ws", headers={"Origin": f"http://{client.host}:{client.port}"})
            seen: List[Dict[str, Any]] = []
            await until(later, lambda e: e["type"] == "snapshot_done", seen)
            assert [e for e in seen if e["type"] == "userdata"] == [live]  # the last good one, not the bad one
            await ws.close()
            await later.close()
    run(check())
