"""SMACH API: StateMachine construction, execution, callbacks, introspection, failure paths, preemption."""

from __future__ import annotations

import threading
from typing import Any, List, Tuple

import pytest

from flex_nav.compat import smach
from flex_nav.compat.smach import _hooks

WAIT_S = 10.0  # [s] bound of every wait on another thread (never reached when the code is right)


class Scripted(smach.State):
    """Returns the scripted outcomes in turn (then the last one) and records each execution."""

    def __init__(self, script, outcomes=None, input_keys=(), output_keys=(), action=None):
        super().__init__(outcomes=outcomes or sorted(set(script)), input_keys=input_keys, output_keys=output_keys)
        self.script = list(script)
        self.runs = 0
        self.action = action

    def execute(self, ud):
        self.runs += 1
        if self.action is not None:
            self.action(ud)
        return self.script[min(self.runs, len(self.script)) - 1]


class Blocking(smach.State):
    """Blocks until preempted, then services the preempt (or not) and returns."""

    def __init__(self, service=True, outcome="preempted"):
        super().__init__(outcomes=["done", "preempted"])
        self.started = threading.Event()
        self.service = service
        self.outcome = outcome
        self.saw_preempt_at_start = None

    def execute(self, ud):
        self.saw_preempt_at_start = self.preempt_requested()
        self.started.set()
        poll = threading.Event()
        for _ in range(int(WAIT_S / 0.005)):
            if self.preempt_requested():
                break
            poll.wait(0.005)
        else:
            raise AssertionError("never preempted")
        if self.service:
            self.service_preempt()
        return self.outcome


def machine(*states, outcomes=("done", "failed")):
    """A StateMachine of (label, state, transitions) triples."""
    sm = smach.StateMachine(outcomes=list(outcomes))
    with sm:
        for label, state, transitions in states:
            smach.StateMachine.add(label, state, transitions=transitions)
    return sm


def run_in_thread(sm, ud=None):
    result = {}

    def target():
        try:
            result["outcome"] = sm.execute(ud)
        except Exception as err:
            result["error"] = err

    thread = threading.Thread(target=target, daemon=True)
    thread.start()
    return thread, result


# --- construction ---------------------------------------------------------------------------------
def test_first_added_state_is_initial_and_unbound_outcomes_fall_through():
    a = Scripted(["next"], outcomes=["next", "done"])
    b = Scripted(["done"])
    sm = machine(("A", a, {"next": "B"}), ("B", b, {}))
    assert sm.get_initial_states() == ["A"]
    assert sm.execute() == "done"  # B.done is unbound: the machine's outcome of the same name
    assert (a.runs, b.runs) == (1, 1)
    assert ("done", "B", None) in sm.get_internal_edges()


def test_add_outside_an_opened_container_on_the_class_is_invalid_state_error():
    with pytest.raises(smach.InvalidStateError, match="no container is opened"):
        smach.StateMachine.add("A", Scripted(["done"]))


def test_add_on_an_instance_without_with_adds_to_that_instance():
    sm = smach.StateMachine(outcomes=["done"])
    sm.add("A", Scripted(["done"]), transitions={"done": "done"})
    assert list(sm.get_children()) == ["A"]
    assert sm.execute() == "done"


def test_class_add_acts_on_the_innermost_opened_container():
    outer = smach.StateMachine(outcomes=["done"])
    with outer:
        inner = smach.StateMachine(outcomes=["ok"])
        with inner:
            smach.StateMachine.add("LEAF", Scripted(["ok"]))
        smach.StateMachine.add("INNER", inner, transitions={"ok": "done"})
    assert list(outer.get_children()) == ["INNER"]
    assert list(inner.get_children()) == ["LEAF"]
    assert outer.execute() == "done"


def test_with_returns_the_container_and_opened_works_too():
    sm = smach.StateMachine(outcomes=["done"])
    with sm as opened:
        assert opened is sm and sm.is_opened()
    assert not sm.is_opened()
    with sm.opened(ignored="kw") as same:
        assert same is sm
        smach.StateMachine.add("A", Scripted(["done"]))
    assert sm.execute() == "done"


def test_wrong_container_kind_for_the_construction_method():
    cc = smach.Concurrence(outcomes=["done"], default_outcome="done")
    with cc, pytest.raises(smach.InvalidStateError, match="opened container is a Concurrence"):
        smach.StateMachine.add("A", Scripted(["done"]))


def test_duplicate_label_and_label_equal_to_outcome_are_invalid_state_errors():
    sm = smach.StateMachine(outcomes=["done"])
    with sm:
        smach.StateMachine.add("A", Scripted(["done"]))
        with pytest.raises(smach.InvalidStateError, match=r"'A' is already used \(labels: A\)"):
            smach.StateMachine.add("A", Scripted(["done"]))
        with pytest.raises(smach.InvalidStateError, match="also an outcome of the machine"):
            smach.StateMachine.add("done", Scripted(["done"]))
        with pytest.raises(smach.InvalidStateError, match="must be a SMACH state"):
            smach.StateMachine.add("B", object())


def test_transition_for_an_unregistered_outcome_names_the_registered_ones():
    sm = smach.StateMachine(outcomes=["done"])
    with sm, pytest.raises(smach.InvalidTransitionError, match=r"'typo'.*registered: ok, bad"):
        smach.StateMachine.add("A", Scripted(["ok"], outcomes=["ok", "bad"]), transitions={"typo": "done"})


def test_unknown_target_fails_consistency_at_execute_naming_valid_targets(caplog):
    sm = smach.StateMachine(outcomes=["done"])
    with sm:
        smach.StateMachine.add("A", Scripted(["ok"], outcomes=["ok"]), transitions={"ok": "NOWHERE"})
    assert "consistency check failed" in caplog.text  # logged when the with block closes, as SMACH does
    with pytest.raises(smach.InvalidTransitionError, match=r"unknown target 'NOWHERE' \(valid targets: A, done\)"):
        sm.execute()
    assert not sm.is_running()


def test_unbound_outcome_that_is_not_a_machine_outcome_fails_consistency():
    sm = machine(("A", Scripted(["ok"], outcomes=["ok", "lost"]), {"ok": "done"}))
    with pytest.raises(smach.InvalidTransitionError, match="'lost' has no transition"):
        sm.check_consistency()


def test_empty_machine_fails_consistency():
    with pytest.raises(smach.InvalidTransitionError, match="no initial state"):
        smach.StateMachine(outcomes=["done"]).execute()


def test_add_auto_connects_outcomes_to_the_next_state_unless_overridden():
    a = Scripted(["go"], outcomes=["go", "stop"])
    b = Scripted(["go"], outcomes=["go", "stop"])
    c = Scripted(["done"], outcomes=["done"])
    sm = smach.StateMachine(outcomes=["done", "stopped"])
    with sm:
        smach.StateMachine.add_auto("A", a, ["go"], transitions={"stop": "stopped"})
        smach.StateMachine.add_auto("B", b, ["go", "stop"], transitions={"stop": "stopped"})
        smach.StateMachine.add("C", c)
        with pytest.raises(smach.InvalidStateError, match=r"connector outcomes nope.*registered: done"):
            smach.StateMachine.add_auto("D", Scripted(["done"]), ["nope"])
    assert sm._transitions["A"] == {"go": "B", "stop": "stopped"}
    assert sm._transitions["B"] == {"go": "C", "stop": "stopped"}  # the explicit transition wins


# --- execution and userdata -----------------------------------------------------------------------------
def test_input_keys_are_copied_in_and_output_keys_out_with_remapping():
    def work(ud):
        ud.out = ud.inp * 10

    inner = smach.StateMachine(outcomes=["ok"], input_keys=["a"], output_keys=["b"])
    with inner:
        smach.StateMachine.add(
            "W",
            Scripted(["ok"], input_keys=["inp"], output_keys=["out"], action=work),
            remapping={"inp": "a", "out": "b"},
        )
    outer = smach.StateMachine(outcomes=["done"], input_keys=["x"], output_keys=["y"])
    with outer:
        smach.StateMachine.add("INNER", inner, transitions={"ok": "done"}, remapping={"a": "x", "b": "y"})
    parent = smach.UserData()
    parent.x = 4
    assert outer.execute(parent) == "done"
    assert parent.y == 40
    assert inner.userdata.b == 40  # container userdata persists between executions, as in SMACH


def test_state_returning_unregistered_outcome_is_invalid_transition_naming_registered():
    sm = machine(("A", Scripted(["weird"], outcomes=["done"]), {}))
    with pytest.raises(smach.InvalidTransitionError, match=r"returned outcome 'weird'.*registered: done"):
        sm.execute()
    sm = machine(("A", smach.CBState(lambda ud: None, outcomes=["done"]), {}))
    with pytest.raises(smach.InvalidTransitionError, match="returned outcome None"):
        sm.execute()


def test_state_raising_is_invalid_user_code_error_chained_and_machine_is_reset():
    def boom(ud):
        raise RuntimeError("sensor unplugged")

    sm = machine(("A", smach.CBState(boom, outcomes=["done"]), {}))
    with pytest.raises(
        smach.InvalidUserCodeError, match=r"state 'A' \(CBState\) raised RuntimeError: sensor unplugged"
    ) as info:
        sm.execute()
    assert isinstance(info.value.__cause__, RuntimeError)
    assert not sm.is_running() and sm.get_active_states() == []


def test_errors_of_nested_containers_pass_through_unchanged():
    inner = machine(("X", Scripted(["bad"], outcomes=["done"]), {}))
    outer = machine(("INNER", inner, {"done": "done", "failed": "failed"}))
    with pytest.raises(smach.InvalidTransitionError, match="'bad'"):
        outer.execute()


def test_reading_undeclared_key_inside_execute_is_invalid_user_code():
    sm = smach.StateMachine(outcomes=["done"])
    sm.userdata.hidden = 1
    with sm:
        smach.StateMachine.add("A", smach.CBState(lambda ud: ud.hidden and "done", outcomes=["done"]))
    with pytest.raises(smach.InvalidUserCodeError, match="declares as input only: none"):
        sm.execute()


def test_execute_is_not_reentrant():
    blocker = Blocking()
    sm = machine(("B", blocker, {"done": "done", "preempted": "failed"}))
    thread, _ = run_in_thread(sm)
    assert blocker.started.wait(WAIT_S)
    with pytest.raises(smach.InvalidStateError, match="already running"):
        sm.execute()
    sm.request_preempt()
    thread.join(WAIT_S)


# --- callbacks and introspection ---------------------------------------------------------------------------------
def test_start_transition_termination_callbacks_get_smach_arguments():
    events: List[Tuple[Any, ...]] = []
    sm = machine(("A", Scripted(["next"], outcomes=["next"]), {"next": "B"}), ("B", Scripted(["done"]), {}))
    sm.register_start_cb(lambda ud, initial, tag: events.append(("start", initial, tag)), ["s"])
    sm.register_transition_cb(lambda ud, active, tag: events.append(("transition", active, tag)), ["t"])
    sm.register_termination_cb(lambda ud, terminal, outcome, tag: events.append(("end", terminal, outcome, tag)), ["e"])
    assert sm.execute() == "done"
    assert events == [("start", ["A"], "s"), ("transition", ["B"], "t"), ("end", ["B"], "done", "e")]


def test_callback_that_raises_fails_the_machine():
    sm = machine(("A", Scripted(["done"]), {}))
    sm.register_termination_cb(lambda ud, terminal, outcome: 1 / 0)
    with pytest.raises(smach.InvalidUserCodeError, match=r"termination callback.*ZeroDivisionError"):
        sm.execute()
    with pytest.raises(smach.InvalidStateError, match="must be callable"):
        sm.register_start_cb("not callable")


def test_active_states_and_is_running_during_execution():
    seen = []
    sm = smach.StateMachine(outcomes=["done"])

    def look(ud: Any) -> str:
        seen.append((sm.get_active_states(), sm.is_running()))
        return "done"

    with sm:
        smach.StateMachine.add("A", smach.CBState(look, outcomes=["done"]))
    assert sm.get_active_states() == [] and not sm.is_running()
    sm.execute()
    assert seen == [(["A"], True)]
    assert sm.get_active_states() == []


def test_set_initial_state_with_userdata_and_invalid_choices():
    seen: List[Any] = []
    a = Scripted(["done"])
    b = Scripted(["done"], input_keys=["v"], action=lambda ud: seen.append(ud.v))
    sm = machine(("A", a, {}), ("B", b, {}))
    starts = []
    sm.register_start_cb(lambda ud, initial: starts.append(initial))
    injected = smach.UserData()
    injected.v = 42
    sm.set_initial_state(["B"], injected)
    assert sm.get_initial_states() == ["B"] and starts == [["B"]]  # introspection hears about it
    assert sm.execute() == "done"
    assert (a.runs, b.runs, seen) == (0, 1, [42])


def test_set_initial_state_before_the_state_is_added_is_checked_at_execute(caplog):
    # SMACH stores the label and checks it when the machine runs: it may name a state added later
    a, b = Scripted(["done"]), Scripted(["done"])
    sm = smach.StateMachine(outcomes=["done"])
    starts = []
    sm.register_start_cb(lambda ud, initial: starts.append(initial))
    sm.set_initial_state(["B"])
    assert sm.get_initial_states() == ["B"] and starts == []  # nothing to announce yet
    assert "'B' is not a state of the machine yet (states: none)" in caplog.text
    with sm:
        smach.StateMachine.add("A", a, transitions={"done": "done"})  # added first, but not the initial state
        smach.StateMachine.add("B", b, transitions={"done": "done"})
    assert "consistency check failed" not in caplog.text
    assert sm.execute() == "done"
    assert (a.runs, b.runs) == (0, 1)


def test_an_initial_state_never_added_fails_at_execute_naming_it():
    sm = machine(("A", Scripted(["done"]), {}))
    sm.set_initial_state(["C"])
    assert sm.get_initial_states() == ["C"]
    with pytest.raises(smach.InvalidTransitionError, match=r"initial state 'C' is not in the state machine"):
        sm.execute()
    assert not sm.is_running()
    sm.set_initial_state(["A"])  # put right, the machine runs
    assert sm.execute() == "done"


def test_more_than_one_initial_state_takes_the_first_with_a_warning(caplog):
    a, b = Scripted(["done"]), Scripted(["done"])
    sm = machine(("A", a, {}), ("B", b, {}))
    sm.set_initial_state(["B", "A"])
    assert "exactly one initial state" in caplog.text and "taking 'B'" in caplog.text
    assert sm.get_initial_states() == ["B"]
    assert sm.execute() == "done" and (a.runs, b.runs) == (0, 1)


def test_getitem_names_the_available_states():
    sm = machine(("A", Scripted(["done"]), {}))
    assert sm["A"] is sm.get_children()["A"]
    with pytest.raises(KeyError, match=r"no state 'Z' \(states: A\)"):
        sm["Z"]


def test_container_is_a_smach_container_for_introspection_tools():
    sm = machine(("A", Scripted(["done"]), {}))
    assert isinstance(sm, smach.Container) and isinstance(sm, smach.State)
    from flex_nav.compat.smach import container  # noqa: PLC0415

    assert isinstance(sm, container.Container)


# --- preemption -----------------------------------------------------------------------------------------------------
def test_preempt_propagates_to_the_running_state_and_machine_returns_preempted():
    blocker = Blocking(service=True)
    after = Scripted(["done"])
    sm = machine(
        ("B", blocker, {"done": "AFTER", "preempted": "preempted"}),
        ("AFTER", after, {}),
        outcomes=("done", "preempted"),
    )
    thread, result = run_in_thread(sm)
    assert blocker.started.wait(WAIT_S)
    sm.request_preempt()
    thread.join(WAIT_S)
    assert result == {"outcome": "preempted"}
    assert after.runs == 0
    assert not sm.preempt_requested()  # the child serviced it, so the machine did too


def test_unserviced_preempt_preempts_the_next_state_before_it_runs():
    blocker = Blocking(service=False, outcome="done")
    nxt = Blocking(service=True)
    sm = machine(
        ("B", blocker, {"done": "N", "preempted": "failed"}), ("N", nxt, {"done": "done", "preempted": "failed"})
    )
    thread, result = run_in_thread(sm)
    assert blocker.started.wait(WAIT_S)
    sm.request_preempt()
    thread.join(WAIT_S)
    assert nxt.saw_preempt_at_start is True
    assert result == {"outcome": "failed"}
    assert not blocker.preempt_requested()  # recalled when the preempt moved on to the next state


def test_preempt_requested_before_execute_preempts_the_initial_state():
    first = Blocking(service=True)
    sm = machine(("F", first, {"done": "done", "preempted": "failed"}))
    sm.request_preempt()
    assert sm.execute() == "failed"
    assert first.saw_preempt_at_start is True


def test_preempt_reaches_the_leaf_of_nested_machines():
    leaf = Blocking(service=True)
    inner = machine(("LEAF", leaf, {"done": "done", "preempted": "preempted"}), outcomes=("done", "preempted"))
    outer = machine(("INNER", inner, {"done": "done", "preempted": "preempted"}), outcomes=("done", "preempted"))
    thread, result = run_in_thread(outer)
    assert leaf.started.wait(WAIT_S)
    outer.request_preempt()
    thread.join(WAIT_S)
    assert result == {"outcome": "preempted"}


@pytest.fixture
def shutdown_flag():
    saved = _hooks.HOOKS.shutdown
    flag = threading.Event()
    smach.set_shutdown_check(flag.is_set)
    yield flag
    _hooks.HOOKS.shutdown = saved


def test_shutdown_between_states_stops_with_preempted(shutdown_flag):
    second = Scripted(["done"])
    sm = machine(
        ("A", Scripted(["next"], outcomes=["next"], action=lambda ud: shutdown_flag.set()), {"next": "B"}),
        ("B", second, {}),
        outcomes=("done", "preempted"),
    )
    assert sm.execute() == "preempted"
    assert second.runs == 0
    assert second.preempt_requested()
