"""The parameter checks every layer uses: numbers (finite, bounds, > 0, unit), integers, booleans, strings,
ROS names and choices, each raising :class:`ConfigError` that names the owner, the parameter, the bad value and
what is valid, e.g. ``MoveDistanceState: speed_mps must be <= 1.0 [m/s], got 20.0``.

Owners are a state (``MoveDistanceState``), a parameter set (``planner``, ``pure pursuit``) or a file
(``lab.yaml``, with a dotted path as the parameter). The ``*_problem`` predicates hold the rules themselves and
return the rule a value breaks (``"must be > 0"``) or None, for an adapter that words its messages its own way
(the ROS parameter reader: ``parameter ~timeout = -1.0 is outside [0.0, 3600.0]``). No rospy here: the pure core,
the states and the simulator validate with this module.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any, Collection, List, Mapping, Optional, Tuple, Type, TypeVar

from flex_nav.exceptions import ConfigError, choices_message
from flex_nav.nav.control.topic_name import topic_name_problem

P = TypeVar("P")

SHOWN_CHARS = 80  # a bad value longer than this (repr) is cut in messages


def shown(value: object) -> str:
    """``repr(value)``, cut to :data:`SHOWN_CHARS` characters."""
    text = repr(value)
    return text if len(text) <= SHOWN_CHARS else text[: SHOWN_CHARS - 3] + "..."


# --- the rules -----------------------------------------------------------------------------------------------------


def number_problem(
    value: object, *, minimum: Optional[float] = None, maximum: Optional[float] = None, positive: bool = False
) -> Optional[str]:
    """The rule ``value`` breaks, or None: a finite int or float (not a bool), > 0 if ``positive``, within
    [``minimum``, ``maximum``]."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        return "must be a finite number"
    if positive and not value > 0.0:
        return "must be > 0"
    if minimum is not None and value < minimum:
        return f"must be >= {minimum}"
    if maximum is not None and value > maximum:
        return f"must be <= {maximum}"
    return None


def integer_problem(value: object, *, minimum: Optional[int] = None, maximum: Optional[int] = None) -> Optional[str]:
    """The rule ``value`` breaks, or None: an int (not a bool) within [``minimum``, ``maximum``]."""
    if (
        isinstance(value, bool)
        or not isinstance(value, int)
        or (minimum is not None and value < minimum)
        or (maximum is not None and value > maximum)
    ):
        if minimum is not None and maximum is not None:
            return f"must be an integer in {minimum}..{maximum}"
        if minimum is not None:
            return f"must be an integer >= {minimum}"
        if maximum is not None:
            return f"must be an integer <= {maximum}"
        return "must be an integer"
    return None


def boolean_problem(value: object) -> Optional[str]:
    """The rule ``value`` breaks, or None: true or false (not 0, 1 or a string)."""
    return None if isinstance(value, bool) else "must be true or false"


def text_problem(value: object) -> Optional[str]:
    """The rule ``value`` breaks, or None: a string."""
    return None if isinstance(value, str) else "must be a string"


# --- the checks: value back, or ConfigError ------------------------------------------------------------------------


def number(
    owner: str,
    name: str,
    value: Any,
    *,
    minimum: Optional[float] = None,
    maximum: Optional[float] = None,
    positive: bool = False,
    unit: str = "",
) -> float:
    """``value`` as a finite float within the bounds (``positive``: strictly > 0); ``unit`` (``"[m/s]"``) goes
    into the message."""
    problem = number_problem(value, minimum=minimum, maximum=maximum, positive=positive)
    if problem is not None:
        unit_text = f" {unit}" if unit else ""
        raise ConfigError(f"{owner}: {name} {problem}{unit_text}, got {shown(value)}")
    return float(value)


def integer(owner: str, name: str, value: Any, *, minimum: Optional[int] = None, maximum: Optional[int] = None) -> int:
    """``value`` as an int within the bounds (a bool or a float such as 2.0 is refused)."""
    problem = integer_problem(value, minimum=minimum, maximum=maximum)
    if problem is not None:
        raise ConfigError(f"{owner}: {name} {problem}, got {shown(value)}")
    return int(value)


def boolean(owner: str, name: str, value: Any) -> bool:
    problem = boolean_problem(value)
    if problem is not None:
        raise ConfigError(f"{owner}: {name} {problem}, got {shown(value)}")
    return bool(value)


def text(owner: str, name: str, value: Any) -> str:
    problem = text_problem(value)
    if problem is not None:
        raise ConfigError(f"{owner}: {name} {problem}, got {shown(value)}")
    return str(value)


def name(owner: str, what: str, value: Any, *, allow_empty: bool = False) -> str:
    """A topic or action name: a legal ROS graph name (:mod:`flex_nav.nav.control.topic_name`), empty only if
    ``allow_empty``."""
    if not isinstance(value, str):
        raise ConfigError(f"{owner}: {what} must be a string, got {shown(value)}")
    if not value and not allow_empty:
        raise ConfigError(f"{owner}: {what} must not be empty")
    if value != value.strip() or any(c.isspace() for c in value):
        raise ConfigError(f"{owner}: {what} must not contain blanks, got {shown(value)}")
    problem = topic_name_problem(value) if value else None
    if problem is not None:
        raise ConfigError(f"{owner}: {what}: {problem}")
    return value


def choice(owner: str, what: str, value: Any, valid: Collection[str]) -> str:
    """One of ``valid``; the message lists them (:func:`flex_nav.exceptions.choices_message`)."""
    if value not in valid:
        raise ConfigError(choices_message(f"{owner}: {what}", value, valid))
    return str(value)


def names(owner: str, what: str, value: Any, *, allow_empty: bool = True) -> List[str]:
    """A list of distinct legal names (a single string is refused: ``[a]``, not ``a``)."""
    if isinstance(value, str) or not isinstance(value, (list, tuple)):
        raise ConfigError(f"{owner}: {what} must be a list of names, got {shown(value)}")
    result = [name(owner, f"{what} item", item) for item in value]
    if not result and not allow_empty:
        raise ConfigError(f"{owner}: {what} must name at least one item")
    dupes = sorted({n for n in result if result.count(n) > 1})
    if dupes:
        raise ConfigError(f"{owner}: {what} repeats {', '.join(dupes)}")
    return result


def dataclass_from_mapping(cls: Type[P], values: Mapping[str, Any], owner: str) -> P:
    """A parameter dataclass from a dict (e.g. a node's private ROS parameters). ``owner`` (a node name) starts the
    message of an unknown key, which lists the valid names. An integer given for a ``float`` field is taken (YAML
    and rosparam write ``1`` for ``1.0``); everything else is left to the dataclass's own checks."""
    kinds = {f.name: f.type for f in dataclasses.fields(cls)}  # type: ignore[arg-type]
    for key in values:
        if key not in kinds:
            raise ConfigError(choices_message(f"{owner}: parameter", key, list(kinds)))
    converted = {
        key: float(value) if kinds[key] in ("float", float) and isinstance(value, int) and not isinstance(value, bool)
        else value
        for key, value in values.items()
    }
    try:
        return cls(**converted)
    except ConfigError as err:
        raise ConfigError(f"{owner}: {err}") from err


def planar_pose(owner: str, what: str, value: Any) -> Tuple[float, float, float]:
    """``value`` as a finite (x [m], y [m], yaw [rad]); ConfigError naming ``what`` and the value otherwise."""
    try:
        values = tuple(float(v) for v in value)
    except (TypeError, ValueError) as err:
        raise ConfigError(f"{owner}: {what} must be (x [m], y [m], yaw [rad]), got {value!r}") from err
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise ConfigError(f"{owner}: {what} must be a finite (x [m], y [m], yaw [rad]), got {value!r}")
    return values[0], values[1], values[2]
