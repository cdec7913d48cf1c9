"""A runner's behavior structure, read from its ``~structure`` JSON into typed records (checked, bounded).

The JSON comes over ROS from any node that publishes on the topic, so it is read strictly: every field of the
schema of :mod:`flex_nav.behavior.structure` is checked for its type, the text and the number of states are
bounded, and anything else is a :class:`~flex_nav.console.errors.StructureError` naming the field.
"""

from __future__ import annotations

import dataclasses
import json
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple

from flex_nav.behavior.behavior import ParameterInfo
from flex_nav.behavior.structure import KINDS, SCHEMA, VERSION
from flex_nav.console.errors import StructureError

MAX_STRUCTURE_CHARS = 4 * 1024 * 1024  # a structure text longer than this is refused (explore's: 37 kB)
MAX_STATES = 5000  # states of one structure (the loader's own limit is 1 000 states a load, sub-behaviors apart)
PARAMETER_TYPES = ("float", "int", "bool", "str", "list", "dict")
MAX_LEVEL = 3  # autonomy levels are 0 (off) .. 3 (full)


@dataclasses.dataclass(frozen=True)
class StateInfo:
    """One state of a loaded behavior (see the STATE entry of the schema)."""

    path: str
    label: str
    parent: Optional[str]
    kind: str
    class_name: str
    behavior: str
    outcomes: Tuple[str, ...]
    transitions: Mapping[str, str]
    autonomy: Mapping[str, int]
    children: Tuple[str, ...]
    initial: Optional[str]
    conditions: Tuple[Tuple[str, Tuple[Tuple[str, str], ...]], ...]

    @property
    def is_container(self) -> bool:
        return self.kind != "state"

    def child_path(self, label: str) -> str:
        return f"{self.path.rstrip('/')}/{label}"


@dataclasses.dataclass(frozen=True)
class StartableInfo:
    """A behavior the runner can start by name, with its parameters (or why they could not be read)."""

    name: str
    parameters: Tuple[ParameterInfo, ...]
    error: str

    def parameter(self, name: str) -> Optional[ParameterInfo]:
        return next((p for p in self.parameters if p.name == name), None)


@dataclasses.dataclass(frozen=True)
class BehaviorStructure:
    """What a runner says about its loaded behavior (``behavior`` "" and no states: none loaded)."""

    behavior: str
    description: str
    parameters: Tuple[ParameterInfo, ...]
    values: Mapping[str, Any]
    states: Mapping[str, StateInfo]  # by path, depth first (containers before their children)
    startable: Mapping[str, StartableInfo]  # by name
    startable_truncated: bool = False

    @classmethod
    def empty(cls) -> BehaviorStructure:
        return cls("", "", (), {}, {}, {})

    @classmethod
    def from_json(cls, text: str, max_chars: int = MAX_STRUCTURE_CHARS) -> BehaviorStructure:
        """Read ``text``; StructureError naming the first field that does not follow the schema."""
        if len(text) > max_chars:
            raise StructureError(f"structure: {len(text)} characters, more than the {max_chars} accepted")
        try:
            data = json.loads(text)
        except (ValueError, RecursionError) as err:
            raise StructureError(f"structure: not JSON ({err})") from err
        return cls.from_dict(data)

    @classmethod
    def from_dict(cls, data: Any) -> BehaviorStructure:
        top = _Fields(data, "structure")
        schema, version = top.text("schema"), top.get("version", int)
        if schema != SCHEMA or version != VERSION:
            raise StructureError(f"structure: schema {schema!r} version {version!r} is not {SCHEMA!r} version "
                                 f"{VERSION} (a runner of another flex_nav version?)")
        raw_states = top.items("states")
        if len(raw_states) > MAX_STATES:
            raise StructureError(f"structure: {len(raw_states)} states, more than the {MAX_STATES} accepted")
        states: Dict[str, StateInfo] = {}
        for index, raw in enumerate(raw_states):
            state = _state(_Fields(raw, f"structure: states[{index}]"))
            if state.path in states:
                raise StructureError(f"structure: state path {state.path!r} is listed twice")
            if state.parent is not None and state.parent not in states:
                raise StructureError(f"structure: state {state.path!r} comes before its parent {state.parent!r}")
            states[state.path] = state
        startable: Dict[str, StartableInfo] = {}
        for index, raw in enumerate(top.items("startable")):
            entry = _Fields(raw, f"structure: startable[{index}]")
            name = entry.text("name")
            startable[name] = StartableInfo(name, _parameters(entry, "parameters"), entry.text("error"))
        return cls(
            behavior=top.text("behavior"),
            description=top.text("description"),
            parameters=_parameters(top, "parameters"),
            values=top.get("values", dict),
            states=states,
            startable=startable,
            startable_truncated=top.get("startable_truncated", bool),
        )

    @property
    def loaded(self) -> bool:
        return bool(self.states)

    def state(self, path: str) -> Optional[StateInfo]:
        return self.states.get(path)

    def ancestors(self, path: str) -> List[str]:
        """Paths of the containers above ``path``, nearest first (none for an unknown path)."""
        found: List[str] = []
        state = self.states.get(path)
        while state is not None and state.parent is not None:
            found.append(state.parent)
            state = self.states.get(state.parent)
        return found


class _Fields:
    """Typed access to one JSON object of the structure; errors name the field."""

    def __init__(self, data: Any, where: str) -> None:
        if not isinstance(data, dict):
            raise StructureError(f"{where} must be an object, got {type(data).__name__}")
        self.data = data
        self.where = where

    def get(self, key: str, kind: type) -> Any:
        if key not in self.data:
            raise StructureError(f"{self.where} has no {key!r}")
        value = self.data[key]
        if not isinstance(value, kind) or (isinstance(value, bool) and kind is not bool):
            raise StructureError(f"{self.where}.{key} must be {kind.__name__}, got {type(value).__name__}")
        return value

    def text(self, key: str) -> str:
        return str(self.get(key, str))

    def optional_text(self, key: str) -> Optional[str]:
        return None if self.data.get(key) is None else self.text(key)

    def items(self, key: str) -> List[Any]:
        return list(self.get(key, list))

    def names(self, key: str) -> Tuple[str, ...]:
        values = self.items(key)
        if not all(isinstance(v, str) and v for v in values):
            raise StructureError(f"{self.where}.{key} must be a list of names")
        return tuple(values)

    def name_map(self, key: str, kind: type) -> Dict[str, Any]:
        values = self.get(key, dict)
        for name, value in values.items():
            if not isinstance(value, kind) or isinstance(value, bool):
                raise StructureError(f"{self.where}.{key}[{name!r}] must be {kind.__name__}")
        return dict(values)


def _state(fields: _Fields) -> StateInfo:
    path, kind = fields.text("path"), fields.text("kind")
    if not path.startswith("/"):
        raise StructureError(f"{fields.where}.path {path!r} must start with '/'")
    if kind not in KINDS:
        raise StructureError(f"{fields.where}.kind {kind!r} is not one of {', '.join(KINDS)}")
    outcomes = fields.names("outcomes")
    autonomy = fields.name_map("autonomy", int)
    for outcome, level in autonomy.items():
        if outcome not in outcomes or not 0 <= level <= MAX_LEVEL:
            raise StructureError(f"{fields.where}.autonomy: {outcome!r}: {level} is not a level 0..3 of an outcome")
    conditions = []
    for index, raw in enumerate(fields.items("conditions")):
        condition = _Fields(raw, f"{fields.where}.conditions[{index}]")
        pairs = condition.items("when")
        if not all(isinstance(p, list) and len(p) == 2 and all(isinstance(x, str) for x in p) for p in pairs):
            raise StructureError(f"{condition.where}.when must be a list of [state, outcome] pairs")
        conditions.append((condition.text("outcome"), tuple((p[0], p[1]) for p in pairs)))
    return StateInfo(
        path=path,
        label=fields.text("label"),
        parent=fields.optional_text("parent"),
        kind=kind,
        class_name=fields.text("class"),
        behavior=fields.text("behavior"),
        outcomes=outcomes,
        transitions=fields.name_map("transitions", str),
        autonomy=autonomy,
        children=fields.names("children"),
        initial=fields.optional_text("initial"),
        conditions=tuple(conditions),
    )


def _parameters(fields: _Fields, key: str) -> Tuple[ParameterInfo, ...]:
    infos = []
    for index, raw in enumerate(fields.items(key)):
        entry = _Fields(raw, f"{fields.where}.{key}[{index}]")
        type_name = entry.text("type")
        if type_name not in PARAMETER_TYPES:
            raise StructureError(f"{entry.where}.type {type_name!r} is not one of {', '.join(PARAMETER_TYPES)}")
        bounds = []
        for bound in ("min", "max"):
            value = entry.data.get(bound)
            if value is not None and (not isinstance(value, (int, float)) or isinstance(value, bool)):
                raise StructureError(f"{entry.where}.{bound} must be a number or null")
            bounds.append(value)
        choices = entry.data.get("choices")
        if choices is not None and not isinstance(choices, list):
            raise StructureError(f"{entry.where}.choices must be a list or null")
        infos.append(ParameterInfo(
            name=entry.text("name"),
            type=type_name,
            default=entry.data.get("default"),
            has_default=entry.get("has_default", bool),
            minimum=bounds[0],
            maximum=bounds[1],
            choices=tuple(choices) if choices is not None else None,
            description=entry.text("description"),
        ))
    return tuple(infos)


STATUS_TYPE = "flex_nav/BehaviorStatus"


def runner_names(topics: Sequence[Tuple[str, str]]) -> List[str]:
    """The behavior runners among the master's published ``(topic, type)`` pairs: every ``<runner>/status`` of
    type flex_nav/BehaviorStatus (``/robot1/behavior_runner/status`` -> ``/robot1/behavior_runner``), sorted."""
    return sorted({topic[: -len("/status")] for topic, kind in topics
                   if kind == STATUS_TYPE and topic.endswith("/status") and len(topic) > len("/status")})
