#!/usr/bin/env python3
"""rostest node for obstacle_classifier.test: the smoothed class and safe_to_push for a person and for a box."""

import sys
import unittest

import rospy
import rostest
from message_log import MessageLog
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import Image
from std_msgs.msg import String
from std_srvs.srv import SetBool

from flex_nav.msg import ObstacleClass
from flex_nav.perception.image import to_depth
from flex_nav.ros.node import init_node

WAIT_S = 60.0  # [s] the sim and two classifiers start on a shared 2-core machine


def latest(topic, msg_type=ObstacleClass):
    """Every message of ``topic`` from now on (waits of at most WAIT_S)."""
    return MessageLog(topic, msg_type, queue_size=None, wait_s=WAIT_S)


def call(service, data):
    rospy.wait_for_service(service, timeout=WAIT_S)
    return rospy.ServiceProxy(service, SetBool)(data)


class TestObstacleClassifier(unittest.TestCase):
    def test_person_is_published_and_never_safe_to_push(self):
        msg = latest("/robot1/obstacle_class").newest(lambda m: m.votes >= 3)
        self.assertEqual(msg.label, "person")
        self.assertEqual(msg.window, 5)
        self.assertEqual(list(msg.labels), ["person", "movable", "clear"])
        self.assertLessEqual(sum(bytearray(msg.counts)), 5)
        self.assertGreaterEqual(bytearray(msg.counts)[0], 3)
        self.assertGreater(msg.confidence, 0.5)
        self.assertEqual(msg.header.frame_id, "robot1/camera_rgb_optical_frame")
        answer = call("/robot1/safe_to_push", False)
        self.assertFalse(answer.success, answer.message)
        self.assertIn("person", answer.message)
        fresh = call("/robot1/safe_to_push", True)
        self.assertFalse(fresh.success, fresh.message)
        self.assertIn("person", fresh.message)

    def test_box_is_published_and_safe_to_push(self):
        msg = latest("/robot2/obstacle_class").newest(lambda m: m.votes >= 3)
        self.assertEqual(msg.label, "movable")
        self.assertEqual(msg.frame_label, "movable")
        answer = call("/robot2/safe_to_push", False)
        self.assertTrue(answer.success, answer.message)
        self.assertTrue(answer.message.startswith("safe: movable"), answer.message)
        fresh = call("/robot2/safe_to_push", True)  # forget the window, wait for 5 new frames
        self.assertTrue(fresh.success, fresh.message)
        self.assertRegex(fresh.message, r"^safe: movable [3-5]/5 votes")

    def test_the_fused_decision_and_both_cues_are_published_and_answered(self):
        box = latest("/robot2/obstacle_fusion", String).newest(lambda m: m.data.startswith("fused movable"))
        self.assertIn("(row 6: the camera sees a movable object", box.data)
        self.assertIn("| lidar box", box.data)  # the 0.3 m box 1 m ahead: a straight face or a corner
        person = latest("/robot1/obstacle_fusion", String).newest(lambda m: m.data.startswith("fused person"))
        self.assertIn("| camera", person.data)
        answer = call("/robot2/safe_to_push", False)
        self.assertTrue(answer.success, answer.message)  # the camera's answer, as before
        self.assertIn("; fused ", answer.message)

    def test_the_simulated_depth_image_is_registered_to_the_colour_image(self):
        rgb = rospy.wait_for_message("/robot1/camera/rgb/image_raw", Image, timeout=WAIT_S)
        depth = rospy.wait_for_message("/robot1/camera/depth/image_raw", Image, timeout=WAIT_S)
        self.assertEqual(depth.encoding, "32FC1")
        self.assertEqual((depth.width, depth.height, depth.header.frame_id),
                         (rgb.width, rgb.height, rgb.header.frame_id))
        metres = to_depth(depth.data, depth.width, depth.height, depth.encoding, depth.step,
                          bigendian=bool(depth.is_bigendian))
        centre = float(metres[depth.height // 2, depth.width // 2])
        # the person stands 1.1 m ahead of the robot's centre, the camera 0.18 m forward of it: the near side
        # of the person is closer than 0.92 m, and more than 0.5 m away (a person is < 0.42 m in radius)
        self.assertTrue(0.5 < centre < 0.92, f"depth in the image centre {centre} m")

    def test_without_depth_images_nothing_is_classified_or_safe(self):
        log = latest("/rosout_agg", Log)
        latest("/robot2/obstacle_class").newest(lambda m: m.votes >= 3)  # colour and depth frames are flowing
        warning = log.newest(lambda m: m.name == "/robot2/classifier_without_depth" and m.level == Log.WARN
                            and "no colour image has had a depth image" in m.msg)  # repeated every 5 s
        self.assertIn("on /robot2/camera/depth/not_published within 0.1 s", warning.msg)
        without = latest("/robot2/obstacle_class_without_depth")
        answer = call("/robot2/safe_to_push_without_depth", False)
        self.assertFalse(answer.success, answer.message)
        self.assertIn("no camera image classified yet", answer.message)
        self.assertIn("needs a depth image on /robot2/camera/depth/not_published", answer.message)
        self.assertEqual(without.since(0), [])


if __name__ == "__main__":
    init_node("test_obstacle_classifier", master_timeout_s=WAIT_S)
    rostest.rosrun("flex_nav", "test_obstacle_classifier", TestObstacleClassifier, sys.argv)
