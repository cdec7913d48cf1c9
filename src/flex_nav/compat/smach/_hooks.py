"""Where SMACH's log messages go and how it detects shutdown: process-wide settings, as in SMACH.

smach_ros calls ``smach.set_loggers(rospy.loginfo, rospy.logwarn, rospy.logdebug, rospy.logerr)`` and
``smach.set_shutdown_check(rospy.is_shutdown)`` once at import. These two settings configure the
process (like Python's logging configuration) and hold no state of any running state machine, so they
stay process-wide here too; everything a running container owns lives in the container.
Defaults: Python logging under ``flex_nav.compat.smach``; never shut down.
"""

from __future__ import annotations

import logging
from typing import Callable

LOGGER = logging.getLogger("flex_nav.compat.smach")

LogFn = Callable[[str], object]


def _never() -> bool:
    return False


class Hooks:
    """The four loggers and the shutdown check (one instance, :data:`HOOKS`)."""

    __slots__ = ("debug", "error", "info", "shutdown", "warn")

    def __init__(self) -> None:
        self.info: LogFn = LOGGER.info
        self.warn: LogFn = LOGGER.warning
        self.debug: LogFn = LOGGER.debug
        self.error: LogFn = LOGGER.error
        self.shutdown: Callable[[], object] = _never

    def info_enabled(self) -> bool:
        """False only when the default info logger would drop the message (lets callers skip formatting)."""
        return self.info != LOGGER.info or LOGGER.isEnabledFor(logging.INFO)

    def debug_enabled(self) -> bool:
        return self.debug != LOGGER.debug or LOGGER.isEnabledFor(logging.DEBUG)


HOOKS = Hooks()
