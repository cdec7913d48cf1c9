"""PrivateMaster and ManagedProcess: a real roscore on a free port, stopped by PID; nodes never hang without one."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from flex_nav.exceptions import NotReadyError
from flex_nav.ros.master_probe import master_is_up, master_pid, node_pid
from flex_nav.testing.private_master import PrivateMaster, free_port
from flex_nav.testing.process import ManagedProcess, wait_until

REPO_ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.ros
def test_master_starts_on_free_port_with_own_home_and_stops(tmp_path: Path) -> None:
    with PrivateMaster(ros_home=tmp_path / "home") as master:
        assert master.port not in (0, 11311)
        assert master_is_up(master.uri)
        assert master.env["ROS_MASTER_URI"] == master.uri
        assert master.env["ROS_HOME"] == str(tmp_path / "home")
        assert master.env["ROS_IP"] == "127.0.0.1"
        process = master.process
        assert process is not None and process.running()
    assert not process.running()
    assert not master_is_up(master.uri)


@pytest.mark.ros
def test_two_masters_side_by_side(tmp_path: Path) -> None:
    with PrivateMaster(ros_home=tmp_path / "a") as first, PrivateMaster(ros_home=tmp_path / "b") as second:
        assert first.uri != second.uri
        assert master_is_up(first.uri) and master_is_up(second.uri)


@pytest.mark.ros
def test_a_master_orphaned_by_a_killed_roscore_is_stopped_too(tmp_path: Path) -> None:
    """roslaunch runs rosmaster in a session of its own: a roscore killed before it could stop it (SIGKILL after
    the grace period on a loaded machine) leaves the master running; stop() must end it as well."""
    master = PrivateMaster(ros_home=tmp_path).start()
    roscore = master.process
    assert roscore is not None
    orphan = master_pid(master.uri)
    rosout = None
    try:
        wait_until(lambda: node_pid(master.uri, "/rosout") is not None, 10.0, "rosout to register")
        rosout = node_pid(master.uri, "/rosout")
        assert orphan is not None and orphan != roscore.pid
        assert rosout is not None and rosout not in (orphan, roscore.pid)
        os.killpg(roscore.pid, signal.SIGKILL)  # roscore's group only: the master and rosout live on
        time.sleep(0.5)
        assert master_is_up(master.uri), "the master should have outlived roscore (its own session)"
        assert _running(rosout), "rosout should have outlived roscore (its own session)"
        master.stop()
        wait_until(lambda: not master_is_up(master.uri, timeout_s=0.2), 5.0, "the orphaned master to stop")
        wait_until(lambda: not _running(rosout), 5.0, "the orphaned rosout to stop")
    finally:
        for pid in (orphan, rosout):
            if pid is not None and _running(pid):
                os.kill(pid, signal.SIGKILL)


def _running(pid: int) -> bool:
    """True while process ``pid`` exists and is not a zombie."""
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    return "\nState:\tZ" not in status


def test_master_is_up_false_quickly_for_closed_port() -> None:
    assert master_is_up(f"http://127.0.0.1:{free_port()}/", timeout_s=0.5) is False


def test_managed_process_group_is_killed_when_sigint_is_ignored(tmp_path: Path) -> None:
    # A parent that ignores SIGINT and has a child: stop() must still end both.
    script = "import signal, subprocess, time; signal.signal(signal.SIGINT, signal.SIG_IGN); " \
             "subprocess.Popen(['sleep', '60']); time.sleep(60)"
    proc = ManagedProcess([sys.executable, "-c", script], log_path=tmp_path / "log")
    time.sleep(0.3)
    code = proc.stop(timeout_s=0.5)
    assert code is not None and code != 0
    time.sleep(0.2)
    table = subprocess.run(["ps", "-eo", "pgid=,stat="], capture_output=True, text=True, check=True).stdout
    rows = [line.split() for line in table.splitlines()]
    alive = [row for row in rows if row[0] == str(proc.pid) and not row[1].startswith("Z")]
    assert alive == [], f"processes of group {proc.pid} still alive: {alive}"


def test_wait_until_raises_with_what() -> None:
    with pytest.raises(NotReadyError, match=r"the moon: not ready after 0\.1 s"):
        wait_until(lambda: False, 0.1, "the moon")


def test_node_without_master_fails_with_message_instead_of_hanging(tmp_path: Path) -> None:
    env = dict(os.environ)
    env.update(ROS_MASTER_URI=f"http://127.0.0.1:{free_port()}/", ROS_HOME=str(tmp_path), ROS_IP="127.0.0.1")
    code = (
        "import sys; from flex_nav.ros.node import init_node; init_node('lonely', master_timeout_s=1.0); sys.exit(0)"
    )
    proc = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=60, check=False
    )
    assert proc.returncode == 2
    assert "no ROS master answers at ROS_MASTER_URI=" in proc.stderr
