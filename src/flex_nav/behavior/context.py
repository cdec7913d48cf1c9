"""The per-behavior context: everything that belongs to one running behavior and to nothing else.

FlexBE keeps autonomy, preemption, the active priority container and the ROS proxies in class
attributes, so one process can run one behavior. Here each behavior gets one
:class:`BehaviorContext`; states reach it as ``self.context``. Two behaviors (two robots) in one
process have two contexts and never see each other's autonomy, preemption, pauses, hooks or proxies.

What is injected: the name, the clock (:mod:`flex_nav.behavior.clock`), the proxies (whatever the
runner provides: the ROS adapter passes its per-behavior proxy set; pure tests pass a fake or None)
and a Python logger. What it carries: the current autonomy, whether autonomy is enforced
(``supervised``), the preemption flag, the event :class:`~flex_nav.behavior.events.Hooks`, and the
engine's bookkeeping (outcome requests, locks, priority containers). The executor is the only writer
of the mutable parts, from its own thread; operator commands reach it through the executor.

:func:`current_context` returns the context whose states are being run by the executor in this
thread (a ``contextvars`` variable, set around each tick): compatibility layers use it to route
FlexBE's static ``Logger`` calls or proxy constructors to the right behavior.
"""

from __future__ import annotations

import contextlib
import contextvars
import logging
from typing import TYPE_CHECKING, Any, Dict, Iterator, List, Optional

from flex_nav.behavior.autonomy import Autonomy
from flex_nav.behavior.clock import Clock, MonotonicClock
from flex_nav.behavior.events import (
    ActiveStatesEvent,
    Hooks,
    LogEvent,
    LogLevel,
    RequestEvent,
    TransitionEvent,
)
from flex_nav.exceptions import BehaviorRuntimeError, NotReadyError

if TYPE_CHECKING:
    from flex_nav.behavior.container import Container
    from flex_nav.behavior.state import PendingReason, State

_PY_LEVELS = {
    LogLevel.INFO: logging.INFO,
    LogLevel.WARN: logging.WARNING,
    LogLevel.HINT: logging.INFO,
    LogLevel.ERROR: logging.ERROR,
    LogLevel.DEBUG: logging.DEBUG,
}

# Why a leaf is not being executed (bit mask on State._hold_mask).
HOLD_PAUSE = 1  # the operator paused the behavior
HOLD_PRIORITY = 2  # a priority container outside this state is active
HOLD_REQUEST = 4  # an outcome waits for the operator: everything holds still until none does

_CURRENT: contextvars.ContextVar[Optional[BehaviorContext]] = contextvars.ContextVar(
    "flex_nav_behavior_context", default=None
)


def current_context() -> Optional[BehaviorContext]:
    """The context of the behavior being ticked in this thread, or None outside a tick."""
    return _CURRENT.get()


@contextlib.contextmanager
def using_context(context: BehaviorContext) -> Iterator[BehaviorContext]:
    """Make ``context`` the current one for the ``with`` block (e.g. while constructing states)."""
    token = _CURRENT.set(context)
    try:
        yield context
    finally:
        _CURRENT.reset(token)


def _hook_error(kind: str, hook: object, err: Exception) -> BehaviorRuntimeError:
    name = getattr(hook, "__qualname__", None) or repr(hook)
    return BehaviorRuntimeError(f"{kind} hook {name} raised {type(err).__name__}: {err}")


class BehaviorContext:
    """Autonomy, preemption, hooks, clock, proxies and bookkeeping of one behavior."""

    def __init__(
        self,
        name: str = "behavior",
        *,
        autonomy: object = Autonomy.FULL,
        supervised: bool = True,
        clock: Optional[Clock] = None,
        proxies: Any = None,
        logger: Optional[logging.Logger] = None,
    ) -> None:
        self.name = name
        self.clock: Clock = clock if clock is not None else MonotonicClock()
        self.proxies = proxies
        self.hooks = Hooks()
        self.logger = logger if logger is not None else logging.getLogger(f"flex_nav.behavior.{name}")
        self._autonomy = int(Autonomy.parse(autonomy))
        self._gate = bool(supervised)  # enforce autonomy levels (False: every transition fires)
        self._preempt_requested = False
        self._priority: List[Container] = []  # stack of active priority containers, innermost last
        self._held: List[State] = []  # leaves held by a priority container
        self._requests: Dict[str, State] = {}  # path -> state whose outcome waits for the operator
        self._request_held: List[State] = []  # leaves held (HOLD_REQUEST) while an outcome waits
        self._lock_count = 0  # number of locked nodes (0: skip lock checks on the hot path)
        self._changed = False  # the active set changed during this tick
        self._root: Optional[State] = None
        self._finished = False

    # --- what states read ----------------------------------------------------------------------
    @property
    def autonomy(self) -> Autonomy:
        return Autonomy(self._autonomy)

    @property
    def supervised(self) -> bool:
        """True if transitions wait for the operator when their level is not below the autonomy."""
        return self._gate

    @property
    def preempt_requested(self) -> bool:
        return self._preempt_requested

    @property
    def root(self) -> Optional[State]:
        return self._root

    def now(self) -> float:
        """Current time [s] on this behavior's clock."""
        return self.clock.now()

    def require_proxies(self) -> Any:
        """The injected proxies, or NotReadyError if the runner injected none."""
        if self.proxies is None:
            raise NotReadyError(f"behavior {self.name!r} has no proxies: its runner did not inject any")
        return self.proxies

    def log(self, level: LogLevel, message: str, path: str = "") -> None:
        """Log for the operator (log hooks) and to the Python logger.

        Called from a state this runs in the executor's thread; called from another thread (e.g. a
        proxy callback) the log hooks run in that thread.
        """
        self.logger.log(_PY_LEVELS.get(level, logging.INFO), "%s%s", f"[{path}] " if path else "", message)
        if self.hooks.log:
            event = LogEvent(self.clock.now(), LogLevel(level), message, path)
            for hook in self.hooks.log:
                try:
                    hook(event)
                except Exception as err:
                    raise _hook_error("log", hook, err) from err

    # --- engine side (called by containers and the executor, in the executor's thread) ----------
    def _emit_transition(  # noqa: PLR0917  (internal, hot path: no kwargs packing)
        self, now: float, path: str, outcome: str, target: str, target_path: str, required: int, forced: bool
    ) -> None:
        event = TransitionEvent(now, path, outcome, target, target_path, Autonomy(required), forced)
        for hook in self.hooks.transition:
            try:
                hook(event)
            except Exception as err:
                raise _hook_error("transition", hook, err) from err

    def _emit_request(  # noqa: PLR0917  (internal)
        self, now: float, path: str, outcome: str, required: int, reason: PendingReason, pending: bool
    ) -> None:
        """An outcome waits for the operator (``pending``) or stopped waiting; ``reason.value`` is sent."""
        if self.hooks.request:
            event = RequestEvent(now, path, outcome, Autonomy(required), reason.value, pending)
            for hook in self.hooks.request:
                try:
                    hook(event)
                except Exception as err:
                    raise _hook_error("request", hook, err) from err

    def _emit_active(self, now: float, paths: tuple[str, ...]) -> None:
        event = ActiveStatesEvent(now, paths)
        for hook in self.hooks.active:
            try:
                hook(event)
            except Exception as err:
                raise _hook_error("active", hook, err) from err

    def _claim_priority(self, owner: Container) -> None:
        """``owner`` (a priority container) became active: hold every active leaf outside it."""
        self._priority.append(owner)
        if self._root is None:
            return
        for leaf in list(self._root._active_leaves()):
            if owner not in leaf._ancestors:
                self._hold_leaf(leaf, HOLD_PRIORITY)

    def _release_priority(self, owner: Container, now: float) -> None:
        """``owner`` left: give the held leaves back unless another priority container still excludes them."""
        if owner in self._priority:
            self._priority.remove(owner)
        inner = self._priority[-1] if self._priority else None
        still: List[State] = []
        for leaf in self._held:
            if not leaf._active:
                continue
            if inner is not None and inner not in leaf._ancestors:
                still.append(leaf)
                continue
            self._release_leaf(leaf, HOLD_PRIORITY, now)
        self._held = still

    def _sync_request_hold(self, now: float) -> None:
        """While any outcome waits for the operator, hold every active leaf (on_pause: motion states stop,
        action states cancel their goals) — a monitor's outcome held for approval must not leave the
        controller beside it driving, nor a motion state its last command. Released (on_resume) when no
        outcome waits any more; leaves that were left meanwhile are simply dropped."""
        if self._requests:
            if self._root is not None:
                for leaf in list(self._root._active_leaves()):
                    if not leaf._hold_mask & HOLD_REQUEST:
                        self._hold_leaf(leaf, HOLD_REQUEST)
                        self._request_held.append(leaf)
            return
        held, self._request_held = self._request_held, []
        for leaf in held:
            if leaf._active:
                self._release_leaf(leaf, HOLD_REQUEST, now)

    def _outside_priority(self, leaf: State) -> bool:
        return bool(self._priority) and self._priority[-1] not in leaf._ancestors

    def _hold_leaf(self, leaf: State, reason: int) -> None:
        if leaf._hold_mask & reason:
            return
        first = leaf._hold_mask == 0
        leaf._hold_mask |= reason
        leaf._due = float("inf")
        if reason == HOLD_PRIORITY:
            self._held.append(leaf)
        if first and leaf._entered:
            leaf._call_pause()

    def _release_leaf(self, leaf: State, reason: int, now: float) -> None:
        if not leaf._hold_mask & reason:
            return
        leaf._hold_mask &= ~reason
        if leaf._hold_mask:
            return
        if leaf._entered:
            leaf._call_resume()
        leaf._wake(now)
