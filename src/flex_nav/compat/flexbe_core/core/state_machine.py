"""flexbe_core.core.state_machine: FlexBE's StateMachine: flex_nav's engine StateMachine with FlexBE's construction
idiom and FlexBE's direct execution.

``sm.execute(userdata)`` (FlexBE code driving the machine itself) executes the active child once: the first call
checks the transitions (StateMachineError names a missing target), takes ``userdata`` (or keeps ``sm._userdata``)
and adds the machine's own defaults (``sm.userdata.key = value``); a child outcome moves to the next child, or is
returned when it leaves the machine. ``sm.sleep()`` waits for the active child's rate, ``sm.spin()`` runs to an
outcome. The subclasses add FlexBE's locks (:mod:`.lockable_state_machine`), preemption
(:mod:`.preemptable_state_machine`) and autonomy with error capture (:mod:`.operatable_state_machine`). flex_nav's
executor runs the same object through the engine instead (``with sm:``, validation, autonomy per behavior).
"""

from __future__ import annotations

from typing import Any, Optional, Sequence

from flex_nav.behavior.state_machine import StateMachine as EngineStateMachine
from flex_nav.compat.flexbe_core.core.container_support import FlexBEContainer, Wiring
from flex_nav.compat.flexbe_core.core.exceptions import StateError


class StateMachine(FlexBEContainer, EngineStateMachine):
    """A FlexBE state machine (one active child)."""

    def __init__(
        self, outcomes: Sequence[str] = (), input_keys: Sequence[str] = (), output_keys: Sequence[str] = ()
    ) -> None:
        EngineStateMachine.__init__(self, outcomes, input_keys, output_keys)
        self._init_flexbe()

    def _flexbe_add(self, label: str, state: Any, wiring: Wiring) -> Any:
        return EngineStateMachine.add(
            self, label, state, transitions=wiring.transitions, autonomy=wiring.autonomy, remapping=wiring.remapping
        )

    # --- FlexBE's direct execution ----------------------------------------------------------------------------
    def execute(self, userdata: Any = None) -> Optional[str]:
        """One step of FlexBE's execution: the active child executes once."""
        if self._flexbe_current is None:
            self._flexbe_begin(userdata)
            self._flexbe_current = self._children[self.initial_state or ""]
        return self._execute_current_state()

    def _execute_current_state(self) -> Optional[str]:
        state = self._flexbe_current
        with self._flexbe_view(state) as userdata:
            outcome = state.execute(userdata)
        if outcome is None:
            return None
        return self._flexbe_transition(state, outcome)

    def _flexbe_transition(self, state: Any, outcome: str) -> Optional[str]:
        try:
            target = self._transitions[state.name][outcome]
        except KeyError:
            raise StateError(f"Returned outcome '{outcome}' is not registered as transition!") from None
        self._flexbe_current = self._children.get(target)
        return target if self._flexbe_current is None else None


__all__ = ["StateMachine"]
