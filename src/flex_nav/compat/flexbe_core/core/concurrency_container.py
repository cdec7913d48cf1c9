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
"""

from __future__ import annotations

from typing import Any, Mapping, Sequence

from flex_nav.behavior.concurrency import ConcurrencyContainer as EngineConcurrencyContainer
from flex_nav.compat.flexbe_core.core.container_support import FlexBEContainer, Wiring
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
        return EngineConcurrencyContainer.add(self, label, state, remapping=wiring.remapping, autonomy=wiring.autonomy)


__all__ = ["ConcurrencyContainer"]
