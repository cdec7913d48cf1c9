"""A behavior's structure as JSON, for operator tools: what the behavior_runner publishes on ``~structure``.

:func:`describe` walks a loaded :class:`~flex_nav.behavior.behavior.Behavior` (nothing runs, nothing is imported)
and :func:`structure_json` writes the text. The schema (``"schema": "flex_nav/behavior_structure"``,
``"version": 1``)::

    {
      "schema": "flex_nav/behavior_structure", "version": 1,
      "behavior": "flex_planner",           # "" when no behavior is loaded (then "states" is [])
      "description": "...",
      "autonomy_levels": ["off", "low", "high", "full"],   # index = level, as in the runner's messages
      "parameters": [PARAMETER, ...],       # the loaded behavior's declared parameters
      "values": {"navigate": "flex_navigate", ...},        # the values it was loaded with
      "states": [STATE, ...],               # depth first, every container before its children
      "startable": [{"name": "explore", "parameters": [PARAMETER, ...], "error": ""}, ...],
      "startable_truncated": false          # true: more behaviors on the search path than MAX_STARTABLE
    }

    STATE = {
      "path": "/Navigate/FollowPath",       # as in the runner's messages and commands; the root is "/"
      "label": "FollowPath",                # the root: the behavior's name
      "parent": "/Navigate",                # None for the root
      "kind": "state" | "state_machine" | "concurrency" | "priority" | "sub_behavior",
      "class": "flex_nav_states.follow_path_state.FollowPathState",   # module.Class of the state object
      "behavior": "flex_navigate",          # sub_behavior only: the included behavior's name, else ""
      "outcomes": ["done", "failed"],
      "transitions": {"done": "Next", "failed": "failed"},   # in a state machine: outcome -> sibling label or
                                            # the parent's outcome; {} for the root and concurrent children
      "autonomy": {"done": 0, "failed": 2}, # level each outcome needs (0 off .. 3 full; fires alone only below
                                            # the current autonomy); every outcome listed, all 0 for the root
      "children": ["A", "B"],               # containers: child labels in order, else []
      "initial": "A",                       # state machines (and priority, sub_behavior): the initial label
      "conditions": [{"outcome": "arrived", "when": [["Follow", "done"]]}]   # concurrency only, else []
    }

    PARAMETER = {"name": "max_replans", "type": "float", "default": 5.0, "has_default": true,
                 "min": 0.0, "max": null, "choices": null, "description": "..."}

``error`` of a startable behavior is "" or why its parameters could not be read (the behavior is still listed:
the runner says the same when it is started). Values that JSON cannot hold (a YAML date, a non-finite float in a
list) are given as their ``repr``.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

from flex_nav.behavior.autonomy import Autonomy
from flex_nav.behavior.behavior import Behavior, ParameterInfo
from flex_nav.behavior.concurrency import ConcurrencyContainer
from flex_nav.behavior.container import Container, child_path
from flex_nav.behavior.priority import PriorityContainer
from flex_nav.behavior.state import State
from flex_nav.behavior.state_machine import StateMachine
from flex_nav.behavior.yaml_limits import DEFAULT_LIMITS, LoadLimits
from flex_nav.behavior.yaml_loader import list_behaviors, parameter_schema
from flex_nav.exceptions import FlexNavError

SCHEMA = "flex_nav/behavior_structure"
VERSION = 1
KINDS = ("state", "state_machine", "concurrency", "priority", "sub_behavior")
AUTONOMY_LEVELS = tuple(level.name.lower() for level in Autonomy)
MAX_STARTABLE = 100  # behaviors of the search path listed (each one's parameters read within the load limits)


def jsonable(value: Any) -> Any:
    """``value`` with everything JSON cannot hold (non-finite floats, dates, tuples' types) made plain."""
    if value is None or isinstance(value, (bool, int, str)):
        return value
    if isinstance(value, float):
        return value if math.isfinite(value) else repr(value)
    if isinstance(value, (list, tuple)):
        return [jsonable(item) for item in value]
    if isinstance(value, dict):
        return {str(key): jsonable(item) for key, item in value.items()}
    return repr(value)


def parameter_json(info: ParameterInfo) -> Dict[str, Any]:
    return {
        "name": info.name,
        "type": info.type,
        "default": jsonable(info.default) if info.has_default else None,
        "has_default": info.has_default,
        "min": info.minimum,
        "max": info.maximum,
        "choices": jsonable(list(info.choices)) if info.choices is not None else None,
        "description": info.description,
    }


def _kind(state: State, path: str, sub_behaviors: Dict[str, str]) -> str:
    if path in sub_behaviors:
        return "sub_behavior"
    if isinstance(state, PriorityContainer):
        return "priority"
    if isinstance(state, StateMachine):
        return "state_machine"
    if isinstance(state, ConcurrencyContainer):
        return "concurrency"
    return "state"


def _states(state: State, path: str, *, label: str, parent: Optional[Container], parent_path: Optional[str],
            sub_behaviors: Dict[str, str], out: List[Dict[str, Any]]) -> None:
    outcomes = list(state.outcomes)
    transitions: Dict[str, str] = {}
    levels: Dict[str, int] = dict.fromkeys(outcomes, 0)
    if parent is not None:
        levels = {outcome: int(level) for outcome, level in parent.autonomy_of(label).items()}
        if isinstance(parent, StateMachine):
            transitions = parent.transitions_of(label)
    kind = _kind(state, path, sub_behaviors)
    entry: Dict[str, Any] = {
        "path": path,
        "label": label,
        "parent": parent_path,
        "kind": kind,
        "class": f"{type(state).__module__}.{type(state).__qualname__}",
        "behavior": sub_behaviors.get(path, ""),
        "outcomes": outcomes,
        "transitions": transitions,
        "autonomy": levels,
        "children": list(state.children) if isinstance(state, Container) else [],
        "initial": state.initial_state if isinstance(state, StateMachine) else None,
        "conditions": [{"outcome": outcome, "when": [list(pair) for pair in pairs]}
                       for outcome, pairs in state.conditions] if isinstance(state, ConcurrencyContainer) else [],
    }
    out.append(entry)
    if isinstance(state, Container):
        for child_label, child in state.children.items():
            _states(child, child_path(path, child_label), label=child_label, parent=state, parent_path=path,
                    sub_behaviors=sub_behaviors, out=out)


def startable_behaviors(search_path: Sequence[Union[str, Path]], limits: LoadLimits = DEFAULT_LIMITS,
                        max_count: int = MAX_STARTABLE) -> Tuple[List[Dict[str, Any]], bool]:
    """The behaviors a runner with ``search_path`` can start by name, each with its parameters (or the reason they
    could not be read), at most ``max_count`` of them in name order; and whether more were left out."""
    found = list_behaviors(search_path)
    entries: List[Dict[str, Any]] = []
    for name in sorted(found)[:max_count]:
        try:
            params, error = [parameter_json(p) for p in parameter_schema(found[name], search_path, limits)], ""
        except FlexNavError as err:
            params, error = [], str(err) or type(err).__name__
        entries.append({"name": name, "parameters": params, "error": error})
    return entries, len(found) > max_count


def describe(behavior: Optional[Behavior], startable: Sequence[Dict[str, Any]] = (),
             startable_truncated: bool = False) -> Dict[str, Any]:
    """The structure of ``behavior`` (None: no behavior loaded) as a JSON-ready dict (schema in the module doc)."""
    states: List[Dict[str, Any]] = []
    if behavior is not None:
        _states(behavior.root, "/", label=behavior.name, parent=None, parent_path=None,
                sub_behaviors=behavior.sub_behaviors, out=states)
    return {
        "schema": SCHEMA,
        "version": VERSION,
        "behavior": behavior.name if behavior is not None else "",
        "description": behavior.description if behavior is not None else "",
        "autonomy_levels": list(AUTONOMY_LEVELS),
        "parameters": [parameter_json(p) for p in behavior.parameter_schema] if behavior is not None else [],
        "values": jsonable(behavior.parameters) if behavior is not None else {},
        "states": states,
        "startable": list(startable),
        "startable_truncated": startable_truncated,
    }


def structure_json(behavior: Optional[Behavior], search_path: Sequence[Union[str, Path]] = (),
                   limits: LoadLimits = DEFAULT_LIMITS, max_startable: int = MAX_STARTABLE) -> str:
    """:func:`describe` of ``behavior`` with the behaviors startable from ``search_path``, as compact JSON text."""
    startable, truncated = startable_behaviors(search_path, limits, max_startable)
    return json.dumps(describe(behavior, startable, truncated), separators=(",", ":"), allow_nan=False)
