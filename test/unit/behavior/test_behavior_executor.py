"""Executor: pause/resume, preempt, lock/unlock, hooks, thread-safe commands, isolation of behaviors."""

from __future__ import annotations

import threading
from typing import List

import pytest
from unit.behavior.behavior_testlib import (
    Journal,
    ScriptedState,
    assert_refused,
    chain,
    executor,
    one_state,
    record_events,
    spin,
)

from flex_nav.behavior import (
    Autonomy,
    BehaviorContext,
    BehaviorExecutor,
    BehaviorStatus,
    LogLevel,
    ManualClock,
    PriorityContainer,
    State,
    StateMachine,
    current_context,
)
from flex_nav.behavior.builtin_states import Wait
from flex_nav.behavior.context import HOLD_REQUEST
from flex_nav.behavior.events import RequestEvent, TransitionEvent
from flex_nav.exceptions import BehaviorRuntimeError, ConfigError, NotReadyError
from flex_nav.testing.fake_proxies import FakeProxies


def looping(journal, label="Loop", rate_hz=10.0):
    return one_state(ScriptedState(journal, script=[], rate_hz=rate_hz), label)


def looping_executor(**kwargs):
    """A journal, and the executor of a looping behavior (``looping``) that records in it."""
    journal = Journal()
    return journal, executor(looping(journal), **kwargs)


def test_pause_and_resume():
    journal, ex = looping_executor()
    events = record_events(ex)
    spin(ex, 3)
    ex.pause()
    ex.run(timeout_s=10.0, stop_on_timeout=False)
    assert ex.status is BehaviorStatus.PAUSED
    assert journal.of("Loop") == ["start", "enter", "execute", "execute", "execute", "pause"]
    ex.resume()
    spin(ex, 2)
    assert journal.of("Loop")[-3:] == ["resume", "execute", "execute"]
    assert [e.status for e in events["status"]] == [
        BehaviorStatus.RUNNING,
        BehaviorStatus.PAUSED,
        BehaviorStatus.RUNNING,
    ]
    assert ex.pause().done() is False  # queued until the executor applies it


def test_preempt_exits_active_states_and_stops_all():
    journal, ex = looping_executor()
    events = record_events(ex)
    spin(ex, 2)
    ex.preempt()
    result = ex.run(timeout_s=1.0)
    assert (result.status, result.outcome, result.reason) == (
        BehaviorStatus.PREEMPTED,
        "preempted",
        "preempted by the operator",
    )
    assert journal.of("Loop")[-2:] == ["exit", "stop"]
    assert ex.context.preempt_requested
    assert events["status"][-1].status is BehaviorStatus.PREEMPTED
    assert ex.wait(0.0)


def test_preempt_while_paused_still_exits():
    journal, ex = looping_executor()
    spin(ex, 1)
    ex.pause()
    ex.spin_once()
    ex.preempt()
    assert ex.run(timeout_s=1.0).status is BehaviorStatus.PREEMPTED
    assert journal.of("Loop")[-3:] == ["pause", "exit", "stop"]


def test_run_timeout_preempts_or_keeps_running():
    _, ex = looping_executor()
    assert ex.run(timeout_s=1.0, stop_on_timeout=False).status is BehaviorStatus.RUNNING
    result = ex.run(timeout_s=1.0)
    assert result.status is BehaviorStatus.PREEMPTED
    assert result.reason == "run() timed out after 1.0 s"


def test_should_stop_is_checked_while_waiting():
    stop: List[bool] = []
    _, ex = looping_executor(should_stop=lambda: bool(stop))
    spin(ex, 2)
    stop.append(True)
    result = ex.run(timeout_s=100.0)
    assert (result.status, result.reason) == (BehaviorStatus.PREEMPTED, "stopped: shutdown requested")


def test_lock_holds_the_transition_leaving_a_container_until_unlock():
    journal = Journal()
    inner = StateMachine(outcomes=["finished", "failed"])
    inner.add("X", ScriptedState(journal), transitions={"done": "Y", "failed": "failed"})
    inner.add("Y", ScriptedState(journal), transitions={"done": "finished", "failed": "failed"})
    outer = StateMachine(outcomes=["ok", "bad"])
    outer.add("Inner", inner, transitions={"finished": "After", "failed": "bad"})
    outer.add("After", ScriptedState(journal), transitions={"done": "ok", "failed": "bad"})
    ex = executor(outer)
    events = record_events(ex)
    ex.lock("/Inner")
    ex.run(timeout_s=5.0, stop_on_timeout=False)
    # inside the locked container transitions go on; leaving it is held (Y stays active, not re-executed)
    assert journal.of("X") == ["start", "enter", "execute", "exit"]
    assert journal.of("Y") == ["start", "enter", "execute", "pause"]  # held still while the lock holds it
    assert [(r.path, r.outcome, r.reason) for r in ex.requested_outcomes()] == [("/Inner/Y", "done", "lock")]
    assert_refused(ex, ex.approve("/Inner/Y"), "waits for an unlock")
    ex.unlock("/Inner")
    assert ex.run(timeout_s=5.0).outcome == "ok"
    assert [(e.outcome, e.reason, e.pending) for e in events["request"]] == [
        ("done", "lock", True),
        ("done", "lock", False),
    ]


def test_a_forced_outcome_held_by_a_lock_is_still_forced_after_the_unlock():
    """Forcing an outcome that would leave a locked container: it waits for the unlock like any other
    (reported as a "lock" request, approval refused), and when it fires it is still the operator's:
    the forced container is exited without handing its outputs up, the transition says forced."""
    journal = Journal()

    def write_x(userdata, n):
        userdata.x = n

    inner = StateMachine(outcomes=["finished", "failed"], output_keys=["x"])
    inner.add(
        "W",
        ScriptedState(journal, script=[], output_keys=["x"], action=write_x),
        transitions={"done": "finished", "failed": "failed"},
    )
    mid = StateMachine(outcomes=["finished", "failed"], output_keys=["x"])
    mid.add("Inner", inner, transitions={"finished": "finished", "failed": "failed"})
    outer = StateMachine(outcomes=["ok", "bad"], output_keys=["x"])
    outer.add("Mid", mid, transitions={"finished": "ok", "failed": "bad"})
    ex = executor(outer)
    events = record_events(ex)
    ex.lock("/Mid")
    spin(ex, 3)
    ex.force_transition("/Mid/Inner", "finished")
    spin(ex, 2)
    assert [(r.path, r.outcome, r.reason) for r in ex.requested_outcomes()] == [("/Mid/Inner", "finished", "lock")]
    assert ex.active_paths() == ("/Mid/Inner/W",)
    assert_refused(ex, ex.approve("/Mid/Inner"), "waits for an unlock")
    ex.unlock("/Mid")
    result = ex.run(timeout_s=2.0)
    assert (result.status, result.outcome) == (BehaviorStatus.FINISHED, "ok")
    assert "x" not in result.outputs  # forced: Inner's outputs were not handed up (W wrote x)
    assert journal.of("W")[-2:] == ["exit", "stop"]
    fired = [(e.path, e.outcome, e.forced) for e in events["transition"]]
    assert fired == [("/Mid/Inner", "finished", True), ("/Mid", "finished", False)]
    assert [(e.path, e.outcome, e.reason, e.pending) for e in events["request"]] == [
        ("/Mid/Inner", "finished", "lock", True),
        ("/Mid/Inner", "finished", "lock", False),
    ]


def test_lock_of_a_leaf_and_unlock_errors():
    journal = Journal()
    ex = executor(chain(journal, ["A", "B"]))
    ex.lock("/A")
    ex.run(timeout_s=2.0, stop_on_timeout=False)
    assert ex.active_paths() == ("/A",)
    assert_refused(ex, ex.unlock("/B"), "'/B' is not locked")
    ex.unlock("/A")
    assert ex.run(timeout_s=2.0).status is BehaviorStatus.FINISHED


def test_a_locked_single_state_root_holds_still_until_unlocked():
    journal = Journal()
    ex = executor(ScriptedState(journal))  # the root is the state itself: its outcome waits in the executor
    ex.lock("/")
    ex.run(timeout_s=2.0, stop_on_timeout=False)
    assert [(r.path, r.reason) for r in ex.requested_outcomes()] == [("/", "lock")]
    assert journal.of("behavior") == ["start", "enter", "execute", "pause"]  # stopped, not executed again
    ex.unlock("/")
    assert ex.run(timeout_s=2.0).status is BehaviorStatus.FINISHED
    assert journal.of("behavior")[-2:] == ["exit", "stop"]


def test_lock_then_autonomy_both_apply():
    journal = Journal()
    ex = executor(one_state(ScriptedState(journal), autonomy={"done": Autonomy.FULL}))
    ex.lock("/")
    ex.run(timeout_s=1.0, stop_on_timeout=False)
    assert [(r.path, r.reason) for r in ex.requested_outcomes()] == [("/A", "lock")]
    ex.unlock("/")
    ex.run(timeout_s=1.0, stop_on_timeout=False)
    assert [(r.path, r.reason) for r in ex.requested_outcomes()] == [("/A", "autonomy")]
    ex.approve("/A")
    assert ex.run(timeout_s=1.0).outcome == "finished"


def test_hooks_receive_transitions_logs_status_and_active_states():
    journal = Journal()

    class Talker(State):
        def __init__(self) -> None:
            super().__init__(outcomes=["done"])

        def execute(self, userdata):
            self.log_hint("hello operator")
            return "done"

    sm = StateMachine(outcomes=["finished", "failed"])
    sm.add("Talk", Talker(), transitions={"done": "A"})
    sm.add("A", ScriptedState(journal), transitions={"done": "finished", "failed": "failed"})
    ex = executor(sm)
    events = record_events(ex)
    ex.run(timeout_s=5.0)
    assert [(e.level, e.message, e.path) for e in events["log"]] == [(LogLevel.HINT, "hello operator", "/Talk")]
    assert [(e.path, e.outcome, e.target) for e in events["transition"]] == [
        ("/Talk", "done", "A"),
        ("/A", "done", "finished"),
    ]
    assert [e.paths for e in events["active"]] == [("/A",)]
    assert [(e.status, e.outcome) for e in events["status"]] == [
        (BehaviorStatus.RUNNING, None),
        (BehaviorStatus.FINISHED, "finished"),
    ]


def test_a_failing_hook_fails_the_behavior_after_exiting_states():
    journal = Journal()
    ex = executor(chain(journal, ["A", "B"]))

    def broken(event):
        raise ValueError("publisher gone")

    ex.context.hooks.transition.append(broken)
    result = ex.run(timeout_s=5.0)
    assert result.status is BehaviorStatus.FAILED
    assert result.reason.startswith(
        "transition hook test_a_failing_hook_fails_the_behavior_after_exiting_states.<locals>.broken "
        "raised ValueError: publisher gone"
    )
    assert result.error is not None and isinstance(result.error.__cause__, ValueError)
    assert journal.of("A") == ["start", "enter", "execute", "exit", "stop"]
    assert journal.of("B") == ["start", "stop"]  # activated, never entered: no on_exit


def test_commands_from_another_thread_with_a_real_clock():
    """A ROS callback thread approves and preempts while the executor runs on the monotonic clock."""
    journal = Journal()
    sm = StateMachine(outcomes=["finished", "failed"])
    sm.add("A", ScriptedState(journal), transitions={"done": "B", "failed": "failed"}, autonomy={"done": Autonomy.FULL})
    sm.add("B", ScriptedState(journal, script=[], rate_hz=100.0), transitions={"done": "finished", "failed": "failed"})
    ex = BehaviorExecutor(sm)
    requested = threading.Event()
    entered_b = threading.Event()

    def on_request(event: RequestEvent) -> None:
        if event.pending:
            requested.set()

    def on_transition(event: TransitionEvent) -> None:
        if event.target == "B":
            entered_b.set()

    ex.context.hooks.request.append(on_request)
    ex.context.hooks.transition.append(on_transition)
    results = []
    runner = threading.Thread(target=lambda: results.append(ex.run(timeout_s=60.0)))
    runner.start()
    try:
        assert requested.wait(10.0)
        assert ex.active_paths() == ("/A",)
        assert ex.approve("/A").result(timeout=10.0) == "approved /A -> done"
        assert entered_b.wait(10.0)
        assert ex.preempt().result(timeout=10.0) == "preempted"
    finally:
        if runner.is_alive() and not ex.status.is_terminal:
            ex.preempt()
        runner.join(10.0)
    assert not runner.is_alive()
    assert results[0].status is BehaviorStatus.PREEMPTED
    assert journal.of("B")[-2:] == ["exit", "stop"]


def test_two_behaviors_in_one_process_never_interfere():
    """Autonomy, requests, priority, pause, preemption and hooks are per behavior."""
    j1, j2 = Journal(), Journal()

    def build(journal):
        sm = StateMachine(outcomes=["finished", "failed"])
        prio = PriorityContainer(outcomes=["done"])
        prio.add(
            "P", ScriptedState(journal, script=[None] * 5 + ["done"], outcomes=["done"]), transitions={"done": "done"}
        )
        sm.add(
            "A",
            ScriptedState(journal),
            transitions={"done": "Prio", "failed": "failed"},
            autonomy={"done": Autonomy.HIGH},
        )
        sm.add("Prio", prio, transitions={"done": "L"})
        sm.add(
            "L",
            ScriptedState(journal, script=[None] * 20 + ["done"]),
            transitions={"done": "finished", "failed": "failed"},
        )
        return sm

    clock = ManualClock()
    ex1 = BehaviorExecutor(build(j1), clock=clock, autonomy=Autonomy.FULL)
    ex2 = BehaviorExecutor(build(j2), clock=clock, autonomy=Autonomy.LOW)
    ev1, ev2 = record_events(ex1), record_events(ex2)
    for _ in range(4):
        ex1.spin_once()
        ex2.spin_once()
        clock.advance(0.1)
    assert ex1.requested_outcomes() == []
    assert [r.path for r in ex2.requested_outcomes()] == ["/A"]
    book1, book2 = ex1.context.__flex_nav_runtime__, ex2.context.__flex_nav_runtime__
    assert book1.priority and not book2.priority  # only behavior 1 entered its priority container
    # behavior 2's A is held by its own waiting outcome, never by behavior 1's priority container
    a2 = book2.requests["/A"]
    assert a2.hold_mask == HOLD_REQUEST and j2.calls.count(("A", "pause")) == 1
    ex2.pause()
    ex2.spin_once()
    ex1.preempt()
    ex1.spin_once()
    assert ex1.status is BehaviorStatus.PREEMPTED and ex2.status is BehaviorStatus.PAUSED
    assert not ex2.context.preempt_requested
    ex2.resume()
    ex2.approve("/A")
    while not ex2.status.is_terminal:
        ex2.spin_once()
        clock.advance(0.1)
    assert ex2.result().outcome == "finished"
    assert [e.path for e in ev1["transition"]] == ["/A"]  # then preempted inside its priority container
    assert [e.path for e in ev2["transition"]] == ["/A", "/Prio/P", "/Prio", "/L"]
    assert ev1["status"][-1].status is BehaviorStatus.PREEMPTED
    assert ev2["status"][-1].status is BehaviorStatus.FINISHED


def test_a_running_state_tree_cannot_join_a_second_behavior():
    journal = Journal()
    sm = chain(journal, ["A"])
    ex = executor(sm)
    ex.start()
    with pytest.raises(ConfigError, match="already belongs to running behavior"):
        executor(sm)


def test_current_context_and_proxies_are_per_behavior():
    seen = []

    class Probe(State):
        def __init__(self) -> None:
            super().__init__(outcomes=["done"])

        def execute(self, userdata):
            seen.append((current_context() is self.context, self.context.require_proxies()))
            return "done"

    def build():
        sm = StateMachine(outcomes=["finished"])
        sm.add("P", Probe(), transitions={"done": "finished"})
        return sm

    robot1, robot2 = FakeProxies(ManualClock()), FakeProxies(ManualClock())
    BehaviorExecutor(build(), clock=ManualClock(), proxies=robot1).run(timeout_s=1.0)
    BehaviorExecutor(build(), context=BehaviorContext("r2", clock=ManualClock(), proxies=robot2)).run(timeout_s=1.0)
    assert seen == [(True, robot1), (True, robot2)]
    assert current_context() is None
    with pytest.raises(NotReadyError, match="no proxies"):
        BehaviorContext("x").require_proxies()
    with pytest.raises(ConfigError, match="either a context or"):
        BehaviorExecutor(build(), context=BehaviorContext("y"), autonomy=Autonomy.LOW)


def test_keyboard_interrupt_in_a_state_exits_states_before_propagating():
    journal = Journal()

    def interrupt(ud, n):
        if n == 3:
            raise KeyboardInterrupt

    ex = executor(one_state(ScriptedState(journal, script=[], action=interrupt)))
    with pytest.raises(KeyboardInterrupt):
        ex.run(timeout_s=10.0)
    result = ex.result()
    assert (result.status, result.reason) == (BehaviorStatus.PREEMPTED, "interrupted by KeyboardInterrupt")
    assert journal.of("A")[-2:] == ["exit", "stop"]


def test_only_one_thread_drives_a_behavior():
    journal = Journal()
    sm = looping(journal)
    ex = executor(sm)
    errors = []

    def reenter(event):
        try:
            ex.spin_once()
        except BehaviorRuntimeError as err:
            errors.append(str(err))

    ex.context.hooks.status.append(reenter)
    ex.run(timeout_s=0.5)
    assert errors and errors[0].startswith("spin_once: behavior 'behavior' is already being run by another thread")


def test_initial_active_states_are_reported_on_the_first_tick():
    # An operator interface that connects to a behavior whose first state keeps running must learn it.
    sm = StateMachine(outcomes=["finished"])
    sm.add("Hold", Wait(wait_time_s=10.0), transitions={"done": "finished"})
    ex = executor(sm)
    events = record_events(ex)
    ex.start()
    ex.spin_once()
    assert [e.paths for e in events["active"]] == [("/Hold",)]
    ex.spin_once()
    assert len(events["active"]) == 1  # reported once, not on every tick
