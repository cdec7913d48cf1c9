"""flexbe_core.core.lockable_state: a state that can be locked: while ``_locked``, an outcome it returns is stored
and given only after the unlock (and only if no locked container would be left by it)."""

from typing import Optional

from flex_nav.compat.flexbe_core.core.manually_transitionable_state import ManuallyTransitionableState


class LockableState(ManuallyTransitionableState):
    """FlexBE's locking layer (flex_nav's executor has its own ``lock`` / ``unlock`` commands)."""

    _locked = False
    _stored_outcome: Optional[str] = None

    def is_locked(self) -> bool:
        return self._locked


__all__ = ["LockableState"]
