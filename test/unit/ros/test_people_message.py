"""The controllers' tracked people as the PoseArray the operator console draws (no master needed)."""

from __future__ import annotations

import math

import pytest
import rospy

from flex_nav.perception.moving_obstacles import Track
from flex_nav.ros.moving_obstacles_ros import people_message


def test_tracks_become_poses_facing_their_motion() -> None:
    walking = Track(track_id=1, x=1.0, y=2.0, vx=0.0, vy=0.8, radius=0.2, stamp_s=5.0, hits=4)
    standing = Track(track_id=2, x=-1.0, y=0.5, vx=0.0, vy=0.0, radius=0.2, stamp_s=5.0, hits=9)
    msg = people_message([walking, standing], "robot1/odom", rospy.Time(5, 0))
    assert msg.header.frame_id == "robot1/odom" and msg.header.stamp == rospy.Time(5, 0)
    assert [(p.position.x, p.position.y) for p in msg.poses] == [(1.0, 2.0), (-1.0, 0.5)]
    assert 2.0 * math.atan2(msg.poses[0].orientation.z, msg.poses[0].orientation.w) == pytest.approx(math.pi / 2)
    assert (msg.poses[1].orientation.z, msg.poses[1].orientation.w) == (0.0, 1.0)
    assert people_message([], "map", rospy.Time(0)).poses == []
