"""A virtual X display (Xvfb) on a free display number, and pictures of its screen (ImageMagick's ``import``).

For GUI programs under test (RViz): ``with VirtualDisplay(log_path=...) as display:`` start the program with
``DISPLAY=display.name``, then ``display.screenshot(path)``. Xvfb runs in its own process group and is stopped
by PID when the block ends. Nothing here imports rospy.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import time
from pathlib import Path

from flex_nav.exceptions import NotReadyError
from flex_nav.testing.process import ManagedProcess, StopsOnExit

FIRST_DISPLAY = 90  # the numbers tried: FIRST_DISPLAY .. + DISPLAYS_TRIED - 1 (clear of :0 and ssh's :10 and up)
DISPLAYS_TRIED = 60
STARTUP_TIMEOUT_S = 10.0  # [s] Xvfb's socket must appear by then
SCREENSHOT_TIMEOUT_S = 30.0  # [s] bound of one ``import``
X_SOCKETS = Path("/tmp/.X11-unix")  # noqa: S108 - where every X server puts its socket


def missing_tools(*tools: str) -> list[str]:
    """The commands of ``tools`` that are not on PATH."""
    return [tool for tool in tools if shutil.which(tool) is None]


def display_in_use(number: int) -> bool:
    """Another X server holds display ``:number`` (its lock file or its socket exists)."""
    lock = Path(f"/tmp/.X{number}-lock")  # noqa: S108 - the X servers' lock file
    return lock.exists() or (X_SOCKETS / f"X{number}").exists()


class VirtualDisplay(StopsOnExit):
    """``Xvfb :N -screen 0 WIDTHxHEIGHTx24`` on the first free N from :data:`FIRST_DISPLAY`."""

    def __init__(self, width: int = 1400, height: int = 900, log_path: Path | None = None,
                 startup_timeout_s: float = STARTUP_TIMEOUT_S) -> None:
        self.width = width
        self.height = height
        self.log_path = log_path
        self.startup_timeout_s = startup_timeout_s
        self.number: int | None = None
        self.process: ManagedProcess | None = None

    @property
    def name(self) -> str:
        """The DISPLAY value (``:N``); RuntimeError before :meth:`start`."""
        if self.number is None:
            raise RuntimeError("the virtual display is not started")
        return f":{self.number}"

    def start(self) -> VirtualDisplay:
        missing = missing_tools("Xvfb")
        if missing:
            raise NotReadyError("Xvfb not installed (Debian package xvfb): run tools/install.sh")
        tried: list[str] = []
        for number in range(FIRST_DISPLAY, FIRST_DISPLAY + DISPLAYS_TRIED):
            if display_in_use(number):
                continue
            proc = ManagedProcess(["Xvfb", f":{number}", "-screen", "0", f"{self.width}x{self.height}x24",
                                   "-nolisten", "tcp", "-noreset"], log_path=self.log_path)
            deadline = time.monotonic() + self.startup_timeout_s
            while proc.running() and not (X_SOCKETS / f"X{number}").exists() and time.monotonic() < deadline:
                time.sleep(0.05)
            if proc.running() and (X_SOCKETS / f"X{number}").exists():
                self.number, self.process = number, proc
                return self
            proc.stop(1.0)  # lost a race for this number, or Xvfb failed: its log says which
            tried.append(f":{number}")
        raise NotReadyError(f"Xvfb did not start on any free display (tried {', '.join(tried) or 'none free'}); "
                            f"log {self.log_path}")

    def stop(self) -> int | None:
        code = self.process.stop(2.0) if self.process is not None else None
        self.process = None
        return code

    def __enter__(self) -> VirtualDisplay:
        return self.start()

    def env(self, base: dict[str, str] | None = None) -> dict[str, str]:
        """``base`` (default: this process's environment) with DISPLAY set to this display."""
        return {**(os.environ if base is None else base), "DISPLAY": self.name}

    def screenshot(self, out: Path, timeout_s: float = SCREENSHOT_TIMEOUT_S) -> Path:
        """The whole screen to ``out`` (the format from its suffix, e.g. PNG), by ImageMagick's ``import``."""
        if missing_tools("import"):
            raise NotReadyError("ImageMagick's import not installed (Debian package imagemagick): run tools/install.sh")
        out.parent.mkdir(parents=True, exist_ok=True)
        try:
            done = subprocess.run(["import", "-display", self.name, "-window", "root", str(out)],
                                  capture_output=True, text=True, timeout=timeout_s, check=False)
        except subprocess.TimeoutExpired as err:
            raise NotReadyError(f"import -window root on {self.name} took over {timeout_s:g} s") from err
        if done.returncode != 0 or not out.exists():
            raise NotReadyError(f"import -window root on {self.name} failed ({done.returncode}): "
                                f"{done.stderr.strip()[-500:]}")
        return out
