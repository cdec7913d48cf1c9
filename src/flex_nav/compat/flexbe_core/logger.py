"""FlexBE's Logger: behavior logs for the operator, routed to the behavior that is running (or being built).

``Logger.loginfo("...")`` is a static call, so FlexBE sends it to one process-wide topic. Here it
goes to the log of the behavior whose states are being ticked (or constructed) in the calling thread
(:func:`flex_nav.behavior.current_context`): its hooks reach that behavior's operator interface and
its Python logger. Outside any behavior the message goes to the Python logger ``flex_nav.compat.flexbe``.

Severities are FlexBE's (``REPORT_INFO`` 0, ``REPORT_WARN`` 1, ``REPORT_HINT`` 2, ``REPORT_ERROR`` 3,
``REPORT_DEBUG`` 10); an unknown one is logged as debug with a note, as FlexBE does. The ``*_throttle``
variants log a given (severity, text) at most once per ``period`` [s] of the behavior's clock; their
memory belongs to the behavior (a weak map keyed by its context), so two behaviors never suppress each
other's messages. Outside a behavior the throttle variants log every call.
"""

from __future__ import annotations

import logging
import weakref
from typing import Any, Dict

from flex_nav.behavior.context import BehaviorContext, current_context
from flex_nav.behavior.events import LogLevel

_LOGGER = logging.getLogger("flex_nav.compat.flexbe")
_PY_LEVELS = {0: logging.INFO, 1: logging.WARNING, 2: logging.INFO, 3: logging.ERROR, 10: logging.DEBUG}

# per-behavior throttle memory: (severity, text) -> last time logged [s, behavior clock]
_THROTTLE: weakref.WeakKeyDictionary[BehaviorContext, Dict[str, float]] = weakref.WeakKeyDictionary()


def _format(text: Any, args: Any) -> str:
    return str(text) % args if args else str(text)


class Logger:
    """Static logging calls of FlexBE states and behaviors."""

    REPORT_INFO = 0
    REPORT_WARN = 1
    REPORT_HINT = 2
    REPORT_ERROR = 3
    REPORT_DEBUG = 10

    LOGGING_TOPIC = "flexbe/log"

    @staticmethod
    def initialize(*_args: Any) -> None:
        """FlexBE creates its log publisher here; flex_nav's runner publishes behavior logs itself."""

    @staticmethod
    def log(text: Any, severity: int) -> None:
        """Log ``text`` with a FlexBE severity to the current behavior (and the Python logger)."""
        message = str(text)
        try:
            level = LogLevel(severity)
        except ValueError:
            level = LogLevel.DEBUG
            message = f"{message} (unknown log level {severity!r})"
        ctx = current_context()
        if ctx is not None:
            ctx.log(level, message)
        else:
            _LOGGER.log(_PY_LEVELS.get(int(level), logging.DEBUG), "%s", message)

    @staticmethod
    def log_throttle(period: float, text: Any, severity: int) -> None:
        """Like :meth:`log`, but a given (severity, text) at most once per ``period`` [s]."""
        ctx = current_context()
        if ctx is not None:
            memory = _THROTTLE.setdefault(ctx, {})
            key = f"{severity}_{text}"
            now = ctx.clock.now()
            last = memory.get(key)
            if last is not None and now - last <= period:
                return
            memory[key] = now
        Logger.log(text, severity)

    @staticmethod
    def local(text: Any, severity: int) -> None:
        """Log to the Python logger only (not to the operator)."""
        level = _PY_LEVELS.get(severity, logging.DEBUG) if isinstance(severity, int) else logging.DEBUG
        _LOGGER.log(level, "%s", str(text))

    @staticmethod
    def logdebug(text: Any, *args: Any) -> None:
        Logger.log(_format(text, args), Logger.REPORT_DEBUG)

    @staticmethod
    def loginfo(text: Any, *args: Any) -> None:
        Logger.log(_format(text, args), Logger.REPORT_INFO)

    @staticmethod
    def logwarn(text: Any, *args: Any) -> None:
        Logger.log(_format(text, args), Logger.REPORT_WARN)

    @staticmethod
    def loghint(text: Any, *args: Any) -> None:
        Logger.log(_format(text, args), Logger.REPORT_HINT)

    @staticmethod
    def logerr(text: Any, *args: Any) -> None:
        Logger.log(_format(text, args), Logger.REPORT_ERROR)

    @staticmethod
    def logdebug_throttle(period: float, text: Any, *args: Any) -> None:
        Logger.log_throttle(period, _format(text, args), Logger.REPORT_DEBUG)

    @staticmethod
    def loginfo_throttle(period: float, text: Any, *args: Any) -> None:
        Logger.log_throttle(period, _format(text, args), Logger.REPORT_INFO)

    @staticmethod
    def logwarn_throttle(period: float, text: Any, *args: Any) -> None:
        Logger.log_throttle(period, _format(text, args), Logger.REPORT_WARN)

    @staticmethod
    def loghint_throttle(period: float, text: Any, *args: Any) -> None:
        Logger.log_throttle(period, _format(text, args), Logger.REPORT_HINT)

    @staticmethod
    def logerr_throttle(period: float, text: Any, *args: Any) -> None:
        Logger.log_throttle(period, _format(text, args), Logger.REPORT_ERROR)

    @staticmethod
    def localdebug(text: Any, *args: Any) -> None:
        Logger.local(_format(text, args), Logger.REPORT_DEBUG)

    @staticmethod
    def localinfo(text: Any, *args: Any) -> None:
        Logger.local(_format(text, args), Logger.REPORT_INFO)

    @staticmethod
    def localwarn(text: Any, *args: Any) -> None:
        Logger.local(_format(text, args), Logger.REPORT_WARN)

    @staticmethod
    def localerr(text: Any, *args: Any) -> None:
        Logger.local(_format(text, args), Logger.REPORT_ERROR)

    # FlexBE code also calls these (rospy-style names)
    warning = logwarn
    error = logerr
    info = loginfo


__all__ = ["Logger"]
