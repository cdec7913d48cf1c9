"""FlexBE's ConcurrencyContainer: flex_nav's single-threaded concurrency with FlexBE's conditions.

::

    cc = ConcurrencyContainer(outcomes=['finished', 'failed'], conditions=[
        ('finished', [('Move', 'done'), ('Look', 'done')]),
        ('failed', [('Move', 'failed')]),
    ])
    with cc:
        OperatableStateMachine.add('Move', MoveState(), transitions={'done': 'finished', 'failed': 'failed'},
                                   autonomy={'done': Autonomy.Off, 'failed': Autonomy.Off})

Conditions are checked in order; the first whose (child, outcome) pairs all hold gives the outcome,
and children still running are exited. The transitions FlexBE's generated code gives the children
name container outcomes; they are checked (registered outcome, known target) but the conditions
decide. ``conditions`` may also be a mapping outcome -> pairs (its order is kept).

Executed directly by FlexBE code (``cc.execute(userdata)``), one step executes every child that has not finished
and is due at its own rate (``sleep_duration <= 0``), as FlexBE does; ``cc.sleep()`` waits until the next child is
due; a child's error is kept in ``_last_exception``; a ``'preempted'`` child makes the container return it.
"""

from __future__ import annotations

import functools
from typing import Any, Dict, Mapping, Optional, Sequence

from flex_nav.behavior.concurrency import ConcurrencyContainer as EngineConcurrencyContainer
from flex_nav.compat.flexbe_core.core.container_support import FlexBEContainer, Wiring
from flex_nav.compat.flexbe_core.core.preemptable_state import PreemptableState
from flex_nav.exceptions import UnknownTargetError, UnregisteredOutcomeError


class ConcurrencyContainer(FlexBEContainer, EngineConcurrencyContainer):
    """Children run concurrently (one thread, ticked in turn); ordered conditions decide the outcome."""

    def __init__(
        self,
        conditions: Any = (),
        outcomes: Sequence[str] = (),
        input_keys: Sequence[str] = (),
        output_keys: Sequence[str] = (),
    ) -> None:
        pairs = list(conditions.items()) if isinstance(conditions, Mapping) else list(conditions)
        EngineConcurrencyContainer.__init__(self, outcomes, pairs, input_keys, output_keys)
        self._init_flexbe()
        self._flexbe_transition_map: Dict[str, Dict[str, str]] = {}
        self._returned_outcomes: Dict[str, Optional[str]] = {}

    def _flexbe_add(self, label: str, state: Any, wiring: Wiring) -> Any:
        registered = getattr(state, "outcomes", ())
        for outcome, target in (wiring.transitions or {}).items():
            if outcome not in registered:
                raise UnregisteredOutcomeError(
                    f"concurrency container: transition of {label!r} names outcome {outcome!r} that "
                    f"{type(state).__name__} does not register (valid: {', '.join(registered) or 'none'})",
                    self.path,
                    label,
                    outcome,
                    "transition",
                )
            if target not in self.outcomes:
                raise UnknownTargetError(
                    f"concurrency container: transition {label!r}.{outcome} goes to {target!r}, which is not an "
                    f"outcome of the container (valid: {', '.join(self.outcomes)})",
                    self.path,
                    label,
                    outcome,
                    "transition",
                )
        added = EngineConcurrencyContainer.add(self, label, state, remapping=wiring.remapping, autonomy=wiring.autonomy)
        self._flexbe_transition_map[label] = dict(wiring.transitions or {})
        return added

    def _flexbe_transitions(self) -> Dict[str, Mapping[str, str]]:
        return dict(self._flexbe_transition_map)

    # --- FlexBE's direct execution ----------------------------------------------------------------------------
    def execute(self, userdata: Any = None) -> Optional[str]:
        """One step: every unfinished child that is due executes once; the first condition that holds is returned."""
        if self._flexbe_current is None:
            self._flexbe_begin(userdata)
            self._flexbe_current = next(iter(self._children.values()))
            self._returned_outcomes = {}
        return self._flexbe_step()

    def _flexbe_step(self) -> Optional[str]:
        from flex_nav.compat.flexbe_core.core.priority_container import PriorityContainer  # noqa: PLC0415

        for state in self._states:
            if self._returned_outcomes.get(state.name) is not None:
                continue  # finished
            active = PriorityContainer.active_container
            if active is not None and not all(a == s for a, s in zip(active.split("/"), state.path.split("/"))):
                skipped = state if hasattr(state, "_notify_skipped") else None
                if skipped is None and isinstance(state, FlexBEContainer):
                    skipped = state.get_deep_state()
                if skipped is not None and hasattr(skipped, "_notify_skipped"):
                    skipped._notify_skipped()
                continue  # another branch has priority
            if state.sleep_duration <= 0:
                self._flexbe_current = state
                self._returned_outcomes[state.name] = self._flexbe_guarded(
                    functools.partial(self._execute_child, state)
                )
                if state.sleep_duration <= 0:
                    state.sleep()  # returns at once: starts the child's next period
        if any(outcome == PreemptableState._preempted_name for outcome in self._returned_outcomes.values()):
            self._flexbe_current = None
            return PreemptableState._preempted_name
        outcome = self._match_flexbe()
        if outcome is None:
            return None
        self.on_exit(self._userdata)
        return outcome

    def _execute_child(self, state: Any) -> Optional[str]:
        with self._flexbe_view(state) as userdata:
            return state.execute(userdata)  # type: ignore[no-any-return]

    def _exit_child(self, state: Any) -> None:
        state.on_exit(self._flexbe_view(state))

    def _match_flexbe(self) -> Optional[str]:
        returned = self._returned_outcomes
        for outcome, pairs in self.conditions:
            if all(returned.get(label) == child_outcome for label, child_outcome in pairs):
                return outcome
        return None

    def on_exit(self, userdata: Any) -> None:
        """Exit the children that have not finished (directly executed container); the container is left."""
        for state in self._states:
            if self._returned_outcomes.get(state.name) is None:
                state._entering = True
                self._flexbe_guarded(functools.partial(self._exit_child, state))
        self._returned_outcomes = {}
        self._flexbe_current = None

    def on_enter(self, userdata: Any) -> None:
        for state in self._states:
            state._entering = True

    def sleep(self) -> None:
        """Wait until the next unfinished child is due."""
        duration = self.sleep_duration
        if duration > 0:
            self.wait(seconds=duration)

    @property
    def sleep_duration(self) -> float:
        """[s] until the next unfinished child is due (0 when one is due, or none is running)."""
        waits = [s.sleep_duration for s in self._states if self._returned_outcomes.get(s.name) is None]
        return max(0.0, min(waits)) if waits else 0.0

    def _enable_ros_control(self) -> None:
        """As FlexBE 1.x: control goes to the first child only (the others are reached through its container)."""
        self._is_controlled = True
        states = self._states
        if states and hasattr(states[0], "_enable_ros_control"):
            states[0]._enable_ros_control()

    def _disable_ros_control(self) -> None:
        self._is_controlled = False
        states = self._states
        if states and hasattr(states[0], "_disable_ros_control"):
            states[0]._disable_ros_control()


__all__ = ["ConcurrencyContainer"]
