"""The State base class: FlexBE's lifecycle and semantics, with no ROS and no class-level state.

Write a state by subclassing :class:`State`::

    class Wait(State):
        '''Waits for a time.

        -- wait_time_s  float  [s] how long to wait.

        <= done  The time has passed.
        '''

        def __init__(self, wait_time_s: float) -> None:
            super().__init__(outcomes=["done"])
            self._wait_time_s = wait_time_s
            self._end_s = 0.0

        def on_enter(self, userdata: UserDataView) -> None:
            self._end_s = self.now_s() + self._wait_time_s

        def execute(self, userdata: UserDataView) -> str | None:
            return "done" if self.now_s() >= self._end_s else None

Lifecycle (who calls what, and when):

- ``__init__(params...)``: configuration only (parameters are constructor arguments). No I/O: a
  behavior must be loadable, validated and drawable offline.
- ``on_start()``: once when the behavior starts, for every state (active or not): set up middleware
  through ``self.context.proxies``.
- ``on_enter(userdata)``: each time the state becomes active, right before its first ``execute``.
- ``execute(userdata)``: called at the state's rate (``rate_hz``, default 10 Hz) while it is active;
  returns one of its outcomes to finish, or ``None`` to keep running. It must never block.
- ``on_exit(userdata)``: once after each ``on_enter``, when the state is left: by its own outcome,
  a forced transition, a preemption, the end of its concurrency container, or a failure elsewhere.
  This is where a state stops what it started (cancel a goal, stop the robot).
- ``on_pause()`` / ``on_resume(userdata)``: the operator paused the behavior, a priority container
  outside this state became active (and later left), or an outcome anywhere in the behavior waits for the
  operator (below). Between them ``execute`` is not called.
- ``on_stop()``: once when the behavior ends (finished, preempted or failed), for every state.

An outcome whose transition needs more autonomy than the behavior has is *requested*: the state
stays active but is not executed again; it leaves (``on_exit``) when the operator approves or forces
an outcome, or when the autonomy is raised. While any outcome waits so (or for an unlock), every active
state is paused (``on_pause``; the requesting one too), so the robot holds still — a bumper monitor's
outcome waiting for approval does not leave the controller beside it driving — and the states resume
(``on_resume``) when none waits. Parameters, keys and outcomes are documented in the class docstring (see
:mod:`flex_nav.behavior.docstring`).

Engine internals (names starting with ``_``) are shared with the containers in this package; a
subclass must not touch them.
"""

from __future__ import annotations

import enum
import math
from typing import TYPE_CHECKING, Any, Dict, FrozenSet, Iterable, Iterator, NamedTuple, Optional, Sequence, Tuple

from flex_nav.behavior.events import LogLevel
from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import BehaviorConstructionError, BehaviorError, BehaviorRuntimeError, ConfigError

if TYPE_CHECKING:
    from flex_nav.behavior.container import Container
    from flex_nav.behavior.context import BehaviorContext

DEFAULT_RATE_HZ = 10.0  # [Hz] FlexBE's default execution rate of a state


class PendingReason(enum.Enum):
    """Why an outcome has not fired yet. ``.value`` is what operators see (events, ROS messages)."""

    AUTONOMY = "autonomy"  # the state's outcome needs more autonomy: it waits for approval or a higher level
    LOCK = "lock"  # the transition would leave a locked state or container: it waits for an unlock
    FORCED = "forced"  # the operator forced this outcome: it fires at the next tick, unless a lock holds it


class Route(NamedTuple):
    """What happens when a child returns one outcome: precomputed by its container when attached."""

    next_state: Optional[State]  # the state entered next; None when the transition leaves the container
    container_outcome: Optional[str]  # the container's outcome when the transition leaves it, else None
    required: int  # the Autonomy level the transition needs (it fires alone only below the current one)
    target: str  # label of the next state, or the container outcome ("" in a concurrency container)
    target_path: str  # path of the next state ("" when the transition leaves the container)


class Pending:
    """An outcome of a state that has not fired yet.

    ``reason``: :attr:`PendingReason.AUTONOMY` or ``LOCK``: the state's own outcome waits for the
    operator or for an unlock. :attr:`PendingReason.FORCED`: the operator chose the outcome; the state
    is exited without finishing (a container does not hand its outputs up) and no autonomy check
    applies, but a lock still holds it.
    ``announced``: what the operator was told the outcome waits for (``AUTONOMY`` or ``LOCK``, sent as a
    ``RequestEvent`` with ``pending=True``), None while nothing is announced. A forced outcome held by a
    lock keeps reason ``FORCED`` and is announced as ``LOCK``.
    ``approved``: the operator let the state's own outcome fire (bypasses the autonomy check, not a lock).
    """

    __slots__ = ("announced", "approved", "outcome", "reason", "required")

    def __init__(self, outcome: str, reason: PendingReason, required: int) -> None:
        self.outcome = outcome
        self.reason = reason
        self.required = required
        self.approved = False
        self.announced: Optional[PendingReason] = None

    def __repr__(self) -> str:
        waits = f", announced as {self.announced.value}" if self.announced is not None else ""
        approved = ", approved" if self.approved else ""
        return f"Pending({self.outcome!r}, {self.reason.value}, required={self.required}{approved}{waits})"


def _names(what: str, values: Iterable[str], owner: str) -> Tuple[str, ...]:
    if isinstance(values, str):
        raise ConfigError(f"{owner}: {what} must be a list of names, not the string {values!r}")
    names = tuple(values)
    for name in names:
        if not isinstance(name, str) or not name:
            raise ConfigError(f"{owner}: {what} must be non-empty strings, got {name!r}")
    if len(set(names)) != len(names):
        dupes = sorted({n for n in names if names.count(n) > 1})
        raise ConfigError(f"{owner}: {what} repeat {', '.join(dupes)}")
    return names


class State:
    """A leaf state (and the base of every container). See the module docstring for the lifecycle."""

    def __init__(
        self,
        outcomes: Sequence[str],
        input_keys: Sequence[str] = (),
        output_keys: Sequence[str] = (),
        rate_hz: float = DEFAULT_RATE_HZ,
    ) -> None:
        owner = type(self).__name__
        self._outcomes: Tuple[str, ...] = _names("outcomes", outcomes, owner)
        if not self._outcomes:
            raise ConfigError(f"{owner}: a state needs at least one outcome")
        self._input_keys: Tuple[str, ...] = _names("input_keys", input_keys, owner)
        self._output_keys: Tuple[str, ...] = _names("output_keys", output_keys, owner)
        self._period_s = 0.0
        self.rate_hz = rate_hz
        # structure (set when added to a container / attached to a behavior)
        self._label = ""
        self._path = ""
        self._parent: Optional[Container] = None
        self._ctx: Optional[BehaviorContext] = None
        self._ancestors: FrozenSet[State] = frozenset()
        self._routes: Dict[str, Route] = {}
        self._ud: UserDataView = None  # type: ignore[assignment]  # set by attach
        self._locked = False
        # run state
        self._active = False
        self._entering = False  # on_enter is due at the next tick
        self._entered = False  # on_enter was called, on_exit not yet
        self._due = math.inf  # [s] next tick time; inf: nothing to do until woken
        self._next_s = -math.inf  # [s] earliest next execute (rate limit, kept across re-entries)
        self._pending: Optional[Pending] = None
        self._hold_mask = 0  # context.HOLD_* bits: paused by the operator / held by a priority container
        self._calls_enter = True
        self._calls_exit = True

    # --- declaration ----------------------------------------------------------------------------
    @property
    def outcomes(self) -> Tuple[str, ...]:
        """Registered outcomes, in declaration order."""
        return self._outcomes

    @property
    def input_keys(self) -> Tuple[str, ...]:
        return self._input_keys

    @property
    def output_keys(self) -> Tuple[str, ...]:
        return self._output_keys

    @property
    def rate_hz(self) -> float:
        """[Hz] how often ``execute`` is called while the state is active."""
        return 1.0 / self._period_s if self._period_s > 0.0 else math.inf

    @rate_hz.setter
    def rate_hz(self, value: float) -> None:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not value > 0.0:
            raise ConfigError(f"{type(self).__name__}: rate_hz must be a number > 0 [Hz], got {value!r}")
        self._period_s = 0.0 if math.isinf(value) else 1.0 / float(value)

    # --- place in the behavior -------------------------------------------------------------------
    @property
    def name(self) -> str:
        """The label of this state in its container ("" before it is added)."""
        return self._label

    @property
    def path(self) -> str:
        """``/Label/Inner`` path in the running behavior ("/" for the root, "" before attach)."""
        return self._path

    @property
    def parent(self) -> Optional[Container]:
        return self._parent

    @property
    def context(self) -> BehaviorContext:
        """The behavior this state runs in (raises before the behavior is attached)."""
        if self._ctx is None:
            raise BehaviorRuntimeError(
                f"{type(self).__name__} {self._label or '(unnamed)'} is not attached to a running behavior yet: "
                "use self.context from on_start() on, not in the constructor"
            )
        return self._ctx

    @property
    def is_active(self) -> bool:
        return self._active

    @property
    def preempt_requested(self) -> bool:
        return self._ctx is not None and self._ctx._preempt_requested

    def now_s(self) -> float:
        """[s] current time on the behavior's clock."""
        return self.context.clock.now()

    # --- logging for the operator ----------------------------------------------------------------
    def log(self, level: LogLevel, message: str) -> None:
        self.context.log(level, message, self._path)

    def log_info(self, message: str) -> None:
        self.context.log(LogLevel.INFO, message, self._path)

    def log_warn(self, message: str) -> None:
        self.context.log(LogLevel.WARN, message, self._path)

    def log_hint(self, message: str) -> None:
        self.context.log(LogLevel.HINT, message, self._path)

    def log_error(self, message: str) -> None:
        self.context.log(LogLevel.ERROR, message, self._path)

    # --- lifecycle hooks (override) -----------------------------------------------------------------
    def on_start(self) -> None:
        """Called once for every state when the behavior starts."""

    def on_enter(self, userdata: UserDataView) -> None:
        """Called each time the state becomes active, before its first execute."""

    def execute(self, userdata: UserDataView) -> Optional[str]:
        """Return an outcome to finish, or None to keep running. Never block."""
        raise NotImplementedError(f"{type(self).__name__} must implement execute(userdata)")

    def on_exit(self, userdata: UserDataView) -> None:
        """Called once after each on_enter, when the state is left for any reason."""

    def on_pause(self) -> None:
        """The behavior was paused (or a priority container elsewhere became active)."""

    def on_resume(self, userdata: UserDataView) -> None:
        """The pause is over; execute will be called again."""

    def on_stop(self) -> None:
        """Called once for every state when the behavior ends."""

    # --- engine internals ------------------------------------------------------------------------
    def _attach(self, ctx: BehaviorContext, path: str, ancestors: FrozenSet[State]) -> None:
        """Bind to a behavior context (recursive in containers). The parent sets _ud and _routes."""
        owner = self._ctx
        if owner is not None and owner is not ctx and not owner._finished:
            raise BehaviorConstructionError(
                f"state {self._path!r} ({type(self).__name__}) already belongs to running behavior {owner.name!r}; "
                "build a new state instance for each behavior",
                field="state",
            )
        self._ctx = ctx
        self._path = path
        self._ancestors = ancestors
        self._locked = False
        self._reset_run_state()
        cls = type(self)
        self._calls_enter = cls.on_enter is not State.on_enter or "on_enter" in self.__dict__
        self._calls_exit = cls.on_exit is not State.on_exit or "on_exit" in self.__dict__

    def _reset_run_state(self) -> None:
        self._next_s = -math.inf
        self._active = False
        self._entering = False
        self._entered = False
        self._due = math.inf
        self._pending = None
        self._hold_mask = 0

    def _walk(self) -> Iterator[State]:
        """This state and everything below it, depth first, parents before children."""
        yield self

    def _active_leaves(self) -> Iterator[State]:
        if self._active:
            yield self

    def _active_paths(self) -> Iterator[str]:
        if self._active:
            yield self._path

    def _activate(self, now: float) -> None:
        self._active = True
        self._entering = True
        # a state never executes faster than its rate, even when it is re-entered at once (loops)
        self._due = now if self._next_s <= now else self._next_s
        ctx = self._ctx
        if ctx is not None and ctx._priority and ctx._outside_priority(self):
            from flex_nav.behavior.context import HOLD_PRIORITY  # noqa: PLC0415  (cycle; rare path)

            ctx._hold_leaf(self, HOLD_PRIORITY)

    def _tick(self, now: float) -> Optional[str]:
        """Run one step (the caller checked that it is due and not pending); return the outcome or None."""
        phase = "execute"
        try:
            if self._entering:
                self._entering = False
                self._entered = True
                if self._calls_enter:
                    phase = "on_enter"
                    self.on_enter(self._ud)
                    phase = "execute"
            outcome = self.execute(self._ud)
        except BehaviorError:
            raise
        except Exception as err:
            raise BehaviorRuntimeError(
                f"state {self._path!r} ({type(self).__name__}) raised {type(err).__name__} in {phase}: {err}"
            ) from err
        self._next_s = now + self._period_s
        if outcome is None:
            self._due = self._next_s
        return outcome

    def _leave(self) -> None:
        """Normal exit after one of its outcomes fired: on_exit (if entered)."""
        self._active = False
        self._due = math.inf
        if self._pending is not None:
            self._drop_pending()
        if self._hold_mask:
            self._hold_mask = 0
        if self._entered:
            self._entered = False
            if self._calls_exit:
                self._user_call("on_exit", self.on_exit, self._ud)

    def _abort(self) -> None:
        """Exit without an outcome (preempt, forced transition, end of a concurrency, failure)."""
        self._leave()

    def _drop_pending(self) -> None:
        pending = self._pending
        self._pending = None
        ctx = self._ctx
        if ctx is None or pending is None:
            return
        ctx._requests.pop(self._path, None)
        if pending.announced is not None:
            ctx._emit_request(ctx.clock.now(), self._path, pending.outcome, pending.required, pending.announced, False)

    def _wake(self, now: float) -> None:
        """Make this state due now, and every container above it."""
        self._due = now
        node = self._parent
        while node is not None:
            node._due = min(node._due, now)
            node = node._parent

    def _call_pause(self) -> None:
        self._user_call("on_pause", self.on_pause)

    def _call_resume(self) -> None:
        self._user_call("on_resume", self.on_resume, self._ud)

    def _user_call(self, what: str, fn: Any, *args: Any) -> None:
        try:
            fn(*args)
        except BehaviorError:
            raise
        except Exception as err:
            raise BehaviorRuntimeError(
                f"state {self._path!r} ({type(self).__name__}) raised {type(err).__name__} in {what}: {err}"
            ) from err

    def __repr__(self) -> str:
        where = self._path or self._label or "unattached"
        return f"<{type(self).__name__} {where}>"
