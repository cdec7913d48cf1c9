"""Every command from the browser checked against the runner's structure before it becomes a BehaviorCommand.

A command is a JSON object from the page, e.g. ``{"command": "force", "path": "/GetPath", "outcome": "planned"}``
(the envelope keys ``type``, ``id`` and ``robot`` are the server's and ignored here). :func:`validate_command`
returns the runner's ``(command, args)`` (msg/BehaviorCommand.msg) or raises
:class:`~flex_nav.console.errors.CommandRefused` with a reason naming the bad value and the valid ones:

================  =============================================  ================================================
command           fields                                         checked
================  =============================================  ================================================
approve           path, [outcome]                                path a state of the loaded behavior, outcome one
                                                                 of its outcomes
force             path, outcome                                  the same, and the state active (when the console
                                                                 knows the active states)
autonomy          level                                          off, low, high, full or 0..3
pause, resume,    (none)
preempt, stop
lock, unlock      path                                           a state or container of the loaded behavior
start             behavior, [autonomy], [parameters {name: v}]   a behavior the runner lists as startable; each
                                                                 parameter declared, of its type, within min/max,
                                                                 one of its choices; those without a default given
================  =============================================  ================================================

Nothing is evaluated: values are JSON values already; a start's parameter values are written as YAML by PyYAML's
safe emitter and read back with the runner's own bounded ``safe_load`` before they are sent, so the runner reads
exactly the value that was checked (a value that would not round-trip is refused).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any, Dict, List, Mapping, Optional, Sequence, Set, Tuple

import yaml

from flex_nav.behavior.autonomy import Autonomy
from flex_nav.behavior.behavior import ParameterInfo
from flex_nav.behavior.yaml_limits import safe_load_bounded
from flex_nav.console.errors import CommandRefused
from flex_nav.console.model import BehaviorStructure, StateInfo
from flex_nav.exceptions import FlexNavError

ENVELOPE = ("type", "id", "robot")  # keys of the page's message that are not the command's
FIELDS: Dict[str, Tuple[Tuple[str, ...], Tuple[str, ...]]] = {  # command: (required fields, optional fields)
    "approve": (("path",), ("outcome",)),
    "force": (("path", "outcome"), ()),
    "autonomy": (("level",), ()),
    "pause": ((), ()),
    "resume": ((), ()),
    "preempt": ((), ()),
    "stop": ((), ()),
    "lock": (("path",), ()),
    "unlock": (("path",), ()),
    "start": (("behavior",), ("autonomy", "parameters")),
}
COMMANDS = tuple(FIELDS)
LEVELS = tuple(level.name.lower() for level in Autonomy)
MAX_TEXT_CHARS = 512  # a path, outcome, level or behavior name longer than this is refused unread
MAX_VALUE_CHARS = 16 * 1024  # a start parameter's value, written as YAML
MAX_LISTED = 25  # valid choices named in a refusal (then "and N more")


@dataclasses.dataclass(frozen=True)
class RunnerCommand:
    """What is published on the runner's ``command`` topic."""

    command: str
    args: Tuple[str, ...] = ()


def _listed(values: Sequence[object]) -> str:
    shown = [v if isinstance(v, str) else repr(v) for v in values[:MAX_LISTED]]
    more = f", and {len(values) - MAX_LISTED} more" if len(values) > MAX_LISTED else ""
    return (", ".join(shown) or "none") + more


def _shown(value: object) -> str:
    text = repr(value)
    return text if len(text) <= 80 else f"{text[:80]}... ({len(text)} characters)"


def refuse_choice(what: str, field: str, value: object, choices: Sequence[object]) -> CommandRefused:
    return CommandRefused(f"{what} {_shown(value)} is not valid (valid: {_listed(choices)})", field, choices)


def _text(request: Mapping[str, Any], field: str, command: str) -> str:
    value = request[field]
    if not isinstance(value, str) or not value:
        raise CommandRefused(f"{command}: {field} must be a non-empty string, got {_shown(value)}", field)
    if len(value) > MAX_TEXT_CHARS:
        raise CommandRefused(f"{command}: {field} is {len(value)} characters long (at most {MAX_TEXT_CHARS})", field)
    return value


def parse_level(value: object, field: str = "level") -> str:
    """An autonomy level as the runner takes it (``off`` .. ``full``), from a name or 0..3."""
    if isinstance(value, int) and not isinstance(value, bool) and 0 <= value < len(LEVELS):
        return LEVELS[value]
    if isinstance(value, str) and value.strip().lower() in LEVELS:
        return value.strip().lower()
    raise refuse_choice("autonomy level", field, value, [*LEVELS, 0, 1, 2, 3])


def _state(structure: BehaviorStructure, path: str, command: str) -> StateInfo:
    if not structure.loaded:
        raise CommandRefused(f"{command}: no behavior is loaded on this runner (start one first)", "path")
    state = structure.state(path)
    if state is None:
        raise refuse_choice(f"{command}: state path", "path", path, list(structure.states))
    return state


def _outcome(state: StateInfo, outcome: str, command: str) -> str:
    if outcome not in state.outcomes:
        raise refuse_choice(f"{command}: outcome of {state.path}", "outcome", outcome, state.outcomes)
    return outcome


def _active_set(structure: BehaviorStructure, active: Sequence[str]) -> Set[str]:
    """The active paths and every container above them (a container is active while a child is)."""
    found: Set[str] = set()
    for path in active:
        found.add(path)
        found.update(structure.ancestors(path))
    return found


def validate_command(request: Mapping[str, Any], structure: BehaviorStructure,
                     active: Optional[Sequence[str]] = None) -> RunnerCommand:
    """The runner command for ``request`` (see the module doc), or CommandRefused saying why not. ``active``: the
    active state paths the runner last reported (None: unknown, not checked)."""
    command = request.get("command")
    if not isinstance(command, str) or command not in FIELDS:
        raise refuse_choice("command", "command", command, COMMANDS)
    required, optional = FIELDS[command]
    for field in request:
        if field not in (*ENVELOPE, "command", *required, *optional):
            raise refuse_choice(f"{command}: field", str(field), field, [*required, *optional])
    missing = [field for field in required if field not in request]
    if missing:
        raise CommandRefused(f"{command} needs {', '.join(missing)}", missing[0])
    if command in ("approve", "force", "lock", "unlock"):
        state = _state(structure, _text(request, "path", command), command)
        args: List[str] = [state.path]
        if "outcome" in request:
            args.append(_outcome(state, _text(request, "outcome", command), command))
        if command == "force" and active is not None:
            running = _active_set(structure, active)
            if state.path not in running:
                raise CommandRefused(f"force: state {state.path!r} is not active (active: {_listed(list(active))})",
                                     "path", list(active))
        return RunnerCommand(command, tuple(args))
    if command == "autonomy":
        return RunnerCommand(command, (parse_level(request["level"]),))
    if command == "start":
        return _start(request, structure)
    return RunnerCommand(command)


def _start(request: Mapping[str, Any], structure: BehaviorStructure) -> RunnerCommand:
    name = _text(request, "behavior", "start")
    startable = structure.startable.get(name)
    if startable is None:
        raise refuse_choice("start: behavior", "behavior", name, sorted(structure.startable))
    args = [name]
    if "autonomy" in request:
        args.append(f"autonomy={parse_level(request['autonomy'], 'autonomy')}")
    given = request.get("parameters", {})
    if not isinstance(given, dict):
        raise CommandRefused(f"start: parameters must be an object {{name: value}}, got {_shown(given)}", "parameters")
    if startable.error:
        raise CommandRefused(f"start: the parameters of {name!r} cannot be read: {startable.error}", "behavior")
    declared = [p.name for p in startable.parameters]
    for key, value in given.items():
        info = startable.parameter(key)
        if info is None:
            raise refuse_choice(f"start {name}: parameter", f"parameters.{key}", key, declared)
        args.append(f"{key}={to_yaml(info, check_parameter(info, value))}")
    lacking = [p.name for p in startable.parameters if not p.has_default and p.name not in given]
    if lacking:
        raise CommandRefused(f"start {name}: parameter(s) {', '.join(lacking)} have no default: give a value",
                             f"parameters.{lacking[0]}")
    return RunnerCommand("start", tuple(args))


_JSON_TYPES: Dict[str, Tuple[type, ...]] = {
    "float": (float, int), "int": (int,), "bool": (bool,), "str": (str,), "list": (list,), "dict": (dict,),
}


def check_parameter(info: ParameterInfo, value: Any) -> Any:
    """``value`` for parameter ``info`` (an int made a float for a float parameter), or CommandRefused: the type,
    finiteness, min/max and choices the runner's loader checks."""
    field = f"parameters.{info.name}"
    kinds = _JSON_TYPES.get(info.type)
    if kinds is None:
        raise CommandRefused(f"parameter {info.name!r} has the unknown type {info.type!r}", field)
    if not isinstance(value, kinds) or (isinstance(value, bool) and info.type != "bool"):
        raise CommandRefused(f"parameter {info.name!r} must be {info.type}, got {type(value).__name__} "
                             f"{_shown(value)}", field)
    if info.type == "float" and isinstance(value, (int, float)):
        value = float(value)
        if not math.isfinite(value):
            raise CommandRefused(f"parameter {info.name!r} must be finite, got {value!r}", field)
    if info.minimum is not None and value < info.minimum:
        raise CommandRefused(f"parameter {info.name!r} = {value!r} is below its minimum {info.minimum!r}", field)
    if info.maximum is not None and value > info.maximum:
        raise CommandRefused(f"parameter {info.name!r} = {value!r} is above its maximum {info.maximum!r}", field)
    if info.choices is not None and value not in info.choices:
        raise refuse_choice(f"parameter {info.name!r} value", field, value, list(info.choices))
    return value


def to_yaml(info: ParameterInfo, value: Any) -> str:
    """``value`` as the YAML text of a runner's ``KEY=VALUE`` argument, checked to read back as ``value``."""
    field = f"parameters.{info.name}"
    text = yaml.safe_dump(value, default_flow_style=True, allow_unicode=True, width=math.inf).rstrip("\n")
    text = text[:-4] if text.endswith("\n...") else text
    if len(text) > MAX_VALUE_CHARS:
        raise CommandRefused(f"parameter {info.name!r}: the value is {len(text)} characters long as YAML "
                             f"(at most {MAX_VALUE_CHARS})", field)
    try:
        back = safe_load_bounded(text, f"parameter {info.name}") if text else ""
    except FlexNavError as err:
        raise CommandRefused(f"parameter {info.name!r}: the value cannot be sent ({err})", field) from err
    if back != value or type(back) is not type(value):
        raise CommandRefused(f"parameter {info.name!r}: the value {_shown(value)} would reach the runner as "
                             f"{_shown(back)}; not sent", field)
    return text
