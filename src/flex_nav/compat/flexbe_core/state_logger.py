"""flexbe_core.state_logger: FlexBE's StateLogger, whose decorators and calls FlexBE code may use.

FlexBE writes structured state events to a log file; flex_nav publishes a behavior's transitions, requests and
logs through its runner instead, so the decorators return the class unchanged and the calls do nothing.
"""

from __future__ import annotations

from typing import Any, Callable, TypeVar

T = TypeVar("T")


def _keep(cls: T) -> T:
    return cls


class StateLogger:
    """FlexBE's state event logger (no-op here: flex_nav's runner reports what states do)."""

    enabled = False

    @staticmethod
    def initialize(*_args: Any, **_kwargs: Any) -> None:
        """FlexBE opens its log file here."""

    @staticmethod
    def shutdown() -> None:
        """FlexBE closes its log file here."""

    @staticmethod
    def log(*_args: Any, **_kwargs: Any) -> None:
        """FlexBE writes one structured event here."""

    @staticmethod
    def log_events(*_args: Any, **_kwargs: Any) -> Callable[[T], T]:
        return _keep

    @staticmethod
    def log_outcomes(*_args: Any, **_kwargs: Any) -> Callable[[T], T]:
        return _keep

    @staticmethod
    def log_userdata(*_args: Any, **_kwargs: Any) -> Callable[[T], T]:
        return _keep


__all__ = ["StateLogger"]
