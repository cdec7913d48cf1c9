"""SMACH's Python API with SMACH's semantics, for code written against ``import smach``.

Written from SMACH's documentation (not from its code). Everything SMACH exports is here:
:class:`State`, :class:`CBState`, :func:`cb_interface` / :class:`CBInterface`, :class:`UserData`,
:class:`Remapper`, :class:`Container`, :class:`StateMachine` (``add``, ``add_auto``, ``with sm:`` /
``opened()``, ``set_initial_state``, callbacks), :class:`Sequence`, :class:`Concurrence`
(``outcome_map``, ``default_outcome``, ``outcome_cb``, ``child_termination_cb``), :class:`Iterator`,
preemption, ``set_loggers`` / ``loginfo`` ..., ``set_shutdown_check`` / ``is_shutdown``, the four
exception types, and the container introspection smach_ros relies on. The submodules have SMACH's
names (``smach.state``, ``smach.container``, ``smach.user_data``, ...), so
:func:`flex_nav.compat.install_aliases` can make ``import smach`` resolve here when SMACH is absent.

Where flex_nav is stricter than SMACH (always loudly, never silently): an inconsistent container
raises from ``execute`` instead of returning None; writing an undeclared userdata key raises instead
of being logged and dropped; input-only values are read-only views for every type (ROS messages,
lists, dicts); a callback that raises fails its container; a bare string given as a list of outcomes
or keys is refused. The "opened container" of ``with sm:`` is tracked per thread, not per process.
To run a SMACH state inside a flex_nav behavior, wrap it in
:class:`flex_nav.compat.smach_adapter.SmachStateAdapter`.
"""

from flex_nav.compat.smach.concurrence import Concurrence
from flex_nav.compat.smach.container import Container
from flex_nav.compat.smach.exceptions import (
    InvalidConstructionError,
    InvalidStateError,
    InvalidTransitionError,
    InvalidUserCodeError,
)
from flex_nav.compat.smach.iterator import Iterator
from flex_nav.compat.smach.log import logdebug, logerr, loginfo, logwarn, set_loggers
from flex_nav.compat.smach.sequence import Sequence
from flex_nav.compat.smach.state import CBState, State
from flex_nav.compat.smach.state_machine import StateMachine
from flex_nav.compat.smach.user_data import Remapper, UserData
from flex_nav.compat.smach.util import CBInterface, cb_interface, has_smach_interface, is_shutdown, set_shutdown_check

__all__ = [
    "CBInterface",
    "CBState",
    "Concurrence",
    "Container",
    "InvalidConstructionError",
    "InvalidStateError",
    "InvalidTransitionError",
    "InvalidUserCodeError",
    "Iterator",
    "Remapper",
    "Sequence",
    "State",
    "StateMachine",
    "UserData",
    "cb_interface",
    "has_smach_interface",
    "is_shutdown",
    "logdebug",
    "logerr",
    "loginfo",
    "logwarn",
    "set_loggers",
    "set_shutdown_check",
]
