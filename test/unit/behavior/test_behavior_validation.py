"""Build-time validation: each construction error names the bad item and the valid choices."""

from __future__ import annotations

from typing import Any, Dict

import pytest
from unit.behavior.behavior_testlib import Journal, ScriptedState, executor

from flex_nav.behavior import Autonomy, ConcurrencyContainer, StateMachine
from flex_nav.exceptions import (
    BehaviorConstructionError,
    ConfigError,
    LabelClashError,
    MissingInitialStateError,
    MissingTransitionError,
    UndeclaredKeyError,
    UnknownTargetError,
    UnreachableStateError,
    UnregisteredOutcomeError,
)


def state(**kwargs):
    return ScriptedState(Journal(), **kwargs)


def machine(**kwargs):
    kwargs.setdefault("outcomes", ["finished", "failed"])
    return StateMachine(**kwargs)


def test_errors_are_config_errors():
    assert issubclass(BehaviorConstructionError, ConfigError)
    assert issubclass(UnknownTargetError, BehaviorConstructionError)


def test_unknown_target():
    sm = machine()
    sm.add("A", state(), transitions={"done": "Nowhere", "failed": "failed"})
    with pytest.raises(UnknownTargetError) as info:
        sm.validate()
    assert "transition 'A'.done goes to unknown target 'Nowhere' (valid: A, finished, failed)" in str(info.value)
    assert (info.value.label, info.value.item, info.value.field) == ("A", "done", "transition")


def test_unregistered_outcome_in_transitions():
    sm = machine()
    with pytest.raises(
        UnregisteredOutcomeError,
        match=r"names outcome 'succeeded' that ScriptedState does not register \(valid: done, failed\)",
    ):
        sm.add("A", state(), transitions={"succeeded": "finished"})


def test_unregistered_outcome_in_autonomy():
    sm = machine()
    with pytest.raises(UnregisteredOutcomeError, match=r"autonomy of 'A' names outcome 'ok'.*\(valid: done, failed\)"):
        sm.add("A", state(), transitions={"done": "finished", "failed": "failed"}, autonomy={"ok": Autonomy.LOW})


def test_bad_autonomy_level():
    sm = machine()
    with pytest.raises(
        BehaviorConstructionError,
        match=r"autonomy level 'medium' is not valid \(valid: off, low, high, full, 0, 1, 2, 3\)",
    ):
        sm.add("A", state(), transitions={"done": "finished", "failed": "failed"}, autonomy={"done": "medium"})


ENDS = {"done": "finished", "failed": "failed"}  # transitions of a state that ends the machine

INVALID_MACHINES = {  # test id: (the states added, label and transitions; the error validate() raises; its message)
    "missing_transition": (
        [("A", {"done": "finished"})],
        MissingTransitionError,
        r"outcome 'failed' of state 'A' has no transition \(valid targets: A, finished, failed\)",
    ),
    "unreachable_state": (
        [("A", ENDS), ("Orphan", {"done": "A", "failed": "failed"})],
        UnreachableStateError,
        r"state 'Orphan' cannot be reached from the initial state 'A' \(reachable: A\)",
    ),
    "label_outcome_clash": (
        [("finished", ENDS)],
        LabelClashError,
        r"state label 'finished' is also an outcome of the machine \(outcomes: finished, failed\)",
    ),
}


@pytest.mark.parametrize(("added", "error", "match"), INVALID_MACHINES.values(), ids=INVALID_MACHINES.keys())
def test_validate_names_the_problem(added, error, match):
    sm = machine()
    for label, transitions in added:
        sm.add(label, state(), transitions=transitions)
    with pytest.raises(error, match=match):
        sm.validate()


def test_duplicate_label():
    sm = machine()
    sm.add("A", state(), transitions={"done": "finished", "failed": "failed"})
    with pytest.raises(LabelClashError, match=r"state label 'A' is used twice \(labels: A\)"):
        sm.add("A", state(), transitions={"done": "finished", "failed": "failed"})


@pytest.mark.parametrize("label", ["", "a/b", " A"])
def test_malformed_label(label):
    with pytest.raises(LabelClashError, match="must be a non-empty name"):
        machine().add(label, state(), transitions={})


def test_missing_initial_state():
    with pytest.raises(MissingInitialStateError, match=r"state machine / has no states"):
        machine().validate()
    sm = machine()
    sm.add("A", state(), transitions={"done": "finished", "failed": "failed"})
    sm.set_initial_state("Start")
    with pytest.raises(MissingInitialStateError, match=r"initial state 'Start' is not one of its states \(valid: A\)"):
        sm.validate()


def test_set_initial_state_changes_start_and_reachability():
    journal = Journal()
    sm = machine()
    sm.add("A", ScriptedState(journal), transitions={"done": "finished", "failed": "failed"})
    sm.add("B", ScriptedState(journal), transitions={"done": "A", "failed": "failed"})
    sm.set_initial_state("B")
    result = executor(sm).run(timeout_s=5.0)
    assert result.outcome == "finished"
    assert [who for who, call in journal.calls if call == "enter"] == ["B", "A"]


def test_undeclared_input_key():
    sm = machine()
    sm.add("A", state(input_keys=["goal"]), transitions={"done": "finished", "failed": "failed"})
    with pytest.raises(UndeclaredKeyError) as info:
        sm.validate()
    assert "input key 'goal' of state 'A' is neither an input key nor a userdata default" in str(info.value)
    assert "(available: none)" in str(info.value)


def test_input_key_provided_by_sibling_output_or_default_or_container_input():
    seen: Dict[str, Any] = {}

    def write_plan(ud, _n):
        ud.plan = "p"

    def read_all(ud, _n):
        seen.update(plan=ud.plan, goal=ud.goal, tries=ud.tries)

    sm = machine(input_keys=["goal"], userdata={"tries": 0})
    sm.add("A", state(output_keys=["plan"], action=write_plan), transitions={"done": "B", "failed": "failed"})
    sm.add("B", state(input_keys=["plan", "goal", "tries"], action=read_all),
           transitions={"done": "finished", "failed": "failed"})
    sm.validate()  # accepted: each of B's keys has a source
    result = executor(sm, inputs={"goal": "g"}).run(timeout_s=5.0)
    assert result.outcome == "finished"
    assert seen == {"plan": "p", "goal": "g", "tries": 0}


def test_remapped_input_key_is_checked_under_the_container_name():
    sm = machine(input_keys=["goal"])
    sm.add(
        "A",
        state(input_keys=["target"]),
        transitions={"done": "finished", "failed": "failed"},
        remapping={"target": "gaol"},
    )
    with pytest.raises(UndeclaredKeyError, match=r"input key 'target' \(remapped to 'gaol'\).*\(available: goal\)"):
        sm.validate()


def test_remapping_of_undeclared_key():
    with pytest.raises(
        UndeclaredKeyError, match=r"remapping of 'A' names key 'x' that ScriptedState does not declare \(valid: a, b\)"
    ):
        machine().add(
            "A", state(input_keys=["a"], output_keys=["b"]), transitions={"done": "finished"}, remapping={"x": "y"}
        )


def test_container_output_key_must_be_produced():
    sm = machine(output_keys=["result"])
    sm.add("A", state(output_keys=["other"]), transitions={"done": "finished", "failed": "failed"})
    with pytest.raises(UndeclaredKeyError, match=r"output key 'result' is produced by no state.*\(available: other\)"):
        sm.validate()


def test_nested_errors_name_the_nested_path():
    inner = machine()
    inner.add("X", state(), transitions={"done": "Y", "failed": "failed"})
    outer = machine()
    outer.add("Inner", inner, transitions={"finished": "finished", "failed": "failed"})
    with pytest.raises(
        UnknownTargetError, match=r"state machine /Inner: transition 'X'.done goes to unknown target 'Y'"
    ):
        outer.validate()


def test_executor_validates_before_running():
    journal = Journal()
    sm = machine()
    sm.add("A", ScriptedState(journal), transitions={"done": "B", "failed": "failed"})
    with pytest.raises(UnknownTargetError):
        executor(sm)
    assert journal.calls == []  # nothing started


def test_concurrency_condition_errors():
    def cc(conditions):
        c = ConcurrencyContainer(outcomes=["ok", "bad"], conditions=conditions)
        c.add("A", state())
        c.add("B", state())
        return c

    with pytest.raises(UnknownTargetError, match=r"condition for 'ok' names unknown state 'C' \(valid: A, B\)"):
        cc([("ok", [("C", "done")])]).validate()
    with pytest.raises(
        UnregisteredOutcomeError,
        match=r"condition for 'ok' names outcome 'yes' of 'A' that it does not register \(valid: done, failed\)",
    ):
        cc([("ok", [("A", "yes")])]).validate()
    with pytest.raises(
        UnregisteredOutcomeError,
        match=r"condition outcome 'great' is not an outcome of the container \(valid: ok, bad\)",
    ):
        cc([("great", [("A", "done")])]).validate()
    with pytest.raises(BehaviorConstructionError, match="has no conditions"):
        cc([]).validate()
    with pytest.raises(BehaviorConstructionError, match="lists no"):
        cc([("ok", [])]).validate()
    with pytest.raises(MissingInitialStateError, match="has no states"):
        ConcurrencyContainer(outcomes=["ok"], conditions=[("ok", [("A", "done")])]).validate()


def test_state_declarations_are_checked():
    with pytest.raises(ConfigError, match="at least one outcome"):
        ScriptedState(Journal(), outcomes=[])
    with pytest.raises(ConfigError, match="repeat done"):
        ScriptedState(Journal(), outcomes=["done", "done"])
    with pytest.raises(ConfigError, match="not the string"):
        ScriptedState(Journal(), input_keys="goal")
