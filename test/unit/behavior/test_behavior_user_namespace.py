"""A state subclass owns its namespace: the engine keeps everything it needs about a state in one record
(``__flex_nav_runtime__``), never in names a user may pick for their own (``self._path``, ``self._active``,
``self._pending``, a helper ``self._abort()``, ...)."""

from __future__ import annotations

import copy
from typing import Any, Callable, List, Optional

from unit.behavior.behavior_testlib import Journal, ScriptedState, executor, spin

from flex_nav.behavior import Autonomy, BehaviorStatus, ConcurrencyContainer, State, StateMachine

# Every attribute the engine used to keep on the state instance itself, and every engine method it had there.
OLD_ENGINE_ATTRIBUTES = (
    "_outcomes", "_input_keys", "_output_keys", "_period_s",
    "_label", "_path", "_parent", "_ctx", "_ancestors", "_routes", "_ud", "_locked",
    "_active", "_entering", "_entered", "_due", "_next_s", "_pending", "_hold_mask", "_calls_enter", "_calls_exit",
)  # fmt: skip
OLD_ENGINE_METHODS = (
    "_attach", "_reset_run_state", "_walk", "_active_leaves", "_active_paths", "_activate", "_tick", "_leave",
    "_abort", "_drop_pending", "_wake", "_call_pause", "_call_resume", "_user_call",
)  # fmt: skip


class Busy(State):
    """Finishes after ``steps`` executions; uses every old engine name as its own (strings, own methods)."""

    _tick: Callable[[], str]  # one of the OLD_ENGINE_METHODS, all set below as the state's own methods

    def __init__(self, journal: Journal, steps: int) -> None:
        super().__init__(outcomes=["done", "failed"], input_keys=["goal"], output_keys=["result"])
        self.journal = journal
        self.steps = steps
        self.executions = 0
        self.own_calls: List[str] = []
        self._claim("init")

    def _claim(self, when: str) -> None:
        for name in OLD_ENGINE_ATTRIBUTES:
            setattr(self, name, f"{when}:{name}")

    def on_start(self) -> None:
        self.journal.add(self.name, "start")

    def on_enter(self, userdata: Any) -> None:
        self.journal.add(self.name, "enter")
        self._claim("enter")

    def execute(self, userdata: Any) -> Optional[str]:
        self.journal.add(self.name, "execute")
        self._tick()  # the state's own helper, not the engine's
        self.executions += 1
        if self.executions < self.steps:
            return None
        userdata.result = f"{self.name} reached {userdata.goal}"
        return "done"

    def on_exit(self, userdata: Any) -> None:
        self.journal.add(self.name, "exit")
        self._claim("exit")

    def on_pause(self) -> None:
        self.journal.add(self.name, "pause")

    def on_resume(self, userdata: Any) -> None:
        self.journal.add(self.name, "resume")

    def on_stop(self) -> None:
        self.journal.add(self.name, "stop")


def _own_method(name: str) -> Callable[..., str]:
    def method(self: Busy, *args: Any, **kwargs: Any) -> str:
        self.own_calls.append(name)
        return f"own {name}"

    method.__name__ = name
    return method


for _name in OLD_ENGINE_METHODS:
    setattr(Busy, _name, _own_method(_name))


def test_the_engine_sets_one_attribute_on_a_state():
    class Probe(State):
        def execute(self, userdata: Any) -> Optional[str]:
            return "done"

    assert set(vars(Probe(outcomes=["done"]))) == {"__flex_nav_runtime__"}


def test_a_shallow_copy_of_a_state_has_a_record_of_its_own():
    journal = Journal()
    one = ScriptedState(journal)
    two = copy.copy(one)
    sm = StateMachine(outcomes=["finished", "failed"])
    sm.add("One", one, transitions={"done": "Two", "failed": "failed"})
    sm.add("Two", two, transitions={"done": "finished", "failed": "failed"})
    assert executor(sm).run(timeout_s=1.0).outcome == "finished"
    assert journal.of("One") == journal.of("Two") == ["start", "enter", "execute", "exit", "stop"]
    assert (one.name, one.path) == ("One", "/One")


def test_a_state_using_the_old_engine_names_as_its_own_runs_correctly():
    """Autonomy request and approval, pause/resume, a lock, a concurrency container and userdata, with states
    that set ``_path``, ``_active``, ``_pending``, ``_due``, ... in __init__/on_enter/on_exit and define
    ``_tick``, ``_abort``, ... themselves. (On the engine that kept its bookkeeping in those names, the
    machine could not even be built: the state's own ``_parent`` said it was already in a container.)"""
    journal = Journal()
    first, a, b = Busy(journal, steps=1), Busy(journal, steps=2), Busy(journal, steps=4)
    both = ConcurrencyContainer(
        outcomes=["done", "failed"],
        conditions=[
            ("done", [("A", "done"), ("B", "done")]),
            ("failed", [("A", "failed")]),
            ("failed", [("B", "failed")]),
        ],
        input_keys=["goal"],
        output_keys=["result"],
    )
    both.add("A", a)
    both.add("B", b)
    sm = StateMachine(outcomes=["finished", "failed"], input_keys=["goal"], output_keys=["result"])
    sm.add("First", first, transitions={"done": "Both", "failed": "failed"}, autonomy={"done": Autonomy.HIGH})
    sm.add("Both", both, transitions={"done": "finished", "failed": "failed"})
    ex = executor(sm, inputs={"goal": "the dock"}, autonomy=Autonomy.LOW)

    ex.run(timeout_s=1.0, stop_on_timeout=False)
    assert [(r.path, r.outcome, r.reason) for r in ex.requested_outcomes()] == [("/First", "done", "autonomy")]
    assert first.path == "/First" and first.is_active and first.outcomes == ("done", "failed")
    ex.approve("/First")
    ex.lock("/Both")
    spin(ex, 3)
    ex.pause()
    ex.spin_once()
    ex.resume()
    ex.run(timeout_s=1.0, stop_on_timeout=False)
    assert [(r.path, r.outcome, r.reason) for r in ex.requested_outcomes()] == [("/Both", "done", "lock")]
    ex.unlock("/Both")
    result = ex.run(timeout_s=2.0)

    assert (result.status, result.outcome) == (BehaviorStatus.FINISHED, "finished"), result.reason
    assert result.outputs == {"result": "B reached the dock"}  # B finished last: its output is the one handed up
    assert journal.of("First") == ["start", "enter", "execute", "pause", "exit", "stop"]
    assert journal.of("A") == ["start", "enter", "execute", "execute", "exit", "stop"]
    assert journal.of("B") == ["start", "enter", *["execute"] * 2, "pause", "resume", *["execute"] * 2, "exit", "stop"]
    for state, label, path in ((first, "First", "/First"), (a, "A", "/Both/A"), (b, "B", "/Both/B")):
        assert state.own_calls == ["_tick"] * state.steps  # the engine never called the state's own methods
        assert (state.name, state.path, state.is_active) == (label, path, False)
        own = [getattr(state, name) for name in OLD_ENGINE_ATTRIBUTES]
        assert own == [f"exit:{name}" for name in OLD_ENGINE_ATTRIBUTES]  # nor touched its attributes
