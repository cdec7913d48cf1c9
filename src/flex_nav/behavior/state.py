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

The engine's bookkeeping of a state (its place in the behavior, whether it is active, when it is
due, a pending outcome, ...) is kept in ONE record, :class:`StateRuntime`, held in the one attribute
``__flex_nav_runtime__``. A subclass owns every other name: ``self._path``, ``self._active``,
``self._pending``, ``self._tick()`` or ``self._abort()`` are its own and the engine never reads them.
The engine modules (state, containers, context, executor) talk to a state through that record's
documented fields and methods, nothing else.
"""

from __future__ import annotations

import copy
import enum
import math
from typing import TYPE_CHECKING, Any, Dict, FrozenSet, Iterable, Iterator, NamedTuple, Optional, Sequence, Tuple

from flex_nav.behavior.context import HOLD_PRIORITY
from flex_nav.behavior.events import LogLevel
from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import BehaviorConstructionError, BehaviorError, BehaviorRuntimeError, ConfigError

if TYPE_CHECKING:
    from flex_nav.behavior.container import Container, ContainerRuntime
    from flex_nav.behavior.context import BehaviorContext, ContextRuntime

DEFAULT_RATE_HZ = 10.0  # [Hz] FlexBE's default execution rate of a state
# [s] a tick due this little after the clock's time counts as due now: a clock's stamp is not an exact float sum of
# periods (1.1 + 0.1 > 1.2), and a tick found not quite due would wait for the next clock step (a simulated clock's,
# or a lockstep simulation's) and every later tick would come that much later
DUE_SLACK_S = 1e-6


class PendingReason(enum.Enum):
    """Why an outcome has not fired yet. ``.value`` is what operators see (events, ROS messages)."""

    AUTONOMY = "autonomy"  # the state's outcome needs more autonomy: it waits for approval or a higher level
    LOCK = "lock"  # the transition would leave a locked state or container: it waits for an unlock
    FORCED = "forced"  # the operator forced this outcome: it fires at the next tick, unless a lock holds it


class Route(NamedTuple):
    """What happens when a child returns one outcome: precomputed by its container when attached."""

    next_state: Optional[StateRuntime]  # the state entered next; None when the transition leaves the container
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


class StateRuntime:
    """The engine's record of one state: everything the engine keeps about it, in one place.

    Held as ``state.__flex_nav_runtime__``; a state's own code never touches it. The engine modules
    read and write these fields and call these methods; this is their interface to a state (a
    container's record, :class:`~flex_nav.behavior.container.ContainerRuntime`, drives its children).

    Declaration (from the constructor): ``outcomes``, ``input_keys``, ``output_keys`` (tuples in
    declaration order), ``period_s`` [s] (1 / rate_hz; 0 for every tick).

    Place in the behavior (set when added to a container and attached): ``label`` (in its container),
    ``path`` (``/A/B``), ``parent`` (the container's record), ``ctx`` (the behavior's
    :class:`~flex_nav.behavior.context.ContextRuntime`), ``ancestors`` (records of the containers
    above), ``routes`` (outcome -> :class:`Route`, set by the parent), ``ud`` (its userdata view, set by
    the parent), ``locked`` (by the operator).

    Run state: ``active``; ``entering`` (on_enter is due at the next tick); ``entered`` (on_enter was
    called, on_exit not yet); ``due`` [s] (next tick; inf: nothing to do until woken); ``next_s`` [s]
    (earliest next execute: the rate limit, kept across re-entries); ``pending`` (a :class:`Pending`
    outcome); ``hold_mask`` (``context.HOLD_*`` bits: why it is held still); ``calls_enter`` /
    ``calls_exit`` (the state overrides on_enter / on_exit).
    """

    __slots__ = (
        "active",
        "ancestors",
        "calls_enter",
        "calls_exit",
        "ctx",
        "due",
        "entered",
        "entering",
        "hold_mask",
        "input_keys",
        "label",
        "locked",
        "next_s",
        "outcomes",
        "output_keys",
        "parent",
        "path",
        "pending",
        "period_s",
        "routes",
        "state",
        "ud",
    )

    def __init__(
        self,
        state: State,
        outcomes: Tuple[str, ...],
        input_keys: Tuple[str, ...],
        output_keys: Tuple[str, ...],
        period_s: float = 0.0,
    ) -> None:
        self.state = state  # the user's object: its hooks are called from here
        self.outcomes = outcomes
        self.input_keys = input_keys
        self.output_keys = output_keys
        self.period_s = period_s
        self.label = ""
        self.path = ""
        self.parent: Optional[ContainerRuntime] = None
        self.ctx: Optional[ContextRuntime] = None
        self.ancestors: FrozenSet[StateRuntime] = frozenset()
        self.routes: Dict[str, Route] = {}
        self.ud: UserDataView = None  # type: ignore[assignment]  # set by the parent before attach
        self.locked = False
        self.active = False
        self.entering = False
        self.entered = False
        self.due = math.inf
        self.next_s = -math.inf
        self.pending: Optional[Pending] = None
        self.hold_mask = 0
        self.calls_enter = True
        self.calls_exit = True

    # --- the engine's calls (a container's record overrides those marked *) --------------------------
    def attach(self, ctx: ContextRuntime, path: str, ancestors: FrozenSet[StateRuntime]) -> None:
        """* Bind to a behavior (recursive in containers). The parent set ``ud`` and ``routes`` before."""
        owner = self.ctx
        if owner is not None and owner is not ctx and not owner.finished:
            raise BehaviorConstructionError(
                f"state {self.path!r} ({type(self.state).__name__}) already belongs to running behavior "
                f"{owner.context.name!r}; build a new state instance for each behavior",
                field="state",
            )
        self.ctx = ctx
        self.path = path
        self.ancestors = ancestors
        self.locked = False
        self.reset()
        state = self.state
        cls = type(state)
        self.calls_enter = cls.on_enter is not State.on_enter or "on_enter" in state.__dict__
        self.calls_exit = cls.on_exit is not State.on_exit or "on_exit" in state.__dict__

    def reset(self) -> None:
        """Forget the run state of an earlier behavior."""
        self.next_s = -math.inf
        self.active = False
        self.entering = False
        self.entered = False
        self.due = math.inf
        self.pending = None
        self.hold_mask = 0

    def walk(self) -> Iterator[StateRuntime]:
        """* This state and everything below it, depth first, parents before children."""
        yield self

    def active_leaves(self) -> Iterator[StateRuntime]:
        """* The active states that are not containers, at and below this one."""
        if self.active:
            yield self

    def active_paths(self) -> Iterator[str]:
        """* Paths of the deepest active states (a container whose outcome waits counts itself)."""
        if self.active:
            yield self.path

    def activate(self, now: float) -> None:
        """* Become active: on_enter and the first execute happen at the next tick."""
        self.active = True
        self.entering = True
        # a state never executes faster than its rate, even when it is re-entered at once (loops)
        self.due = now if self.next_s <= now + DUE_SLACK_S else self.next_s
        ctx = self.ctx
        if ctx is not None and ctx.priority and ctx.outside_priority(self):
            ctx.hold_leaf(self, HOLD_PRIORITY)

    def tick(self, now: float) -> Optional[str]:
        """* Run one step (the caller checked that it is due and not pending); return the outcome or None."""
        state = self.state
        phase = "execute"
        try:
            if self.entering:
                self.entering = False
                self.entered = True
                if self.calls_enter:
                    phase = "on_enter"
                    state.on_enter(self.ud)
                    phase = "execute"
            outcome = state.execute(self.ud)
        except BehaviorError:
            raise
        except Exception as err:
            raise BehaviorRuntimeError(
                f"state {self.path!r} ({type(state).__name__}) raised {type(err).__name__} in {phase}: {err}"
            ) from err
        self.next_s = now + self.period_s
        if outcome is None:
            self.due = self.next_s
        return outcome

    def leave(self) -> None:
        """* Normal exit after one of its outcomes fired: on_exit (if entered)."""
        self.active = False
        self.due = math.inf
        if self.pending is not None:
            self.drop_pending()
        if self.hold_mask:
            self.hold_mask = 0
        if self.entered:
            self.entered = False
            if self.calls_exit:
                self.user_call("on_exit", self.state.on_exit, self.ud)

    def abort(self) -> None:
        """* Exit without an outcome (preempt, forced transition, end of a concurrency, failure)."""
        self.leave()

    def drop_pending(self) -> None:
        """Forget the pending outcome; withdraw it from the operator if it was announced."""
        pending = self.pending
        self.pending = None
        ctx = self.ctx
        if ctx is None or pending is None:
            return
        ctx.requests.pop(self.path, None)
        if pending.announced is not None:
            ctx.emit_request(ctx.now(), self.path, pending.outcome, pending.required, pending.announced, False)

    def wake(self, now: float) -> None:
        """Make this state due now, and every container above it."""
        self.due = now
        node = self.parent
        while node is not None:
            node.due = min(node.due, now)
            node = node.parent

    def call_pause(self) -> None:
        self.user_call("on_pause", self.state.on_pause)

    def call_resume(self) -> None:
        self.user_call("on_resume", self.state.on_resume, self.ud)

    def user_call(self, what: str, fn: Any, *args: Any) -> None:
        """Call a hook of the state; an error other than a BehaviorError is wrapped with the state's path."""
        try:
            fn(*args)
        except BehaviorError:
            raise
        except Exception as err:
            raise BehaviorRuntimeError(
                f"state {self.path!r} ({type(self.state).__name__}) raised {type(err).__name__} in {what}: {err}"
            ) from err

    def copy_for(self, state: State) -> StateRuntime:
        """This record, copied for ``state``, a shallow copy of this record's state."""
        twin = copy.copy(self)
        twin.state = state
        return twin

    def __repr__(self) -> str:
        return f"<runtime of {self.state!r}>"


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
        declared = _names("outcomes", outcomes, owner)
        if not declared:
            raise ConfigError(f"{owner}: a state needs at least one outcome")
        self.__flex_nav_runtime__: StateRuntime = StateRuntime(
            self, declared, _names("input_keys", input_keys, owner), _names("output_keys", output_keys, owner)
        )
        self.rate_hz = rate_hz

    # --- declaration ----------------------------------------------------------------------------
    @property
    def outcomes(self) -> Tuple[str, ...]:
        """Registered outcomes, in declaration order."""
        return self.__flex_nav_runtime__.outcomes

    @property
    def input_keys(self) -> Tuple[str, ...]:
        return self.__flex_nav_runtime__.input_keys

    @property
    def output_keys(self) -> Tuple[str, ...]:
        return self.__flex_nav_runtime__.output_keys

    @property
    def rate_hz(self) -> float:
        """[Hz] how often ``execute`` is called while the state is active."""
        period_s = self.__flex_nav_runtime__.period_s
        return 1.0 / period_s if period_s > 0.0 else math.inf

    @rate_hz.setter
    def rate_hz(self, value: float) -> None:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not value > 0.0:
            raise ConfigError(f"{type(self).__name__}: rate_hz must be a number > 0 [Hz], got {value!r}")
        self.__flex_nav_runtime__.period_s = 0.0 if math.isinf(value) else 1.0 / float(value)

    # --- place in the behavior -------------------------------------------------------------------
    @property
    def name(self) -> str:
        """The label of this state in its container ("" before it is added)."""
        return self.__flex_nav_runtime__.label

    @property
    def path(self) -> str:
        """``/Label/Inner`` path in the running behavior ("/" for the root, "" before attach)."""
        return self.__flex_nav_runtime__.path

    @property
    def parent(self) -> Optional[Container]:
        parent = self.__flex_nav_runtime__.parent
        return parent.container if parent is not None else None

    @property
    def context(self) -> BehaviorContext:
        """The behavior this state runs in (raises before the behavior is attached)."""
        rt = self.__flex_nav_runtime__
        if rt.ctx is None:
            raise BehaviorRuntimeError(
                f"{type(self).__name__} {rt.label or '(unnamed)'} is not attached to a running behavior yet: "
                "use self.context from on_start() on, not in the constructor"
            )
        return rt.ctx.context

    @property
    def is_active(self) -> bool:
        return self.__flex_nav_runtime__.active

    @property
    def preempt_requested(self) -> bool:
        ctx = self.__flex_nav_runtime__.ctx
        return ctx is not None and ctx.preempt_requested

    def now_s(self) -> float:
        """[s] current time on the behavior's clock."""
        return self.context.clock.now()

    # --- logging for the operator ----------------------------------------------------------------
    def log(self, level: LogLevel, message: str) -> None:
        self.context.log(level, message, self.__flex_nav_runtime__.path)

    def log_info(self, message: str) -> None:
        self.context.log(LogLevel.INFO, message, self.__flex_nav_runtime__.path)

    def log_warn(self, message: str) -> None:
        self.context.log(LogLevel.WARN, message, self.__flex_nav_runtime__.path)

    def log_hint(self, message: str) -> None:
        self.context.log(LogLevel.HINT, message, self.__flex_nav_runtime__.path)

    def log_error(self, message: str) -> None:
        self.context.log(LogLevel.ERROR, message, self.__flex_nav_runtime__.path)

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

    def __copy__(self) -> State:
        """A shallow copy with its own engine record (as when the bookkeeping was plain attributes), so the
        copy can be added to a container of its own."""
        cls = type(self)
        twin = cls.__new__(cls)
        twin.__dict__.update(self.__dict__)
        twin.__flex_nav_runtime__ = self.__flex_nav_runtime__.copy_for(twin)
        return twin

    def __repr__(self) -> str:
        rt = self.__flex_nav_runtime__
        where = rt.path or rt.label or "unattached"
        return f"<{type(self).__name__} {where}>"
