"""Userdata: declared keys only, typed errors, remapping, nesting, zero-copy read-only inputs."""

from __future__ import annotations

import copy
import enum
from typing import Any, Dict, NamedTuple

import numpy as np
import pytest
from unit.behavior.behavior_testlib import Journal, ScriptedState, executor

from flex_nav.behavior import BehaviorStatus, ConcurrencyContainer, StateMachine, readonly, unwrap
from flex_nav.exceptions import ConfigError, ReadOnlyUserDataError, UserDataKeyError


class Message:
    """Stand-in for a ROS message: plain attributes, nested message, list payload."""

    def __init__(self) -> None:
        self.header = Header()
        self.data = list(range(10))
        self.tags = {"a": [1]}


class Header:
    def __init__(self) -> None:
        self.frame_id = "map"
        self.stamp = 1.5


def run_one(state, **kwargs):
    sm = StateMachine(outcomes=["finished", "failed"], **kwargs.pop("sm", {}))
    sm.add("S", state, transitions={"done": "finished", "failed": "failed"}, remapping=kwargs.pop("remapping", None))
    return executor(sm, **kwargs).run(timeout_s=5.0)


def test_read_and_write_declared_keys_and_outputs_reach_the_caller():
    def action(ud, n):
        ud.total = ud.a + ud["b"]
        ud["copy"] = ud.a

    state = ScriptedState(Journal(), input_keys=["a", "b"], output_keys=["total", "copy"], action=action)
    result = run_one(state, sm={"input_keys": ["a", "b"], "output_keys": ["total"]}, inputs={"a": 2, "b": 3})
    assert result.status is BehaviorStatus.FINISHED
    assert result.outputs == {"total": 5}  # "copy" is not a root output


def test_undeclared_read_is_a_typed_error_naming_the_declared_keys():
    state = ScriptedState(Journal(), input_keys=["a"], action=lambda ud, n: ud.secret)
    result = run_one(state, sm={"input_keys": ["a"]}, inputs={"a": 1})
    assert result.status is BehaviorStatus.FAILED
    assert isinstance(result.error, UserDataKeyError)
    assert "state '/S' reads userdata key 'secret' which it does not declare as input (inputs: a)" in result.reason


def test_undeclared_write_is_a_typed_error():
    def action(ud, n):
        ud.other = 1

    result = run_one(ScriptedState(Journal(), output_keys=["x"], action=action))
    assert isinstance(result.error, UserDataKeyError)
    assert "writes userdata key 'other' which it does not declare as output (outputs: x)" in result.reason


def test_write_to_input_only_key_is_refused():
    def action(ud, n):
        ud.a = 5

    result = run_one(
        ScriptedState(Journal(), input_keys=["a"], action=action), sm={"input_keys": ["a"]}, inputs={"a": 1}
    )
    assert isinstance(result.error, ReadOnlyUserDataError)
    assert "writes userdata key 'a' which is input-only" in result.reason


def test_read_of_key_without_value_says_which_keys_have_one():
    sm = StateMachine(outcomes=["finished", "failed"], userdata={"z": 0})
    sm.add(
        "W", ScriptedState(Journal(), output_keys=["x"], script=["done"]), transitions={"done": "R", "failed": "failed"}
    )
    sm.add(
        "R",
        ScriptedState(Journal(), input_keys=["x"], action=lambda ud, n: ud.x),
        transitions={"done": "finished", "failed": "failed"},
    )
    result = executor(sm).run(timeout_s=5.0)
    assert isinstance(result.error, UserDataKeyError)
    assert "state '/R' reads userdata key 'x' which has no value yet (keys with a value: z)" in result.reason


def test_view_helpers():
    seen: Dict[str, Any] = {}

    def action(ud, n):
        seen["keys"] = ud.keys()
        seen["in"] = ("a" in ud, "missing" in ud)
        seen["get"] = ud.get("a")
        seen["hasattr"] = hasattr(ud, "undeclared")
        seen["copy"] = copy.copy(ud).a
        try:
            copy.deepcopy(ud)
            seen["deepcopy"] = "allowed"
        except TypeError:
            seen["deepcopy"] = "refused"

    run_one(
        ScriptedState(Journal(), input_keys=["a"], output_keys=["b"], action=action),
        sm={"input_keys": ["a"]},
        inputs={"a": 7},
    )
    assert seen == {
        "keys": ("a", "b"),
        "in": (True, False),
        "get": 7,
        "hasattr": False,
        "copy": 7,
        "deepcopy": "refused",
    }


def test_remapping_renames_keys_both_ways():
    def action(ud, n):
        ud.out = ud.inp * 10

    state = ScriptedState(Journal(), input_keys=["inp"], output_keys=["out"], action=action)
    result = run_one(
        state,
        sm={"input_keys": ["value"], "output_keys": ["result"]},
        remapping={"inp": "value", "out": "result"},
        inputs={"value": 4},
    )
    assert result.outputs == {"result": 40}


def test_nested_machine_passes_declared_keys_in_and_out_only():
    journal = Journal()
    inner = StateMachine(outcomes=["finished", "failed"], input_keys=["x"], output_keys=["y"], userdata={"scratch": 1})

    def compute(ud, n):
        ud.y = ud.x + ud.scratch
        ud.scratch = 100

    inner.add(
        "C",
        ScriptedState(journal, input_keys=["x", "scratch"], output_keys=["y", "scratch"], action=compute),
        transitions={"done": "finished", "failed": "failed"},
    )
    outer = StateMachine(
        outcomes=["finished", "failed"], input_keys=["start"], output_keys=["end", "scratch"], userdata={"scratch": -1}
    )
    outer.add(
        "Inner", inner, transitions={"finished": "finished", "failed": "failed"}, remapping={"x": "start", "y": "end"}
    )
    result = executor(outer, inputs={"start": 5}).run(timeout_s=5.0)
    assert result.status is BehaviorStatus.FINISHED
    assert result.outputs == {"end": 6, "scratch": -1}  # the inner scratch never leaks out


def test_nested_machine_starts_fresh_on_each_activation():
    seen = []
    inner = StateMachine(outcomes=["finished", "failed"], userdata={"count": 0}, output_keys=["count"])

    def bump(ud, n):
        ud.count = ud.count + 1
        seen.append(ud.count)

    inner.add(
        "Bump",
        ScriptedState(Journal(), input_keys=["count"], output_keys=["count"], action=bump, then="done"),
        transitions={"done": "finished", "failed": "failed"},
    )
    outer = StateMachine(outcomes=["finished", "failed"], userdata={"count": 0})
    outer.add("Inner", inner, transitions={"finished": "Again", "failed": "failed"})
    outer.add(
        "Again",
        ScriptedState(Journal(), script=["failed", "done"]),
        transitions={"failed": "Inner", "done": "finished"},
    )
    result = executor(outer).run(timeout_s=5.0)
    assert result.outcome == "finished"
    assert seen == [1, 1]


def test_input_only_values_are_read_only_views_without_copy():
    msg = Message()
    seen: Dict[str, Any] = {}

    def action(ud, n):
        view = ud.msg
        seen["isinstance"] = isinstance(view, Message)
        seen["same"] = unwrap(view) is msg
        seen["frame"] = view.header.frame_id
        seen["sum"] = sum(view.data)
        for attempt, fn in {
            "attr": lambda: setattr(view, "data", []),
            "nested attr": lambda: setattr(view.header, "frame_id", "odom"),
            "list item": lambda: view.data.__setitem__(0, 99),
            "dict item": lambda: view.tags.__setitem__("b", 1),
            "nested list in dict": lambda: view.tags["a"].__setitem__(0, 5),
            "del": lambda: delattr(view, "tags"),
        }.items():
            try:
                fn()
                seen[attempt] = "allowed"
            except ReadOnlyUserDataError:
                seen[attempt] = "refused"
        try:
            view.data.append(1)
            seen["append"] = "allowed"
        except ReadOnlyUserDataError as err:
            seen["append"] = str(err)

    result = run_one(
        ScriptedState(Journal(), input_keys=["msg"], action=action), sm={"input_keys": ["msg"]}, inputs={"msg": msg}
    )
    assert result.status is BehaviorStatus.FINISHED, result.reason
    assert seen["isinstance"] and seen["same"]
    assert seen["frame"] == "map" and seen["sum"] == 45
    assert {
        k: v for k, v in seen.items() if k not in ("isinstance", "same", "frame", "sum", "append")
    } == dict.fromkeys(["attr", "nested attr", "list item", "dict item", "nested list in dict", "del"], "refused")
    assert seen["append"].startswith("cannot call append() on input-only userdata (a read-only view of list)")
    assert msg.data == list(range(10)) and msg.header.frame_id == "map" and msg.tags == {"a": [1]}


def test_input_output_key_gives_the_real_object():
    msg = Message()

    def action(ud, n):
        ud.msg.data.append(10)

    result = run_one(
        ScriptedState(Journal(), input_keys=["msg"], output_keys=["msg"], action=action),
        sm={"input_keys": ["msg"], "output_keys": ["msg"]},
        inputs={"msg": msg},
    )
    assert result.status is BehaviorStatus.FINISHED
    assert msg.data[-1] == 10


def test_protection_follows_input_only_keys_into_nested_machines():
    """A key that is input-only for the outer machine stays read-only even for an in/out inner state."""
    msg = Message()
    inner = StateMachine(outcomes=["finished", "failed"], input_keys=["msg"], output_keys=["msg"])

    def mutate(ud, n):
        ud.msg.data.append(1)

    inner.add(
        "M",
        ScriptedState(Journal(), input_keys=["msg"], output_keys=["msg"], action=mutate),
        transitions={"done": "finished", "failed": "failed"},
    )
    outer = StateMachine(outcomes=["finished", "failed"], input_keys=["msg"])
    outer.add("Inner", inner, transitions={"finished": "finished", "failed": "failed"})
    result = executor(outer, inputs={"msg": msg}).run(timeout_s=5.0)
    assert isinstance(result.error, ReadOnlyUserDataError)
    assert "cannot call append() on input-only userdata" in result.reason
    assert msg.data == list(range(10))


def test_numpy_inputs_are_non_writeable_views():
    cloud = np.zeros((1000, 3))
    seen: Dict[str, Any] = {}

    def action(ud, n):
        view = ud.cloud
        seen["shares"] = np.shares_memory(view, cloud)
        try:
            view[0, 0] = 1.0
            seen["write"] = "allowed"
        except ValueError:
            seen["write"] = "refused"

    run_one(
        ScriptedState(Journal(), input_keys=["cloud"], action=action),
        sm={"input_keys": ["cloud"]},
        inputs={"cloud": cloud},
    )
    assert seen == {"shares": True, "write": "refused"}
    assert cloud.flags.writeable  # the caller's array is untouched


def test_readonly_named_tuples_keep_fields_and_enums_and_functions_pass():
    class Pose(NamedTuple):
        x: float
        tags: list

    class Mode(enum.Enum):
        FAST = 1

    view = readonly(Pose(1.0, [1]))
    assert (view.x, view[0], len(view), isinstance(view, Pose)) == (1.0, 1.0, 2, True)
    with pytest.raises(ReadOnlyUserDataError):
        view.tags.append(2)
    assert readonly(Mode.FAST) is Mode.FAST
    assert readonly(len) is len


def test_readonly_of_immutables_is_identity_and_views_compare_equal():
    for value in (1, 2.5, "s", b"b", None, True, (1, 2)[0]):
        assert readonly(value) is value
    assert readonly([1, 2]) == [1, 2]
    assert readonly({"a": 1}) == {"a": 1}
    assert readonly({1, 2}) == {1, 2}
    assert readonly((1, [2])) == (1, [2])
    assert [list(item) for item in readonly([[1], [2]])] == [[1], [2]]
    with pytest.raises(ReadOnlyUserDataError):
        readonly({1, 2}).add(3)
    with pytest.raises(ReadOnlyUserDataError):
        readonly({"a": 1}).update(b=2)
    ba = readonly(bytearray(b"xy"))
    with pytest.raises(TypeError):
        ba[0] = 1


def test_undeclared_root_input_and_missing_input_are_config_errors():
    sm = StateMachine(outcomes=["finished", "failed"], input_keys=["goal"])
    sm.add("S", ScriptedState(Journal(), input_keys=["goal"]), transitions={"done": "finished", "failed": "failed"})
    with pytest.raises(ConfigError, match=r"input key 'gaol' is not valid \(valid: goal\)"):
        executor(sm, inputs={"gaol": 1})
    sm2 = StateMachine(outcomes=["finished", "failed"], input_keys=["goal"])
    sm2.add("S", ScriptedState(Journal(), input_keys=["goal"]), transitions={"done": "finished", "failed": "failed"})
    with pytest.raises(ConfigError, match=r"needs a value for input key\(s\) goal"):
        executor(sm2)


def test_concurrent_children_share_the_container_store():
    def write(ud, n):
        ud.shared = "from A"

    got = []

    def read_shared(ud, n):
        if n > 1:
            got.append(ud.shared)

    cc = ConcurrencyContainer(
        outcomes=["done"], conditions=[("done", [("A", "done"), ("B", "done")])], output_keys=["shared"]
    )
    cc.add("A", ScriptedState(Journal(), output_keys=["shared"], action=write))
    cc.add(
        "B",
        ScriptedState(
            Journal(),
            input_keys=["shared"],
            script=[None, "done"],
            action=read_shared,
        ),
    )
    sm = StateMachine(outcomes=["done"], output_keys=["shared"])
    sm.add("CC", cc, transitions={"done": "done"})
    result = executor(sm).run(timeout_s=5.0)
    assert result.outputs == {"shared": "from A"}
    assert got == ["from A"]


def test_nested_machine_entered_without_a_value_for_its_input_fails_loudly():
    """Validation accepts a key a sibling writes; at run time the sibling took a path that did not write it."""
    inner = StateMachine(outcomes=["finished", "failed"], input_keys=["plan"])
    inner.add(
        "Use", ScriptedState(Journal(), input_keys=["plan"]), transitions={"done": "finished", "failed": "failed"}
    )
    outer = StateMachine(outcomes=["finished", "failed"], userdata={"other": 1})
    outer.add(
        "Plan",
        ScriptedState(Journal(), output_keys=["plan"], script=["failed"]),
        transitions={"done": "Inner", "failed": "Inner"},
    )
    outer.add("Inner", inner, transitions={"finished": "finished", "failed": "failed"})
    result = executor(outer).run(timeout_s=5.0)
    assert result.status is BehaviorStatus.FAILED
    assert isinstance(result.error, UserDataKeyError)
    assert (
        "state machine /Inner: input key 'plan' has no value in its parent (keys with a value: other)" in result.reason
    )
