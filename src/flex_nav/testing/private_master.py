"""A private ROS master (``roscore -p <free port>``) with its own ROS_HOME, for tests and the demo.

Never joins the default master on 11311: other processes on the machine may own it.
Nothing here imports rospy; readiness is checked over the master's XML-RPC API with a socket timeout.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import signal
import socket
import tempfile
import time
from pathlib import Path

from flex_nav.exceptions import NotReadyError
from flex_nav.ros.master_probe import master_is_up, master_pid
from flex_nav.testing.process import ManagedProcess, StopsOnExit

REPO_ROOT = Path(__file__).resolve().parents[3]
MASTER_STARTUP_TIMEOUT_S = 20.0  # [s] roscore is ready in 0.5-1 s on an idle machine
START_ATTEMPTS = 3  # a free port can be taken between probing and binding; retry with another


def free_port() -> int:
    """A TCP port on 127.0.0.1 that was free a moment ago."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


def ros_environment(master_uri: str, ros_home: Path) -> dict[str, str]:
    """The environment for nodes that talk to ``master_uri``: loopback IP, own ROS_HOME, this package findable,
    the project venv first on PATH (rostest and rosrun resolve ``#!/usr/bin/env python3`` from PATH)."""
    env = dict(os.environ)
    venv_bin = REPO_ROOT / ".venv" / "bin"
    path_parts = [str(venv_bin)] if venv_bin.is_dir() else []
    env["PATH"] = os.pathsep.join([*path_parts, env.get("PATH", "/usr/bin:/bin")])
    package_path = env.get("ROS_PACKAGE_PATH", "")
    if str(REPO_ROOT) not in package_path.split(os.pathsep):
        env["ROS_PACKAGE_PATH"] = os.pathsep.join(p for p in (str(REPO_ROOT), package_path) if p)
    env.update(
        ROS_MASTER_URI=master_uri,
        ROS_IP="127.0.0.1",
        ROS_HOSTNAME="127.0.0.1",
        ROS_HOME=str(ros_home),
        ROS_LOG_DIR=str(ros_home / "log"),
        PYTHONUNBUFFERED="1",
    )
    return env


class PrivateMaster(StopsOnExit):
    """``roscore`` on a free port with a fresh ROS_HOME; a context manager that always stops it.

    ``env`` is the environment to give every process that should use this master.
    """

    def __init__(self, ros_home: Path | None = None, startup_timeout_s: float = MASTER_STARTUP_TIMEOUT_S) -> None:
        self._own_home = ros_home is None
        self.ros_home = ros_home if ros_home is not None else Path(tempfile.mkdtemp(prefix="flex_nav_ros_home_"))
        self.startup_timeout_s = startup_timeout_s
        self.port = 0
        self.uri = ""
        self.env: dict[str, str] = {}
        self.process: ManagedProcess | None = None

    def start(self) -> PrivateMaster:
        self.ros_home.mkdir(parents=True, exist_ok=True)
        roscore = shutil.which("roscore")
        if roscore is None:
            raise NotReadyError("roscore is not on PATH; run tools/install.sh (Debian package python3-roslaunch)")
        errors: list[str] = []
        for _attempt in range(START_ATTEMPTS):
            self.port = free_port()
            self.uri = f"http://127.0.0.1:{self.port}/"
            self.env = ros_environment(self.uri, self.ros_home)
            log = self.ros_home / f"roscore-{self.port}.log"
            self.process = ManagedProcess([roscore, "-p", str(self.port)], env=self.env, log_path=log)
            deadline = time.monotonic() + self.startup_timeout_s
            while time.monotonic() < deadline and self.process.running():
                if master_is_up(self.uri):
                    return self
                time.sleep(0.05)
            errors.append(f"port {self.port}: {self.process.log_tail(500).strip() or 'no output'}")
            self.process.stop()
            self.process = None
        raise NotReadyError(
            f"roscore did not come up within {self.startup_timeout_s:.0f} s in {START_ATTEMPTS} attempts: "
            + " | ".join(errors)
        )

    def stop(self) -> None:
        if self.process is not None:
            # roslaunch starts rosmaster in a session of its own: when roscore is too slow to stop it (a loaded
            # machine) and gets SIGKILL, the master would outlive it, orphaned. Ask for its pid first.
            orphan = master_pid(self.uri) if self.uri else None
            self.process.stop()
            self.process = None
            # The same holds for rosout, also in a session of its own; it may not have registered yet when a
            # master is stopped right after start, so it is found by its log directory under our ROS_HOME.
            rosouts = [int(entry.name) for entry in Path("/proc").iterdir()
                       if entry.name.isdigit() and self._is_our_rosout(int(entry.name))]
            ours = ([orphan] if orphan is not None and self._is_our_master(orphan) else []) + rosouts
            for pid in ours:  # checked on /proc just now: not a reused pid
                with contextlib.suppress(ProcessLookupError, PermissionError):
                    os.kill(pid, signal.SIGKILL)
        if self._own_home:
            shutil.rmtree(self.ros_home, ignore_errors=True)

    def _is_our_master(self, pid: int) -> bool:
        """True while process ``pid`` is a rosmaster serving this master's port."""
        args = _cmdline(pid)
        serves_port = any(a == "-p" and b == str(self.port) for a, b in zip(args, args[1:]))
        return serves_port and any(Path(a).name == "rosmaster" for a in args[:2])

    def _is_our_rosout(self, pid: int) -> bool:
        """True while process ``pid`` is a rosout logging under this master's ROS_HOME."""
        args = _cmdline(pid)
        log_prefix = f"__log:={self.ros_home}{os.sep}"
        return bool(args) and Path(args[0]).name == "rosout" and any(a.startswith(log_prefix) for a in args)

    def __enter__(self) -> PrivateMaster:
        return self.start()


def _cmdline(pid: int) -> list[str]:
    """The arguments of process ``pid`` from /proc (empty if it is gone)."""
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().decode(errors="replace").split("\0")
    except OSError:
        return []
