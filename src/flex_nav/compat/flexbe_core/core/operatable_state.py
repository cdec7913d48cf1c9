"""flexbe_core.core.operatable_state: the autonomy layer: an outcome whose transition needs more autonomy than
``OperatableStateMachine.autonomy_level`` is held back (requested) while the state is controlled
(``_enable_ros_control``), as in FlexBE; flex_nav's executor applies its own autonomy levels per behavior."""

from typing import Optional

from flex_nav.compat.flexbe_core.core.preemptable_state import PreemptableState


class OperatableState(PreemptableState):
    """FlexBE's autonomy layer."""

    _last_requested_outcome: Optional[str] = None


__all__ = ["OperatableState"]
