"""SMACH API: State, CBState, cb_interface, UserData, Remapper, loggers (documented SMACH behavior)."""

from __future__ import annotations

from typing import Any

import pytest

from flex_nav.compat import smach
from flex_nav.compat.smach import _hooks
from flex_nav.exceptions import BehaviorConstructionError, BehaviorRuntimeError, ReadOnlyUserDataError


class Msg:
    """Stands in for a ROS message (a plain object with fields)."""

    def __init__(self, x: float) -> None:
        self.x = x


def test_state_registers_outcomes_and_keys_in_order_with_io_keys_on_both_sides():
    state = smach.State(outcomes=["b", "a"], input_keys=["in1"], output_keys=["out1"], io_keys=["both"])
    assert state.get_registered_outcomes() == ("b", "a")
    assert state.get_registered_input_keys() == ("in1", "both")
    assert state.get_registered_output_keys() == ("out1", "both")
    state.register_outcomes(["c", "a"])
    state.register_input_keys(["in2"])
    state.register_output_keys(["out2"])
    state.register_io_keys(["io2"])
    assert state.get_registered_outcomes() == ("b", "a", "c")
    assert state.get_registered_input_keys() == ("in1", "both", "in2", "io2")
    assert state.get_registered_output_keys() == ("out1", "both", "out2", "io2")
    assert state._outcomes == {"a", "b", "c"}  # SMACH keeps sets there; code written for SMACH may read them


def test_a_bare_string_as_list_of_outcomes_is_refused():
    with pytest.raises(smach.InvalidStateError, match="not the string 'done'"):
        smach.State(outcomes="done")
    with pytest.raises(smach.InvalidStateError, match="non-empty strings"):
        smach.State(outcomes=["ok", 3])  # type: ignore[list-item]  # on purpose


def test_base_execute_is_abstract():
    with pytest.raises(NotImplementedError, match="must implement execute"):
        smach.State(outcomes=["done"]).execute(smach.UserData())


def test_preempt_flag_request_service_recall():
    state = smach.State(outcomes=["done"])
    assert not state.preempt_requested()
    state.request_preempt()
    assert state.preempt_requested()
    state.service_preempt()
    assert not state.preempt_requested()
    state.request_preempt()
    state.recall_preempt()
    assert not state.preempt_requested()
    state.request_shutdown()
    assert state.preempt_requested() and state._shutdown_requested


def test_exceptions_are_smach_names_in_flex_nav_family():
    assert issubclass(smach.InvalidStateError, BehaviorConstructionError)
    assert issubclass(smach.InvalidTransitionError, BehaviorConstructionError)
    assert issubclass(smach.InvalidConstructionError, BehaviorConstructionError)
    assert issubclass(smach.InvalidUserCodeError, BehaviorRuntimeError)
    from flex_nav.compat.smach import exceptions  # noqa: PLC0415

    assert exceptions.InvalidUserCodeError is smach.InvalidUserCodeError


# --- CBState and cb_interface -----------------------------------------------------------------------
def test_cbstate_calls_callback_with_userdata_args_and_kwargs():
    calls = []

    def cb(ud, a, b, c=0):
        calls.append((ud.x, a, b, c))
        return "done"

    state = smach.CBState(cb, cb_args=[1, 2], cb_kwargs={"c": 3}, outcomes=["done"], input_keys=["x"])
    ud = smach.UserData()
    ud.x = 7
    assert state.execute(smach.Remapper(ud, ["x"], [])) == "done"
    assert calls == [(7, 1, 2, 3)]


def test_cb_interface_adds_its_outcomes_and_keys_to_the_cbstate():
    @smach.cb_interface(outcomes=["extra"], input_keys=["goal"], output_keys=["result"], io_keys=["count"])
    def cb(ud):
        ud.result = ud.goal * 2
        ud.count = ud.count + 1
        return "extra"

    assert isinstance(cb, smach.CBInterface)
    assert smach.has_smach_interface(cb)
    assert cb.get_registered_outcomes() == ("extra",)
    assert cb.get_registered_input_keys() == ("goal", "count")
    assert cb.get_registered_output_keys() == ("result", "count")
    state = smach.CBState(cb, outcomes=["done"])
    assert state.get_registered_outcomes() == ("done", "extra")
    ud = smach.UserData()
    ud.goal, ud.count = 4, 0
    remapper = smach.Remapper(ud, state.get_registered_input_keys(), state.get_registered_output_keys())
    assert state.execute(remapper) == "extra"
    assert (ud.result, ud.count) == (8, 1)
    assert cb.__name__ == "cb"


def test_cb_interface_on_a_method_binds_self():
    class Holder:
        factor = 3

        @smach.cb_interface(outcomes=["ok"])
        def cb(self, ud):
            return "ok" if self.factor == 3 else "bad"

    holder = Holder()
    assert holder.cb(None) == "ok"
    assert holder.cb.get_registered_outcomes() == ("ok",)


def test_cbstate_refuses_a_non_callable():
    with pytest.raises(smach.InvalidStateError, match="needs a callable"):
        smach.CBState("not a function", outcomes=["done"])  # type: ignore[arg-type]  # on purpose


def test_has_smach_interface_false_for_plain_function():
    assert not smach.has_smach_interface(lambda ud: "done")


# --- UserData -------------------------------------------------------------------------------------------
def test_userdata_attribute_and_item_access_share_data_dict():
    ud = smach.UserData()
    ud.a = 1
    ud["b"] = 2
    assert (ud["a"], ud.b) == (1, 2)
    assert ud._data == {"a": 1, "b": 2}
    assert sorted(ud.keys()) == ["a", "b"]
    assert "a" in ud and "z" not in ud
    assert sorted(ud) == ["a", "b"]
    ud._data = {"c": 3}  # smach_ros's introspection replaces the dict like this
    assert ud.c == 3 and ud.keys() == ["c"]


def test_userdata_missing_key_is_a_key_error_and_an_attribute_error_naming_the_keys():
    ud = smach.UserData()
    ud.present = 1
    with pytest.raises(KeyError, match=r"no key 'absent' \(keys: present\)"):
        ud["absent"]
    with pytest.raises(AttributeError):
        ud.absent  # noqa: B018
    assert not hasattr(ud, "absent")
    assert getattr(ud, "absent", "default") == "default"


def test_userdata_update_extract_merge_with_remapping():
    ud = smach.UserData()
    ud.update({"a": 1})
    other = smach.UserData()
    other.b = [1, 2]
    ud.update(other)
    assert (ud.a, ud.b) == (1, [1, 2])
    extracted = ud.extract(["b"], {"local_b": "b"})
    assert extracted.keys() == ["local_b"]
    assert extracted.local_b == [1, 2] and extracted.local_b is not ud.b  # shallow copy
    target = smach.UserData()
    target.merge(ud, ["a", "b"], {"a": "renamed_a"})
    assert (target.renamed_a, target.b) == (1, [1, 2])


# --- Remapper ---------------------------------------------------------------------------------------------
def test_remapper_renames_reads_and_writes():
    ud = smach.UserData()
    ud.container_in = 5
    view = smach.Remapper(ud, ["x"], ["y"], {"x": "container_in", "y": "container_out"})
    assert view.x == 5 and view["x"] == 5
    view.y = 10
    assert ud.container_out == 10
    view["y"] = 11
    assert ud.container_out == 11
    assert "x" in view and "y" not in view  # only inputs are readable
    assert view.keys() == ["x"]


def test_remapper_undeclared_read_and_write_raise_invalid_user_code_naming_declared_keys():
    ud = smach.UserData()
    ud.secret = 1
    view = smach.Remapper(ud, ["a", "b"], ["c"])
    with pytest.raises(smach.InvalidUserCodeError, match=r"'secret'.*input only: a, b"):
        view.secret  # noqa: B018
    with pytest.raises(smach.InvalidUserCodeError, match=r"'a'.*output only: c"):
        view.a = 2
    with pytest.raises(smach.InvalidUserCodeError, match=r"'zz'.*output only: c"):
        view["zz"] = 2
    assert ud.keys() == ["secret"]


def test_remapper_input_only_values_are_read_only_views_and_io_values_are_writable():
    ud = smach.UserData()
    ud.msg = Msg(1.0)
    ud.items = [1, 2]
    ud.io = Msg(2.0)
    view = smach.Remapper(ud, ["msg", "items", "io"], ["io"])
    with pytest.raises(ReadOnlyUserDataError):
        view.msg.x = 5.0
    with pytest.raises(ReadOnlyUserDataError):
        view.items.append(3)
    assert isinstance(view.msg, Msg) and view.msg.x == 1.0
    assert ud.msg.x == 1.0 and ud.items == [1, 2]
    view.io.x = 9.0
    assert ud.io.x == 9.0


def test_remapper_missing_declared_key_is_a_key_error_and_empty_list_remapping_is_accepted():
    no_remapping: Any = []  # what smach_ros passes for "no remapping", outside the declared Mapping
    view = smach.Remapper(smach.UserData(), ["goal"], [], no_remapping)
    with pytest.raises(KeyError, match="'goal' has no value yet"):
        view.goal  # noqa: B018
    with pytest.raises(smach.InvalidUserCodeError, match="must be a mapping"):
        smach.Remapper(smach.UserData(), ["a"], [], [("a", "b")])  # type: ignore[arg-type]  # on purpose


def test_remapper_over_a_remapper_reaches_the_outer_userdata():
    ud = smach.UserData()
    ud.outer = 3
    middle = smach.Remapper(ud, ["m"], ["m"], {"m": "outer"})
    inner = smach.Remapper(middle, ["i"], ["i"], {"i": "m"})
    assert inner.i == 3
    inner.i = 4
    assert ud.outer == 4


# --- loggers and shutdown ------------------------------------------------------------------------------------
@pytest.fixture
def restore_hooks():
    saved = (_hooks.HOOKS.info, _hooks.HOOKS.warn, _hooks.HOOKS.debug, _hooks.HOOKS.error, _hooks.HOOKS.shutdown)
    yield
    (_hooks.HOOKS.info, _hooks.HOOKS.warn, _hooks.HOOKS.debug, _hooks.HOOKS.error, _hooks.HOOKS.shutdown) = saved


def test_set_loggers_routes_messages_in_smach_argument_order(restore_hooks):
    seen = []
    from flex_nav.compat.smach import loginfo as early_loginfo  # noqa: PLC0415

    smach.set_loggers(
        lambda m: seen.append(("info", m)),
        lambda m: seen.append(("warn", m)),
        lambda m: seen.append(("debug", m)),
        lambda m: seen.append(("error", m)),
    )
    early_loginfo("i")
    smach.logwarn("w")
    smach.logdebug("d")
    smach.logerr("e")
    assert seen == [("info", "i"), ("warn", "w"), ("debug", "d"), ("error", "e")]
    with pytest.raises(ValueError, match="error logger must be callable"):
        smach.set_loggers(print, print, print, "nope")  # type: ignore[arg-type]  # on purpose


def test_shutdown_check(restore_hooks):
    assert smach.is_shutdown() is False
    smach.set_shutdown_check(lambda: True)
    assert smach.is_shutdown() is True
    with pytest.raises(ValueError, match="needs a callable"):
        smach.set_shutdown_check(True)  # type: ignore[arg-type]  # on purpose
