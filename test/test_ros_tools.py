"""Debian's ROS command-line tools see flex_nav's types in a shell where ``source .venv/bin/activate`` ran.

``/usr/bin/rostopic``, ``rosmsg``, ``rossrv`` and ``rosbag`` run the system python, not the venv's: the activate
script (written by tools/install.sh) puts flex_nav's generated message classes on PYTHONPATH and the messages
expanded from ``action/`` on CMAKE_PREFIX_PATH. Each check also runs once without the activation, to show the
check can fail.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
import rosbag
from harness import REPO_ROOT

from flex_nav.msg import BumperEvent
from flex_nav.testing.private_master import PrivateMaster

ACTIVATE = REPO_ROOT / ".venv" / "bin" / "activate"
COMMAND_TIMEOUT_S = 60.0  # [s] each tool call

pytestmark = pytest.mark.skipif(not ACTIVATE.is_file(), reason="no venv: run tools/install.sh")


def shell(command: str, *, activate: bool, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    """``command`` in bash, after ``source .venv/bin/activate`` if ``activate``; a clean PYTHONPATH and
    CMAKE_PREFIX_PATH either way (the test runner's own settings must not help)."""
    base = dict(env if env is not None else os.environ)
    for name in ("PYTHONPATH", "CMAKE_PREFIX_PATH", "VIRTUAL_ENV"):
        base.pop(name, None)
    base["ROS_PACKAGE_PATH"] = f"{REPO_ROOT}{os.pathsep}/opt/ros/noetic/share"
    base["PATH"] = "/usr/bin:/bin"
    script = (f"source {ACTIVATE} && " if activate else "") + command
    return subprocess.run(["bash", "-c", script], env=base, capture_output=True, text=True,
                          timeout=COMMAND_TIMEOUT_S, check=False)


@pytest.mark.parametrize(("tool", "type_name", "expected"), [
    ("rosmsg", "flex_nav/BumperEvent", "uint8 PRESSED=1"),
    ("rosmsg", "flex_nav/GetPathActionGoal", "flex_nav/GetPathGoal goal"),  # expanded from action/GetPath.action
    ("rossrv", "flex_nav/MapFile", "bool ok"),
])
def test_rosmsg_and_rossrv_show_flex_nav_types(tool: str, type_name: str, expected: str) -> None:
    shown = shell(f"/usr/bin/{tool} show {type_name}", activate=True)
    assert shown.returncode == 0, shown.stderr
    assert expected in shown.stdout


def test_without_the_activation_rosmsg_does_not_know_the_action_messages() -> None:
    shown = shell("/usr/bin/rosmsg show flex_nav/GetPathActionGoal", activate=False)
    assert shown.returncode != 0
    assert "Cannot locate message [GetPathActionGoal]" in shown.stdout + shown.stderr


@pytest.mark.ros
def test_rostopic_echoes_a_flex_nav_message(ros_master: PrivateMaster) -> None:
    publisher = subprocess.Popen(  # a latched flex_nav message from the venv's python
        [sys.executable, "-c", (
            "import rospy; from flex_nav.msg import BumperEvent\n"
            "rospy.init_node('bumper_publisher')\n"
            "pub = rospy.Publisher('bumper', BumperEvent, queue_size=1, latch=True)\n"
            "pub.publish(BumperEvent(bumper=BumperEvent.CENTER, state=BumperEvent.PRESSED))\n"
            "rospy.sleep(60.0)\n")],
        env=ros_master.env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 20.0
        typed = shell("/usr/bin/rostopic type /bumper", activate=True, env=ros_master.env)
        while typed.stdout.strip() != "flex_nav/BumperEvent" and time.monotonic() < deadline:
            time.sleep(0.5)
            typed = shell("/usr/bin/rostopic type /bumper", activate=True, env=ros_master.env)
        assert typed.stdout.strip() == "flex_nav/BumperEvent", typed.stderr
        echoed = shell("/usr/bin/rostopic echo -n 1 /bumper", activate=True, env=ros_master.env)
        assert echoed.returncode == 0, echoed.stderr
        assert "bumper: 1" in echoed.stdout and "state: 1" in echoed.stdout
    finally:
        publisher.kill()  # started here, stopped by its PID
        publisher.wait(timeout=10.0)


@pytest.fixture
def bag_with_flex_nav_message(tmp_path: Path) -> Path:
    path = tmp_path / "event.bag"
    with rosbag.Bag(str(path), "w") as bag:
        bag.write("/bumper", BumperEvent(bumper=BumperEvent.LEFT, state=BumperEvent.PRESSED))
    return path


def test_rosbag_check_finds_no_migration_with_the_activation(bag_with_flex_nav_message: Path) -> None:
    checked = shell(f"/usr/bin/rosbag check {bag_with_flex_nav_message}", activate=True)
    assert checked.returncode == 0, checked.stderr
    assert "Bag file does not need any migrations" in checked.stdout


def test_rosbag_check_without_the_activation_reports_the_type_unknown(bag_with_flex_nav_message: Path) -> None:
    checked = shell(f"/usr/bin/rosbag check {bag_with_flex_nav_message}", activate=False)
    assert "flex_nav/BumperEvent" in checked.stdout and "Unknown" in checked.stdout
