"""flexbe_testing.data_provider: FlexBE's special values in test cases: ``"None"`` is None, ``"lambda ..."`` is
evaluated to a function, ``"//text"`` is ``"/text"``. Bag files as a data source (``data:``) need rosbag and are
not supported here (:class:`~flex_nav.exceptions.ConfigError`)."""

from __future__ import annotations

from typing import Any, Optional

from flex_nav.exceptions import ConfigError


class DataProvider:
    """Parses the values of a test case."""

    def __init__(self, bagfile: Optional[str] = None) -> None:
        if bagfile is not None:
            raise ConfigError(f"test data from a bag file ({bagfile}) is not supported by flex_nav's flexbe_testing")

    def parse(self, value: Any) -> Any:
        if not isinstance(value, str):
            return value
        if value == "None":
            return None
        if value.startswith("lambda "):
            return eval(value, {"__builtins__": __builtins__})  # noqa: S307  (FlexBE's contract: test authors' lambdas)
        if len(value) > 1 and value[:2] == "//":
            return value[1:]
        return value


__all__ = ["DataProvider"]
