"""The test harness itself: a bounded command that is interrupted leaves nothing running."""

from __future__ import annotations

import os
import subprocess
import sys
import time

import pytest
from harness import run_command_bounded

# a command that starts a grandchild in its own process group, then waits: both must be gone afterwards
PARENT = "import subprocess, time; subprocess.Popen(['sleep', '120']); time.sleep(120)"


def _group_alive(pgid: int) -> bool:
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return False
    return True


def test_an_interrupted_bounded_run_stops_its_whole_process_group(monkeypatch: pytest.MonkeyPatch) -> None:
    real_communicate = subprocess.Popen.communicate
    started: list[int] = []

    def interrupted_once(self: subprocess.Popen[str], input: str | None = None,
                         timeout: float | None = None) -> tuple[str, str]:
        if not started:  # the first wait for the command is interrupted, as by Ctrl-C
            started.append(self.pid)
            time.sleep(0.5)  # the grandchild has started
            raise KeyboardInterrupt
        return real_communicate(self, input, timeout)

    monkeypatch.setattr(subprocess.Popen, "communicate", interrupted_once)
    with pytest.raises(KeyboardInterrupt):
        run_command_bounded([sys.executable, "-c", PARENT], env=dict(os.environ), timeout_s=60.0)
    assert started, "the command never ran"
    for _ in range(50):  # the grandchild is reaped by init once its parent is gone: a bounded wait for that
        if not _group_alive(started[0]):
            break
        time.sleep(0.1)
    assert not _group_alive(started[0]), "a process of the interrupted command's group is still running"
