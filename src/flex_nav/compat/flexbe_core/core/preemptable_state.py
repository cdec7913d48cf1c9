"""flexbe_core.core.preemptable_state: ``PreemptableState.preempt`` (FlexBE's process-wide preempt flag) and the
``preempted`` outcome.

The flag governs FlexBE code that drives states itself (direct ``execute()``): while it is set, every EventState
returns ``'preempted'`` instead of executing, and its state machine returns ``'preempted'``. As in FlexBE, creating
a state clears it. A behavior run by flex_nav's executor is preempted through its executor (``preempt()``), never by
this class attribute, so two behaviors in one process never preempt each other.
"""

from typing import Any

from flex_nav.compat.flexbe_core.core.lockable_state import LockableState


class PreemptableState(LockableState):
    """FlexBE's preemption layer."""

    _preempted_name = "preempted"
    preempt = False
    switching = False

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        PreemptableState.preempt = False


__all__ = ["PreemptableState"]
