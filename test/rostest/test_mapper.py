#!/usr/bin/env python3
"""rostest node for mapper.test: the mapper's ROS interface on the simulator without a map.

The tests run in the order of their names (unittest sorts them): a map and map -> odom appear and grow as the
robot drives; dynamic_map serves the same map; save_map writes a map_server pair that flex_nav's map loader reads
(and refuses paths it cannot write, keeping the graph); serialize_map / deserialize_map round-trip the graph (a bad
file is refused and the map kept); the probe mapper drops bad beams and scans in unknown frames, and restarts its
odometry reference on a scan stamped back in time.
"""

import math
import sys
import tempfile
import time
import unittest
from pathlib import Path

import numpy as np
import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import PoseWithCovarianceStamped, Twist, Vector3
from message_log import MessageLog
from nav_msgs.msg import OccupancyGrid
from nav_msgs.srv import GetMap
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import LaserScan
from std_msgs.msg import String

from flex_nav.nav.costmap.map_io import load_map
from flex_nav.ros.node import init_node
from flex_nav.srv import MapFile

WAIT_S = 60.0  # [s] bound on every wait


class WallLog(MessageLog):
    def now_s(self):
        return time.monotonic()


def known_cells(grid):
    return int(np.count_nonzero(np.asarray(grid.data, dtype=np.int8) >= 0))


class TestMapper(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        init_node("test_mapper")
        cls.maps = WallLog("/map", OccupancyGrid, wait_s=WAIT_S)
        cls.probe_maps = WallLog("/probe/map", OccupancyGrid, wait_s=WAIT_S)
        cls.status = WallLog("/robot1/mapper/status", String, wait_s=WAIT_S)
        cls.rosout = WallLog("/rosout_agg", Log, queue_size=None, wait_s=WAIT_S)
        cls.scans = WallLog("/robot1/scan", LaserScan, wait_s=WAIT_S)
        cls.poses = WallLog("/robot1/pose", PoseWithCovarianceStamped, wait_s=WAIT_S)
        cls.cmd = rospy.Publisher("/robot1/cmd_vel", Twist, queue_size=1)
        cls.probe_scan = rospy.Publisher("/probe/scan", LaserScan, queue_size=5)
        cls.tf_buffer = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf_buffer)
        for name in ("/robot1/dynamic_map", "/robot1/mapper/save_map", "/robot1/mapper/serialize_map",
                     "/robot1/mapper/deserialize_map"):
            rospy.wait_for_service(name, timeout=WAIT_S)
        cls.dynamic_map = rospy.ServiceProxy("/robot1/dynamic_map", GetMap)
        cls.save_map = rospy.ServiceProxy("/robot1/mapper/save_map", MapFile)
        cls.serialize = rospy.ServiceProxy("/robot1/mapper/serialize_map", MapFile)
        cls.deserialize = rospy.ServiceProxy("/robot1/mapper/deserialize_map", MapFile)
        cls.folder = Path(tempfile.mkdtemp(prefix="flex_nav_mapper_"))

    def drive(self, v, w, duration_s):
        end = time.monotonic() + duration_s
        while time.monotonic() < end and not rospy.is_shutdown():
            self.cmd.publish(Twist(linear=Vector3(x=v), angular=Vector3(z=w)))
            time.sleep(0.05)
        self.cmd.publish(Twist())

    def logged(self, text, after):
        line = self.rosout.wait_for(lambda m: text in m.msg, after=after)
        self.assertIsNotNone(line, f"no log line with {text!r}")
        return line

    def test_1_map_and_transform_appear_and_grow(self):
        first = self.maps.wait_for(lambda m: m.info.width > 0)
        self.assertIsNotNone(first, "no map on /map")
        self.assertEqual(first.header.frame_id, "map")
        self.assertAlmostEqual(first.info.resolution, 0.05, places=6)
        before = known_cells(first)
        count = self.maps.count()
        self.drive(0.3, 0.4, 6.0)  # an arc: new keyframes, new cells
        grown = self.maps.wait_for(lambda m: known_cells(m) > before + 200, after=count)
        self.assertIsNotNone(grown, f"the map did not grow past {before} known cells")
        tf = self.tf_buffer.lookup_transform("map", "robot1/odom", rospy.Time(0), rospy.Duration(5.0))
        self.assertTrue(all(math.isfinite(v) for v in (tf.transform.translation.x, tf.transform.translation.y)))
        status = self.status.wait_for(lambda m: "keyframes" in m.data)
        self.assertIsNotNone(status)
        pose = self.poses.wait_for(lambda m: m.header.frame_id == "map")
        self.assertIsNotNone(pose, "no robot pose on /robot1/pose")

    def test_2_dynamic_map_serves_the_map(self):
        served = self.dynamic_map().map
        self.assertGreater(served.info.width, 0)
        self.assertEqual(served.header.frame_id, "map")
        self.assertGreater(known_cells(served), 500)

    def test_3_save_map_writes_a_map_server_pair(self):
        target = self.folder / "lab_map"
        reply = self.save_map(path=str(target))
        self.assertTrue(reply.ok, reply.message)
        grid = load_map(target.with_suffix(".yaml"))
        self.assertTrue(target.with_suffix(".pgm").is_file())
        served = self.dynamic_map().map
        self.assertAlmostEqual(grid.resolution, served.info.resolution, places=6)
        self.assertGreater(int(np.count_nonzero(grid.occupancy == 100)), 50)
        self.assertGreater(int(np.count_nonzero(grid.occupancy == 0)), 500)

    def test_4_save_map_refuses_what_it_cannot_write(self):
        reply = self.save_map(path="/nonexistent_folder_flex_nav/map")
        self.assertFalse(reply.ok)
        self.assertIn("/nonexistent_folder_flex_nav", reply.message)
        reply = self.save_map(path="  ")
        self.assertFalse(reply.ok)
        self.assertIn("path must name a file", reply.message)
        self.assertGreater(known_cells(self.dynamic_map().map), 500)  # the graph is kept

    def test_5_serialize_and_deserialize(self):
        target = self.folder / "graph"
        reply = self.serialize(path=str(target))
        self.assertTrue(reply.ok, reply.message)
        self.assertTrue(target.with_suffix(".posegraph").is_file())
        broken = self.folder / "broken"
        broken.with_suffix(".posegraph").write_text("{not json", encoding="utf-8")
        before = known_cells(self.dynamic_map().map)
        reply = self.deserialize(path=str(broken))
        self.assertFalse(reply.ok)
        self.assertIn("the current map is kept", reply.message)
        self.assertEqual(known_cells(self.dynamic_map().map), before)
        reply = self.deserialize(path=str(target))
        self.assertTrue(reply.ok, reply.message)
        self.assertGreater(known_cells(self.dynamic_map().map), 500)

    def test_6_probe_drops_bad_beams_unknown_frames_and_time_going_back(self):
        mark = self.rosout.count()
        dropped = "beams NaN, -inf or outside [0.02, 5.6] m: dropped"
        deadline = time.monotonic() + WAIT_S
        while not any(dropped in m.msg for m in self.rosout.since(mark)) and time.monotonic() < deadline:
            scan = self.scans.wait_for(lambda _m: True, after=max(0, self.scans.count() - 1))
            ranges = list(scan.ranges)
            for i in range(0, len(ranges) // 2):  # the first half of every scan broken, four ways
                ranges[i] = (math.nan, -math.inf, -1.0, 1e6)[i % 4]
            scan.ranges = ranges
            self.probe_scan.publish(scan)
            time.sleep(0.2)
        line = self.logged("of 681 " + dropped, mark).msg
        self.assertEqual(int(line.split("scan: ")[1].split(" of ")[0]), 340, line)
        self.assertIsNotNone(self.probe_maps.wait_for(lambda m: known_cells(m) > 100), "the probe made no map")
        scan = self.scans.wait_for(lambda _m: True, after=max(0, self.scans.count() - 1))
        scan.header.frame_id = "nowhere"
        self.probe_scan.publish(scan)
        self.logged("scan ignored: its frame 'nowhere' cannot be placed in the base frame 'robot1/base_footprint'",
                    mark)
        scan = self.scans.wait_for(lambda _m: True, after=max(0, self.scans.count() - 1))
        scan.header.stamp -= rospy.Duration(5.0)
        self.probe_scan.publish(scan)
        self.logged("(time went back): odometry reference restarted", mark)


if __name__ == "__main__":
    rostest.rosrun("flex_nav", "mapper_check", TestMapper, sys.argv)
