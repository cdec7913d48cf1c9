"""LogState: log a message for the operator, optionally with userdata values filled in."""

from __future__ import annotations

import re
from typing import Dict, Optional, Sequence

from flex_nav.behavior.events import LogLevel
from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView, unwrap
from flex_nav.exceptions import ConfigError
from flex_nav_states import validation
from flex_nav_states.messages import describe

SEVERITIES: Dict[str, LogLevel] = {
    "info": LogLevel.INFO,
    "warn": LogLevel.WARN,
    "hint": LogLevel.HINT,
    "error": LogLevel.ERROR,
    "debug": LogLevel.DEBUG,
}
_PLACEHOLDER = re.compile(r"\{([A-Za-z_][A-Za-z0-9_]*)\}")


class LogState(State):
    """Logs a message for the operator when entered, then finishes at once.

    ``{key}`` in the text is replaced by a short description of userdata ``key`` (poses as (x, y, yaw),
    paths as size and length, other values as text); every placeholder must be listed in ``keys``. Nothing
    is evaluated: only plain ``{name}`` placeholders are recognised.

    -- text      str   The message, e.g. "goal {goal} reached".
    -- severity  str   One of info, warn, hint, error, debug.
    -- keys      list  Userdata keys used in the text; they become the state's input keys.

    <= done  The message was logged.
    """

    def __init__(self, text: str = "", severity: str = "info", keys: Sequence[str] = ()) -> None:
        owner = type(self).__name__
        key_list = validation.names(owner, "keys", keys)
        super().__init__(outcomes=["done"], input_keys=key_list)
        self._text = validation.text(owner, "text", text)
        self._level = SEVERITIES[validation.choice(owner, "severity", severity, SEVERITIES)]
        used = set(_PLACEHOLDER.findall(self._text))
        unknown = sorted(used - set(key_list))
        if unknown:
            raise ConfigError(
                f"{owner}: text uses {', '.join('{' + k + '}' for k in unknown)} not listed in keys "
                f"(keys: {', '.join(key_list) or 'none'})"
            )

    def on_enter(self, userdata: UserDataView) -> None:
        def fill(match: re.Match[str]) -> str:
            return describe(unwrap(userdata[match.group(1)]))

        self.log(self._level, _PLACEHOLDER.sub(fill, self._text))

    def execute(self, userdata: UserDataView) -> Optional[str]:
        return "done"
