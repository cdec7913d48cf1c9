"""flexbe_core.core.state: the root of FlexBE's state classes, on flex_nav's engine State.

FlexBE's constructor keywords (``outcomes``, ``input_keys``, ``output_keys``, ``io_keys``; repeated names merged)
and FlexBE's place in a container: ``name`` (the label), ``parent`` and ``path`` (``/Outer/Inner``, "" for a root
that was never attached). While flex_nav's executor runs the state, ``path`` is the engine's.
"""

from __future__ import annotations

from typing import Any, Iterable, List

from flex_nav.behavior.state import State as EngineState
from flex_nav.compat.flexbe_core.core.exceptions import StateError
from flex_nav.exceptions import ConfigError


def merged(*groups: Iterable[str]) -> List[str]:
    """The names of ``groups`` in order, each once (FlexBE merges repeated outcomes and keys)."""
    return list(dict.fromkeys(name for group in groups for name in group))


def flexbe_path(state: Any) -> str:
    """FlexBE's path of a state: "" for a root, ``parent.path + "/" + name`` below it."""
    parent = state.parent
    return "" if parent is None else f"{flexbe_path(parent)}/{state.name}"


class State(EngineState):
    """Base of FlexBE's state classes (RosState, ..., EventState)."""

    def __init__(
        self,
        outcomes: Iterable[str] = (),
        input_keys: Iterable[str] = (),
        output_keys: Iterable[str] = (),
        io_keys: Iterable[str] = (),
    ) -> None:
        given = (("outcomes", outcomes), ("input_keys", input_keys), ("output_keys", output_keys), ("io_keys", io_keys))
        for what, values in given:
            if isinstance(values, str):  # merging would split the string into letters
                raise ConfigError(f"{type(self).__name__}: {what} must be a list of names, not the string {values!r}")
        super().__init__(
            outcomes=merged(outcomes),
            input_keys=merged(input_keys, io_keys),
            output_keys=merged(output_keys, io_keys),
        )

    @property
    def path(self) -> str:
        attached = self.__flex_nav_runtime__.path
        return attached if attached else flexbe_path(self)

    def set_name(self, value: str) -> None:
        """FlexBE's label setter: a state added to a container has its name (adding sets it)."""
        if self.name:
            raise StateError(f"Cannot change the name of a state! ({self.name!r} -> {value!r})")
        self.__flex_nav_runtime__.label = value

    def set_parent(self, value: Any) -> None:
        """FlexBE's parent setter: only the container that adds a state sets it."""
        if self.parent is not None or value is not None:
            raise StateError("Cannot change the parent of a state! (containers set it when they add the state)")


__all__ = ["State", "flexbe_path", "merged"]
