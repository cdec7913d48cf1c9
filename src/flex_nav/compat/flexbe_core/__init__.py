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
  ``ProxySubscriberCached``, ``ProxyActionClient``, ``ProxyServiceCaller`` with FlexBE's method names and,
  on purpose, FlexBE's process-wide connections (:mod:`~flex_nav.compat.flexbe_core.proxy.hub`); flex_nav's
  own states keep one set of connections per behavior.
- FlexBE code that drives states itself (``state.execute(userdata)``, ``sm.execute(None)``, ``sleep()``,
  flexbe_testing's Tester) gets FlexBE 1.x's semantics: on_enter on the first call, on_exit with an outcome,
  ``PreemptableState.preempt``, ``OperatableStateMachine.autonomy_level``, ``sm._last_exception``,
  :class:`~flex_nav.compat.flexbe_core.core.user_data.UserData` views. These class-level knobs govern that
  direct execution only; a behavior run by flex_nav's executor keeps autonomy, preemption and priority in its
  own context, so two behaviors in one process never see each other's.

:func:`flex_nav.compat.install_aliases` makes ``import flexbe_core`` resolve here when FlexBE is absent.
Not provided: FlexBE's onboard engine internals (behavior switching, ``BehaviorLibrary``, the App's command
topics, ``ProxyTransformListener``; ``StateLogger`` is a no-op); flex_nav's runner and operator interface replace
them.
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
