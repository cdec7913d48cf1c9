"""flexbe_core.core: FlexBE's state and container classes (mapped onto flex_nav's engine).

The state classes form FlexBE's chain (``State`` -> ``RosState`` -> ``ManuallyTransitionableState`` ->
``LockableState`` -> ``PreemptableState`` -> ``OperatableState`` -> ``EventState``), the containers
``StateMachine`` -> ``LockableStateMachine`` -> ``PreemptableStateMachine`` -> ``OperatableStateMachine`` ->
``PriorityContainer``, plus ``ConcurrencyContainer``; ``user_data.UserData`` and ``exceptions`` as in FlexBE.
"""

from flex_nav.compat.flexbe_core.core.concurrency_container import ConcurrencyContainer
from flex_nav.compat.flexbe_core.core.event_state import EventState
from flex_nav.compat.flexbe_core.core.lockable_state import LockableState
from flex_nav.compat.flexbe_core.core.lockable_state_machine import LockableStateMachine
from flex_nav.compat.flexbe_core.core.manually_transitionable_state import ManuallyTransitionableState
from flex_nav.compat.flexbe_core.core.operatable_state import OperatableState
from flex_nav.compat.flexbe_core.core.operatable_state_machine import OperatableStateMachine
from flex_nav.compat.flexbe_core.core.preemptable_state import PreemptableState
from flex_nav.compat.flexbe_core.core.preemptable_state_machine import PreemptableStateMachine
from flex_nav.compat.flexbe_core.core.priority_container import PriorityContainer
from flex_nav.compat.flexbe_core.core.ros_state import RosState
from flex_nav.compat.flexbe_core.core.state import State
from flex_nav.compat.flexbe_core.core.state_machine import StateMachine
from flex_nav.compat.flexbe_core.core.user_data import UserData

__all__ = [
    "ConcurrencyContainer",
    "EventState",
    "LockableState",
    "LockableStateMachine",
    "ManuallyTransitionableState",
    "OperatableState",
    "OperatableStateMachine",
    "PreemptableState",
    "PreemptableStateMachine",
    "PriorityContainer",
    "RosState",
    "State",
    "StateMachine",
    "UserData",
]
