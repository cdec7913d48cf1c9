"""Every ``test/rostest/*.test`` file, run with rostest against a private master (one per file)."""

from __future__ import annotations

import pytest
from harness import ROSTEST_DIR, run_rostest

from flex_nav.testing.private_master import PrivateMaster

ROSTEST_FILES = sorted(p.name for p in ROSTEST_DIR.glob("*.test"))


def test_rostest_files_exist() -> None:
    assert "actions.test" in ROSTEST_FILES


@pytest.mark.ros
@pytest.mark.parametrize("test_file", ROSTEST_FILES)
def test_rostest_file(ros_master: PrivateMaster, test_file: str) -> None:
    outcome = run_rostest(ros_master, test_file)
    assert outcome.passed, f"rostest {test_file} failed (exit {outcome.returncode}):\n{outcome.output[-6000:]}"
    assert "FAILURES: 0" in outcome.output and "ERRORS: 0" in outcome.output
