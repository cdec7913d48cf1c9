"""The typed exceptions of flex_nav.

Every error flex_nav raises on purpose derives from :class:`FlexNavError`, so a caller can catch
the family, and each subclass says what kind of failure it is. Messages name the bad value and,
where there is a fixed set, the valid choices (see :func:`choices_message`). Causes are chained
with ``raise ... from err``.
"""

from __future__ import annotations

from collections.abc import Iterable


class FlexNavError(Exception):
    """Base class of all flex_nav errors."""


class ConfigError(FlexNavError, ValueError):
    """A parameter, file or argument has a bad value (found when loading or constructing)."""


class NotReadyError(FlexNavError):
    """Something needed is not there yet (no master, no server, no message, no transform)."""


class TimedOutError(FlexNavError):
    """A bounded wait ran out."""


class InstallError(FlexNavError):
    """The installation is incomplete (e.g. the action classes were not generated)."""


def choices_message(what: str, bad: object, valid: Iterable[object]) -> str:
    """Format ``"<what> 'bad' is not valid (valid: a, b, c)"`` with the choices sorted as given."""
    listed = ", ".join(repr(v) if not isinstance(v, str) else v for v in valid)
    return f"{what} {bad!r} is not valid (valid: {listed or 'none'})"
