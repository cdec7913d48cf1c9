"""Constructor-time checks of state parameters: each error names the state, the parameter and the bad value.

A behavior file is validated when it is loaded (constructors run then), so a typo in a YAML parameter is
reported before the robot moves, never halfway through a run.
"""

from __future__ import annotations

import math
from typing import Any, Collection, List, Optional

from flex_nav.exceptions import ConfigError, choices_message
from flex_nav.nav.control.topic_name import topic_name_problem

# Sanity bounds of the motion states' speed parameters: far above what the supported bases drive (0.3-0.7 m/s,
# 1.5-2 rad/s in config/), so a value beyond them is a unit mistake (cm/s, deg/s), refused at load time.
MAX_LINEAR_MPS = 1.0  # [m/s]
MAX_ANGULAR_RADPS = 3.2  # [rad/s]


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
    """``value`` as a finite float within the bounds (``positive``: strictly > 0)."""
    unit_text = f" {unit}" if unit else ""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ConfigError(f"{owner}: {name} must be a finite number{unit_text}, got {value!r}")
    if positive and not value > 0.0:
        raise ConfigError(f"{owner}: {name} must be > 0{unit_text}, got {value!r}")
    if minimum is not None and value < minimum:
        raise ConfigError(f"{owner}: {name} must be >= {minimum}{unit_text}, got {value!r}")
    if maximum is not None and value > maximum:
        raise ConfigError(f"{owner}: {name} must be <= {maximum}{unit_text}, got {value!r}")
    return float(value)


def name(owner: str, what: str, value: Any, *, allow_empty: bool = False) -> str:
    """A topic or action name: a string without blanks (empty only if ``allow_empty``)."""
    if not isinstance(value, str):
        raise ConfigError(f"{owner}: {what} must be a string, got {value!r}")
    if not value and not allow_empty:
        raise ConfigError(f"{owner}: {what} must not be empty")
    if value != value.strip() or any(c.isspace() for c in value):
        raise ConfigError(f"{owner}: {what} must not contain blanks, got {value!r}")
    problem = topic_name_problem(value) if value else None
    if problem is not None:
        raise ConfigError(f"{owner}: {what}: {problem}")
    return value


def text(owner: str, what: str, value: Any) -> str:
    if not isinstance(value, str):
        raise ConfigError(f"{owner}: {what} must be a string, got {value!r}")
    return value


def choice(owner: str, what: str, value: Any, valid: Collection[str]) -> str:
    if value not in valid:
        raise ConfigError(choices_message(f"{owner}: {what}", value, valid))
    return str(value)


def names(owner: str, what: str, value: Any, *, allow_empty: bool = True) -> List[str]:
    """A list of distinct non-empty names (a single string is refused: ``[a]``, not ``a``)."""
    if isinstance(value, str) or not isinstance(value, (list, tuple)):
        raise ConfigError(f"{owner}: {what} must be a list of names, got {value!r}")
    result = [name(owner, f"{what} item", item) for item in value]
    if not result and not allow_empty:
        raise ConfigError(f"{owner}: {what} must name at least one item")
    dupes = sorted({n for n in result if result.count(n) > 1})
    if dupes:
        raise ConfigError(f"{owner}: {what} repeats {', '.join(dupes)}")
    return result
