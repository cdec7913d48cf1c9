"""Scripted test states and helpers for the behavior engine tests (no ROS).

ScriptedState returns a scripted sequence of outcomes/None from execute and records every
lifecycle call in a shared Journal, so tests can assert on the exact order of calls.
"""

from __future__ import annotations

import concurrent.futures
from typing import Any, Callable, Dict, Iterable, List, Optional, Sequence, Tuple, Union

import pytest

from flex_nav.behavior import Behavior, BehaviorExecutor, ManualClock, State, StateMachine
from flex_nav.behavior.container import Container
from flex_nav.exceptions import BehaviorCommandError


class Journal:
    """Ordered record of (state label, call) pairs shared by the scripted states of one test."""

    def __init__(self) -> None:
        self.calls: List[Tuple[str, str]] = []

    def add(self, label: str, call: str) -> None:
        self.calls.append((label, call))

    def of(self, label: str) -> List[str]:
        return [call for who, call in self.calls if who == label]

    def count(self, label: str, call: str) -> int:
        return self.of(label).count(call)

    def clear(self) -> None:
        self.calls.clear()


class ScriptedState(State):
    """Returns ``script`` items from successive execute calls (then ``then`` forever).

    ``action(userdata, n)`` runs inside execute before returning (n = execute count, from 1).
    """

    def __init__(
        self,
        journal: Journal,
        script: Sequence[Optional[str]] = ("done",),
        outcomes: Sequence[str] = ("done", "failed"),
        input_keys: Sequence[str] = (),
        output_keys: Sequence[str] = (),
        then: Optional[str] = None,
        action: Optional[Callable[[Any, int], None]] = None,
        raise_in: str = "",
        rate_hz: float = 10.0,
    ) -> None:
        super().__init__(outcomes=outcomes, input_keys=input_keys, output_keys=output_keys, rate_hz=rate_hz)
        self.journal = journal
        self.script = list(script)
        self.then = then
        self.action = action
        self.raise_in = raise_in
        self.executions = 0
        self.execute_times: List[float] = []

    def _record(self, call: str) -> None:
        self.journal.add(self.name, call)
        if self.raise_in == call:
            raise RuntimeError(f"scripted failure in {call}")

    def on_start(self) -> None:
        self._record("start")

    def on_enter(self, userdata: Any) -> None:
        self._record("enter")

    def execute(self, userdata: Any) -> Optional[str]:
        self.executions += 1
        self.execute_times.append(self.now_s())
        self._record("execute")
        if self.action is not None:
            self.action(userdata, self.executions)
        index = self.executions - 1
        return self.script[index] if index < len(self.script) else self.then

    def on_exit(self, userdata: Any) -> None:
        self._record("exit")

    def on_pause(self) -> None:
        self._record("pause")

    def on_resume(self, userdata: Any) -> None:
        self._record("resume")

    def on_stop(self) -> None:
        self._record("stop")


def chain(journal: Journal, labels: Iterable[str], outcomes: Sequence[str] = ("finished", "failed")) -> StateMachine:
    """A machine A -> B -> ... -> outcomes[0], every state finishing on its first execute."""
    sm = StateMachine(outcomes=outcomes)
    labels = list(labels)
    for i, label in enumerate(labels):
        target = labels[i + 1] if i + 1 < len(labels) else outcomes[0]
        sm.add(label, ScriptedState(journal), transitions={"done": target, "failed": outcomes[-1]})
    return sm


def child(state: State, *labels: str) -> State:
    """The state at ``labels`` below ``state``, each step a container."""
    for label in labels:
        assert isinstance(state, Container), f"{label}: {state!r} is not a container"
        state = state[label]
    return state


def one_state(state: State, label: str = "A", **add: Any) -> StateMachine:
    """A machine of the one state ``label``: its done finishes the machine, its failed fails it (``add``: more
    arguments of ``StateMachine.add``, e.g. ``autonomy``)."""
    sm = StateMachine(outcomes=["finished", "failed"])
    sm.add(label, state, transitions={"done": "finished", "failed": "failed"}, **add)
    return sm


def executor(root: Union[Behavior, State], **kwargs: Any) -> BehaviorExecutor:
    kwargs.setdefault("clock", ManualClock())
    return BehaviorExecutor(root, **kwargs)


def spin(ex: BehaviorExecutor, times: int) -> None:
    """Tick ``times`` times, moving the manual clock to each next due time."""
    clock = ex.context.clock
    assert isinstance(clock, ManualClock)
    for _ in range(times):
        ex.spin_once()
        due = ex.due_s
        if due != float("inf") and due > clock.now():
            clock.advance(due - clock.now())


def assert_refused(ex: BehaviorExecutor, command: concurrent.futures.Future[str], match: str) -> None:
    """The executor refuses the queued ``command`` when it applies it (its next tick), with a message matching
    ``match``."""
    ex.spin_once()
    with pytest.raises(BehaviorCommandError, match=match):
        command.result(timeout=0)


def record_events(ex: BehaviorExecutor) -> Dict[str, List[Any]]:
    events: Dict[str, List[Any]] = {k: [] for k in ("transition", "request", "log", "status", "command", "active")}
    hooks = ex.context.hooks
    hooks.transition.append(events["transition"].append)
    hooks.request.append(events["request"].append)
    hooks.log.append(events["log"].append)
    hooks.status.append(events["status"].append)
    hooks.command.append(events["command"].append)
    hooks.active.append(events["active"].append)
    return events
