"""pytest is the single test entry: pure unit tests (no master) and ROS tests against a private roscore.

Fixtures:
  ros_master  a fresh ``roscore -p <free port>`` with its own ROS_HOME, stopped by PID after the test.
Helpers for commands and rostests are in ``harness.py`` (``run_command_bounded``, ``run_rostest``).
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from flex_nav.testing.private_master import PrivateMaster


@pytest.fixture
def ros_master(tmp_path: Path) -> Iterator[PrivateMaster]:
    master = PrivateMaster(ros_home=tmp_path / "ros_home").start()
    try:
        yield master
    finally:
        master.stop()
