"""Autonomy levels, outcome requests, approval, forced transitions, set_autonomy."""

from __future__ import annotations

import pytest
from unit.behavior.behavior_testlib import Journal, ScriptedState, executor, one_state, record_events, spin

from flex_nav.behavior import Autonomy, BehaviorStatus, ConcurrencyContainer, StateMachine
from flex_nav.exceptions import BehaviorCommandError, ConfigError


def two_states(journal, level, then="done"):
    sm = StateMachine(outcomes=["finished", "failed"])
    sm.add(
        "A", ScriptedState(journal, then=then), transitions={"done": "B", "failed": "failed"}, autonomy={"done": level}
    )
    sm.add("B", ScriptedState(journal), transitions={"done": "finished", "failed": "failed"})
    return sm


@pytest.mark.parametrize(
    ("required", "current", "fires"),
    [
        (Autonomy.OFF, Autonomy.OFF, False),
        (Autonomy.OFF, Autonomy.LOW, True),
        (Autonomy.LOW, Autonomy.LOW, False),
        (Autonomy.LOW, Autonomy.HIGH, True),
        (Autonomy.HIGH, Autonomy.HIGH, False),
        (Autonomy.HIGH, Autonomy.FULL, True),
        (Autonomy.FULL, Autonomy.FULL, False),
    ],
)
def test_transition_fires_only_when_required_level_is_below_autonomy(required, current, fires):
    journal = Journal()
    ex = executor(two_states(journal, required), autonomy=current)
    result = ex.run(timeout_s=2.0, stop_on_timeout=False)
    if fires:
        assert result.status is BehaviorStatus.FINISHED
    else:
        assert result.status is BehaviorStatus.RUNNING
        assert [(r.path, r.outcome, r.required, r.reason) for r in ex.requested_outcomes()] == [
            ("/A", "done", required, "autonomy")
        ]
        assert ex.active_paths() == ("/A",)


def test_requested_state_is_not_executed_again_while_waiting():
    journal = Journal()
    ex = executor(two_states(journal, Autonomy.HIGH), autonomy=Autonomy.LOW)
    ex.run(timeout_s=30.0, stop_on_timeout=False)  # 30 s of clock time at 10 Hz
    assert journal.of("A") == ["start", "enter", "execute", "pause"]  # held still while its outcome waits
    assert journal.of("B") == ["start"]


def test_approve_fires_the_requested_outcome_and_announces_it():
    journal = Journal()
    ex = executor(two_states(journal, Autonomy.HIGH), autonomy=Autonomy.LOW)
    events = record_events(ex)
    ex.run(timeout_s=1.0, stop_on_timeout=False)
    assert [(e.path, e.outcome, e.pending) for e in events["request"]] == [("/A", "done", True)]
    future = ex.approve("/A", "done")
    result = ex.run(timeout_s=5.0)
    assert future.result(timeout=0) == "approved /A -> done"
    assert result.status is BehaviorStatus.FINISHED
    assert [(e.path, e.outcome, e.pending) for e in events["request"]] == [("/A", "done", True), ("/A", "done", False)]
    first = events["transition"][0]
    assert (first.path, first.outcome, first.target, first.target_path, first.required, first.forced) == (
        "/A",
        "done",
        "B",
        "/B",
        Autonomy.HIGH,
        True,
    )
    assert journal.of("A") == ["start", "enter", "execute", "pause", "exit", "stop"]


def test_raising_autonomy_releases_waiting_outcomes():
    journal = Journal()
    ex = executor(two_states(journal, Autonomy.HIGH), autonomy=Autonomy.LOW)
    ex.run(timeout_s=1.0, stop_on_timeout=False)
    assert ex.requested_outcomes()
    ex.set_autonomy("full")
    assert ex.run(timeout_s=5.0).status is BehaviorStatus.FINISHED
    assert ex.autonomy is Autonomy.FULL


def test_lowering_autonomy_makes_later_transitions_wait():
    journal = Journal()
    sm = two_states(journal, Autonomy.LOW)
    ex = executor(sm, autonomy=Autonomy.FULL)
    ex.set_autonomy(Autonomy.OFF)
    ex.run(timeout_s=1.0, stop_on_timeout=False)
    assert [r.path for r in ex.requested_outcomes()] == ["/A"]


def test_unsupervised_ignores_autonomy():
    journal = Journal()
    ex = executor(two_states(journal, Autonomy.FULL), autonomy=Autonomy.OFF, supervised=False)
    assert ex.run(timeout_s=5.0).status is BehaviorStatus.FINISHED


def test_force_transition_leaves_a_running_state_without_executing_it_again():
    journal = Journal()
    ex = executor(one_state(ScriptedState(journal, script=[None])))
    spin(ex, 3)
    assert journal.count("A", "execute") == 3
    ex.force_transition("/A", "failed")
    result = ex.run(timeout_s=5.0)
    assert result.outcome == "failed"
    assert journal.count("A", "execute") == 3
    assert journal.of("A")[-2:] == ["exit", "stop"]


def test_force_another_outcome_than_the_requested_one():
    journal = Journal()
    ex = executor(two_states(journal, Autonomy.FULL))
    events = record_events(ex)
    ex.run(timeout_s=1.0, stop_on_timeout=False)
    ex.force_transition("/A", "failed")
    result = ex.run(timeout_s=5.0)
    assert result.outcome == "failed"
    assert [(e.outcome, e.pending) for e in events["request"]] == [("done", True), ("done", False)]


def test_force_on_a_nested_container_exits_its_active_state():
    journal = Journal()
    inner = one_state(ScriptedState(journal, script=[None]), "Deep")
    outer = StateMachine(outcomes=["ok", "bad"])
    outer.add("Inner", inner, transitions={"finished": "ok", "failed": "bad"})
    ex = executor(outer)
    spin(ex, 2)
    assert ex.active_paths() == ("/Inner/Deep",)
    ex.force_transition("/Inner", "failed")
    result = ex.run(timeout_s=5.0)
    assert result.outcome == "bad"
    assert journal.of("Deep")[-2:] == ["exit", "stop"]


def test_force_the_root_finishes_the_behavior():
    journal = Journal()
    ex = executor(one_state(ScriptedState(journal, script=[None])))
    spin(ex, 1)
    ex.force_transition("/", "failed")
    result = ex.run(timeout_s=1.0)
    assert (result.status, result.outcome, result.reason) == (
        BehaviorStatus.FINISHED,
        "failed",
        "outcome forced by the operator",
    )
    assert journal.of("A")[-2:] == ["exit", "stop"]


def test_nested_autonomy_gates_both_levels():
    """The inner transition to the machine's outcome and the outer transition each need their level."""
    journal = Journal()
    inner = one_state(ScriptedState(journal), "X", autonomy={"done": Autonomy.HIGH})
    outer = StateMachine(outcomes=["ok", "bad"])
    outer.add("Inner", inner, transitions={"finished": "ok", "failed": "bad"}, autonomy={"finished": Autonomy.FULL})
    ex = executor(outer, autonomy=Autonomy.HIGH)
    ex.run(timeout_s=1.0, stop_on_timeout=False)
    assert [r.path for r in ex.requested_outcomes()] == ["/Inner/X"]
    ex.approve("/Inner/X")
    ex.run(timeout_s=1.0, stop_on_timeout=False)
    assert [(r.path, r.outcome) for r in ex.requested_outcomes()] == [("/Inner", "finished")]
    assert ex.active_paths() == ("/Inner",)
    ex.approve("/Inner")
    assert ex.run(timeout_s=1.0).outcome == "ok"


def test_command_validation_names_valid_choices():
    journal = Journal()
    ex = executor(two_states(journal, Autonomy.OFF))
    with pytest.raises(BehaviorCommandError, match=r"state path '/C' is not valid \(valid: /, /A, /B\)"):
        ex.force_transition("/C", "done")
    with pytest.raises(
        BehaviorCommandError, match=r"state '/A' has no outcome 'ok' is not valid \(valid: done, failed\)"
    ):
        ex.force_transition("/A", "ok")
    with pytest.raises(BehaviorCommandError, match="autonomy level 'max' is not valid"):
        ex.set_autonomy("max")


def test_dynamic_command_failures_are_reported_through_the_future_and_hooks():
    journal = Journal()
    ex = executor(two_states(journal, Autonomy.FULL))
    events = record_events(ex)
    ex.run(timeout_s=1.0, stop_on_timeout=False)
    not_active = ex.force_transition("/B", "done")
    no_request = ex.approve("/B")
    wrong = ex.approve("/A", "failed")
    ex.spin_once()
    with pytest.raises(BehaviorCommandError, match=r"state '/B' is not active \(active: /A\)"):
        not_active.result(timeout=0)
    with pytest.raises(BehaviorCommandError, match=r"state '/B' requests no outcome \(requests: /A \(done\)\)"):
        no_request.result(timeout=0)
    with pytest.raises(BehaviorCommandError, match="requests 'done', not 'failed'; use force_transition"):
        wrong.result(timeout=0)
    assert [(e.command, e.ok) for e in events["command"]] == [
        ("force_transition", False),
        ("approve", False),
        ("approve", False),
    ]
    assert ex.status is BehaviorStatus.RUNNING  # a refused command does not fail the behavior


def test_commands_after_the_end_are_refused():
    journal = Journal()
    ex = executor(two_states(journal, Autonomy.OFF))
    ex.run(timeout_s=5.0)
    with pytest.raises(BehaviorCommandError, match="has ended"):
        ex.preempt()


def test_autonomy_parse():
    assert Autonomy.parse("High") is Autonomy.HIGH
    assert Autonomy.parse(0) is Autonomy.OFF
    for bad in (True, 4, "none", 1.5):
        with pytest.raises(ConfigError, match="valid: off, low, high, full, 0, 1, 2, 3"):
            Autonomy.parse(bad)


def nested_with_output(journal):
    inner = StateMachine(outcomes=["finished", "failed"], output_keys=["result"])
    inner.add(
        "W",
        ScriptedState(journal, output_keys=["result"], action=lambda ud, n: setattr(ud, "result", 42)),
        transitions={"done": "finished", "failed": "failed"},
    )
    outer = StateMachine(outcomes=["ok", "bad"], output_keys=["result"])
    outer.add("Inner", inner, transitions={"finished": "ok", "failed": "bad"}, autonomy={"finished": Autonomy.FULL})
    return outer


@pytest.mark.parametrize(
    ("command", "outcome", "outputs"),
    [("approve", "ok", {"result": 42}), ("force_same", "ok", {"result": 42}), ("force_other", "bad", {})],
)
def test_approving_a_finished_container_hands_outputs_up_forcing_another_outcome_does_not(command, outcome, outputs):
    journal = Journal()
    ex = executor(nested_with_output(journal))
    ex.run(timeout_s=1.0, stop_on_timeout=False)
    assert [(r.path, r.outcome) for r in ex.requested_outcomes()] == [("/Inner", "finished")]
    if command == "approve":
        message = ex.approve("/Inner")
    elif command == "force_same":
        message = ex.force_transition("/Inner", "finished")
    else:
        message = ex.force_transition("/Inner", "failed")
    result = ex.run(timeout_s=1.0)
    assert message.result(timeout=0).startswith("forced" if command == "force_other" else "approved")
    assert (result.outcome, result.outputs) == (outcome, outputs)


def _drive_and_monitor(journal, bump_level, conditions):
    cc = ConcurrencyContainer(outcomes=["blocked", "arrived"], conditions=conditions)
    cc.add("Drive", ScriptedState(journal, script=[None] * 40 + ["done"]))
    cc.add("Bump", ScriptedState(journal, script=[None] * 5 + ["bumper"], outcomes=["bumper"]),
           autonomy={"bumper": bump_level})
    sm = StateMachine(outcomes=["finished", "failed"])
    sm.add("Go", cc, transitions={"blocked": "failed", "arrived": "finished"})
    return sm


def test_a_monitor_outcome_waiting_for_the_operator_holds_its_siblings_still():
    """The bumper monitor's outcome needs High at autonomy Low: the driving sibling is paused (its on_pause stops
    the robot) the moment the request is raised and not executed until the operator decides."""
    journal = Journal()
    ex = executor(_drive_and_monitor(journal, Autonomy.HIGH, [("blocked", [("Bump", "bumper")]),
                                                                ("arrived", [("Drive", "done")])]),
                  autonomy=Autonomy.LOW)
    ex.run(timeout_s=30.0, stop_on_timeout=False)
    assert [r.path for r in ex.requested_outcomes()] == ["/Go/Bump"]
    drive = journal.of("Drive")
    assert drive[-1] == "pause" and drive.count("execute") == 6  # six ticks side by side, then held
    assert journal.of("Bump")[-1] == "pause"
    ex.approve("/Go/Bump")
    assert ex.run(timeout_s=5.0).outcome == "failed"
    assert journal.of("Drive")[-3:] == ["pause", "exit", "stop"]  # left without running again


def test_siblings_resume_when_the_waiting_outcome_does_not_end_the_container():
    journal = Journal()
    ex = executor(_drive_and_monitor(journal, Autonomy.HIGH, [("blocked", [("Bump", "bumper"), ("Drive", "done")]),
                                                                ("arrived", [("Drive", "done")])]),
                  autonomy=Autonomy.LOW)
    ex.run(timeout_s=30.0, stop_on_timeout=False)
    assert journal.of("Drive")[-1] == "pause"
    ex.approve("/Go/Bump")
    assert ex.run(timeout_s=30.0).outcome == "failed"  # Bump and then Drive finished: "blocked"
    drive = journal.of("Drive")
    assert drive[drive.index("pause") + 1] == "resume" and drive.count("execute") == 41
