"""Helpers for tests that run commands and rostests against a private master (importable: pythonpath=test)."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
from dataclasses import dataclass
from pathlib import Path
from xml.etree import ElementTree

import pytest

from flex_nav.testing.private_master import PrivateMaster

REPO_ROOT = Path(__file__).resolve().parent.parent
ROSTEST_DIR = REPO_ROOT / "test" / "rostest"


@dataclass
class RostestOutcome:
    returncode: int
    output: str

    @property
    def passed(self) -> bool:
        return self.returncode == 0 and "RESULT: SUCCESS" in self.output


def system_env() -> dict[str, str]:
    """The environment of a whole-system run started from a test: this repository's venv first on PATH, the
    package on ROS_PACKAGE_PATH, loopback ROS_IP (each run starts its own private master)."""
    env = dict(os.environ)
    env["PATH"] = f"{REPO_ROOT / '.venv' / 'bin'}{os.pathsep}{env.get('PATH', '')}"
    env["ROS_PACKAGE_PATH"] = f"{REPO_ROOT}{os.pathsep}{env.get('ROS_PACKAGE_PATH', '')}"
    env["ROS_IP"] = "127.0.0.1"
    return env


STOP_GRACE_S = 20.0  # [s] an interrupted run's time to stop what it started (SIGTERM) before its group is killed


def run_command_bounded(
    argv: list[str], env: dict[str, str], timeout_s: float, cwd: Path = REPO_ROOT
) -> RostestOutcome:
    """Run ``argv`` in its own process group; on timeout kill the whole group and fail with its output. Interrupted
    in between (Ctrl-C, pytest-timeout), it sends the command SIGTERM (runs stop what they started on it), kills
    the group if that does not end it within ``STOP_GRACE_S``, and re-raises: nothing is left running."""
    with subprocess.Popen(
        argv, env=env, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True
    ) as proc:
        try:
            output, _ = proc.communicate(timeout=timeout_s)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            output, _ = proc.communicate(timeout=5.0)
            pytest.fail(f"{' '.join(argv)} did not finish within {timeout_s} s; output:\n{output[-4000:]}")
        except BaseException:
            _stop_group(proc)
            raise
    return RostestOutcome(proc.returncode, output)


def _stop_group(proc: subprocess.Popen[str]) -> None:
    with contextlib.suppress(ProcessLookupError):
        os.killpg(proc.pid, signal.SIGTERM)
    try:
        proc.communicate(timeout=STOP_GRACE_S)  # reads on: a run blocked writing to a full pipe could not stop
    except subprocess.TimeoutExpired:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate(timeout=5.0)


ROSTEST_DEFAULT_TIME_LIMIT_S = 60.0  # [s] rostest's own limit of a <test> without time-limit
ROSTEST_MARGIN_S = 90.0  # [s] launching, and rostest's reporting after its own limit, on a loaded machine


def rostest_time_limit_s(test_file: str) -> float:
    """The largest ``time-limit`` [s] of the <test> tags in ``test/rostest/<test_file>``."""
    root = ElementTree.parse(ROSTEST_DIR / test_file).getroot()
    limits = [float(tag.get("time-limit", ROSTEST_DEFAULT_TIME_LIMIT_S)) for tag in root.iter("test")]
    return max(limits, default=ROSTEST_DEFAULT_TIME_LIMIT_S)


def run_rostest(master: PrivateMaster, test_file: str) -> RostestOutcome:
    """rostest on ``test_file``, killed only well after the file's own time limit (rostest reports that one)."""
    return run_command_bounded(
        ["rostest", "--reuse-master", "flex_nav", test_file], env=master.env,
        timeout_s=rostest_time_limit_s(test_file) + ROSTEST_MARGIN_S,
    )
