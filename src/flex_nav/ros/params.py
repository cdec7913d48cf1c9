"""Reading private parameters with their type, range and choices checked when the node starts.

A bad value raises ConfigError naming the parameter, the value and what is valid, so a node dies at
start with a clear message instead of misbehaving later. The rules are :mod:`flex_nav.validation`'s; the
messages are worded for a parameter server (``parameter /relay/timeout = -1.0 is outside [0.0, 3600.0]``).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import Any

import rospy

from flex_nav import validation
from flex_nav.exceptions import ConfigError, choices_message
from flex_nav.ros.private_ns import private_name

_MISSING = object()


def _resolved(name: str) -> str:
    return rospy.resolve_name(private_name(name)) if name.startswith("~") else name


def param_float(
    name: str, default: float | None = None, minimum: float = -math.inf, maximum: float = math.inf
) -> float:
    """A finite float parameter within [minimum, maximum]; ``default`` None means required. What ``float()``
    takes counts as a number (a string such as "0.5" set with ``type="str"``, a bool)."""
    raw = _get(name, default)
    try:
        value = float(raw)
    except (TypeError, ValueError):
        raise ConfigError(f"parameter {_resolved(name)} = {raw!r} is not a number") from None
    if validation.number_problem(value, minimum=minimum, maximum=maximum) is not None:
        raise ConfigError(f"parameter {_resolved(name)} = {raw!r} is outside [{minimum}, {maximum}]")
    return value


def param_int(name: str, default: int | None = None, minimum: int | None = None, maximum: int | None = None) -> int:
    raw = _get(name, default)
    if validation.integer_problem(raw) is not None:
        raise ConfigError(f"parameter {_resolved(name)} = {raw!r} is not an integer")
    if validation.integer_problem(raw, minimum=minimum, maximum=maximum) is not None:
        raise ConfigError(f"parameter {_resolved(name)} = {raw!r} is outside [{minimum}, {maximum}]")
    return int(raw)


def param_bool(name: str, default: bool | None = None) -> bool:
    raw = _get(name, default)
    if validation.boolean_problem(raw) is not None:
        raise ConfigError(f"parameter {_resolved(name)} = {raw!r} is not true/false")
    return bool(raw)


def param_str(name: str, default: str | None = None, choices: Sequence[str] | None = None) -> str:
    raw = _get(name, default)
    if validation.text_problem(raw) is not None:
        raise ConfigError(f"parameter {_resolved(name)} = {raw!r} is not a string")
    if choices is not None and raw not in choices:
        raise ConfigError(choices_message(f"parameter {_resolved(name)}", raw, choices))
    return str(raw)


def _get(name: str, default: Any) -> Any:
    value = rospy.get_param(private_name(name), _MISSING if default is None else default)
    if value is _MISSING:
        raise ConfigError(f"required parameter {_resolved(name)} is not set")
    return value


def reject_unknown(namespace: str, known: Iterable[str]) -> None:
    """ConfigError if the parameter namespace (``"~"``, ``"~planner/"``, ...) holds a name not in ``known``.

    A misspelt parameter would otherwise be ignored silently and its default used; this names it and the
    valid names when the node starts.
    """
    key = namespace.rstrip("/") or namespace
    values = rospy.get_param(private_name(key), {})
    if not isinstance(values, dict):
        raise ConfigError(f"parameter {_resolved(key)} must be a dictionary, got {values!r}")
    valid = sorted(set(known))
    for name in sorted(values):
        if name not in valid:
            raise ConfigError(
                f"parameter {_resolved(key).rstrip('/')}/{name} is not a parameter of this node "
                f"(valid: {', '.join(valid)})"
            )
