#!/usr/bin/env python
# ruff: noqa: UP008  (written in FlexBE's / SMACH's own idiom on purpose)
from flexbe_core import EventState, Logger


class LogState(EventState):
    """
    Logs a message for the operator.

    -- text      string  The message.
    -- severity  int     Logger.REPORT_* level (default: hint).

    <= done              The message was logged.
    """

    def __init__(self, text, severity=Logger.REPORT_HINT):
        super(LogState, self).__init__(outcomes=['done'])
        self._text = text
        self._severity = severity

    def on_enter(self, userdata):
        Logger.log(self._text, self._severity)

    def execute(self, userdata):
        return 'done'
