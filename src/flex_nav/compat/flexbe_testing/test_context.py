"""flexbe_testing.test_context: the context a test case runs in (FlexBE's default one: nothing to start)."""

from __future__ import annotations

from typing import Any


class TestContext:
    """Default context of a test case: ``with context:``, ``verify()``, ``spin_once()``."""

    __test__ = False  # not a pytest test class

    def __enter__(self) -> TestContext:
        return self

    def __exit__(self, *_exc: Any) -> None:
        return None

    def verify(self) -> bool:
        return True

    def spin_once(self) -> None:
        return None

    def wait_for_finishing(self) -> None:
        return None

    @property
    def success(self) -> bool:
        return True


__all__ = ["TestContext"]
