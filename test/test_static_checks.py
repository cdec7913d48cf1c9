"""ruff and mypy as tests, so the single pytest run also fails on lint or type errors."""

from __future__ import annotations

import os
import sys

import pytest
from harness import REPO_ROOT, run_command_bounded

VENV_BIN = REPO_ROOT / ".venv" / "bin"


def test_ruff_clean() -> None:
    outcome = run_command_bounded([str(VENV_BIN / "ruff"), "check", "--no-cache", "."], env=_env(), timeout_s=300)
    assert outcome.returncode == 0, f"ruff found problems:\n{outcome.output[-8000:]}"


@pytest.mark.parametrize(
    "targets",
    [
        ["-p", "flex_nav", "-p", "flex_nav_states", "-p", "flex_nav_sim", "-p", "tools"],
        sorted(str(p.relative_to(REPO_ROOT)) for p in (REPO_ROOT / "bench").glob("*.py")),  # scripts, not a package
    ],
    ids=["packages", "bench"],
)
def test_mypy_clean(targets: list[str]) -> None:
    outcome = run_command_bounded([sys.executable, "-m", "mypy", *targets], env=_env(), timeout_s=600)
    assert outcome.returncode == 0, f"mypy found problems:\n{outcome.output[-8000:]}"
    assert "Success" in outcome.output


def test_layers_kept() -> None:
    # the contracts in pyproject.toml ([tool.importlinter]): the pure core imports no rospy and nothing of the ROS
    # side; applications, test harness, nodes and adapters only import downwards
    outcome = run_command_bounded([str(VENV_BIN / "lint-imports"), "--no-cache"], env=_env(), timeout_s=300)
    assert outcome.returncode == 0, f"import-linter found a layer violation:\n{outcome.output[-8000:]}"
    assert "0 broken" in outcome.output


def _env() -> dict[str, str]:
    env = dict(os.environ)
    env["MYPYPATH"] = str(REPO_ROOT / "src")
    return env
