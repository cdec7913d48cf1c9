"""The console's typed errors: a refused browser command, a structure that cannot be read, a graph not drawn.

They extend the families of :mod:`flex_nav.exceptions` (a refusal and a bad structure are ConfigErrors, a missing
or failing Graphviz is a NotReadyError), so callers that catch those keep working.
"""

from __future__ import annotations

from typing import Optional, Sequence

from flex_nav.exceptions import ConfigError, NotReadyError


class CommandRefused(ConfigError):  # noqa: N818  (a refusal, not a crash: the page shows its reason)
    """A command from the browser that does not reach the runner. ``field`` names what was wrong (``command``,
    ``path``, ``outcome``, ``level``, ``behavior``, ``parameters.NAME``, ``robot``, ...), ``choices`` the valid
    values when there is a fixed set; the message says both."""

    def __init__(self, message: str, field: str = "", choices: Optional[Sequence[object]] = None) -> None:
        super().__init__(message)
        self.field = field
        self.choices = tuple(choices) if choices is not None else None


class StructureError(ConfigError):
    """A runner's ``~structure`` JSON that does not follow the schema of :mod:`flex_nav.behavior.structure`."""


class GraphvizError(NotReadyError):
    """Graphviz's ``dot`` is missing or failed to lay out a graph."""


class MapViewError(ConfigError):
    """A map the console does not show (its size or resolution), or an overlay of an unknown kind."""


class UserdataError(ConfigError):
    """A runner's ``~userdata`` JSON that does not follow the schema of :mod:`flex_nav.behavior.userdata_summary`."""
