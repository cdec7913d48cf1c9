"""FlexBE's PriorityContainer: while it is active, every state outside it is paused (engine semantics).

The claim is held by the running behavior's context, not by a class attribute as in FlexBE, so two
behaviors never pause each other. ``conditions`` is accepted for FlexBE's signature and unused (as in
FlexBE).
"""

from __future__ import annotations

from typing import Any, Optional, Sequence

from flex_nav.behavior.priority import PriorityContainer as EnginePriorityContainer
from flex_nav.behavior.state_machine import StateMachine
from flex_nav.compat.flexbe_core.core.operatable_state_machine import OperatableStateMachine


class PriorityContainer(OperatableStateMachine, EnginePriorityContainer):
    """A state machine that pauses everything else while it runs."""

    def __init__(
        self,
        conditions: Optional[Any] = None,
        outcomes: Sequence[str] = (),
        input_keys: Sequence[str] = (),
        output_keys: Sequence[str] = (),
    ) -> None:
        StateMachine.__init__(self, outcomes, input_keys, output_keys)
        self._init_flexbe()


__all__ = ["PriorityContainer"]
