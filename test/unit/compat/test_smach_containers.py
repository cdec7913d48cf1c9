"""SMACH API: Sequence, Concurrence (threads, outcome policy, preemption, failures), Iterator."""

from __future__ import annotations

import threading
from typing import Any, Callable, Dict, Optional

import pytest

from flex_nav.compat import smach

WAIT_S = 10.0  # [s] bound of every wait on another thread


def cb_state(outcome, outcomes=None, **keys):
    return smach.CBState(lambda ud: outcome, outcomes=outcomes or [outcome], **keys)


class Waiter(smach.State):
    """Waits until preempted (services it, returns 'preempted') or released (returns 'done')."""

    def __init__(self, service=True):
        super().__init__(outcomes=["done", "preempted"])
        self.release = threading.Event()
        self.started = threading.Event()
        self.service = service

    def execute(self, ud):
        self.started.set()
        poll = threading.Event()
        for _ in range(int(WAIT_S / 0.005)):
            if self.preempt_requested():
                if self.service:
                    self.service_preempt()
                return "preempted"
            if self.release.is_set():
                return "done"
            poll.wait(0.005)
        raise AssertionError("neither preempted nor released")


def once_started(waiter: Waiter, outcome: str) -> Callable[[Any], Optional[str]]:
    """A CBState callback: ``outcome`` once ``waiter`` has started (None, not an outcome, if it does not in WAIT_S)."""

    def wait(ud: Any) -> Optional[str]:
        return outcome if waiter.started.wait(WAIT_S) else None

    return wait


# --- Sequence -------------------------------------------------------------------------------------------
def test_sequence_connects_states_in_order_and_the_last_falls_through():
    order = []

    def step(name: str) -> Callable[[Any], str]:
        def run(ud: Any) -> str:
            order.append(name)
            return "succeeded"

        return run

    seq = smach.Sequence(outcomes=["succeeded", "aborted"], connector_outcome="succeeded")
    with seq:
        for name in ("A", "B", "C"):
            smach.Sequence.add(name, smach.CBState(step(name), outcomes=["succeeded", "aborted"]))
    assert seq.execute() == "succeeded"
    assert order == ["A", "B", "C"]
    assert seq._transitions["A"]["succeeded"] == "B" and seq._transitions["C"]["succeeded"] is None


def test_sequence_explicit_connector_transition_overrides_the_automatic_one():
    seq = smach.Sequence(outcomes=["succeeded", "aborted"], connector_outcome="succeeded")
    with seq:
        smach.Sequence.add("A", cb_state("succeeded", ["succeeded", "aborted"]), transitions={"succeeded": "C"})
        smach.Sequence.add("B", cb_state("aborted", ["succeeded", "aborted"]))
        smach.Sequence.add("C", cb_state("succeeded", ["succeeded", "aborted"]))
    assert seq._transitions["A"]["succeeded"] == "C"
    assert seq.execute() == "succeeded"


def test_sequence_state_without_connector_outcome_is_invalid_transition():
    seq = smach.Sequence(outcomes=["succeeded"], connector_outcome="succeeded")
    with seq:
        smach.Sequence.add("A", cb_state("other"))
        with pytest.raises(
            smach.InvalidTransitionError, match=r"'A' does not register the connector.*registered: other"
        ):
            smach.Sequence.add("B", cb_state("succeeded"))


# --- Concurrence: construction --------------------------------------------------------------------------
def test_concurrence_outcome_policy_is_validated_at_construction():
    with pytest.raises(smach.InvalidStateError, match="default outcome 'nope' is not one of its outcomes"):
        smach.Concurrence(outcomes=["a"], default_outcome="nope")
    with pytest.raises(smach.InvalidStateError, match="outcome_map names outcome 'x'"):
        smach.Concurrence(outcomes=["a"], default_outcome="a", outcome_map={"x": {"C": "done"}})
    with pytest.raises(smach.InvalidStateError, match="outcome_cb 3 is not callable"):
        smach.Concurrence(outcomes=["a"], default_outcome="a", outcome_cb=3)  # type: ignore[arg-type]  # on purpose


def test_concurrence_consistency_checks_children_named_in_the_outcome_map():
    cc = smach.Concurrence(outcomes=["a"], default_outcome="a", outcome_map={"a": {"GHOST": "done"}})
    with cc:
        smach.Concurrence.add("REAL", cb_state("done"))
    with pytest.raises(smach.InvalidTransitionError, match=r"child 'GHOST'.*children: REAL"):
        cc.execute()
    cc2 = smach.Concurrence(outcomes=["a"], default_outcome="a", outcome_map={"a": {"REAL": "typo"}})
    with cc2:
        smach.Concurrence.add("REAL", cb_state("done"))
        with pytest.raises(smach.InvalidStateError, match="already used"):
            smach.Concurrence.add("REAL", cb_state("done"))
    with pytest.raises(smach.InvalidTransitionError, match=r"'typo'.*registered: done"):
        cc2.execute()
    with pytest.raises(smach.InvalidStateError, match="no children"):
        smach.Concurrence(outcomes=["a"], default_outcome="a").execute()


def test_concurrence_initial_states_are_ignored_with_a_warning_and_userdata_merged(caplog):
    # SMACH: a Concurrence always starts every child; labels (even of children added later) are no error
    seen: Dict[str, Any] = {}

    def record(name: str) -> Callable[[Any], str]:
        def run(ud: Any) -> str:
            seen[name] = ud.v if name == "LATER" else True
            return "done"

        return run

    cc = smach.Concurrence(outcomes=["ok"], default_outcome="ok", input_keys=["v"])
    injected = smach.UserData()
    injected.v = 7
    cc.set_initial_state(["LATER"], injected)
    assert "initial states ['LATER'] ignored" in caplog.text
    with cc:
        smach.Concurrence.add("LATER", smach.CBState(record("LATER"), outcomes=["done"], input_keys=["v"]))
        smach.Concurrence.add("OTHER", smach.CBState(record("OTHER"), outcomes=["done"]))
    assert cc.execute() == "ok"
    assert seen == {"LATER": 7, "OTHER": True}


# --- Concurrence: running --------------------------------------------------------------------------------
def test_children_really_run_at_the_same_time():
    barrier = threading.Barrier(2, timeout=WAIT_S)

    def meet(ud):
        barrier.wait()  # only returns when both children are inside execute at once
        return "done"

    cc = smach.Concurrence(outcomes=["ok"], default_outcome="ok")
    with cc:
        smach.Concurrence.add("A", smach.CBState(meet, outcomes=["done"]))
        smach.Concurrence.add("B", smach.CBState(meet, outcomes=["done"]))
    assert cc.execute() == "ok"


def test_outcome_map_default_and_most_specific_match():
    def concurrence(a, b):
        cc = smach.Concurrence(
            outcomes=["both", "a_only", "neither"],
            default_outcome="neither",
            outcome_map={"a_only": {"A": "good"}, "both": {"A": "good", "B": "good"}},
        )
        with cc:
            smach.Concurrence.add("A", cb_state(a, ["good", "bad"]))
            smach.Concurrence.add("B", cb_state(b, ["good", "bad"]))
        return cc.execute()

    assert concurrence("good", "good") == "both"  # both entries hold: the one with more pairs wins
    assert concurrence("good", "bad") == "a_only"
    assert concurrence("bad", "good") == "neither"


def test_outcome_cb_takes_precedence_and_none_falls_back_to_the_map():
    seen = []

    def decide(outcomes):
        seen.append(dict(outcomes))
        return "custom" if outcomes["A"] == "x" else None

    def concurrence(a):
        cc = smach.Concurrence(
            outcomes=["custom", "mapped", "default"],
            default_outcome="default",
            outcome_map={"mapped": {"A": "y"}},
            outcome_cb=decide,
        )
        with cc:
            smach.Concurrence.add("A", cb_state(a, ["x", "y"]))
        return cc.execute()

    assert concurrence("x") == "custom"
    assert concurrence("y") == "mapped"
    assert seen == [{"A": "x"}, {"A": "y"}]


def test_outcome_cb_returning_unregistered_outcome_or_raising_fails_loudly():
    cc = smach.Concurrence(outcomes=["a", "b"], default_outcome="a", outcome_cb=lambda outcomes: "zzz")
    with cc:
        smach.Concurrence.add("A", cb_state("done"))
    with pytest.raises(smach.InvalidTransitionError, match=r"returned 'zzz'.*\(a, b\)"):
        cc.execute()

    def broken(outcomes: Dict[str, Optional[str]]) -> Optional[str]:
        raise ZeroDivisionError("a bug in the callback")

    cc = smach.Concurrence(outcomes=["a"], default_outcome="a", outcome_cb=broken)
    with cc:
        smach.Concurrence.add("A", cb_state("done"))
    with pytest.raises(smach.InvalidUserCodeError, match=r"outcome_cb.*ZeroDivisionError"):
        cc.execute()


def test_child_termination_cb_true_preempts_the_others():
    waiter = Waiter()
    seen = []

    def stop_when_monitor_fires(outcomes):
        seen.append(dict(outcomes))
        return outcomes["MONITOR"] == "fired"

    cc = smach.Concurrence(
        outcomes=["stopped", "finished"],
        default_outcome="finished",
        outcome_map={"stopped": {"MONITOR": "fired", "WORK": "preempted"}},
        child_termination_cb=stop_when_monitor_fires,
    )
    with cc:
        smach.Concurrence.add("MONITOR", smach.CBState(once_started(waiter, "fired"), outcomes=["fired"]))
        smach.Concurrence.add("WORK", waiter)
    assert cc.execute() == "stopped"
    assert seen[0] == {"MONITOR": "fired", "WORK": None}  # unfinished children are None
    assert not waiter.preempt_requested()


def test_child_termination_cb_list_preempts_only_the_listed_children():
    first, second = Waiter(), Waiter()

    def on_child_done(outcomes):
        if outcomes["TRIGGER"] is not None and outcomes["FIRST"] is None:
            return ["FIRST"]
        return False

    cc = smach.Concurrence(outcomes=["ok"], default_outcome="ok", child_termination_cb=on_child_done)
    outcomes: Dict[str, Optional[str]] = {}
    cc.register_termination_cb(lambda ud, states, outcome: outcomes.update(cc_outcome=outcome))
    with cc:
        smach.Concurrence.add("TRIGGER", smach.CBState(once_started(first, "go"), outcomes=["go"]))
        smach.Concurrence.add("FIRST", first)
        smach.Concurrence.add("SECOND", second)
    result: Dict[str, Optional[str]] = {}
    thread = threading.Thread(target=lambda: result.update(outcome=cc.execute()), daemon=True)
    thread.start()
    assert second.started.wait(WAIT_S)
    for _ in range(int(WAIT_S / 0.005)):  # FIRST is preempted; SECOND keeps running
        if cc.get_active_states() == ["SECOND"]:
            break
        threading.Event().wait(0.005)
    assert cc.get_active_states() == ["SECOND"]
    assert not second.preempt_requested()
    second.release.set()
    thread.join(WAIT_S)
    assert result == {"outcome": "ok"}


def test_child_raising_preempts_the_others_and_raises_invalid_user_code_naming_it():
    waiter = Waiter()

    def boom(ud):
        waiter.started.wait(WAIT_S)
        raise ValueError("bad reading")

    cc = smach.Concurrence(outcomes=["ok"], default_outcome="ok")
    with cc:
        smach.Concurrence.add("WORK", waiter)
        smach.Concurrence.add("BOOM", smach.CBState(boom, outcomes=["done"]))
    with pytest.raises(
        smach.InvalidUserCodeError, match="concurrent state 'BOOM' failed: ValueError: bad reading"
    ) as info:
        cc.execute()
    assert isinstance(info.value.__cause__, ValueError)
    assert not cc.is_running()


def test_child_returning_no_outcome_is_invalid_transition():
    cc = smach.Concurrence(outcomes=["ok"], default_outcome="ok")
    with cc:
        smach.Concurrence.add("A", smach.CBState(lambda ud: None, outcomes=["done"]))
    with pytest.raises(smach.InvalidTransitionError, match=r"'A' returned outcome None.*registered: done"):
        cc.execute()


def test_preempting_the_concurrence_preempts_every_child_and_is_serviced():
    a, b = Waiter(), Waiter()
    cc = smach.Concurrence(
        outcomes=["preempted", "done"],
        default_outcome="done",
        outcome_map={"preempted": {"A": "preempted", "B": "preempted"}},
    )
    with cc:
        smach.Concurrence.add("A", a)
        smach.Concurrence.add("B", b)
    result: Dict[str, Optional[str]] = {}
    thread = threading.Thread(target=lambda: result.update(outcome=cc.execute()), daemon=True)
    thread.start()
    assert a.started.wait(WAIT_S) and b.started.wait(WAIT_S)
    assert sorted(cc.get_active_states()) == ["A", "B"]
    cc.request_preempt()
    thread.join(WAIT_S)
    assert result == {"outcome": "preempted"}
    assert not cc.preempt_requested()


def test_unserviced_child_preempt_is_recalled_and_container_keeps_its_request():
    a = Waiter(service=False)
    cc = smach.Concurrence(outcomes=["done"], default_outcome="done")
    with cc:
        smach.Concurrence.add("A", a)
    cc.request_preempt()  # before execute: children are preempted as soon as they run
    assert cc.execute() == "done"
    assert not a.preempt_requested()
    assert cc.preempt_requested()


def test_concurrence_userdata_keys_and_introspection():
    def produce(ud):
        ud.out = ud.inp + 1
        return "done"

    cc = smach.Concurrence(
        outcomes=["ok"],
        default_outcome="ok",
        input_keys=["inp"],
        output_keys=["out"],
        outcome_map={"ok": {"P": "done"}},
    )
    with cc:
        smach.Concurrence.add("P", smach.CBState(produce, outcomes=["done"], input_keys=["inp"], output_keys=["out"]))
    parent = smach.UserData()
    parent.inp = 1
    starts, ends = [], []
    cc.register_start_cb(lambda ud, initial: starts.append(initial))
    cc.register_termination_cb(lambda ud, terminal, outcome: ends.append((terminal, outcome)))
    assert cc.execute(parent) == "ok"
    assert parent.out == 2
    assert starts == [["P"]] and ends == [(["P"], "ok")]
    assert cc.get_internal_edges() == [("done", "P", "ok")]
    assert cc.get_initial_states() == ["P"] and cc.get_active_states() == []


# --- Iterator ----------------------------------------------------------------------------------------------------
def iterator(items, body, **kwargs):
    it = smach.Iterator(
        outcomes=["succeeded", "aborted"],
        input_keys=[],
        output_keys=[],
        it=items,
        it_label="item",
        exhausted_outcome="succeeded",
    )
    with it:
        smach.Iterator.set_contained_state("BODY", body, **kwargs)
    return it


def test_iterator_runs_the_state_once_per_item_then_returns_exhausted_outcome():
    seen = []

    def see(ud: Any) -> str:
        seen.append(ud.item)
        return "next"

    body = smach.CBState(see, outcomes=["next"], input_keys=["item"])
    it = iterator(lambda: iter("abc"), body, loop_outcomes=["next"])
    assert it.execute() == "succeeded"
    assert seen == ["a", "b", "c"]
    assert it.execute() == "succeeded" and seen == ["a", "b", "c"] * 2  # a callable is evaluated per execution
    assert ("next", "BODY", "BODY") in it.get_internal_edges()


def test_iterator_break_outcome_is_mapped_through_final_outcome_map():
    seen = []

    def see_until_two(ud: Any) -> str:
        seen.append(ud.item)
        return "stop" if ud.item == 2 else "next"

    body = smach.CBState(see_until_two, outcomes=["next", "stop"], input_keys=["item"])
    it = iterator([1, 2, 3], body, break_outcomes=["stop"], final_outcome_map={"stop": "aborted"})
    assert it.execute() == "aborted"
    assert seen == [1, 2]


def test_iterator_validates_outcomes_at_construction_and_consistency():
    body = cb_state("next")
    it = smach.Iterator(outcomes=["succeeded"], input_keys=[], output_keys=[], it=[1], exhausted_outcome="succeeded")
    with it, pytest.raises(smach.InvalidTransitionError, match=r"loop_outcomes names nope.*registered: next"):
        smach.Iterator.set_contained_state("BODY", body, loop_outcomes=["nope"])
    it2 = iterator([1], cb_state("weird", ["next", "weird"]), loop_outcomes=["next"])
    with pytest.raises(smach.InvalidTransitionError, match=r"'weird', which is not one of its outcomes"):
        it2.execute()
    with pytest.raises(smach.InvalidStateError, match="no contained state"):
        smach.Iterator(outcomes=["done"], input_keys=[], output_keys=[]).execute()
    assert "exhausted" in smach.Iterator(outcomes=["done"], input_keys=[], output_keys=[]).get_registered_outcomes()


def test_iterator_preempt_stops_the_loop_after_the_running_state_returns():
    waiter = Waiter()
    it = iterator(range(5), waiter, loop_outcomes=["done"], final_outcome_map={"preempted": "aborted"})
    result: Dict[str, Optional[str]] = {}
    thread = threading.Thread(target=lambda: result.update(outcome=it.execute()), daemon=True)
    thread.start()
    assert waiter.started.wait(WAIT_S)
    assert it.get_active_states() == ["BODY"]
    it.request_preempt()
    thread.join(WAIT_S)
    assert result == {"outcome": "aborted"}
    assert not it.preempt_requested()
