"""SMACH's logging functions: ``loginfo``, ``logwarn``, ``logerr``, ``logdebug`` and ``set_loggers``.

Unlike SMACH (which rebinds module attributes), these functions stay the same objects and forward to
the loggers last given to :func:`set_loggers`, so ``from smach import loginfo`` done before
``set_loggers`` still reaches the new logger.
"""

from __future__ import annotations

from typing import Callable

from flex_nav.compat.smach._hooks import HOOKS
from flex_nav.exceptions import ConfigError


def loginfo(msg: object) -> None:
    HOOKS.info(str(msg))


def logwarn(msg: object) -> None:
    HOOKS.warn(str(msg))


def logdebug(msg: object) -> None:
    HOOKS.debug(str(msg))


def logerr(msg: object) -> None:
    HOOKS.error(str(msg))


def set_loggers(
    info: Callable[[str], object],
    warn: Callable[[str], object],
    debug: Callable[[str], object],
    error: Callable[[str], object],
) -> None:
    """Send SMACH's messages to these functions (SMACH's argument order: info, warn, debug, error)."""
    for name, fn in (("info", info), ("warn", warn), ("debug", debug), ("error", error)):
        if not callable(fn):
            raise ConfigError(f"set_loggers: the {name} logger must be callable, got {fn!r}")
    HOOKS.info, HOOKS.warn, HOOKS.debug, HOOKS.error = info, warn, debug, error


__all__ = ["logdebug", "logerr", "loginfo", "logwarn", "set_loggers"]
