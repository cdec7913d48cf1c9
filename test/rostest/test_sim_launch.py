#!/usr/bin/env python3
"""rostest node for sim_launch.test: launch/sim.launch gives a map, a relay and a camera."""

import math
import sys
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import TwistStamped
from nav_msgs.msg import OccupancyGrid, Odometry
from sensor_msgs.msg import CameraInfo, Image

from flex_nav.nav.costmap.map_io import load_map
from flex_nav.ros.node import init_node
from flex_nav_sim.static_map import shipped_map_path

WAIT_S = 40.0  # [s] wall-time bound on every wait


def wait_message(topic, msg_type):
    try:
        return rospy.wait_for_message(topic, msg_type, timeout=WAIT_S)
    except rospy.ROSException as err:
        raise AssertionError(f"no message on {topic} within {WAIT_S} s: {err}") from err


class TestSimLaunch(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        init_node("test_sim_launch")

    def test_map_is_the_worlds_static_map(self):
        grid = wait_message("/map", OccupancyGrid)
        expected = load_map(shipped_map_path("lab"))
        self.assertEqual((grid.info.width, grid.info.height), (expected.width, expected.height))
        self.assertAlmostEqual(grid.info.origin.position.x, expected.origin[0])
        self.assertEqual(list(grid.data), expected.occupancy.ravel().tolist())

    def test_relay_drives_the_robot(self):
        start = wait_message("/robot1/ground_truth", Odometry)
        pub = rospy.Publisher("/robot1/cmd_vel_stamped", TwistStamped, queue_size=1)
        cmd = TwistStamped()
        cmd.twist.linear.x = 0.3
        deadline = time.monotonic() + WAIT_S
        moved = 0.0
        while moved < 0.2:
            self.assertLess(time.monotonic(), deadline, f"robot1 moved only {moved:.3f} m through the relay")
            cmd.header.stamp = rospy.Time.now()
            pub.publish(cmd)
            time.sleep(0.05)
            now = wait_message("/robot1/ground_truth", Odometry)
            moved = math.hypot(
                now.pose.pose.position.x - start.pose.pose.position.x,
                now.pose.pose.position.y - start.pose.pose.position.y,
            )

    def test_camera(self):
        image = wait_message("/robot1/camera/rgb/image_raw", Image)
        info = wait_message("/robot1/camera/rgb/camera_info", CameraInfo)
        self.assertEqual((image.width, image.height, image.encoding), (320, 240, "rgb8"))
        self.assertEqual(len(image.data), 320 * 240 * 3)
        self.assertEqual(image.header.frame_id, "robot1/camera_rgb_optical_frame")
        self.assertAlmostEqual(info.K[2], 159.5)  # the middle of 320 pixels centred on 0 .. 319
        self.assertAlmostEqual(info.K[5], 119.5)
        self.assertAlmostEqual(info.K[0], 160.0 / math.tan(math.radians(57.0) / 2.0), places=3)
        self.assertGreater(len(set(image.data[::97])), 5)  # not a blank image


if __name__ == "__main__":
    rostest.rosrun("flex_nav", "sim_launch_check", TestSimLaunch, sys.argv)
