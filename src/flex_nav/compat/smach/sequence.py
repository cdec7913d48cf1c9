"""SMACH's Sequence: a StateMachine whose states are chained by one connector outcome, in the order added.

::

    seq = smach.Sequence(outcomes=["succeeded", "aborted"], connector_outcome="succeeded")
    with seq:
        smach.Sequence.add("A", A())       # A.succeeded -> B (added automatically)
        smach.Sequence.add("B", B())       # B.succeeded falls through to the sequence's 'succeeded'

An explicit transition for the connector outcome overrides the automatic one. Every state but the
last must register the connector outcome (:class:`InvalidTransitionError` names its outcomes).
"""

from __future__ import annotations

from typing import Any, Mapping, Optional
from typing import Sequence as Seq

from flex_nav.compat.smach.container import smach_construction
from flex_nav.compat.smach.state_machine import StateMachine
from flex_nav.compat.smach.util import names
from flex_nav.exceptions import InvalidTransitionError


class Sequence(StateMachine):
    """States run one after the other while they return ``connector_outcome``."""

    def __init__(
        self,
        outcomes: Seq[str],
        connector_outcome: str,
        input_keys: Seq[str] = (),
        output_keys: Seq[str] = (),
    ) -> None:
        super().__init__(outcomes, input_keys, output_keys)
        (self._connector_outcome,) = names("connector_outcome", [connector_outcome], "Sequence")
        self._last_added_seq_label: Optional[str] = None

    def _add_in_sequence(
        self,
        label: str,
        state: Any,
        transitions: Optional[Mapping[str, Optional[str]]] = None,
        remapping: Optional[Mapping[str, str]] = None,
    ) -> Any:
        """Add ``state`` and connect the previous state's connector outcome to it (unless overridden)."""
        connector = self._connector_outcome
        previous = self._last_added_seq_label
        if previous is not None:
            registered = self._states[previous].get_registered_outcomes()
            if connector not in registered:
                raise InvalidTransitionError(
                    f"sequence: state {previous!r} does not register the connector outcome {connector!r} "
                    f"needed to continue with {label!r} (registered: {', '.join(registered)})"
                )
        added = StateMachine._add(self, label, state, transitions, remapping)
        if previous is not None and self._transitions[previous].get(connector) is None:
            self._transitions[previous][connector] = label
        self._last_added_seq_label = label
        return added

    add = smach_construction(_add_in_sequence)


__all__ = ["Sequence"]
