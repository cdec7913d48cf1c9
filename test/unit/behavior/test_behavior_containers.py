"""Concurrency container (ordered AND-conditions, single thread) and priority container (pauses others)."""

from __future__ import annotations

import threading
from typing import Any, Set

import pytest
from unit.behavior.behavior_testlib import Journal, ScriptedState, executor, record_events, spin

from flex_nav.behavior import Autonomy, BehaviorStatus, ConcurrencyContainer, PriorityContainer, StateMachine


def concurrency(journal, scripts, conditions, outcomes=("a", "b", "c"), **add_kwargs):
    cc = ConcurrencyContainer(outcomes=outcomes, conditions=conditions)
    for label, script in scripts.items():
        cc.add(label, ScriptedState(journal, script=script), **add_kwargs.get(label, {}))
    sm = StateMachine(outcomes=list(outcomes))
    sm.add("CC", cc, transitions={o: o for o in outcomes})
    return sm


def test_and_condition_waits_for_all_listed_children():
    journal = Journal()
    sm = concurrency(
        journal,
        {"X": [None, "done"], "Y": [None, None, None, "done"]},
        [("a", [("X", "done"), ("Y", "done")])],
    )
    result = executor(sm).run(timeout_s=5.0)
    assert result.outcome == "a"
    assert journal.count("X", "execute") == 2  # finished children are not executed again
    assert journal.count("Y", "execute") == 4


def test_first_matching_condition_wins_in_order():
    journal = Journal()
    sm = concurrency(
        journal,
        {"X": ["done"], "Y": ["done"]},
        [("b", [("Y", "done")]), ("a", [("X", "done")])],
    )
    assert executor(sm).run(timeout_s=5.0).outcome == "b"


def test_still_running_children_are_exited_cleanly_when_a_condition_holds():
    journal = Journal()
    sm = concurrency(
        journal, {"Fast": [None, "failed"], "Slow": [None]}, [("c", [("Fast", "failed")]), ("a", [("Slow", "done")])]
    )
    ex = executor(sm)
    events = record_events(ex)
    result = ex.run(timeout_s=5.0)
    assert result.outcome == "c"
    assert journal.of("Slow") == ["start", "enter", "execute", "execute", "exit", "stop"]
    assert journal.of("Fast") == ["start", "enter", "execute", "execute", "exit", "stop"]
    assert [(e.path, e.outcome, e.target) for e in events["transition"]] == [
        ("/CC/Fast", "failed", ""),
        ("/CC", "c", "c"),
    ]


def test_all_children_finished_without_a_matching_condition_fails_loudly():
    journal = Journal()
    sm = concurrency(journal, {"X": ["failed"], "Y": ["done"]}, [("a", [("X", "done"), ("Y", "done")])])
    result = executor(sm).run(timeout_s=5.0)
    assert result.status is BehaviorStatus.FAILED
    assert (
        "all states finished (X=failed, Y=done) and no condition holds (conditions: a <- X=done and Y=done)"
        in result.reason
    )


def test_children_tick_at_their_own_rates_in_one_thread():
    journal = Journal()
    threads: Set[int] = set()

    def note_thread(ud: Any, n: int) -> None:
        threads.add(threading.get_ident())

    cc = ConcurrencyContainer(outcomes=["a"], conditions=[("a", [("Slow", "done")])])
    fast = ScriptedState(journal, script=[], rate_hz=10.0, action=note_thread)
    slow = ScriptedState(journal, script=[None, None, "done"], rate_hz=2.0, action=note_thread)
    cc.add("Fast", fast)
    cc.add("Slow", slow)
    sm = StateMachine(outcomes=["a"])
    sm.add("CC", cc, transitions={"a": "a"})
    before = threading.active_count()
    counts = []
    result = executor(sm).run(timeout_s=5.0)
    counts.append(threading.active_count())
    assert result.outcome == "a"
    assert slow.execute_times == pytest.approx([0.0, 0.5, 1.0])
    assert fast.execute_times == pytest.approx([i * 0.1 for i in range(11)])
    assert threads == {threading.get_ident()}
    assert counts == [before]


def test_child_autonomy_in_concurrency_requests_outcome():
    journal = Journal()
    sm = concurrency(
        journal, {"X": ["done"], "Y": [None]}, [("a", [("X", "done")])], X={"autonomy": {"done": Autonomy.FULL}}
    )
    ex = executor(sm)
    ex.run(timeout_s=1.0, stop_on_timeout=False)
    assert [(r.path, r.outcome) for r in ex.requested_outcomes()] == [("/CC/X", "done")]
    assert journal.count("X", "execute") == 1
    assert set(ex.active_paths()) == {"/CC/X", "/CC/Y"}
    ex.approve("/CC/X")
    assert ex.run(timeout_s=1.0).outcome == "a"


def test_force_a_concurrent_child():
    journal = Journal()
    sm = concurrency(journal, {"X": [None], "Y": [None]}, [("a", [("X", "done")]), ("b", [("Y", "failed")])])
    ex = executor(sm)
    spin(ex, 2)
    ex.force_transition("/CC/Y", "failed")
    assert ex.run(timeout_s=1.0).outcome == "b"
    assert journal.of("X")[-2:] == ["exit", "stop"]


def priority_behavior(journal, hazard_after=2, recovery_steps=3):
    """Follow (runs long) || Watch -> Recover (priority container) -> back to watching."""
    follow = ScriptedState(journal, script=[None] * 30 + ["done"])
    watch = ScriptedState(journal, script=[None] * (hazard_after - 1) + ["done"], outcomes=["done"])
    recovery = PriorityContainer(outcomes=["recovered"])
    recovery.add(
        "Backup",
        ScriptedState(journal, script=[None] * (recovery_steps - 1) + ["done"], outcomes=["done"]),
        transitions={"done": "recovered"},
    )
    guard = StateMachine(outcomes=["stop"])
    guard.add("Watch", watch, transitions={"done": "Recover"})
    guard.add("Recover", recovery, transitions={"recovered": "Done"})
    guard.add("Done", ScriptedState(journal, script=[None] * 100, outcomes=["done"]), transitions={"done": "stop"})
    cc = ConcurrencyContainer(
        outcomes=["arrived", "failed"],
        conditions=[("arrived", [("Follow", "done")]), ("failed", [("Follow", "failed")])],
    )
    cc.add("Follow", follow)
    cc.add("Guard", guard)
    sm = StateMachine(outcomes=["arrived", "failed"])
    sm.add("Nav", cc, transitions={"arrived": "arrived", "failed": "failed"})
    return sm, follow


def test_priority_container_pauses_the_other_branches_while_active():
    journal = Journal()
    sm, follow = priority_behavior(journal, hazard_after=2, recovery_steps=3)
    result = executor(sm).run(timeout_s=60.0)
    assert result.outcome == "arrived"
    calls = journal.calls
    pause = calls.index(("Follow", "pause"))
    resume = calls.index(("Follow", "resume"))
    # the pause comes right when the priority container starts, the resume right after it ends
    assert calls[pause - 1] == ("Watch", "exit")
    assert calls[pause + 1] == ("Backup", "enter")
    assert calls[resume - 1] == ("Backup", "exit")
    # Follow is never executed while the recovery runs
    between = calls[pause:resume]
    assert ("Follow", "execute") not in between
    assert [c for c in between if c[0] == "Backup"] == [("Backup", "enter")] + [("Backup", "execute")] * 3 + [
        ("Backup", "exit")
    ]
    assert follow.executions == 31  # all its work done, none lost or repeated


def test_priority_container_release_on_preempt_exits_paused_states():
    journal = Journal()
    sm, _ = priority_behavior(journal, hazard_after=1, recovery_steps=100)
    ex = executor(sm)
    spin(ex, 4)
    assert "/Nav/Guard/Recover/Backup" in ex.active_paths()
    ex.preempt()
    result = ex.run(timeout_s=1.0)
    assert result.status is BehaviorStatus.PREEMPTED
    assert journal.of("Follow")[-3:] == ["pause", "exit", "stop"]
    assert ex.context.__flex_nav_runtime__.priority == []


@pytest.mark.parametrize("guard_first", [True, False])
def test_a_sibling_held_by_a_priority_container_resumes_whatever_its_position(guard_first):
    """Work is held while Guard's priority container runs; it resumes when the container finishes,
    also when it is listed before the guard (woken during the same concurrency tick)."""
    journal = Journal()
    guard = PriorityContainer(outcomes=["finished"])
    guard.add(
        "Stop", ScriptedState(journal, script=[None, None, "done"], outcomes=["done"]), transitions={"done": "finished"}
    )
    work = ScriptedState(journal, script=[None, None, None, "done"], outcomes=["done"])
    cc = ConcurrencyContainer(
        outcomes=["finished"], conditions=[("finished", [("Work", "done"), ("Guard", "finished")])]
    )
    if guard_first:
        cc.add("Guard", guard)
    cc.add("Work", work)
    if not guard_first:
        cc.add("Guard", guard)
    sm = StateMachine(outcomes=["finished"])
    sm.add("CC", cc, transitions={"finished": "finished"})
    result = executor(sm).run(timeout_s=10.0)
    assert result.status is BehaviorStatus.FINISHED, result.reason
    # the guard claims priority when the concurrency starts, before Work is ever entered
    executes = [who for who, call in journal.calls if call == "execute"]
    assert executes == ["Stop"] * 3 + ["Work"] * 4
    assert work.execute_times[-1] == pytest.approx(0.5)
