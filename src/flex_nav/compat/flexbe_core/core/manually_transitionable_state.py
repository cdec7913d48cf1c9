"""flexbe_core.core.manually_transitionable_state: a state whose outcome the operator may force (``_force_transition``
is set while a forced or preempting outcome is returned). Forcing itself is flex_nav's ``force_transition``."""

from flex_nav.compat.flexbe_core.core.ros_state import RosState


class ManuallyTransitionableState(RosState):
    """FlexBE's layer for operator-forced outcomes."""

    _force_transition = False


__all__ = ["ManuallyTransitionableState"]
