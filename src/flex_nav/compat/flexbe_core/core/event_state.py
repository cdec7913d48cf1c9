"""FlexBE's EventState on flex_nav's engine: same constructor keywords, same lifecycle hooks, and ``execute()`` that
FlexBE code may call itself.

A FlexBE state library subclasses ``EventState``::

    class WaitState(EventState):
        def __init__(self, wait_time):
            super(WaitState, self).__init__(outcomes=['done'])
            self._wait_time = wait_time
        def on_enter(self, userdata): ...
        def execute(self, userdata): return 'done' if ... else None

Two ways to run it:

- flex_nav's executor (a behavior run by ``behavior_runner`` or :class:`~flex_nav.behavior.BehaviorExecutor`)
  calls the hooks itself: ``on_start()``, ``on_enter(userdata)``, ``execute(userdata)`` (an outcome, or None to keep
  running; never blocking), ``on_exit(userdata)``, ``on_pause()``, ``on_resume(userdata)``, ``on_stop()``, at
  ``rate_hz`` (10 Hz unless ``set_rate``).
- FlexBE code calls ``state.execute(userdata)`` directly (flexbe_testing's Tester, a directly executed
  container, FlexBE's own tests). Then ``execute`` behaves as FlexBE's: the first call after entering runs
  ``on_enter`` first (and ``on_resume`` after a pause), an outcome runs ``on_exit`` and re-arms ``on_enter``,
  ``PreemptableState.preempt`` makes it return ``'preempted'``, a locked state stores its outcome until unlocked,
  and while the state is controlled (``_enable_ros_control()``) an outcome that needs more autonomy than
  ``OperatableStateMachine.autonomy_level`` is held back. ``sleep()`` waits for the state's rate.

Which one is happening is told apart by who calls: the engine passes its own userdata view to a state it has
entered; anything else is a direct call. The user's ``execute`` is wrapped once per class when the class is
defined (no per-instance method swapping); a subclass's ``super().execute(userdata)`` reaches the parent's code
without running the hooks twice. FlexBE's App command topics (pause, repeat, lock over ROS) are not followed:
flex_nav's runner and operator interface replace them.
"""

from __future__ import annotations

import functools
from typing import Any, Callable, Optional

from flex_nav.behavior.userdata import UserDataView
from flex_nav.compat.flexbe_core.core.operatable_state import OperatableState
from flex_nav.compat.flexbe_core.core.preemptable_state import PreemptableState

ExecuteFn = Callable[[Any, Any], Optional[str]]


def _engine_drives(state: Any, userdata: Any) -> bool:
    """The engine calls ``execute`` with its own view, on a state it has entered."""
    return isinstance(userdata, UserDataView) and state.__flex_nav_runtime__.entered


def _wrap_execute(user_execute: ExecuteFn) -> ExecuteFn:
    @functools.wraps(user_execute)
    def execute(self: Any, userdata: Any = None, *args: Any, **kwargs: Any) -> Optional[str]:
        if self.__dict__.get("_flexbe_in_execute") or _engine_drives(self, userdata):
            return user_execute(self, userdata, *args, **kwargs)
        self._flexbe_in_execute = True
        try:
            return self._flexbe_event_execute(  # type: ignore[no-any-return]
                lambda ud: user_execute(self, ud, *args, **kwargs), userdata
            )
        finally:
            self._flexbe_in_execute = False

    execute.__flexbe_wrapped__ = True  # type: ignore[attr-defined]
    return execute


class EventState(OperatableState):
    """Base class of FlexBE states (flexbe_core 1.x's constructor and hooks, flex_nav's engine)."""

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        own = cls.__dict__.get("execute")
        if own is not None and not getattr(own, "__flexbe_wrapped__", False):
            cls.execute = _wrap_execute(own)  # type: ignore[method-assign,assignment]

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._entering = True
        self._skipped = False
        self._paused = False
        self._last_active_container: Optional[str] = None
        self._flexbe_in_execute = False

    # --- FlexBE's direct execution, layer by layer (event -> operatable -> preemptable -> lockable -> user) ----
    def _flexbe_event_execute(self, user_execute: Callable[[Any], Optional[str]], userdata: Any) -> Optional[str]:
        if self._paused and not PreemptableState.preempt:
            self._notify_skipped()
            return None
        if self._entering:
            self._entering = False
            self.on_enter(userdata)
        if self._skipped and not PreemptableState.preempt:
            self._skipped = False
            self.on_resume(userdata)
        outcome = self._flexbe_operatable_execute(user_execute, userdata)
        if outcome is not None and not PreemptableState.preempt:
            self._entering = True
            self.on_exit(userdata)
        return outcome

    def _flexbe_operatable_execute(self, user_execute: Callable[[Any], Optional[str]], userdata: Any) -> Optional[str]:
        outcome = self._flexbe_preemptable_execute(user_execute, userdata)
        parent = self.parent
        if self._is_controlled and parent is not None and hasattr(parent, "is_transition_allowed"):
            if not self._force_transition and not parent.is_transition_allowed(self.name, outcome):
                from flex_nav.compat.flexbe_core.logger import Logger  # noqa: PLC0415

                if outcome != self._last_requested_outcome:
                    Logger.localinfo(f"<-- Want result: {self.name} > {outcome}")
                    self._last_requested_outcome = outcome
                outcome = None
            elif outcome is not None:
                self._last_requested_outcome = None
        self._force_transition = False
        return outcome

    def _flexbe_preemptable_execute(self, user_execute: Callable[[Any], Optional[str]], userdata: Any) -> Optional[str]:
        if PreemptableState.preempt:
            self._force_transition = True
            return self._preempted_name
        return self._flexbe_lockable_execute(user_execute, userdata)

    def _flexbe_lockable_execute(self, user_execute: Callable[[Any], Optional[str]], userdata: Any) -> Optional[str]:
        parent = self.parent
        if self._locked:
            if self._stored_outcome is None:
                self._stored_outcome = user_execute(userdata)
            return None
        if self._stored_outcome is not None:
            if (
                parent is None
                or not hasattr(parent, "transition_allowed")
                or parent.transition_allowed(self.name, self._stored_outcome)
            ):
                outcome, self._stored_outcome = self._stored_outcome, None
                return outcome
            return None
        self._force_transition = False
        result: Optional[str] = user_execute(userdata)
        if result is None:
            return None
        outcome = result
        if (
            parent is not None
            and hasattr(parent, "transition_allowed")
            and not parent.transition_allowed(self.name, outcome)
        ):
            self._stored_outcome = outcome
            return None
        return outcome

    def _notify_skipped(self) -> None:
        """A container does not execute this state now (paused, or another branch has priority)."""
        if not self._skipped:
            self.on_pause()
            self._skipped = True

    # on_start, on_enter, on_exit, on_pause, on_resume, on_stop: the engine State's hooks (same names and meaning)


__all__ = ["EventState"]
