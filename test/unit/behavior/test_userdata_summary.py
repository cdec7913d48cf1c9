"""The userdata summarizer (flex_nav.behavior.userdata_summary) and the executor's active_userdata: bounded JSON,
ROS messages as type and a few fields, nothing of an arbitrary object called; no ROS master."""

from __future__ import annotations

import collections
import dataclasses
import enum
import json
import math
from typing import Any, NamedTuple, Optional

import numpy as np
import pytest
from geometry_msgs.msg import PoseStamped, PoseWithCovarianceStamped, Twist
from nav_msgs.msg import OccupancyGrid, Path
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String
from unit.behavior.behavior_testlib import spin

from flex_nav.behavior import Autonomy, BehaviorExecutor, ManualClock, State, StateMachine
from flex_nav.behavior.builtin_states import Calculation
from flex_nav.behavior.userdata_summary import (
    MISSING,
    SCHEMA,
    StateUserdata,
    SummaryLimits,
    summarize,
    userdata_json,
    userdata_message,
)
from flex_nav.exceptions import ConfigError


def pose(x: float, y: float, yaw_deg: float, frame: str = "map") -> PoseStamped:
    msg = PoseStamped()
    msg.header.frame_id = frame
    msg.pose.position.x, msg.pose.position.y = x, y
    msg.pose.orientation.z = math.sin(math.radians(yaw_deg) / 2.0)
    msg.pose.orientation.w = math.cos(math.radians(yaw_deg) / 2.0)
    return msg


def test_a_pose_stamped_is_its_frame_x_y_and_yaw() -> None:
    assert summarize(pose(7.0, 1.25, 90.0)) == {"type": "geometry_msgs/PoseStamped", "frame": "map", "x": 7.0,
                                                "y": 1.25, "yaw_deg": 90.0}


def test_a_path_is_its_pose_count_length_and_end() -> None:
    path = Path()
    path.header.frame_id = "odom"
    path.poses = [pose(0.0, 0.0, 0.0), pose(3.0, 4.0, 0.0), pose(3.0, 5.0, 0.0)]
    assert summarize(path) == {"type": "nav_msgs/Path", "frame": "odom", "poses": 3, "length_m": 6.0,
                               "end": [3.0, 5.0]}
    assert summarize(Path()) == {"type": "nav_msgs/Path", "frame": "", "poses": 0, "length_m": 0.0}


def test_other_messages_are_summarized_not_dumped() -> None:
    grid = OccupancyGrid()
    grid.info.width, grid.info.height, grid.info.resolution = 2000, 1000, 0.05
    grid.data = [0] * (2000 * 1000)  # 2 M cells: only the geometry is shown
    assert summarize(grid) == {"type": "nav_msgs/OccupancyGrid", "frame": "", "width": 2000, "height": 1000,
                               "resolution": 0.05}
    scan = LaserScan(ranges=[1.0] * 720)
    assert summarize(scan)["ranges"] == 720
    covariance = PoseWithCovarianceStamped()
    covariance.pose.pose.position.x = 2.0
    assert summarize(covariance)["x"] == 2.0
    twist = Twist()
    twist.linear.x, twist.angular.z = 0.3, -0.5
    assert summarize(twist) == {"type": "geometry_msgs/Twist", "vx": 0.3, "wz": -0.5}
    assert summarize(String(data="hello")) == {"type": "std_msgs/String", "data": "hello"}  # generic: its fields


def test_plain_values_strings_and_containers_are_bounded() -> None:
    limits = SummaryLimits(max_items=3, max_string_chars=5)
    assert [summarize(v, limits) for v in (None, True, 3, 2.5, "abc")] == [None, True, 3, 2.5, "abc"]
    assert summarize("abcdefgh", limits) == {"type": "str", "len": 8, "head": "abcde"}
    assert summarize(list(range(1000)), limits) == {"type": "list", "len": 1000, "items": [0, 1, 2]}
    assert summarize({"a": 1, "b": [1], "c": 3, "d": 4}, limits) == {
        "type": "dict", "len": 4, "items": {"a": 1, "b": {"type": "list", "len": 1, "items": [1]}, "c": 3}}
    assert summarize((1, 2), limits)["type"] == "tuple"
    assert summarize(collections.deque([1]), limits)["type"] == "list"
    assert summarize(b"\x00" * 10) == {"type": "bytes", "len": 10}
    assert summarize(float("nan")) == {"type": "float", "value": "nan"}
    assert summarize(-math.inf) == {"type": "float", "value": "-inf"}
    assert summarize(2**80) == {"type": "int", "digits": 25}
    assert summarize(np.float32(0.5)) == 0.5
    assert summarize(np.zeros((4, 2))) == {"type": "ndarray", "shape": [4, 2], "dtype": "float64"}
    deep: Any = [1]
    for _ in range(50):
        deep = [deep]
    json.dumps(summarize(deep))  # nesting is cut at max_depth: no recursion error, valid JSON


class Colour(enum.Enum):
    RED = 1


class Pair(NamedTuple):
    left: int
    right: str


@dataclasses.dataclass
class Box:
    width: float
    label: str


def test_enums_named_tuples_and_dataclasses_show_their_fields() -> None:
    assert summarize(Colour.RED) == {"type": "Colour", "name": "RED"}
    assert summarize(Pair(1, "x")) == {"type": "Pair", "left": 1, "right": "x"}
    assert summarize(Box(0.5, "b")) == {"type": "Box", "width": 0.5, "label": "b"}


class Secretive:
    """An object whose repr, str and pickling must never be used."""

    called = False

    def __repr__(self) -> str:
        Secretive.called = True
        raise AssertionError("repr called")

    __str__ = __repr__

    def __reduce__(self) -> Any:
        Secretive.called = True
        raise AssertionError("pickled")


def test_an_arbitrary_object_is_only_its_class_name() -> None:
    assert summarize(Secretive()) == {"type": f"{__name__}.Secretive"}
    assert summarize([Secretive()])["items"] == [{"type": f"{__name__}.Secretive"}]
    assert not Secretive.called


def test_a_value_over_its_budget_is_cut_and_a_broken_one_named() -> None:
    limits = SummaryLimits(max_value_chars=60, max_items=50, max_string_chars=50)
    cut = summarize({f"key{i}": "v" * 40 for i in range(20)}, limits)
    assert cut["type"] == "dict" and len(cut["cut"]) == 60
    broken = PoseStamped()
    broken.pose.position.x = "not a number"
    summary = summarize(broken)
    assert summary["type"] == "geometry_msgs.msg._PoseStamped.PoseStamped" and "ValueError" in summary["error"]


def test_limits_are_checked() -> None:
    with pytest.raises(ConfigError, match="max_items must be an integer >= 1, got 0"):
        SummaryLimits(max_items=0)


def test_the_message_lists_inputs_and_written_outputs_and_stays_within_its_size() -> None:
    state = StateUserdata("/A/B", (("goal", pose(1.0, 2.0, 0.0)), ("count", MISSING), ("both", 1)),
                          (("plan", MISSING), ("both", 2), ("done", True)))
    message = userdata_message("b", 3.0, [StateUserdata("/", (), ()), StateUserdata("/A", (), ()), state])
    assert message["schema"] == SCHEMA and message["behavior"] == "b" and message["stamp"] == 3.0
    assert [s["path"] for s in message["states"]] == ["/A/B", "/A", "/"]  # deepest first, the root last
    keys = message["states"][0]["keys"]
    assert [(k["key"], k["role"], k["set"]) for k in keys] == [
        ("goal", "in", True), ("count", "in", False), ("both", "in/out", True), ("done", "out", True)]
    assert keys[0]["value"]["x"] == 1.0 and keys[1]["value"] is None
    many = [StateUserdata(f"/S{i}", (("text", "x" * 100),), ()) for i in range(100)]
    text = userdata_json("b", 1.0, many, SummaryLimits(max_message_chars=2000))
    bounded = json.loads(text)
    assert len(text) <= 2000 and bounded["states"] and bounded["states_omitted"] == 100 - len(bounded["states"])
    keys_cut = userdata_message("b", 0.0, [StateUserdata("/K", tuple((f"k{i}", i) for i in range(10)), ())],
                                SummaryLimits(max_keys=4))
    assert len(keys_cut["states"][0]["keys"]) == 4 and keys_cut["states"][0]["keys_omitted"] == 6


class Hold(State):
    """Reads ``goal`` and writes ``seen`` (the goal's x), then stays active."""

    def __init__(self) -> None:
        super().__init__(outcomes=["done"], input_keys=["goal"], output_keys=["seen"])

    def execute(self, userdata: Any) -> Optional[str]:
        userdata.seen = userdata.goal.pose.position.x
        return None


def test_the_executor_reports_the_active_states_keys_and_values() -> None:
    inner = StateMachine(outcomes=["finished"], input_keys=["goal"], output_keys=["seen"])
    inner.add("Hold", Hold(), transitions={"done": "finished"})
    root = StateMachine(outcomes=["finished"], input_keys=["goal"], userdata={"count": 1.0})
    root.add("Count", Calculation("add", 1.0), transitions={"done": "Inner"}, autonomy={"done": "high"},
             remapping={"input_value": "count", "output_value": "count"})
    root.add("Inner", inner, transitions={"finished": "finished"})
    goal = pose(4.0, 0.0, 0.0)
    ex = BehaviorExecutor(root, inputs={"goal": goal}, clock=ManualClock(), autonomy=Autonomy.LOW)
    assert ex.active_userdata() == ()  # not started
    spin(ex, 2)  # Count wrote count = 2 and its outcome waits for the operator (needs High)
    found = {s.path: s for s in ex.active_userdata() or ()}
    assert set(found) == {"/Count", "/"}
    assert found["/Count"].inputs == (("input_value", 2.0),) and found["/Count"].outputs == (("output_value", 2.0),)
    ex.approve("/Count")
    spin(ex, 3)
    found = {s.path: s for s in ex.active_userdata() or ()}
    assert set(found) == {"/Inner/Hold", "/Inner", "/"}
    assert found["/Inner/Hold"].inputs == (("goal", goal),)  # the object itself, not a copy
    assert found["/Inner/Hold"].outputs == (("seen", 4.0),)
    assert found["/Inner"].outputs == (("seen", MISSING),)  # copied out only when Inner finishes
    ex.preempt()
    spin(ex, 1)
    assert ex.active_userdata() == ()
