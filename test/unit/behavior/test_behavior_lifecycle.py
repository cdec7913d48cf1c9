"""State lifecycle: call order, rates, None keeps running, failures exit states and fail loudly."""

from __future__ import annotations

import pytest
from unit.behavior.behavior_testlib import Journal, ScriptedState, chain, executor, spin

from flex_nav.behavior import (
    Behavior,
    BehaviorExecutor,
    BehaviorStatus,
    ConcurrencyContainer,
    ManualClock,
    State,
    StateMachine,
)
from flex_nav.exceptions import BehaviorConstructionError, BehaviorRuntimeError, ConfigError


def test_lifecycle_order_of_a_chain():
    journal = Journal()
    sm = chain(journal, ["A", "B"])
    result = executor(sm).run(timeout_s=10.0)
    assert result.status is BehaviorStatus.FINISHED
    assert result.outcome == "finished"
    assert journal.calls == [
        ("A", "start"),
        ("B", "start"),
        ("A", "enter"),
        ("A", "execute"),
        ("A", "exit"),
        ("B", "enter"),
        ("B", "execute"),
        ("B", "exit"),
        ("A", "stop"),
        ("B", "stop"),
    ]


def test_none_keeps_state_running_at_its_rate():
    journal = Journal()
    sm = StateMachine(outcomes=["finished"])
    slow = ScriptedState(journal, script=[None, None, None, "done"], outcomes=["done"], rate_hz=4.0)
    sm.add("Slow", slow, transitions={"done": "finished"})
    clock = ManualClock(start_s=100.0)
    result = BehaviorExecutor(sm, clock=clock).run(timeout_s=10.0)
    assert result.outcome == "finished"
    assert journal.of("Slow") == ["start", "enter", "execute", "execute", "execute", "execute", "exit", "stop"]
    # first execute at once, then every 1/4 s
    assert slow.execute_times == pytest.approx([100.0, 100.25, 100.5, 100.75])


def test_each_state_has_its_own_rate():
    journal = Journal()
    sm = StateMachine(outcomes=["finished"])
    a = ScriptedState(journal, script=[None, "done"], outcomes=["done"], rate_hz=2.0)
    b = ScriptedState(journal, script=[None, None, "done"], outcomes=["done"], rate_hz=20.0)
    sm.add("A", a, transitions={"done": "B"})
    sm.add("B", b, transitions={"done": "finished"})
    BehaviorExecutor(sm, clock=ManualClock()).run(timeout_s=10.0)
    assert a.execute_times == pytest.approx([0.0, 0.5])
    assert b.execute_times == pytest.approx([0.5, 0.55, 0.6])


def test_rate_must_be_positive():
    journal = Journal()
    with pytest.raises(ConfigError, match="rate_hz must be a number > 0"):
        ScriptedState(journal, rate_hz=0.0)


def test_unregistered_outcome_fails_the_behavior_and_exits_the_state():
    journal = Journal()
    sm = StateMachine(outcomes=["finished"])
    sm.add("A", ScriptedState(journal, script=["bogus"], outcomes=["done"]), transitions={"done": "finished"})
    result = executor(sm).run(timeout_s=10.0)
    assert result.status is BehaviorStatus.FAILED
    assert "returned outcome 'bogus' which it does not register (valid: done" in result.reason
    assert isinstance(result.error, BehaviorRuntimeError)
    assert journal.of("A") == ["start", "enter", "execute", "exit", "stop"]


@pytest.mark.parametrize("where", ["enter", "execute"])
def test_exception_in_state_code_fails_with_path_and_exits_active_states(where):
    journal = Journal()
    sm = StateMachine(outcomes=["finished"])
    sm.add(
        "A", ScriptedState(journal, script=[None], outcomes=["done"], raise_in=where), transitions={"done": "finished"}
    )
    result = executor(sm).run(timeout_s=10.0)
    assert result.status is BehaviorStatus.FAILED
    phase = "on_enter" if where == "enter" else "execute"
    assert f"state '/A' (ScriptedState) raised RuntimeError in {phase}: scripted failure in {where}" in result.reason
    assert result.error is not None and isinstance(result.error.__cause__, RuntimeError)
    assert journal.of("A")[-2:] == ["exit", "stop"]


def test_exception_in_on_exit_still_exits_the_others_and_stops_all():
    journal = Journal()
    cc = ConcurrencyContainer(outcomes=["done"], conditions=[("done", [("A", "done")])])
    cc.add("A", ScriptedState(journal, script=[None, None, "failed"], raise_in="exit"))
    cc.add("B", ScriptedState(journal, script=[None, None, "failed"]))
    sm = StateMachine(outcomes=["done", "failed"])
    sm.add("CC", cc, transitions={"done": "done"})
    ex = executor(sm)
    spin(ex, 1)
    ex.preempt()
    result = ex.run(timeout_s=1.0)
    assert result.status is BehaviorStatus.FAILED
    assert "raised RuntimeError in on_exit" in result.reason
    assert journal.of("A")[-2:] == ["exit", "stop"]
    assert journal.of("B")[-2:] == ["exit", "stop"]


def test_exception_in_on_start_fails_before_anything_runs():
    journal = Journal()
    sm = StateMachine(outcomes=["finished"])
    sm.add("A", ScriptedState(journal, raise_in="start", outcomes=["done"]), transitions={"done": "finished"})
    result = executor(sm).run(timeout_s=1.0)
    assert result.status is BehaviorStatus.FAILED
    assert "in on_start" in result.reason
    assert journal.of("A") == ["start", "stop"]


def test_state_without_execute_fails_loudly():
    class Lazy(State):
        def __init__(self) -> None:
            super().__init__(outcomes=["done"])

    sm = StateMachine(outcomes=["finished"])
    sm.add("Lazy", Lazy(), transitions={"done": "finished"})
    result = executor(sm).run(timeout_s=1.0)
    assert result.status is BehaviorStatus.FAILED
    assert "Lazy must implement execute" in result.reason


def test_context_is_not_available_in_constructor():
    class Eager(State):
        def __init__(self) -> None:
            super().__init__(outcomes=["done"])
            self.context.log_info("hello")  # type: ignore[attr-defined]

        def execute(self, userdata):
            return "done"

    with pytest.raises(BehaviorRuntimeError, match="not attached to a running behavior yet"):
        Eager()


def test_state_instance_cannot_be_in_two_places():
    journal = Journal()
    state = ScriptedState(journal)
    sm = StateMachine(outcomes=["finished", "failed"])
    sm.add("A", state, transitions={"done": "finished", "failed": "failed"})
    with pytest.raises(BehaviorConstructionError, match="already added as 'A'"):
        sm.add("B", state, transitions={"done": "finished", "failed": "failed"})


def test_started_twice_is_refused():
    journal = Journal()
    ex = executor(chain(journal, ["A"]))
    ex.start()
    with pytest.raises(BehaviorRuntimeError, match="already started"):
        ex.start()


def test_behavior_wrapper_names_the_root_and_validates():
    journal = Journal()
    behavior = Behavior("demo", chain(journal, ["A"]), description="d")
    behavior.validate()
    ex = executor(behavior)
    assert ex.context.name == "demo"
    assert ex.root.path == "/"
    assert ex.state_paths == ("/", "/A")
    with pytest.raises(ConfigError, match="behavior name"):
        Behavior("a/b", chain(Journal(), ["A"]))


def test_single_leaf_as_root():
    journal = Journal()
    leaf = ScriptedState(journal, script=[None, "failed"])
    result = executor(leaf).run(timeout_s=5.0)
    assert result.status is BehaviorStatus.FINISHED
    assert result.outcome == "failed"
    assert journal.of("behavior") == ["start", "enter", "execute", "execute", "exit", "stop"]
