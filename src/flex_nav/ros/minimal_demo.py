"""Minimal demo: a private roscore, the four action servers, and a client that sends each a goal.

Run by ``tools/demo.sh`` until the simulated navigation demo lands. Prints what happened; exits 0 when
every server answered as scripted, 1 otherwise. Everything it starts is stopped on exit and on Ctrl-C.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

from flex_nav.private_master import PrivateMaster
from flex_nav.process import ManagedProcess

SERVER_WAIT_S = 20.0  # [s]
RESULT_WAIT_S = 10.0  # [s]


def run_client() -> bool:
    """Send one goal to each server and print the outcome; True when all answered as scripted."""
    import actionlib  # noqa: PLC0415 - rospy is imported only once the master exists
    import rospy  # noqa: PLC0415

    from flex_nav.action_types import ACTION_TYPES  # noqa: PLC0415
    from flex_nav.ros.node import init_node  # noqa: PLC0415

    init_node("minimal_demo_client")
    expected = {
        "get_path_server": ("GetPath", 0),
        "follow_path_server": ("FollowPath", 0),
        "follow_topic_server": ("FollowTopic", 1),
        "clear_costmap": ("ClearCostmap", 0),
    }
    all_ok = True
    for server, (action_name, expected_code) in expected.items():
        spec = ACTION_TYPES[action_name]
        client = actionlib.SimpleActionClient(server, spec.action)
        if not client.wait_for_server(rospy.Duration(SERVER_WAIT_S)):
            print(f"  {server:20s} {action_name:12s} did not come up within {SERVER_WAIT_S:.0f} s")
            all_ok = False
            continue
        started = time.monotonic()
        client.send_goal(spec.goal())
        if not client.wait_for_result(rospy.Duration(RESULT_WAIT_S)):
            client.cancel_goal()
            print(f"  {server:20s} {action_name:12s} no result within {RESULT_WAIT_S:.0f} s")
            all_ok = False
            continue
        result = client.get_result()
        elapsed_ms = 1e3 * (time.monotonic() - started)
        ok = result.code == expected_code
        all_ok &= ok
        print(
            f"  {server:20s} {action_name:12s} -> {spec.code_name(result.code):8s} "
            f"'{result.message}' in {elapsed_ms:6.1f} ms {'(as scripted)' if ok else '(UNEXPECTED)'}"
        )
    return all_ok


def main() -> int:
    started = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="flex_nav_demo_") as home, PrivateMaster(ros_home=Path(home)) as master:
        print(f"roscore up at {master.uri} (ROS_HOME {home})")
        os.environ.update(master.env)
        launch_log = Path(home) / "roslaunch.log"
        with ManagedProcess(["roslaunch", "flex_nav", "minimal_demo.launch"], env=master.env, log_path=launch_log):
            print("servers: get_path_server, follow_path_server, follow_topic_server, clear_costmap")
            try:
                ok = run_client()
            except KeyboardInterrupt:
                print("interrupted; stopping everything")
                return 130
    print(f"{'all servers answered as scripted' if ok else 'SOME SERVERS FAILED'}; "
          f"wall time {time.monotonic() - started:.1f} s")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
