"""flexbe_core.core.preemptable_state_machine: FlexBE's PreemptableStateMachine: while ``PreemptableState.preempt``
is set, a directly executed machine returns ``'preempted'`` (its active child is left) and has no active state."""

from typing import Any, Optional

from flex_nav.compat.flexbe_core.core.lockable_state_machine import LockableStateMachine
from flex_nav.compat.flexbe_core.core.preemptable_state import PreemptableState


class PreemptableStateMachine(LockableStateMachine):
    """A FlexBE state machine that can be preempted."""

    _preempted_name = PreemptableState._preempted_name

    def _flexbe_transition(self, state: Any, outcome: str) -> Optional[str]:
        if outcome == self._preempted_name and outcome not in self._transitions.get(state.name, {}):
            self._flexbe_current = None
            return outcome
        return super()._flexbe_transition(state, outcome)

    def preempt(self) -> None:
        PreemptableState.preempt = True


__all__ = ["PreemptableStateMachine"]
