"""SMACH utilities: the shutdown check and the callback interface decorator.

``@cb_interface(outcomes=..., input_keys=..., output_keys=...)`` declares what a callback adds to the
state that calls it (a :class:`~flex_nav.compat.smach.state.CBState`, or smach_ros's action and
service states): extra outcomes and the userdata keys it reads and writes. :func:`has_smach_interface`
tells whether an object declares them.
"""

from __future__ import annotations

import functools
from typing import Any, Callable, Iterable, List, Optional, Tuple

from flex_nav.compat.smach._hooks import HOOKS
from flex_nav.exceptions import ConfigError, InvalidStateError


def is_shutdown() -> bool:
    """True once the check given to :func:`set_shutdown_check` says so (never, by default)."""
    return bool(HOOKS.shutdown())


def set_shutdown_check(cb: Callable[[], object]) -> None:
    """Containers stop between states (and preempt their children) once ``cb()`` is true."""
    if not callable(cb):
        raise ConfigError(f"set_shutdown_check needs a callable, got {cb!r}")
    HOOKS.shutdown = cb


def has_smach_interface(obj: object) -> bool:
    """True if ``obj`` declares outcomes and userdata keys (a SMACH state or a ``cb_interface`` callback)."""
    return (
        hasattr(obj, "get_registered_input_keys")
        and hasattr(obj, "get_registered_output_keys")
        and hasattr(obj, "get_registered_outcomes")
    )


def names(what: str, values: Optional[Iterable[str]], owner: str) -> List[str]:
    """Validated list of outcome / key names (a bare string is refused: it would be split into letters)."""
    if values is None:
        return []
    if isinstance(values, str):
        raise InvalidStateError(f"{owner}: {what} must be a list of names, not the string {values!r}")
    result = list(values)
    for value in result:
        if not isinstance(value, str) or not value:
            raise InvalidStateError(f"{owner}: {what} must be non-empty strings, got {value!r}")
    return result


def _ordered(values: Iterable[str]) -> Tuple[str, ...]:
    return tuple(dict.fromkeys(values))


class CBInterface:
    """A callback with a declared SMACH interface (outcomes it may return, keys it reads and writes).

    Calling it calls the callback. Decorating a method works too: the interface is kept on the bound
    method.
    """

    __name__: str  # the callback's, as functools.update_wrapper copies it (with its __doc__ and __wrapped__)

    def __init__(
        self,
        cb: Callable[..., Any],
        outcomes: Optional[Iterable[str]] = None,
        input_keys: Optional[Iterable[str]] = None,
        output_keys: Optional[Iterable[str]] = None,
        io_keys: Optional[Iterable[str]] = None,
    ) -> None:
        if not callable(cb):
            raise InvalidStateError(f"cb_interface needs a callable, got {cb!r}")
        owner = getattr(cb, "__name__", type(cb).__name__)
        io = names("io_keys", io_keys, owner)
        self._cb = cb
        self._outcomes = _ordered(names("outcomes", outcomes, owner))
        self._input_keys = _ordered([*names("input_keys", input_keys, owner), *io])
        self._output_keys = _ordered([*names("output_keys", output_keys, owner), *io])
        functools.update_wrapper(self, cb)

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return self._cb(*args, **kwargs)

    def __get__(self, obj: Any, owner: type) -> CBInterface:
        if obj is None:
            return self
        bound = getattr(self._cb, "__get__", None)
        if bound is None:
            return self
        return CBInterface(bound(obj, owner), self._outcomes, self._input_keys, self._output_keys)

    def get_registered_input_keys(self) -> Tuple[str, ...]:
        return self._input_keys

    def get_registered_output_keys(self) -> Tuple[str, ...]:
        return self._output_keys

    def get_registered_outcomes(self) -> Tuple[str, ...]:
        return self._outcomes

    def __repr__(self) -> str:
        return f"<CBInterface {getattr(self._cb, '__name__', self._cb)!r} outcomes={list(self._outcomes)}>"


class cb_interface:  # noqa: N801  (SMACH's name: used as a decorator)
    """Decorator: ``@cb_interface(outcomes=['aborted'], input_keys=['goal'])`` over a callback."""

    def __init__(
        self,
        outcomes: Optional[Iterable[str]] = None,
        input_keys: Optional[Iterable[str]] = None,
        output_keys: Optional[Iterable[str]] = None,
        io_keys: Optional[Iterable[str]] = None,
    ) -> None:
        self._outcomes = outcomes
        self._input_keys = input_keys
        self._output_keys = output_keys
        self._io_keys = io_keys

    def __call__(self, cb: Callable[..., Any]) -> CBInterface:
        return CBInterface(cb, self._outcomes, self._input_keys, self._output_keys, self._io_keys)


__all__ = ["CBInterface", "cb_interface", "has_smach_interface", "is_shutdown", "set_shutdown_check"]
