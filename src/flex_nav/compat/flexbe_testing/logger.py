"""flexbe_testing.logger: what the Tester prints for each case (FlexBE's format, plain text)."""

from __future__ import annotations

import logging

_LOG = logging.getLogger("flex_nav.compat.flexbe_testing")


class Logger:
    """Static printing helpers of the Tester."""

    _counter_value = 0

    @classmethod
    def print_positive(cls, text: object) -> None:
        _LOG.info("  + %s", text)

    @classmethod
    def print_negative(cls, text: object) -> None:
        _LOG.warning("  - %s", text)

    @classmethod
    def print_title(cls, test_name: str, test_class: str, result: object = None) -> None:
        cls._counter_value += 1
        shown = f" > {result}" if result is not None else ""
        _LOG.info("#%2d %s (%s%s)", cls._counter_value, test_name, test_class, shown)

    @classmethod
    def print_result(cls, test_name: str, success: bool) -> None:
        _LOG.info(">>> %s %s!", test_name, "completed" if success else "failed")

    @classmethod
    def print_failure(cls, text: object) -> None:
        _LOG.error(">>> %s", text)

    @classmethod
    def print_error(cls, text: object) -> None:
        _LOG.warning("    %s", text)


__all__ = ["Logger"]
