"""Small generic states that ship with the engine (no ROS): wait, log, decide, calculate, compare.

They are usable from YAML (all parameters are plain data: no callables, nothing is evaluated) and
serve the engine's tests and examples. Navigation states live in ``flex_nav_states``.
"""

from __future__ import annotations

import math
import operator
from typing import Callable, Dict, List, Optional, Sequence

from flex_nav.behavior.events import LogLevel
from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import ConfigError, choices_message


class Wait(State):
    """Waits until a time has passed on the behavior's clock.

    -- wait_time_s  float  [s] How long to wait after entering (>= 0).

    <= done  The time has passed.
    """

    def __init__(self, wait_time_s: float) -> None:
        super().__init__(outcomes=["done"])
        if isinstance(wait_time_s, bool) or not isinstance(wait_time_s, (int, float)) or not wait_time_s >= 0.0:
            raise ConfigError(f"Wait: wait_time_s must be a number >= 0 [s], got {wait_time_s!r}")
        if math.isinf(wait_time_s):
            raise ConfigError("Wait: wait_time_s must be finite")
        self._wait_time_s = float(wait_time_s)
        self._end_s = 0.0

    def on_enter(self, userdata: UserDataView) -> None:
        self._end_s = self.now_s() + self._wait_time_s

    def execute(self, userdata: UserDataView) -> Optional[str]:
        return "done" if self.now_s() >= self._end_s else None


_SEVERITIES = {"info": LogLevel.INFO, "warn": LogLevel.WARN, "hint": LogLevel.HINT, "error": LogLevel.ERROR}


class Log(State):
    """Logs a message for the operator when entered, then finishes.

    -- text      str  The message.
    -- severity  str  One of info, warn, hint, error.

    <= done  The message was logged.
    """

    def __init__(self, text: str, severity: str = "info") -> None:
        super().__init__(outcomes=["done"])
        if not isinstance(text, str):
            raise ConfigError(f"Log: text must be a string, got {text!r}")
        if severity not in _SEVERITIES:
            raise ConfigError(choices_message("Log: severity", severity, _SEVERITIES))
        self._text = text
        self._level = _SEVERITIES[severity]

    def on_enter(self, userdata: UserDataView) -> None:
        self.log(self._level, self._text)

    def execute(self, userdata: UserDataView) -> Optional[str]:
        return "done"


class Decision(State):
    """Returns the outcome chosen by a parameter (a fixed branch, useful in tests and variants).

    -- outcomes  list  The outcomes this state registers.
    -- choice    str   The outcome it returns; one of outcomes.

    <= {outcomes}  The chosen outcome.
    """

    def __init__(self, outcomes: Sequence[str], choice: str) -> None:
        super().__init__(outcomes=list(outcomes))
        if choice not in self.outcomes:
            raise ConfigError(choices_message("Decision: choice", choice, self.outcomes))
        self._choice = choice

    def execute(self, userdata: UserDataView) -> Optional[str]:
        return self._choice


_OPERATIONS: Dict[str, Callable[[float, float], float]] = {
    "add": operator.add,
    "subtract": operator.sub,
    "multiply": operator.mul,
    "divide": operator.truediv,
    "min": min,
    "max": max,
    "set": lambda _value, operand: operand,
}


class Calculation(State):
    """Applies a named arithmetic operation to a userdata value: output = input <operation> operand.

    -- operation  str    One of add, subtract, multiply, divide, min, max, set.
    -- operand    float  The second operand (not 0 for divide).

    ># input_value   float  The first operand.
    #> output_value  float  The result.

    <= done  The result was written.
    """

    def __init__(self, operation: str, operand: float = 0.0) -> None:
        super().__init__(outcomes=["done"], input_keys=["input_value"], output_keys=["output_value"])
        if operation not in _OPERATIONS:
            raise ConfigError(choices_message("Calculation: operation", operation, _OPERATIONS))
        if isinstance(operand, bool) or not isinstance(operand, (int, float)):
            raise ConfigError(f"Calculation: operand must be a number, got {operand!r}")
        if operation == "divide" and operand == 0:
            raise ConfigError("Calculation: cannot divide by an operand of 0")
        self._operation = _OPERATIONS[operation]
        self._operand = operand

    def execute(self, userdata: UserDataView) -> Optional[str]:
        userdata.output_value = self._operation(userdata.input_value, self._operand)
        return "done"


_COMPARISONS: Dict[str, Callable[[float, float], bool]] = {
    "<": operator.lt,
    "<=": operator.le,
    "==": operator.eq,
    "!=": operator.ne,
    ">=": operator.ge,
    ">": operator.gt,
}


class Compare(State):
    """Compares a userdata value with a threshold: ``value <comparison> threshold``.

    -- comparison  str    One of <, <=, ==, !=, >=, >.
    -- threshold   float  The right-hand side.

    ># value  float  The left-hand side.

    <= met      The comparison holds.
    <= not_met  It does not.
    """

    def __init__(self, comparison: str, threshold: float) -> None:
        super().__init__(outcomes=["met", "not_met"], input_keys=["value"])
        if comparison not in _COMPARISONS:
            raise ConfigError(choices_message("Compare: comparison", comparison, _COMPARISONS))
        if isinstance(threshold, bool) or not isinstance(threshold, (int, float)):
            raise ConfigError(f"Compare: threshold must be a number, got {threshold!r}")
        self._compare = _COMPARISONS[comparison]
        self._threshold = threshold

    def execute(self, userdata: UserDataView) -> Optional[str]:
        return "met" if self._compare(userdata.value, self._threshold) else "not_met"


BUILTIN_STATES: List[type] = [Wait, Log, Decision, Calculation, Compare]
