"""Child processes that are always stopped: own process group, bounded waits, cleanup by PID.

Used by the demo, the test harness and the simulator launcher. Nothing here imports rospy.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from types import TracebackType
from typing import IO

from flex_nav.exceptions import NotReadyError

DEFAULT_STOP_TIMEOUT_S = 5.0  # [s] SIGINT grace period before SIGKILL of the process group


class StopsOnExit:
    """Base of the harness's context managers: leaving the ``with`` block calls :meth:`stop`, an error included."""

    def stop(self) -> object:
        raise NotImplementedError

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.stop()


class ManagedProcess(StopsOnExit):
    """A subprocess in its own process group, stopped by PID (SIGINT, then SIGKILL of the group).

    ``log_path`` receives stdout and stderr; without it output goes to ``/dev/null``.
    """

    def __init__(
        self,
        argv: Sequence[str],
        env: Mapping[str, str] | None = None,
        log_path: Path | None = None,
        cwd: Path | None = None,
    ) -> None:
        self.argv = list(argv)
        self.log_path = log_path
        self._log: IO[bytes] | None = open(log_path, "ab") if log_path is not None else None  # noqa: SIM115
        try:
            self.popen = subprocess.Popen(
                self.argv,
                env=dict(env) if env is not None else None,
                cwd=cwd,
                stdin=subprocess.DEVNULL,
                stdout=self._log if self._log is not None else subprocess.DEVNULL,
                stderr=subprocess.STDOUT,
                start_new_session=True,
            )
        except OSError:
            self._close_log()
            raise

    @property
    def pid(self) -> int:
        return self.popen.pid

    def running(self) -> bool:
        return self.popen.poll() is None

    def log_tail(self, max_chars: int = 2000) -> str:
        """The last ``max_chars`` characters of the log, for error messages."""
        if self.log_path is None or not self.log_path.exists():
            return ""
        return self.log_path.read_text(errors="replace")[-max_chars:]

    def stop(self, timeout_s: float = DEFAULT_STOP_TIMEOUT_S) -> int | None:
        """SIGINT the process, wait up to ``timeout_s`` [s], then SIGKILL its whole group.

        Returns the exit code (``None`` if even SIGKILL did not reap it within 1 s).
        """
        if self.popen.poll() is None:
            with contextlib.suppress(ProcessLookupError):
                os.kill(self.popen.pid, signal.SIGINT)
            with contextlib.suppress(subprocess.TimeoutExpired):
                self.popen.wait(timeout=timeout_s)
        # Children of the process (e.g. nodes started by roslaunch) share its group.
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(self.popen.pid, signal.SIGKILL)
        try:
            code: int | None = self.popen.wait(timeout=1.0)
        except subprocess.TimeoutExpired:
            code = None
        self._close_log()
        return code

    def _close_log(self) -> None:
        if self._log is not None:
            self._log.close()
            self._log = None

    def __enter__(self) -> ManagedProcess:
        return self


def wait_until(predicate: object, timeout_s: float, what: str, period_s: float = 0.05) -> None:
    """Poll ``predicate()`` every ``period_s`` [s] until true; raise NotReadyError after ``timeout_s`` [s]."""
    if not callable(predicate):
        raise TypeError(f"predicate must be callable, got {type(predicate).__name__}")
    deadline = time.monotonic() + timeout_s
    while True:
        if predicate():
            return
        if time.monotonic() >= deadline:
            raise NotReadyError(f"{what}: not ready after {timeout_s:.1f} s")
        time.sleep(period_s)
