"""Helpers for tests that run commands and rostests against a private master (importable: pythonpath=test)."""

from __future__ import annotations

import os
import subprocess
from dataclasses import dataclass
from pathlib import Path

import pytest

from flex_nav.private_master import PrivateMaster

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


def run_command_bounded(
    argv: list[str], env: dict[str, str], timeout_s: float, cwd: Path = REPO_ROOT
) -> RostestOutcome:
    """Run ``argv`` in its own process group; on timeout kill the whole group and fail with its output."""
    with subprocess.Popen(
        argv, env=env, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True
    ) as proc:
        try:
            output, _ = proc.communicate(timeout=timeout_s)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, 9)
            output, _ = proc.communicate(timeout=5.0)
            pytest.fail(f"{' '.join(argv)} did not finish within {timeout_s} s; output:\n{output[-4000:]}")
    return RostestOutcome(proc.returncode, output)


def run_rostest(master: PrivateMaster, test_file: str, timeout_s: float = 180.0) -> RostestOutcome:
    return run_command_bounded(
        ["rostest", "--reuse-master", "flex_nav", test_file], env=master.env, timeout_s=timeout_s
    )
