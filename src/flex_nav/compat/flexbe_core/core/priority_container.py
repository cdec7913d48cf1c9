"""FlexBE's PriorityContainer: while it is active, every state outside it is paused.

Run by flex_nav's executor, the claim is held by the running behavior's context (engine semantics), so two
behaviors never pause each other. Executed directly by FlexBE code, it follows FlexBE: while it runs,
``PriorityContainer.active_container`` (process-wide) holds its path, and a directly executed concurrency
container skips (pauses) the branches outside it. ``conditions`` is accepted for FlexBE's signature and unused
(as in FlexBE).
"""

from __future__ import annotations

from typing import Any, Optional, Sequence

from flex_nav.behavior.priority import PriorityContainer as EnginePriorityContainer
from flex_nav.compat.flexbe_core.core.operatable_state_machine import OperatableStateMachine
from flex_nav.compat.flexbe_core.core.state_machine import StateMachine


class PriorityContainer(OperatableStateMachine, EnginePriorityContainer):
    """A state machine that pauses everything else while it runs."""

    active_container: Optional[str] = None  # FlexBE's process-wide claim (direct execution only)

    def __init__(
        self,
        conditions: Optional[Any] = None,
        outcomes: Sequence[str] = (),
        input_keys: Sequence[str] = (),
        output_keys: Sequence[str] = (),
    ) -> None:
        StateMachine.__init__(self, outcomes, input_keys, output_keys)
        self._parent_active_container: Optional[str] = None

    def execute(self, userdata: Any = None) -> Optional[str]:
        active = PriorityContainer.active_container
        own = self.path
        if active is None or not all(a == s for a, s in zip(own.split("/"), active.split("/"))):
            self._parent_active_container = active
            PriorityContainer.active_container = own
        outcome = super().execute(userdata)
        if outcome is not None:
            PriorityContainer.active_container = self._parent_active_container
        return outcome


__all__ = ["PriorityContainer"]
