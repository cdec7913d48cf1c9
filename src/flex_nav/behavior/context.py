"""The per-behavior context: everything that belongs to one running behavior and to nothing else.

FlexBE keeps autonomy, preemption, the active priority container and the ROS proxies in class
attributes, so one process can run one behavior. Here each behavior gets one
:class:`BehaviorContext`; states reach it as ``self.context``. Two behaviors (two robots) in one
process have two contexts and never see each other's autonomy, preemption, pauses, hooks or proxies.

What is injected: the name, the clock (:mod:`flex_nav.behavior.clock`), the proxies (a
:class:`~flex_nav.behavior.proxies.Proxies`: the ROS adapter passes its per-behavior proxy set, pure tests
:class:`flex_nav.testing.fake_proxies.FakeProxies` or None) and a Python logger. What it carries: the current
autonomy, whether autonomy is enforced (``supervised``), the preemption flag, the event
:class:`~flex_nav.behavior.events.Hooks`, and the engine's bookkeeping (outcome requests, locks, priority
containers) in one record, :class:`ContextRuntime`, held as ``context.__flex_nav_runtime__`` like a state's
:class:`~flex_nav.behavior.state.StateRuntime`. The engine (executor and containers) is the only writer
of the mutable parts, from the executor's thread; operator commands reach it through the executor.

:func:`current_context` returns the context whose states are being run by the executor in this
thread (a ``contextvars`` variable, set around each tick): compatibility layers use it to route
FlexBE's static ``Logger`` calls or proxy constructors to the right behavior.
"""

from __future__ import annotations

import contextlib
import contextvars
import logging
from typing import TYPE_CHECKING, Dict, Iterator, List, Optional

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
from flex_nav.behavior.proxies import Proxies
from flex_nav.exceptions import BehaviorRuntimeError, NotReadyError

if TYPE_CHECKING:
    from flex_nav.behavior.container import ContainerRuntime
    from flex_nav.behavior.state import PendingReason, State, StateRuntime

_PY_LEVELS = {
    LogLevel.INFO: logging.INFO,
    LogLevel.WARN: logging.WARNING,
    LogLevel.HINT: logging.INFO,
    LogLevel.ERROR: logging.ERROR,
    LogLevel.DEBUG: logging.DEBUG,
}

# Why a leaf is not being executed (bit mask on StateRuntime.hold_mask).
HOLD_PAUSE = 1  # the operator paused the behavior
HOLD_PRIORITY = 2  # a priority container outside this state is active
HOLD_REQUEST = 4  # an outcome waits for the operator: everything holds still until none does

# The context being ticked in this thread: the executor sets it around each tick (and on_start, commands).
CURRENT_CONTEXT: contextvars.ContextVar[Optional[BehaviorContext]] = contextvars.ContextVar(
    "flex_nav_behavior_context", default=None
)


def current_context() -> Optional[BehaviorContext]:
    """The context of the behavior being ticked in this thread, or None outside a tick."""
    return CURRENT_CONTEXT.get()


@contextlib.contextmanager
def using_context(context: BehaviorContext) -> Iterator[BehaviorContext]:
    """Make ``context`` the current one for the ``with`` block (e.g. while constructing states)."""
    token = CURRENT_CONTEXT.set(context)
    try:
        yield context
    finally:
        CURRENT_CONTEXT.reset(token)


def hook_error(kind: str, hook: object, err: Exception) -> BehaviorRuntimeError:
    """The error that fails the behavior when one of its hooks raised ``err``."""
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
        proxies: Optional[Proxies] = None,
        logger: Optional[logging.Logger] = None,
    ) -> None:
        self.name = name
        self.clock: Clock = clock if clock is not None else MonotonicClock()
        self.proxies: Optional[Proxies] = proxies
        self.hooks = Hooks()
        self.logger = logger if logger is not None else logging.getLogger(f"flex_nav.behavior.{name}")
        self.__flex_nav_runtime__ = ContextRuntime(self, int(Autonomy.parse(autonomy)), bool(supervised))

    # --- what states read ----------------------------------------------------------------------
    @property
    def autonomy(self) -> Autonomy:
        return Autonomy(self.__flex_nav_runtime__.autonomy)

    @property
    def supervised(self) -> bool:
        """True if transitions wait for the operator when their level is not below the autonomy."""
        return self.__flex_nav_runtime__.gate

    @property
    def preempt_requested(self) -> bool:
        return self.__flex_nav_runtime__.preempt_requested

    @property
    def root(self) -> Optional[State]:
        root = self.__flex_nav_runtime__.root
        return root.state if root is not None else None

    def now(self) -> float:
        """Current time [s] on this behavior's clock."""
        return self.clock.now()

    def require_proxies(self) -> Proxies:
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
                    raise hook_error("log", hook, err) from err


class ContextRuntime:
    """The engine's bookkeeping of one behavior: held as ``context.__flex_nav_runtime__``.

    Written by the engine only (executor and containers, in the executor's thread). Fields:
    ``context`` (the public :class:`BehaviorContext`), ``autonomy`` (the current level, an int),
    ``gate`` (enforce autonomy levels; False: every transition fires), ``preempt_requested``,
    ``priority`` (records of the active priority containers, innermost last), ``held`` (leaves held by
    a priority container), ``requests`` (path -> record of a state whose outcome waits for the
    operator), ``request_held`` (leaves held while an outcome waits), ``lock_count`` (locked nodes; 0:
    the hot path skips lock checks), ``changed`` (the active set changed during this tick), ``root``
    (the root state's record), ``finished`` (the behavior ended: its states may join another one).
    """

    __slots__ = (
        "autonomy",
        "changed",
        "context",
        "finished",
        "gate",
        "held",
        "lock_count",
        "preempt_requested",
        "priority",
        "request_held",
        "requests",
        "root",
    )

    def __init__(self, context: BehaviorContext, autonomy: int, gate: bool) -> None:
        self.context = context
        self.autonomy = autonomy
        self.gate = gate
        self.preempt_requested = False
        self.priority: List[ContainerRuntime] = []
        self.held: List[StateRuntime] = []
        self.requests: Dict[str, StateRuntime] = {}
        self.request_held: List[StateRuntime] = []
        self.lock_count = 0
        self.changed = False
        self.root: Optional[StateRuntime] = None
        self.finished = False

    def now(self) -> float:
        """[s] current time on the behavior's clock."""
        return self.context.clock.now()

    # --- events -----------------------------------------------------------------------------------
    def emit_transition(  # noqa: PLR0917  (hot path: no kwargs packing)
        self, now: float, path: str, outcome: str, target: str, target_path: str, required: int, forced: bool
    ) -> None:
        event = TransitionEvent(now, path, outcome, target, target_path, Autonomy(required), forced)
        for hook in self.context.hooks.transition:
            try:
                hook(event)
            except Exception as err:
                raise hook_error("transition", hook, err) from err

    def emit_request(  # noqa: PLR0917
        self, now: float, path: str, outcome: str, required: int, reason: PendingReason, pending: bool
    ) -> None:
        """An outcome waits for the operator (``pending``) or stopped waiting; ``reason.value`` is sent."""
        hooks = self.context.hooks
        if hooks.request:
            event = RequestEvent(now, path, outcome, Autonomy(required), reason.value, pending)
            for hook in hooks.request:
                try:
                    hook(event)
                except Exception as err:
                    raise hook_error("request", hook, err) from err

    def emit_active(self, now: float, paths: tuple[str, ...]) -> None:
        event = ActiveStatesEvent(now, paths)
        for hook in self.context.hooks.active:
            try:
                hook(event)
            except Exception as err:
                raise hook_error("active", hook, err) from err

    # --- holding leaves still ---------------------------------------------------------------------
    def claim_priority(self, owner: ContainerRuntime) -> None:
        """``owner`` (a priority container) became active: hold every active leaf outside it."""
        self.priority.append(owner)
        if self.root is None:
            return
        for leaf in list(self.root.active_leaves()):
            if owner not in leaf.ancestors:
                self.hold_leaf(leaf, HOLD_PRIORITY)

    def release_priority(self, owner: ContainerRuntime, now: float) -> None:
        """``owner`` left: give the held leaves back unless another priority container still excludes them."""
        if owner in self.priority:
            self.priority.remove(owner)
        inner = self.priority[-1] if self.priority else None
        still: List[StateRuntime] = []
        for leaf in self.held:
            if not leaf.active:
                continue
            if inner is not None and inner not in leaf.ancestors:
                still.append(leaf)
                continue
            self.release_leaf(leaf, HOLD_PRIORITY, now)
        self.held = still

    def sync_request_hold(self, now: float) -> None:
        """While any outcome waits for the operator, hold every active leaf (on_pause: motion states stop,
        action states cancel their goals) — a monitor's outcome held for approval must not leave the
        controller beside it driving, nor a motion state its last command. Released (on_resume) when no
        outcome waits any more; leaves that were left meanwhile are simply dropped."""
        if self.requests:
            if self.root is not None:
                for leaf in list(self.root.active_leaves()):
                    if not leaf.hold_mask & HOLD_REQUEST:
                        self.hold_leaf(leaf, HOLD_REQUEST)
                        self.request_held.append(leaf)
            return
        held, self.request_held = self.request_held, []
        for leaf in held:
            if leaf.active:
                self.release_leaf(leaf, HOLD_REQUEST, now)

    def outside_priority(self, leaf: StateRuntime) -> bool:
        """An active priority container does not contain ``leaf``."""
        return bool(self.priority) and self.priority[-1] not in leaf.ancestors

    def hold_leaf(self, leaf: StateRuntime, reason: int) -> None:
        """Stop executing ``leaf`` for ``reason`` (a HOLD_* bit); on_pause when it is the first one."""
        if leaf.hold_mask & reason:
            return
        first = leaf.hold_mask == 0
        leaf.hold_mask |= reason
        leaf.due = float("inf")
        if reason == HOLD_PRIORITY:
            self.held.append(leaf)
        if first and leaf.entered:
            leaf.call_pause()

    def release_leaf(self, leaf: StateRuntime, reason: int, now: float) -> None:
        """Drop ``reason``; on_resume and due now when no reason is left."""
        if not leaf.hold_mask & reason:
            return
        leaf.hold_mask &= ~reason
        if leaf.hold_mask:
            return
        if leaf.entered:
            leaf.call_resume()
        leaf.wake(now)
