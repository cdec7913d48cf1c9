"""flexbe_core.core: FlexBE's state and container classes (mapped onto flex_nav's engine)."""

from flex_nav.compat.flexbe_core.core.concurrency_container import ConcurrencyContainer
from flex_nav.compat.flexbe_core.core.event_state import EventState
from flex_nav.compat.flexbe_core.core.operatable_state_machine import OperatableStateMachine
from flex_nav.compat.flexbe_core.core.priority_container import PriorityContainer

__all__ = ["ConcurrencyContainer", "EventState", "OperatableStateMachine", "PriorityContainer"]
