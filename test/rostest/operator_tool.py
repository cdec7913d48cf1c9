"""The operator tool as a user runs it, for the rostest nodes of the behavior runner (imported from this directory,
not a test itself)."""

import os
import subprocess
from typing import Tuple


def run_operator(*args: str, runner: str, timeout_s: float) -> Tuple[int, str]:
    """``rosrun flex_nav operator --runner RUNNER ARGS``, bounded by ``timeout_s`` [s]: (exit code, output)."""
    proc = subprocess.run(
        ["rosrun", "flex_nav", "operator", "--runner", runner, *args],
        capture_output=True, text=True, timeout=timeout_s, env=dict(os.environ), check=False,
    )
    return proc.returncode, proc.stdout + proc.stderr
