"""The runner's topics as small JSON events for the page, and the matching of the runner's answers to commands.

Each function takes one message of a runner's topic (anything with the fields of the flex_nav message: the ROS
message itself, or a test double) and returns a dict the server sends as JSON. Every event has ``type`` and
``robot`` (the runner's node name, e.g. ``/robot1/behavior_runner``); texts are cut to ``MAX_TEXT_CHARS``.

===========  =========================================================================================
type         fields
===========  =========================================================================================
status       behavior, code, status (READY .. IDLE), outcome, reason, autonomy (0..3), stamp [s]
activity     behavior, autonomy, active [paths], requests [{path, outcome, required, reason}], stamp
transition   behavior, path, outcome, target, required, forced, stamp
log          behavior, level (INFO, WARN, HINT, ERROR, DEBUG), path, text, stamp
feedback     command, args, ok, message, pending, refs (the page's command references it answers)
structure    the structure (:func:`structure_event`) and its SVG
robots       robots [names]
===========  =========================================================================================
"""

from __future__ import annotations

import collections
from typing import Any, Deque, Dict, List, Optional, Protocol, Sequence, Tuple

from flex_nav.console.graph import svg_id
from flex_nav.console.model import BehaviorStructure

STATUS_NAMES = ("READY", "RUNNING", "PAUSED", "FINISHED", "PREEMPTED", "FAILED", "IDLE")  # msg/BehaviorStatus codes
LOG_LEVELS = {0: "INFO", 1: "WARN", 2: "HINT", 3: "ERROR", 10: "DEBUG"}  # msg/BehaviorLog levels
MAX_TEXT_CHARS = 2000  # a log text, a reason or a message is cut here
MAX_ARG_CHARS = 200  # each argument echoed in a feedback event
MAX_PENDING = 256  # commands awaiting the runner's answer, per console (the oldest are forgotten)


class _Stamp(Protocol):
    def to_sec(self) -> float: ...


class _Header(Protocol):
    stamp: _Stamp


class StatusMsg(Protocol):
    header: _Header
    behavior: str
    code: int
    outcome: str
    reason: str
    autonomy: int


class RequestMsg(Protocol):
    path: str
    outcome: str
    required: int
    reason: str


class ActivityMsg(Protocol):
    header: _Header
    behavior: str
    autonomy: int
    active_paths: Sequence[str]
    requests: Sequence[RequestMsg]


class TransitionMsg(Protocol):
    header: _Header
    behavior: str
    path: str
    outcome: str
    target: str
    required: int
    forced: bool


class LogMsg(Protocol):
    header: _Header
    behavior: str
    level: int
    path: str
    text: str


class FeedbackMsg(Protocol):
    command: str
    args: Sequence[str]
    ok: bool
    message: str
    pending: bool


def _cut(text: str, limit: int = MAX_TEXT_CHARS) -> str:
    return text if len(text) <= limit else f"{text[:limit]}... ({len(text)} characters)"


def _stamp(msg: Any) -> float:
    return float(msg.header.stamp.to_sec())


def status_event(robot: str, msg: StatusMsg) -> Dict[str, Any]:
    code = int(msg.code)
    return {
        "type": "status", "robot": robot, "behavior": msg.behavior, "code": code,
        "status": STATUS_NAMES[code] if 0 <= code < len(STATUS_NAMES) else f"UNKNOWN({code})",
        "outcome": msg.outcome, "reason": _cut(msg.reason), "autonomy": int(msg.autonomy), "stamp": _stamp(msg),
    }


def activity_event(robot: str, msg: ActivityMsg) -> Dict[str, Any]:
    return {
        "type": "activity", "robot": robot, "behavior": msg.behavior, "autonomy": int(msg.autonomy),
        "active": list(msg.active_paths),
        "requests": [{"path": r.path, "outcome": r.outcome, "required": int(r.required), "reason": r.reason}
                     for r in msg.requests],
        "stamp": _stamp(msg),
    }


def transition_event(robot: str, msg: TransitionMsg) -> Dict[str, Any]:
    return {
        "type": "transition", "robot": robot, "behavior": msg.behavior, "path": msg.path, "outcome": msg.outcome,
        "target": msg.target, "required": int(msg.required), "forced": bool(msg.forced), "stamp": _stamp(msg),
    }


def log_event(robot: str, msg: LogMsg) -> Dict[str, Any]:
    level = int(msg.level)
    return {
        "type": "log", "robot": robot, "behavior": msg.behavior, "level": LOG_LEVELS.get(level, str(level)),
        "path": msg.path, "text": _cut(msg.text), "stamp": _stamp(msg),
    }


def feedback_event(robot: str, msg: FeedbackMsg, refs: Sequence[str] = ()) -> Dict[str, Any]:
    return {
        "type": "feedback", "robot": robot, "command": msg.command,
        "args": [_cut(a, MAX_ARG_CHARS) for a in msg.args], "ok": bool(msg.ok), "message": _cut(msg.message),
        "pending": bool(msg.pending), "refs": list(refs),
    }


def structure_event(robot: str, structure: BehaviorStructure, svg: str, error: str = "") -> Dict[str, Any]:
    """What the page needs of a structure: each state with its SVG id, the startable behaviors' forms, the
    drawing (``svg``; ``error`` says why there is none)."""
    def parameter(p: Any) -> Dict[str, Any]:
        return {"name": p.name, "type": p.type, "default": p.default, "has_default": p.has_default,
                "min": p.minimum, "max": p.maximum,
                "choices": list(p.choices) if p.choices is not None else None, "description": p.description}

    return {
        "type": "structure", "robot": robot, "behavior": structure.behavior, "description": structure.description,
        "states": [{"path": s.path, "label": s.label, "parent": s.parent, "kind": s.kind, "behavior": s.behavior,
                    "class": s.class_name, "outcomes": list(s.outcomes), "autonomy": dict(s.autonomy),
                    "id": svg_id(s.path)} for s in structure.states.values()],
        "parameters": [parameter(p) for p in structure.parameters],
        "values": dict(structure.values),
        "startable": [{"name": b.name, "error": b.error, "parameters": [parameter(p) for p in b.parameters]}
                      for b in structure.startable.values()],
        "svg": svg, "error": error,
    }


def robots_event(robots: Sequence[str]) -> Dict[str, Any]:
    return {"type": "robots", "robots": sorted(robots)}


class CommandTracker:
    """Which page command each runner answer belongs to: a sent command is remembered under (robot, command,
    args), which the runner's feedback repeats; a final answer (not ``pending``) forgets it. Identical commands
    are answered in the order they were sent. At most ``max_pending`` are remembered (the oldest forgotten)."""

    def __init__(self, max_pending: int = MAX_PENDING) -> None:
        self._pending: Deque[Tuple[Tuple[str, str, Tuple[str, ...]], str]] = collections.deque(maxlen=max_pending)

    def sent(self, robot: str, command: str, args: Sequence[str], ref: str) -> None:
        self._pending.append(((robot, command, tuple(args)), ref))

    def answered(self, robot: str, command: str, args: Sequence[str], pending: bool) -> List[str]:
        """The page references this answer belongs to (the oldest matching command; [] if none)."""
        key = (robot, command, tuple(args))
        for index, (sent_key, ref) in enumerate(self._pending):
            if sent_key == key:
                if not pending:
                    del self._pending[index]
                return [ref]
        return []

    def forget(self, robot: str) -> None:
        """Drop what waits for ``robot`` (its runner went away)."""
        kept = [(key, ref) for key, ref in self._pending if key[0] != robot]
        self._pending.clear()
        self._pending.extend(kept)

    def __len__(self) -> int:
        return len(self._pending)


def known_ref(ref: Optional[object]) -> Optional[str]:
    """A page's command id as the reference kept for it (a short string or number; None otherwise)."""
    if isinstance(ref, bool) or not isinstance(ref, (int, str)):
        return None
    text = str(ref)
    return text if 0 < len(text) <= 64 else None
