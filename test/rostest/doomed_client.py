#!/usr/bin/env python3
"""Helper of test_controller_safety.py: a client node that sends one FollowPath goal (5 m straight ahead in
``map``) to the action server named in argv[1], prints the goal's id and waits to be killed. With argv[2]
``quiet`` it sends nothing: it connects to the server, prints ``connected`` and waits (a restarted client)."""

import sys

import actionlib
import rospy
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path

from flex_nav.msg import FollowPathAction, FollowPathGoal

WAIT_S = 20.0  # [s] bound on the server appearing


def main() -> int:
    rospy.init_node("doomed_client", anonymous=False)
    client = actionlib.ActionClient(sys.argv[1], FollowPathAction)
    if not client.wait_for_server(rospy.Duration(WAIT_S)):
        print("no server", flush=True)
        return 1
    if sys.argv[2:] == ["quiet"]:
        print("connected", flush=True)
        rospy.sleep(600.0)  # until killed
        return 0
    path = Path()
    path.header.frame_id = "map"
    for k in range(51):
        pose = PoseStamped()
        pose.header.frame_id = "map"
        pose.pose.position.x = 0.1 * k
        pose.pose.orientation.w = 1.0
        path.poses.append(pose)
    handle = client.send_goal(FollowPathGoal(path=path))
    print(handle.comm_state_machine.action_goal.goal_id.id, flush=True)
    rospy.sleep(600.0)  # until killed
    return 0


if __name__ == "__main__":
    sys.exit(main())
