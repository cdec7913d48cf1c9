"""BehaviorExecutor: runs one behavior, independent of ROS; thread-safe commands and queries.

::

    executor = BehaviorExecutor(behavior, inputs={"goal": pose}, autonomy=Autonomy.HIGH)
    executor.context.hooks.transition.append(publish_transition)
    result = executor.run(timeout_s=60.0)      # blocks; or spin_once() from your own loop
    if result.status is not BehaviorStatus.FINISHED: ...

Ticking: the executor ticks the root whenever it is due; each active state is due at its own
rate (``rate_hz``), a newly entered state at once (unless it executed less than one period ago).
Between ticks it waits on the injected clock (``Clock.wait_until``), and a command wakes it
immediately. Waits are bounded by ``idle_wait_s``, so a ``should_stop`` check (e.g.
``rospy.is_shutdown``) runs at least that often. One thread drives a behavior (``run`` or
``spin_once``); hooks are called in that thread.

Commands (``set_autonomy``, ``force_transition``, ``approve``, ``pause``, ``resume``, ``preempt``,
``lock``, ``unlock``) may be called from any thread. They are checked at once against the
behavior's structure (an unknown path or outcome raises :class:`BehaviorCommandError` in the caller)
and then applied by the executor's thread between two ticks; each returns a
``concurrent.futures.Future`` that completes when the command was applied (or fails with a
BehaviorCommandError saying why, e.g. the state is not active any more). Queries (``status``,
``result``, ``active_paths``, ``requested_outcomes``, ``autonomy``, ``active_userdata``) are safe from any thread
too.

Failure is loud and safe: an exception in a state, a hook or the engine fails the behavior
(status FAILED, reason naming the state and error), after every active state was exited
(``on_exit``, where states stop the robot) and every state got ``on_stop``.
"""

from __future__ import annotations

import collections
import concurrent.futures
import contextlib
import math
import threading
from typing import Any, Callable, Deque, Dict, Iterator, List, NamedTuple, Optional, Tuple, Union

from flex_nav.behavior.autonomy import Autonomy
from flex_nav.behavior.behavior import Behavior
from flex_nav.behavior.clock import Clock
from flex_nav.behavior.container import Container
from flex_nav.behavior.context import CURRENT_CONTEXT, HOLD_PAUSE, BehaviorContext, hook_error
from flex_nav.behavior.events import BehaviorStatus, CommandEvent, LogLevel, StatusEvent
from flex_nav.behavior.proxies import Proxies
from flex_nav.behavior.state import DUE_SLACK_S, Pending, PendingReason, State, StateRuntime
from flex_nav.behavior.userdata import UserDataView, view_parts
from flex_nav.behavior.userdata_summary import MISSING, StateUserdata
from flex_nav.exceptions import (
    BehaviorCommandError,
    BehaviorError,
    BehaviorRuntimeError,
    ConfigError,
    choices_message,
)

DEFAULT_IDLE_WAIT_S = 0.1  # [s] longest single wait of run(): bounds the should_stop / timeout checks


class BehaviorResult(NamedTuple):
    status: BehaviorStatus
    outcome: Optional[str]  # root outcome (FINISHED), "preempted" (PREEMPTED), None otherwise
    reason: str  # why it ended, human-readable ("" when it finished normally)
    outputs: Dict[str, Any]  # root output keys that have a value
    error: Optional[BaseException]  # the exception that failed it


class OutcomeRequest(NamedTuple):
    path: str
    outcome: str
    required: Autonomy
    reason: str  # what it waits for: PendingReason.AUTONOMY.value ("autonomy") or LOCK.value ("lock")


_Command = Tuple[str, Tuple[str, ...], Callable[[float], str], "concurrent.futures.Future[str]"]


class BehaviorExecutor:
    """Runs one behavior: ticks, supervision commands, status and event hooks."""

    def __init__(
        self,
        behavior: Union[Behavior, State],
        *,
        inputs: Optional[Dict[str, Any]] = None,
        context: Optional[BehaviorContext] = None,
        clock: Optional[Clock] = None,
        autonomy: object = None,
        supervised: Optional[bool] = None,
        proxies: Optional[Proxies] = None,
        should_stop: Optional[Callable[[], bool]] = None,
        idle_wait_s: float = DEFAULT_IDLE_WAIT_S,
    ) -> None:
        if isinstance(behavior, Behavior):
            name, root = behavior.name, behavior.root
        elif isinstance(behavior, State):
            name, root = (behavior.name or "behavior"), behavior
        else:
            raise ConfigError(f"BehaviorExecutor needs a Behavior or a State, got {type(behavior).__name__}")
        if context is None:
            context = BehaviorContext(
                name,
                autonomy=Autonomy.FULL if autonomy is None else autonomy,
                supervised=True if supervised is None else supervised,
                clock=clock,
                proxies=proxies,
            )
        elif clock is not None or autonomy is not None or supervised is not None or proxies is not None:
            raise ConfigError("give either a context or clock/autonomy/supervised/proxies, not both")
        if not idle_wait_s > 0.0:
            raise ConfigError(f"idle_wait_s must be > 0 [s], got {idle_wait_s!r}")
        self._ctx = context
        self._root = root
        self._book = context.__flex_nav_runtime__  # the engine's bookkeeping of this behavior
        self._rt = root.__flex_nav_runtime__  # the root's record
        self._should_stop = should_stop
        self._idle_wait_s = float(idle_wait_s)
        self._lock = threading.RLock()  # held by the executor thread while it ticks or applies commands
        self._driver = threading.Lock()  # held by the one thread in run() / spin_once()
        self._wake = threading.Event()
        self._done = threading.Event()
        self._commands: Deque[_Command] = collections.deque()
        self._status = BehaviorStatus.READY
        self._terminal = False
        self._paused = False
        self._result: Optional[BehaviorResult] = None
        if isinstance(root, Container):
            root.validate()
        # the root reads its inputs from, and writes its outputs to, this store
        self._io: Dict[str, Any] = {}
        for key, value in (inputs or {}).items():
            if key not in root.input_keys:
                raise ConfigError(choices_message(f"behavior {name!r}: input key", key, root.input_keys))
            self._io[key] = value
        defaults = root.userdata_defaults if isinstance(root, Container) else {}
        missing = [k for k in root.input_keys if k not in self._io and k not in defaults]
        if missing:
            raise ConfigError(
                f"behavior {name!r} needs a value for input key(s) {', '.join(missing)} "
                f"(given: {', '.join(self._io) or 'none'})"
            )
        outputs = set(root.output_keys)
        rt = self._rt
        rt.ud = UserDataView(
            self._io,
            {k: (k, k not in outputs) for k in root.input_keys if k in self._io},
            {k: k for k in root.output_keys},
            root,
        )
        rt.routes = {}
        rt.label = rt.label or name
        self._book.root = rt
        self._book.finished = False
        rt.attach(self._book, "/", frozenset())
        self._nodes: Dict[str, StateRuntime] = {node.path: node for node in rt.walk()}

    # --- properties and queries (any thread) --------------------------------------------------------
    @property
    def context(self) -> BehaviorContext:
        return self._ctx

    @property
    def root(self) -> State:
        return self._root

    @property
    def status(self) -> BehaviorStatus:
        return self._status

    @property
    def autonomy(self) -> Autonomy:
        return self._ctx.autonomy

    @property
    def due_s(self) -> float:
        """[s] clock time at which the behavior next needs a tick (inf: none until a command or an event
        wakes a state). For driving it with ``spin_once`` from a manual clock."""
        return self._rt.due

    @property
    def state_paths(self) -> Tuple[str, ...]:
        """Every state path of the behavior (static)."""
        return tuple(self._nodes)

    def result(self) -> BehaviorResult:
        """The final result once ended; before that the current status with no outcome."""
        result = self._result
        if result is not None:
            return result
        return BehaviorResult(self._status, None, "", {}, None)

    def active_paths(self) -> Tuple[str, ...]:
        """Paths of the active states (deepest level; a container whose outcome waits counts itself)."""
        with self._lock:
            if self._terminal or self._status is BehaviorStatus.READY:
                return ()
            return tuple(self._rt.active_paths())

    def requested_outcomes(self) -> List[OutcomeRequest]:
        """Outcomes that wait for the operator (approval, more autonomy, or an unlock)."""
        with self._lock:
            requests = []
            for path, node in self._book.requests.items():
                pending = node.pending
                if pending is not None and pending.announced is not None:
                    waits = pending.announced.value
                    requests.append(OutcomeRequest(path, pending.outcome, Autonomy(pending.required), waits))
            return requests

    def active_userdata(self, timeout_s: float = 0.05) -> Optional[Tuple[StateUserdata, ...]]:
        """Each active state (the deepest ones and the containers above them) with its declared input and output
        keys and the values its container holds for them now: the objects themselves, read under the behavior's
        lock (never copied, so reading is cheap; a value a state changes in place later changes under the caller).
        () when the behavior is not running; None when the executor's thread held the behavior for more than
        ``timeout_s`` [s] (a long tick)."""
        if not self._lock.acquire(timeout=timeout_s):
            return None
        try:
            if self._terminal or self._status is BehaviorStatus.READY:
                return ()
            found: Dict[str, StateUserdata] = {}
            for path in self._rt.active_paths():
                node: Optional[StateRuntime] = self._nodes.get(path)
                while node is not None and node.path not in found:
                    if node.ud is not None:
                        store, read, write = view_parts(node.ud)
                        found[node.path] = StateUserdata(
                            node.path,
                            tuple((key, store.get(store_key, MISSING)) for key, (store_key, _) in read.items()),
                            tuple((key, store.get(store_key, MISSING)) for key, store_key in write.items()),
                        )
                    node = node.parent
            return tuple(found.values())
        finally:
            self._lock.release()

    def wait(self, timeout_s: float) -> bool:
        """Wait (bounded) until the behavior ended; True if it did."""
        return self._done.wait(timeout_s)

    # --- running (the executor's thread) -----------------------------------------------------------------
    def start(self) -> None:
        """on_start for every state, then activate the root. run() and spin_once() call it if needed."""
        with self._lock:
            if self._status is not BehaviorStatus.READY:
                raise BehaviorRuntimeError(f"behavior {self._ctx.name!r} was already started ({self._status.value})")
            token = CURRENT_CONTEXT.set(self._ctx)
            try:
                now = self._ctx.clock.now()
                self._status = BehaviorStatus.RUNNING
                try:
                    for node in self._rt.walk():
                        node.user_call("on_start", node.state.on_start)
                    self._rt.activate(now)
                except Exception as err:
                    self._fail(err, now)
                    return
                self._book.changed = True  # the first tick reports the initial active states
                self._emit_status(now, None, "started")
            finally:
                CURRENT_CONTEXT.reset(token)

    def spin_once(self) -> bool:
        """Apply queued commands and tick the root if it is due now; True if it ticked. Never waits."""
        with self._driving("spin_once"):
            return self._spin_once()

    @contextlib.contextmanager
    def _driving(self, what: str) -> Iterator[None]:
        """One thread at a time drives the behavior (run/spin_once); a second one is an error, not a race."""
        if not self._driver.acquire(blocking=False):
            raise BehaviorRuntimeError(
                f"{what}: behavior {self._ctx.name!r} is already being run by another thread (or from one of its hooks)"
            )
        try:
            yield
        finally:
            self._driver.release()

    def _spin_once(self) -> bool:
        if self._status is BehaviorStatus.READY:
            self.start()
        with self._lock:
            token = CURRENT_CONTEXT.set(self._ctx)
            try:
                if self._commands:
                    self._apply_commands()
                if self._terminal or self._paused:
                    return False
                now = self._ctx.clock.now()
                if self._rt.due > now + DUE_SLACK_S:
                    return False
                self._tick(now)
                return True
            except BaseException as err:
                self._interrupted(err)
                raise
            finally:
                CURRENT_CONTEXT.reset(token)

    def run(self, timeout_s: Optional[float] = None, *, stop_on_timeout: bool = True) -> BehaviorResult:
        """Tick until the behavior ends, or ``timeout_s`` [s] of clock time pass.

        On timeout the behavior is preempted (states exited) unless ``stop_on_timeout`` is False, in
        which case it keeps its state and can be run again.
        """
        with self._driving("run"):
            return self._run(timeout_s, stop_on_timeout)

    def _run(self, timeout_s: Optional[float], stop_on_timeout: bool) -> BehaviorResult:  # noqa: PLR0912, PLR0915
        if self._status is BehaviorStatus.READY:
            self.start()
        ctx = self._ctx
        clock = ctx.clock
        root = self._rt
        wake = self._wake
        lock = self._lock
        commands = self._commands
        should_stop = self._should_stop
        idle_wait_s = self._idle_wait_s
        deadline = math.inf if timeout_s is None else clock.now() + timeout_s
        ticks = 0
        token = CURRENT_CONTEXT.set(ctx)
        try:
            while True:
                if commands:
                    with lock:
                        self._apply_commands()
                if self._terminal:
                    break
                now = clock.now()
                if now >= deadline:
                    if stop_on_timeout:
                        with lock:
                            self._preempt(f"run() timed out after {timeout_s} s", now)
                    break
                if self._paused or root.due > now + DUE_SLACK_S:
                    if should_stop is not None and should_stop():
                        with lock:
                            self._preempt("stopped: shutdown requested", now)
                        break
                    wake.clear()
                    if commands:
                        continue
                    due = math.inf if self._paused else root.due
                    clock.wait_until(min(due, deadline, now + idle_wait_s), wake)
                    continue
                lock.acquire()
                try:
                    self._tick(now)
                finally:
                    lock.release()
                ticks += 1
                if should_stop is not None and not ticks & 255 and should_stop():
                    with lock:
                        self._preempt("stopped: shutdown requested", clock.now())
        except BaseException as err:  # KeyboardInterrupt, SystemExit: stop the states, then let it go
            self._interrupted(err)
            raise
        finally:
            CURRENT_CONTEXT.reset(token)
        return self.result()

    def _interrupted(self, err: BaseException) -> None:
        with self._lock:
            if not self._terminal:
                self._preempt(f"interrupted by {type(err).__name__}", self._ctx.clock.now())

    def _tick(self, now: float) -> None:
        book = self._book
        root = self._rt
        try:
            pending = root.pending
            if pending is not None:  # the root's outcome waits for an unlock
                if root.locked:
                    root.due = math.inf
                    return
                root.drop_pending()
                outcome: Optional[str] = pending.outcome
            else:
                outcome = root.tick(now)
            if outcome is not None:
                self._finish(outcome, now)
            else:
                if book.requests or book.request_held:
                    book.sync_request_hold(now)
                if book.changed and self._ctx.hooks.active:
                    book.changed = False
                    book.emit_active(now, tuple(root.active_paths()))
        except Exception as err:
            self._fail(err, now)

    def _finish(self, outcome: str, now: float) -> None:
        root = self._rt
        if outcome not in root.outcomes:
            raise BehaviorRuntimeError(
                f"root state {root.path!r} returned outcome {outcome!r} which it does not register "
                f"(valid: {', '.join(root.outcomes)})"
            )
        if root.locked:
            pending = Pending(outcome, PendingReason.LOCK, 0)
            pending.announced = PendingReason.LOCK
            root.pending = pending
            root.due = math.inf
            self._book.requests[root.path] = root
            self._book.emit_request(now, root.path, outcome, 0, PendingReason.LOCK, True)
            self._book.sync_request_hold(now)
            return
        root.leave()
        self._end(BehaviorStatus.FINISHED, outcome, "", None, now)

    def _fail(self, err: BaseException, now: float) -> None:
        reason = str(err) if isinstance(err, BehaviorError) else f"{type(err).__name__}: {err}"
        with contextlib.suppress(Exception):  # a failing log hook must not stop the safe shutdown below
            self._ctx.log(LogLevel.ERROR, f"behavior failed: {reason}")
        errors = self._safe_abort()
        if errors:
            reason += "; while exiting states: " + "; ".join(str(e) for e in errors)
        self._end(BehaviorStatus.FAILED, None, reason, err, now)

    def _preempt(self, reason: str, now: float) -> None:
        if self._terminal:
            return
        self._book.preempt_requested = True
        errors = self._safe_abort()
        if errors:
            reason += "; while exiting states: " + "; ".join(str(e) for e in errors)
            self._end(BehaviorStatus.FAILED, None, reason, errors[0], now)
            return
        self._end(BehaviorStatus.PREEMPTED, "preempted", reason, None, now)

    def _safe_abort(self) -> List[BaseException]:
        """Exit every active state; keep going when an on_exit raises (each state exits at most once)."""
        errors: List[BaseException] = []
        for _ in range(len(self._nodes) + 1):
            try:
                self._rt.abort()
                break
            except Exception as err:
                errors.append(err)
        return errors

    def _end(
        self, status: BehaviorStatus, outcome: Optional[str], reason: str, error: Optional[BaseException], now: float
    ) -> None:
        ctx = self._ctx
        for node in self._rt.walk():
            try:
                node.user_call("on_stop", node.state.on_stop)
            except Exception as err:
                reason = f"{reason}; {err}" if reason else str(err)
                with contextlib.suppress(Exception):  # keep stopping the other states
                    ctx.log(LogLevel.ERROR, str(err), node.path)
        outputs = {k: self._io[k] for k in self._root.output_keys if k in self._io}
        self._result = BehaviorResult(status, outcome, reason, outputs, error)
        self._status = status
        self._terminal = True
        self._paused = False
        book = self._book
        book.finished = True
        for node in list(book.requests.values()):
            node.pending = None
        book.requests.clear()
        try:
            self._emit_status(now, outcome, reason)
        except Exception as err:  # the behavior has ended: report the hook's failure, do not re-fail
            ctx.logger.error("status hook of behavior %r raised %s: %s", ctx.name, type(err).__name__, err)
        finally:
            self._done.set()
            self._wake.set()

    def _emit_status(self, now: float, outcome: Optional[str], reason: str) -> None:
        if self._ctx.hooks.status:
            event = StatusEvent(now, self._status, outcome, reason)
            for hook in self._ctx.hooks.status:
                try:
                    hook(event)
                except Exception as err:
                    raise hook_error("status", hook, err) from err

    # --- commands (any thread) ---------------------------------------------------------------------------
    def set_autonomy(self, level: object) -> concurrent.futures.Future[str]:
        """Set the current autonomy; waiting outcomes that it now allows fire at the next tick."""
        try:
            value = Autonomy.parse(level)
        except ConfigError as err:
            raise BehaviorCommandError(str(err)) from err

        def apply(now: float) -> str:
            self._book.autonomy = int(value)
            for node in list(self._book.requests.values()):
                node.wake(now)
            return f"autonomy set to {value.name}"

        return self._submit("set_autonomy", (value.name,), apply)

    def force_transition(self, path: str, outcome: str) -> concurrent.futures.Future[str]:
        """Make the active state at ``path`` leave with ``outcome`` now, whatever its autonomy."""
        node = self._node(path)
        if outcome not in node.outcomes:
            raise BehaviorCommandError(choices_message(f"state {path!r} has no outcome", outcome, node.outcomes))

        def apply(now: float) -> str:
            self._require_active(node)
            if node is self._rt:
                node.abort()
                self._end(BehaviorStatus.FINISHED, outcome, "outcome forced by the operator", None, now)
                return f"forced {path} -> {outcome} (behavior finished)"
            pending = node.pending
            if pending is not None and pending.announced is not None and pending.outcome == outcome:
                pending.approved = True  # forcing the outcome the operator was asked about approves it
                node.wake(now)
                return f"approved {path} -> {outcome}"
            if pending is not None:
                node.drop_pending()
            node.pending = Pending(outcome, PendingReason.FORCED, node.routes[outcome].required)
            node.wake(now)
            return f"forced {path} -> {outcome}"

        return self._submit("force_transition", (path, outcome), apply)

    def approve(self, path: str, outcome: Optional[str] = None) -> concurrent.futures.Future[str]:
        """Let the outcome requested by ``path`` fire (``outcome``, if given, must be the requested one)."""
        node = self._node(path)

        def apply(now: float) -> str:
            pending = node.pending
            if pending is None or pending.announced is None:
                requested = ", ".join(
                    f"{p} ({n.pending.outcome})" for p, n in self._book.requests.items() if n.pending is not None
                )
                raise BehaviorCommandError(f"state {path!r} requests no outcome (requests: {requested or 'none'})")
            if outcome is not None and outcome != pending.outcome:
                raise BehaviorCommandError(
                    f"state {path!r} requests {pending.outcome!r}, not {outcome!r}; use force_transition for another"
                )
            if pending.announced is PendingReason.LOCK:
                raise BehaviorCommandError(f"outcome {pending.outcome!r} of {path!r} waits for an unlock, not approval")
            pending.approved = True
            node.wake(now)
            return f"approved {path} -> {pending.outcome}"

        return self._submit("approve", (path,) if outcome is None else (path, outcome), apply)

    def pause(self) -> concurrent.futures.Future[str]:
        """Stop executing: active states get on_pause and are not executed until resume()."""

        def apply(now: float) -> str:
            if self._paused:
                return "already paused"
            for leaf in list(self._rt.active_leaves()):
                self._book.hold_leaf(leaf, HOLD_PAUSE)
            self._paused = True
            self._status = BehaviorStatus.PAUSED
            self._emit_status(now, None, "paused by the operator")
            return "paused"

        return self._submit("pause", (), apply)

    def resume(self) -> concurrent.futures.Future[str]:
        """Continue after pause(): paused states get on_resume and run again."""

        def apply(now: float) -> str:
            if not self._paused:
                return "not paused"
            self._paused = False
            self._status = BehaviorStatus.RUNNING
            for leaf in list(self._rt.active_leaves()):
                self._book.release_leaf(leaf, HOLD_PAUSE, now)
            self._emit_status(now, None, "resumed by the operator")
            return "resumed"

        return self._submit("resume", (), apply)

    def preempt(self, reason: str = "preempted by the operator") -> concurrent.futures.Future[str]:
        """Stop the behavior: active states are exited, every state gets on_stop, status PREEMPTED."""

        def apply(now: float) -> str:
            self._preempt(reason, now)
            return "preempted"

        return self._submit("preempt", (), apply)

    def lock(self, path: str) -> concurrent.futures.Future[str]:
        """Hold any transition that would leave the state or container at ``path`` until unlock()."""
        node = self._node(path)

        def apply(now: float) -> str:
            if not node.locked:
                node.locked = True
                self._book.lock_count += 1
            return f"locked {path}"

        return self._submit("lock", (path,), apply)

    def unlock(self, path: str) -> concurrent.futures.Future[str]:
        node = self._node(path)

        def apply(now: float) -> str:
            if not node.locked:
                raise BehaviorCommandError(f"state {path!r} is not locked")
            node.locked = False
            self._book.lock_count -= 1
            for waiting in list(self._book.requests.values()):
                waiting.wake(now)
            return f"unlocked {path}"

        return self._submit("unlock", (path,), apply)

    # --- command plumbing ----------------------------------------------------------------------------------
    def _node(self, path: str) -> StateRuntime:
        node = self._nodes.get(path)
        if node is None:
            raise BehaviorCommandError(choices_message("state path", path, self._nodes))
        return node

    def _require_active(self, node: StateRuntime) -> None:
        if not node.active:
            active = ", ".join(self._rt.active_paths()) or "none"
            raise BehaviorCommandError(f"state {node.path!r} is not active (active: {active})")

    def _submit(
        self, name: str, args: Tuple[str, ...], apply: Callable[[float], str]
    ) -> concurrent.futures.Future[str]:
        if self._terminal:
            raise BehaviorCommandError(f"behavior {self._ctx.name!r} has ended ({self._status.value}); {name} refused")
        future: concurrent.futures.Future[str] = concurrent.futures.Future()
        self._commands.append((name, args, apply, future))
        self._wake.set()
        return future

    def _apply_commands(self) -> None:
        ctx = self._ctx
        while self._commands:
            name, args, apply, future = self._commands.popleft()
            now = ctx.clock.now()
            if self._terminal:
                future.set_exception(BehaviorCommandError(f"behavior has ended ({self._status.value}); {name} refused"))
                continue
            try:
                message = apply(now)
            except BehaviorCommandError as err:
                future.set_exception(err)
                self._emit_command(now, name, args, False, str(err))
                ctx.log(LogLevel.WARN, f"command {name} refused: {err}")
                continue
            except Exception as err:
                future.set_exception(err)
                self._fail(err, now)
                continue
            future.set_result(message)
            self._emit_command(now, name, args, True, message)

    def _emit_command(self, now: float, name: str, args: Tuple[str, ...], ok: bool, message: str) -> None:
        if self._ctx.hooks.command:
            event = CommandEvent(now, name, args, ok, message)
            for hook in self._ctx.hooks.command:
                try:
                    hook(event)
                except Exception as err:
                    raise hook_error("command", hook, err) from err
