"""Behavior: a named, validated root state plus what it was built from.

A behavior is what an operator starts by name: a root container (usually a
:class:`~flex_nav.behavior.state_machine.StateMachine`) with its userdata defaults, and the values
of its parameters. Build it in Python::

    root = StateMachine(outcomes=["finished", "failed"])
    root.add("Wait", Wait(wait_time_s=1.0), transitions={"done": "finished"})
    behavior = Behavior("wait_a_bit", root)

or load it from YAML with :func:`flex_nav.behavior.yaml_loader.load_behavior`. States are stateful
objects: run each Behavior instance once (load or build again for the next run).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any, Dict, Mapping, Optional, Sequence, Tuple

from flex_nav.behavior.container import Container
from flex_nav.behavior.state import State
from flex_nav.exceptions import ConfigError


@dataclasses.dataclass(frozen=True)
class ParameterInfo:
    """One declared parameter of a behavior, as its YAML ``parameters:`` entry says (for tools and forms).

    ``type`` is float, int, bool, str, list or dict; ``default`` is meaningful only when ``has_default``;
    ``minimum`` / ``maximum`` bound float and int parameters; ``choices`` (None: any value) lists the valid values.
    """

    name: str
    type: str
    default: Any = None
    has_default: bool = False
    minimum: Optional[float] = None
    maximum: Optional[float] = None
    choices: Optional[Tuple[Any, ...]] = None
    description: str = ""


class Behavior:
    """A root state with a name, a description and the parameter values it was built with.

    ``parameter_schema``: the declared parameters (YAML behaviors; empty for behaviors built in code).
    ``sub_behaviors``: path of each state that is an included behavior -> that behavior's name.
    """

    def __init__(
        self,
        name: str,
        root: State,
        description: str = "",
        parameters: Optional[Dict[str, Any]] = None,
        source: Optional[Path] = None,
        *,
        parameter_schema: Sequence[ParameterInfo] = (),
        sub_behaviors: Optional[Mapping[str, str]] = None,
    ) -> None:
        if not isinstance(name, str) or not name or "/" in name:
            raise ConfigError(f"behavior name {name!r} must be a non-empty string without '/'")
        if not isinstance(root, State):
            raise ConfigError(f"behavior {name!r}: root must be a State, got {type(root).__name__}")
        self.name = name
        self.root = root
        self.description = description
        self.parameters: Dict[str, Any] = dict(parameters or {})
        self.source = source
        self.parameter_schema: Tuple[ParameterInfo, ...] = tuple(parameter_schema)
        self.sub_behaviors: Dict[str, str] = dict(sub_behaviors or {})

    def validate(self) -> None:
        """Raise the first construction error of the tree (BehaviorConstructionError family)."""
        if isinstance(self.root, Container):
            self.root.validate()

    def to_dot(self) -> str:
        """Graphviz dot text of the structure (see :mod:`flex_nav.behavior.dot`)."""
        from flex_nav.behavior.dot import behavior_to_dot  # noqa: PLC0415  (dot imports this module)

        return behavior_to_dot(self)

    def __repr__(self) -> str:
        origin = f" from {self.source}" if self.source else ""
        return f"<Behavior {self.name!r}{origin}>"
