"""Autonomy levels: how much the robot may decide by itself (FlexBE's Off/Low/High/Full, 0..3).

Every transition of a behavior carries a *required* level. A transition fires by itself only when its
required level is strictly below the behavior's current autonomy; otherwise the outcome is *requested*
and waits for the operator (approve, force another outcome, or raise the autonomy). So:

- current autonomy ``OFF``: nothing fires by itself, the operator confirms every transition;
- a transition marked ``FULL``: never fires by itself, it always needs the operator;
- a transition marked ``OFF`` (the default): fires at any autonomy above ``OFF``.
"""

from __future__ import annotations

import enum

from flex_nav.exceptions import ConfigError, choices_message


class Autonomy(enum.IntEnum):
    """Autonomy level of a behavior (current) or of a transition (required)."""

    OFF = 0
    LOW = 1
    HIGH = 2
    FULL = 3

    @classmethod
    def parse(cls, value: object) -> Autonomy:
        """Accept an Autonomy, an int 0..3 or a name (``"off"``, ``"Low"``, ``"HIGH"``, ``"full"``)."""
        if isinstance(value, Autonomy):
            return value
        if isinstance(value, bool):  # bool is an int: refuse True/False explicitly
            raise ConfigError(choices_message("autonomy level", value, _CHOICES))
        if isinstance(value, int):
            try:
                return cls(value)
            except ValueError:
                raise ConfigError(choices_message("autonomy level", value, _CHOICES)) from None
        if isinstance(value, str):
            text = value.strip()
            if text in ("0", "1", "2", "3"):
                return cls(int(text))
            try:
                return cls[text.upper()]
            except KeyError:
                raise ConfigError(choices_message("autonomy level", value, _CHOICES)) from None
        raise ConfigError(choices_message("autonomy level", value, _CHOICES))


_CHOICES = ("off", "low", "high", "full", 0, 1, 2, 3)
