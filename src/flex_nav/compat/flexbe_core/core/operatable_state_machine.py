"""FlexBE's OperatableStateMachine: flex_nav's StateMachine with FlexBE's construction idiom and direct execution.

Run by flex_nav's executor, autonomy levels (``autonomy={'done': Autonomy.High}``), operator requests, locks, pause
and preempt are the engine's, per behavior (:mod:`flex_nav.behavior.state_machine`). Executed directly by FlexBE
code (``sm.execute(userdata)``), it follows FlexBE 1.x: ``OperatableStateMachine.autonomy_level`` (process-wide,
3 = full) gates the outcomes of controlled states, and an error of a child (a state raising, an unregistered
outcome, a bad userdata access, a nested machine with a missing transition target) is kept in
``sm._last_exception``, logged, and the step returns None. See :mod:`.container_support` for ``with sm:``,
``OperatableStateMachine.add(...)`` and ``sm.userdata``.
"""

from __future__ import annotations

from typing import Optional

from flex_nav.compat.flexbe_core.core.preemptable_state_machine import PreemptableStateMachine


class OperatableStateMachine(PreemptableStateMachine):
    """A state machine of a FlexBE behavior."""

    autonomy_level = 3  # FlexBE's process-wide level for directly executed machines (255: no control)

    def _execute_current_state(self) -> Optional[str]:
        return self._flexbe_guarded(super()._execute_current_state)


__all__ = ["OperatableStateMachine"]
