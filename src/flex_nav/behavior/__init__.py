"""flex_nav.behavior: the pure-Python behavior engine (FlexBE-style HFSMs; no rospy import).

The public API, one concept per module:

- :mod:`~flex_nav.behavior.state` -- :class:`State`, the leaf base class and its lifecycle
  (``on_start``, ``on_enter``, ``execute``, ``on_exit``, ``on_pause``, ``on_resume``, ``on_stop``).
- :mod:`~flex_nav.behavior.state_machine` -- :class:`StateMachine` (transitions, remapping, nesting).
- :mod:`~flex_nav.behavior.concurrency` -- :class:`ConcurrencyContainer` (ordered AND-conditions).
- :mod:`~flex_nav.behavior.priority` -- :class:`PriorityContainer` (pauses everything else).
- :mod:`~flex_nav.behavior.autonomy` -- :class:`Autonomy` levels OFF/LOW/HIGH/FULL.
- :mod:`~flex_nav.behavior.userdata` -- declared-key views, zero-copy read-only protection.
- :mod:`~flex_nav.behavior.context` -- :class:`BehaviorContext`: everything one behavior owns.
- :mod:`~flex_nav.behavior.proxies` -- :class:`Proxies`: the typed port through which states reach ROS.
- :mod:`~flex_nav.behavior.events` -- status, log levels, hook events.
- :mod:`~flex_nav.behavior.clock` -- injected clocks (:class:`MonotonicClock`, :class:`ManualClock`).
- :mod:`~flex_nav.behavior.executor` -- :class:`BehaviorExecutor`: ticking, commands, queries.
- :mod:`~flex_nav.behavior.behavior` -- :class:`Behavior`: a named root with its parameters.
- :mod:`~flex_nav.behavior.yaml_loader` -- behaviors from YAML files with line-numbered errors.
- :mod:`~flex_nav.behavior.dot` -- Graphviz export.
- :mod:`~flex_nav.behavior.structure` -- a behavior's structure as JSON for operator tools.
- :mod:`~flex_nav.behavior.docstring` -- the state docstring convention and its parser.
- :mod:`~flex_nav.behavior.builtin_states` -- small generic states (Wait, Log, Decision, ...).

Errors are the BehaviorError family of :mod:`flex_nav.exceptions`.
"""

from flex_nav.behavior.autonomy import Autonomy
from flex_nav.behavior.behavior import Behavior
from flex_nav.behavior.clock import Clock, ManualClock, MonotonicClock
from flex_nav.behavior.concurrency import ConcurrencyContainer
from flex_nav.behavior.container import Container
from flex_nav.behavior.context import BehaviorContext, current_context, using_context
from flex_nav.behavior.events import (
    ActiveStatesEvent,
    BehaviorStatus,
    CommandEvent,
    Hooks,
    LogEvent,
    LogLevel,
    RequestEvent,
    StatusEvent,
    TransitionEvent,
)
from flex_nav.behavior.executor import BehaviorExecutor, BehaviorResult, OutcomeRequest
from flex_nav.behavior.priority import PriorityContainer
from flex_nav.behavior.proxies import Proxies
from flex_nav.behavior.state import State
from flex_nav.behavior.state_machine import StateMachine
from flex_nav.behavior.userdata import UserDataView, readonly, unwrap

__all__ = [
    "ActiveStatesEvent",
    "Autonomy",
    "Behavior",
    "BehaviorContext",
    "BehaviorExecutor",
    "BehaviorResult",
    "BehaviorStatus",
    "Clock",
    "CommandEvent",
    "ConcurrencyContainer",
    "Container",
    "Hooks",
    "LogEvent",
    "LogLevel",
    "ManualClock",
    "MonotonicClock",
    "OutcomeRequest",
    "PriorityContainer",
    "Proxies",
    "RequestEvent",
    "State",
    "StateMachine",
    "StatusEvent",
    "TransitionEvent",
    "UserDataView",
    "current_context",
    "readonly",
    "unwrap",
    "using_context",
]
