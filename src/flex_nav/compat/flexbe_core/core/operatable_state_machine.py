"""FlexBE's OperatableStateMachine: flex_nav's StateMachine with FlexBE's construction idiom.

Autonomy levels (``autonomy={'done': Autonomy.High}``), operator requests, locks, pause and preempt
are the engine's (:mod:`flex_nav.behavior.state_machine`); see :mod:`.container_support` for
``with sm:``, ``OperatableStateMachine.add(...)`` and ``sm.userdata``.
"""

from __future__ import annotations

from typing import Any, Sequence

from flex_nav.behavior.state_machine import StateMachine
from flex_nav.compat.flexbe_core.core.container_support import FlexBEContainer, Wiring


class OperatableStateMachine(FlexBEContainer, StateMachine):
    """A state machine of a FlexBE behavior."""

    def __init__(
        self, outcomes: Sequence[str], input_keys: Sequence[str] = (), output_keys: Sequence[str] = ()
    ) -> None:
        StateMachine.__init__(self, outcomes, input_keys, output_keys)
        self._init_flexbe()

    def _flexbe_add(self, label: str, state: Any, wiring: Wiring) -> Any:
        return StateMachine.add(
            self, label, state, transitions=wiring.transitions, autonomy=wiring.autonomy, remapping=wiring.remapping
        )


__all__ = ["OperatableStateMachine"]
