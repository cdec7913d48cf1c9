"""What a running behavior reports: status, log levels and the events its hooks receive.

Hooks are plain callables registered on a :class:`Hooks` object (one per behavior context). They are
called synchronously in the executor's thread, right after the fact they report, so an operator
interface (the ROS adapter) can publish from them. Event objects are immutable named tuples: cheap
to build and safe to hand to another thread. A hook that raises fails the behavior (loudly, with the
states exited), because a silent supervision channel is worse than a stopped robot.
"""

from __future__ import annotations

import enum
from typing import Callable, List, NamedTuple, Optional, Tuple

from flex_nav.behavior.autonomy import Autonomy


class LogLevel(enum.IntEnum):
    """Severity of a behavior log message (numbers as FlexBE's BehaviorLog uses them)."""

    INFO = 0
    WARN = 1
    HINT = 2
    ERROR = 3
    DEBUG = 10


class BehaviorStatus(enum.Enum):
    """Where a behavior is in its life."""

    READY = "ready"  # built and validated, not started
    RUNNING = "running"
    PAUSED = "paused"
    FINISHED = "finished"  # the root returned an outcome
    PREEMPTED = "preempted"  # stopped on request; active states were exited
    FAILED = "failed"  # an error (see the reason); active states were exited

    @property
    def is_terminal(self) -> bool:
        return self in (BehaviorStatus.FINISHED, BehaviorStatus.PREEMPTED, BehaviorStatus.FAILED)


class TransitionEvent(NamedTuple):
    """A transition fired: state ``path`` left with ``outcome`` towards ``target``.

    ``target`` is the label of the next state or, when the transition leaves the container, the
    container's outcome; ``target_path`` is the next state's path or "" in the latter case. In a
    concurrency container ``target`` is "" (the child finished; the conditions decide).
    """

    time_s: float
    path: str
    outcome: str
    target: str
    target_path: str
    required: Autonomy
    forced: bool


class RequestEvent(NamedTuple):
    """An outcome waits for the operator (``pending``) or stopped waiting (``pending`` False).

    ``reason`` is the value of a :class:`~flex_nav.behavior.state.PendingReason`: ``"autonomy"`` (the
    required level is not below the current autonomy) or ``"lock"`` (the transition would leave a locked
    container).
    """

    time_s: float
    path: str
    outcome: str
    required: Autonomy
    reason: str
    pending: bool


class LogEvent(NamedTuple):
    time_s: float
    level: LogLevel
    message: str
    path: str  # the state that logged, "" for the engine itself


class StatusEvent(NamedTuple):
    time_s: float
    status: BehaviorStatus
    outcome: Optional[str]  # the root's outcome when finished, "preempted" when preempted
    reason: str  # human-readable; the error when failed


class CommandEvent(NamedTuple):
    """An operator command was applied (``ok``) or refused, with why."""

    time_s: float
    command: str
    args: Tuple[str, ...]
    ok: bool
    message: str


class ActiveStatesEvent(NamedTuple):
    """The set of active state paths changed (sent once per tick that changed it)."""

    time_s: float
    paths: Tuple[str, ...]


class Hooks:
    """The event hooks of one behavior: append callables to the lists."""

    __slots__ = ("active", "command", "log", "request", "status", "transition")

    def __init__(self) -> None:
        self.transition: List[Callable[[TransitionEvent], None]] = []
        self.request: List[Callable[[RequestEvent], None]] = []
        self.log: List[Callable[[LogEvent], None]] = []
        self.status: List[Callable[[StatusEvent], None]] = []
        self.command: List[Callable[[CommandEvent], None]] = []
        self.active: List[Callable[[ActiveStatesEvent], None]] = []
