"""flexbe_core 1.x's public API, mapped onto flex_nav's behavior engine, for FlexBE state libraries and behaviors.

- :class:`EventState` is a :class:`flex_nav.behavior.State` with FlexBE's constructor keywords; its
  lifecycle hooks are the engine's (they have the same names and meaning).
- :class:`OperatableStateMachine`, :class:`ConcurrencyContainer` (``conditions=[(outcome, [(label,
  outcome), ...]), ...]``) and :class:`PriorityContainer` are the engine's containers with FlexBE's
  construction idiom (``with sm:``, ``OperatableStateMachine.add(label, state, transitions=...,
  autonomy=..., remapping=...)``, ``sm.userdata.key = default``).
- :class:`Autonomy` Off/Low/High/Full = 0..3; :class:`Logger` routes to the running behavior.
- :class:`Behavior` is the generated-behavior base class; :func:`build_behavior` turns one into a
  flex_nav :class:`~flex_nav.behavior.Behavior` to run in :class:`~flex_nav.behavior.BehaviorExecutor`.
- :mod:`flexbe_core.proxy <flex_nav.compat.flexbe_core.proxy>`: ``ProxyPublisher``,
  ``ProxySubscriberCached``, ``ProxyActionClient``, ``ProxyServiceCaller`` with FlexBE's method names,
  bound to the connections of ONE behavior (the one being built or run), never shared between behaviors.

No global mutable state: autonomy, preemption, priority and proxies belong to the behavior's context.
:func:`flex_nav.compat.install_aliases` makes ``import flexbe_core`` resolve here when FlexBE is absent.
Not provided: FlexBE's onboard engine internals (behavior switching, ``BehaviorLibrary``,
``StateLogger``, ``ProxyTransformListener``); flex_nav's runner and operator interface replace them.
"""

from flex_nav.compat.flexbe_core.autonomy import Autonomy
from flex_nav.compat.flexbe_core.behavior import Behavior, build_behavior
from flex_nav.compat.flexbe_core.core import ConcurrencyContainer, EventState, OperatableStateMachine, PriorityContainer
from flex_nav.compat.flexbe_core.logger import Logger

__all__ = [
    "Autonomy",
    "Behavior",
    "ConcurrencyContainer",
    "EventState",
    "Logger",
    "OperatableStateMachine",
    "PriorityContainer",
    "build_behavior",
]
