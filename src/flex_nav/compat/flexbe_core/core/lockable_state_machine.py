"""flexbe_core.core.lockable_state_machine: FlexBE's LockableStateMachine: ``lock(path)`` / ``unlock(path)`` and
``transition_allowed`` (no outcome leaves a locked machine) for directly executed machines; see
:class:`~flex_nav.compat.flexbe_core.core.container_support.FlexBEContainer`. flex_nav's executor has its own
``lock`` / ``unlock`` commands."""

from flex_nav.compat.flexbe_core.core.state_machine import StateMachine


class LockableStateMachine(StateMachine):
    """A FlexBE state machine that can be locked."""

    path_for_switch = None


__all__ = ["LockableStateMachine"]
