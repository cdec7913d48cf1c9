#!/usr/bin/env python3
"""rostest node: a client of each of the four actions, through a real master, against scripted servers."""

import sys
import unittest

import rostest
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path
from readiness import wait_until_active

from flex_nav.msg import (
    ClearCostmapAction,
    ClearCostmapGoal,
    ClearCostmapResult,
    FollowPathAction,
    FollowPathGoal,
    FollowPathResult,
    FollowTopicAction,
    FollowTopicGoal,
    FollowTopicResult,
    GetPathAction,
    GetPathGoal,
    GetPathResult,
)
from flex_nav.ros.node import init_node
from flex_nav.ros.proxies import ActionClientProxy

SERVER_WAIT_S = 20.0  # [s]
RESULT_WAIT_S = 10.0  # [s]


def connected_client(name, action):
    client = ActionClientProxy(name, action)
    if not client.is_available(SERVER_WAIT_S):
        raise AssertionError(f"action server {name} did not appear within {SERVER_WAIT_S} s")
    return client


class TestActions(unittest.TestCase):
    def test_get_path_succeeds_with_fields(self):
        client = connected_client("get_path_server", GetPathAction)
        goal = GetPathGoal()
        goal.pose = PoseStamped()
        goal.pose.header.frame_id = "map"
        goal.pose.pose.position.x = 1.5
        goal.pose.pose.orientation.w = 1.0
        client.send_goal(goal)
        self.assertTrue(client.wait_for_result(RESULT_WAIT_S))
        self.assertEqual(client.state(), GoalStatus.SUCCEEDED)
        result = client.result()
        self.assertEqual(result.code, GetPathResult.SUCCESS)
        self.assertEqual(result.message, "SUCCESS")
        self.assertIsInstance(result.plan, Path)
        self.assertEqual((GetPathResult.SUCCESS, GetPathResult.EMPTY, GetPathResult.FAILURE), (0, 1, 2))

    def test_follow_path_preempted(self):
        client = connected_client("follow_path_server", FollowPathAction)
        client.send_goal(FollowPathGoal(path=Path()))
        wait_until_active(client, RESULT_WAIT_S)  # also: the server is still working on it
        client.cancel()
        self.assertTrue(client.wait_for_result(RESULT_WAIT_S))
        self.assertEqual(client.state(), GoalStatus.PREEMPTED)
        self.assertEqual(client.result().code, FollowPathResult.PREEMPT)
        self.assertEqual(client.result().message, "preempted")

    def test_follow_topic_failure_carries_reason(self):
        client = connected_client("follow_topic_server", FollowTopicAction)
        goal = FollowTopicGoal()
        goal.topic.data = "plan"
        client.send_goal(goal)
        self.assertTrue(client.wait_for_result(RESULT_WAIT_S))
        self.assertEqual(client.state(), GoalStatus.ABORTED)
        self.assertEqual(client.result().code, FollowTopicResult.FAILURE)
        self.assertEqual(client.result().message, "no publisher on the topic")

    def test_clear_costmap_succeeds(self):
        client = connected_client("clear_costmap", ClearCostmapAction)
        client.send_goal(ClearCostmapGoal())
        self.assertTrue(client.wait_for_result(RESULT_WAIT_S))
        self.assertEqual(client.state(), GoalStatus.SUCCEEDED)
        self.assertEqual(client.result().code, ClearCostmapResult.SUCCESS)


if __name__ == "__main__":
    init_node("test_actions", master_timeout_s=SERVER_WAIT_S)
    rostest.rosrun("flex_nav", "test_actions", TestActions, sys.argv)
