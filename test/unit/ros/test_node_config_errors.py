"""Nodes refuse bad or misspelt parameters at start: exit status 2 and a message naming the parameter
(against a private master); navigation.launch puts every node in the requested namespace."""

import os
import subprocess

import pytest
from harness import REPO_ROOT, run_command_bounded

from flex_nav.testing.private_master import PrivateMaster

NODE_WAIT_S = 60.0  # [s] bound on a node starting and exiting


@pytest.fixture(scope="module")
def shared_master(tmp_path_factory):
    """One private master for all cases (each node exits at once; nothing is left on it)."""
    master = PrivateMaster(ros_home=tmp_path_factory.mktemp("ros_home")).start()
    try:
        yield master
    finally:
        master.stop()


@pytest.mark.ros
@pytest.mark.parametrize(
    ("node", "args", "expected"),
    [
        ("twist_relay", ["_timout:=0.3"],
         "/timout is not a parameter of this node (valid: heartbeat_timeout, timeout)"),
        ("twist_relay", ["_timeout:=-1.0"], "/timeout = -1.0 is outside [0.0, 3600.0]"),
        ("pure_pursuit_path", ["_pure_pursuit/desired_linear_vell:=0.3"],
         "pure pursuit parameter 'desired_linear_vell' is not valid"),
        ("pure_pursuit_path", ["_pure_pursuit/inscribed_radius:=0.5"],
         "inscribed_radius = 0.5 differs from the local costmap's value 0.18"),
        ("get_path_server", ["_global_costmap/robot_radus:=0.2"],
         "global_costmap/robot_radus is not a parameter of this node"),
        ("follow_path_server", ["_planner/lethal_cost:=300"], "lethal_cost = 300 is outside [1, 255]"),
        ("bumper_relay", ["_inputs:=kobuki"], "/inputs is not a parameter of this node (valid: base_frame, input, "
                                              "profile)"),
    ],
)
def test_bad_parameter_stops_the_node(shared_master: PrivateMaster, node, args, expected):
    # a node name of its own per case: private parameters set by one case stay on the shared master
    name = f"__name:=case_{abs(hash((node, *args))) % 10**8}"
    outcome = run_command_bounded(["rosrun", "flex_nav", node, *args, name], env=shared_master.env,
                                  timeout_s=NODE_WAIT_S)
    assert outcome.returncode == 2, outcome.output[-3000:]
    assert expected in outcome.output, outcome.output[-3000:]


def test_navigation_launch_namespaces_every_node():
    done = subprocess.run(
        ["roslaunch", "--nodes", str(REPO_ROOT / "launch" / "navigation.launch"), "namespace:=robot7",
         "pure_pursuit_topic:=false"],
        capture_output=True, text=True, timeout=60, check=True,
        env={**os.environ, "ROS_PACKAGE_PATH": str(REPO_ROOT)},
    )
    assert done.stdout.split() == ["/robot7/navigation"]  # one process hosts them (combined:=true)
    done = subprocess.run(
        ["roslaunch", "--nodes", str(REPO_ROOT / "launch" / "navigation.launch"), "namespace:=robot7",
         "pure_pursuit_topic:=false", "combined:=false"],
        capture_output=True, text=True, timeout=60, check=True,
        env={**os.environ, "ROS_PACKAGE_PATH": str(REPO_ROOT)},
    )
    nodes = done.stdout.split()
    assert nodes == ["/robot7/get_path_server", "/robot7/follow_path_server", "/robot7/follow_topic_server",
                     "/robot7/pure_pursuit_path", "/robot7/twist_relay"]
