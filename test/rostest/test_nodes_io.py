#!/usr/bin/env python3
"""rostest node: map_server / map_saver, twist_relay, and a node's costmap (CostmapROS) fed by scans,
bumper hits and clear_costmap (nodes_io.test)."""

import math
import os
import signal
import subprocess
import sys
import tempfile
import threading
import unittest

import numpy as np
import rospkg
import rospy
import rostest
import tf2_ros
from geometry_msgs.msg import Point32, PointStamped, PolygonStamped, TransformStamped, Twist, TwistStamped
from message_log import MessageLog
from nav_msgs.msg import MapMetaData, OccupancyGrid
from nav_msgs.srv import GetMap
from roscpp.srv import SetLoggerLevel
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import LaserScan
from std_srvs.srv import Trigger
from visualization_msgs.msg import Marker, MarkerArray

from flex_nav.msg import ClearCostmapAction, ClearCostmapGoal, ClearCostmapResult
from flex_nav.nav.costmap.costmap_grid import FREE, LETHAL
from flex_nav.nav.costmap.map_io import load_map
from flex_nav.ros.conversions import grid_map_of
from flex_nav.ros.costmap_ros import CostmapROS
from flex_nav.ros.node import init_node
from flex_nav.ros.proxies import ActionClientProxy

WAIT_S = 20.0  # [s] bound on anything appearing
MAP_YAML = os.path.join(rospkg.RosPack().get_path("flex_nav"), "test", "data", "maps", "test_rooms.yaml")
ROBOT = (1.0, 1.0)  # where the test puts io_base in the map
OBSTACLE = (2.0, 1.0)  # free on the map; the fake scan sees something there
LIDAR_X = 0.12  # [m] io_lidar ahead of io_base (more than two cells of the rolling window)
RELAY_TIMEOUT_S = 0.3  # [s] twist_relay's ~timeout (nodes_io.test)
RESEND_S = 0.1  # [s] a command is sent again this often until it is forwarded (less than RELAY_TIMEOUT_S)
ONE_ZERO_WATCH_S = 0.8  # [s] real test duration: after the timeout's zero, no second one for this long
STALE_DROPPED = "twist_relay: dropped a command stamped before one already forwarded"  # its debug log


class Latest(MessageLog):
    """Every message of a topic, with a wait (at most WAIT_S unless told) for one that satisfies a condition."""

    def __init__(self, topic, msg_type):
        super().__init__(topic, msg_type, wait_s=WAIT_S)


def publish_until_forwarded(pub, msg, out, condition, restamp=False):
    """Publish ``msg`` every RESEND_S until ``out`` has a message meeting ``condition`` since the first, and
    return that one (None after WAIT_S). A subscriber counts its connection before the publishing node does: a
    relay that has just come up may forward the first copies to nobody. ``restamp``: each copy stamped 0.1 s
    before now (a stamp tf can transform at)."""
    mark = out.count()
    deadline = rospy.get_time() + WAIT_S
    while rospy.get_time() < deadline:
        if restamp:
            msg.header.stamp = rospy.Time.now() - rospy.Duration(0.1)
        pub.publish(msg)
        got = out.wait_for(condition, timeout_s=RESEND_S, after=mark)
        if got is not None:
            return got
    return None


def cell_value(msg, x, y):
    grid = grid_map_of(msg)
    return int(grid.occupancy[grid.world_to_cell(x, y)])


class TestNodesIO(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.expected = load_map(MAP_YAML)
        cls.tf = tf2_ros.TransformBroadcaster()
        cls.stop = threading.Event()
        cls.tf_thread = threading.Thread(target=cls.publish_tf, daemon=True)
        cls.tf_thread.start()

    @classmethod
    def tearDownClass(cls):
        cls.stop.set()

    @classmethod
    def publish_tf(cls):
        while not cls.stop.is_set() and not rospy.is_shutdown():
            tf = TransformStamped()
            tf.header.stamp = rospy.Time.now()
            tf.header.frame_id, tf.child_frame_id = "map", "io_base"
            tf.transform.translation.x, tf.transform.translation.y = ROBOT
            tf.transform.rotation.w = 1.0
            lidar = TransformStamped()
            lidar.header.stamp = tf.header.stamp
            lidar.header.frame_id, lidar.child_frame_id = "io_base", "io_lidar"
            lidar.transform.translation.x = LIDAR_X
            lidar.transform.rotation.w = 1.0
            cls.tf.sendTransform([tf, lidar])
            rospy.sleep(0.05)

    # ------------------------------------------------------------------ map_server / map_saver
    def test_map_is_latched_with_metadata_and_service(self):
        grid_msg = Latest("map", OccupancyGrid).wait_for(lambda m: True)
        self.assertIsNotNone(grid_msg, "no map")
        self.assertEqual(grid_msg.header.frame_id, "map")
        np.testing.assert_array_equal(grid_map_of(grid_msg).occupancy, self.expected.occupancy)
        meta = Latest("map_metadata", MapMetaData).wait_for(lambda m: True)
        self.assertEqual((meta.width, meta.height), (160, 100))
        self.assertAlmostEqual(meta.resolution, 0.05, places=6)
        rospy.wait_for_service("static_map", WAIT_S)
        served = rospy.ServiceProxy("static_map", GetMap)().map
        self.assertEqual(list(served.data), list(grid_msg.data))

    def run_saver(self, *args):
        return subprocess.run(["rosrun", "flex_nav", "map_saver", *args], capture_output=True, text=True,
                              timeout=WAIT_S + 10, check=False)

    def test_map_saver_round_trip(self):
        with tempfile.TemporaryDirectory() as folder:
            name = os.path.join(folder, "saved")
            done = self.run_saver("-f", name, "--timeout", "10")
            self.assertEqual(done.returncode, 0, done.stderr)
            saved = load_map(name + ".yaml")
            np.testing.assert_array_equal(saved.occupancy, self.expected.occupancy)
            self.assertEqual(saved.origin, self.expected.origin)
            self.assertAlmostEqual(saved.resolution, self.expected.resolution)

    def test_map_saver_without_map_fails_with_reason(self):
        with tempfile.TemporaryDirectory() as folder:
            done = self.run_saver("-f", os.path.join(folder, "none"), "--timeout", "0.5", "map:=/no_map_here")
            self.assertEqual(done.returncode, 1)
            self.assertIn("no map arrived on /no_map_here within 0.5 s", done.stderr)
            self.assertFalse(os.path.exists(os.path.join(folder, "none.yaml")))

    # ------------------------------------------------------------------ twist_relay
    def test_twist_relay_stops_the_base_when_it_shuts_down(self):
        """Ctrl-C on a launch: the relay's last word to the base is a zero Twist (its timeout is off here, so
        nothing else would send one)."""
        relay = subprocess.Popen(["rosrun", "flex_nav", "twist_relay", "__name:=twist_relay", "__ns:=stopping",
                                  "_timeout:=0.0"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                 start_new_session=True)
        try:
            out = Latest("stopping/cmd_vel", Twist)
            pub = rospy.Publisher("stopping/cmd_vel_stamped", TwistStamped, queue_size=1)
            deadline = rospy.get_time() + WAIT_S
            while (pub.get_num_connections() == 0 or out.sub.get_num_connections() == 0) and \
                    rospy.get_time() < deadline:
                rospy.sleep(0.05)
            self.assertGreater(out.sub.get_num_connections(), 0, "the second relay did not come up")
            cmd = TwistStamped()
            cmd.header.stamp = rospy.Time.now()
            cmd.twist.linear.x = 0.2
            self.assertIsNotNone(publish_until_forwarded(pub, cmd, out, lambda m: m.linear.x == 0.2),
                                 "command not forwarded")
            moving = out.count()
            relay.send_signal(signal.SIGINT)
            relay.wait(timeout=WAIT_S)
            stop = out.wait_for(lambda m: m.linear.x == 0.0 and m.angular.z == 0.0, timeout_s=2.0, after=moving)
            self.assertIsNotNone(stop, "no zero Twist when the relay shut down")
            self.assertEqual(out.msgs[-1].linear.x, 0.0, "a command followed the zero")
            pub.unregister()
            out.sub.unregister()
        finally:
            if relay.poll() is None:
                relay.kill()
                relay.wait(timeout=WAIT_S)

    def test_twist_relay_forwards_drops_non_finite_and_times_out(self):
        logs = Latest("/rosout", Log)  # early: connected long before the relay's log this test waits for
        out = Latest("cmd_vel", Twist)
        pub = rospy.Publisher("cmd_vel_stamped", TwistStamped, queue_size=1)
        deadline = rospy.get_time() + WAIT_S
        while (pub.get_num_connections() == 0 or out.sub.get_num_connections() == 0) and rospy.get_time() < deadline:
            rospy.sleep(0.05)
        self.assertGreater(pub.get_num_connections(), 0, "twist_relay did not subscribe to cmd_vel_stamped")
        self.assertGreater(out.sub.get_num_connections(), 0, "no connection to twist_relay's cmd_vel")
        cmd = TwistStamped()
        cmd.twist.linear.x, cmd.twist.angular.z = 0.25, -0.5
        before = out.count()
        got = publish_until_forwarded(pub, cmd, out, lambda m: m.linear.x == 0.25)
        self.assertIsNotNone(got, "command not forwarded")
        self.assertEqual(got.angular.z, -0.5)
        # silence: exactly one zero Twist after the RELAY_TIMEOUT_S timeout
        zero = out.wait_for(lambda m: m.linear.x == 0.0 and m.angular.z == 0.0, after=out.count() - 1)
        self.assertIsNotNone(zero, "no zero Twist after the timeout")
        rospy.sleep(ONE_ZERO_WATCH_S)
        zeros_after = [m for m in out.msgs[before:] if m.linear.x == 0.0 and m.angular.z == 0.0]
        self.assertEqual(len(zeros_after), 1, "the timeout zero must be sent once")
        # a NaN command is not forwarded; a zero goes out instead
        cmd.twist.linear.x = 0.3
        pub.publish(cmd)
        self.assertIsNotNone(out.wait_for(lambda m: m.linear.x == 0.3, after=out.count()))
        mark = out.count()
        bad = TwistStamped()
        bad.twist.linear.x, bad.twist.angular.z = float("nan"), 0.1
        pub.publish(bad)
        stop = out.wait_for(lambda m: True, after=mark)
        self.assertIsNotNone(stop)
        self.assertEqual((stop.linear.x, stop.angular.z), (0.0, 0.0))
        self.assertFalse(any(math.isnan(m.linear.x) for m in out.msgs))
        # stamped commands from two publishers: a drive stamped before a forwarded stop is dropped
        now = rospy.Time.now()
        halt = TwistStamped()
        halt.header.stamp = now
        mark = out.count()
        pub.publish(halt)
        self.assertIsNotNone(out.wait_for(lambda m: m.linear.x == 0.0, after=mark))
        late = TwistStamped()
        late.header.stamp = now - rospy.Duration(0.1)
        late.twist.linear.x = 0.2
        newer = TwistStamped()
        newer.header.stamp = now + rospy.Duration(0.1)
        newer.twist.linear.x = 0.1
        mark = out.count()
        rospy.wait_for_service("twist_relay/set_logger_level", WAIT_S)
        rospy.ServiceProxy("twist_relay/set_logger_level", SetLoggerLevel)(logger="rosout", level="debug")
        log_mark = logs.count()
        pub.publish(late)
        # the relay took it (and newer cannot displace it from its one-message queue): its debug log says so
        dropped = logs.wait_for(lambda m: m.name == "/twist_relay" and m.msg == STALE_DROPPED, after=log_mark)
        rospy.ServiceProxy("twist_relay/set_logger_level", SetLoggerLevel)(logger="rosout", level="info")
        self.assertIsNotNone(dropped, "the relay did not drop the stale command")
        pub.publish(newer)
        self.assertIsNotNone(out.wait_for(lambda m: m.linear.x == 0.1, after=mark), "newer command not forwarded")
        self.assertFalse(any(m.linear.x == 0.2 for m in out.msgs[mark:]), "a stale command was forwarded")

    def test_twist_relay_sends_no_timeout_zero_and_no_warning_after_a_stop(self):
        """A controller's last command at its goal is a stop: the silence after it is no fault."""
        logs = Latest("/rosout", Log)
        out = Latest("cmd_vel", Twist)
        pub = rospy.Publisher("cmd_vel_stamped", TwistStamped, queue_size=1)
        drive = TwistStamped()
        drive.twist.linear.x = 0.15
        self.assertIsNotNone(publish_until_forwarded(pub, drive, out, lambda m: m.linear.x == 0.15))
        mark, log_mark = out.count(), logs.count()
        pub.publish(TwistStamped())
        self.assertIsNotNone(out.wait_for(lambda m: m.linear.x == 0.0, after=mark), "the stop was not forwarded")
        rospy.sleep(RELAY_TIMEOUT_S + ONE_ZERO_WATCH_S)
        self.assertEqual(out.count() - mark, 1, "a timeout zero followed the stop")
        warnings = [m.msg for m in logs.since(log_mark) if m.name == "/twist_relay" and "no command for" in m.msg]
        self.assertEqual(warnings, [])
        pub.unregister()
        out.sub.unregister()
        logs.sub.unregister()

    # ------------------------------------------------------------------ CostmapROS
    def test_costmap_marks_scan_and_bumper_and_clears(self):
        costmap = Latest("get_path_server/global_costmap/costmap", OccupancyGrid)
        first = costmap.wait_for(lambda m: True)
        self.assertIsNotNone(first, "no costmap published")
        self.assertEqual(first.header.frame_id, "map")
        self.assertEqual(cell_value(first, *OBSTACLE), 0)
        scans = rospy.Publisher("io_scan", LaserScan, queue_size=1)
        scan = LaserScan()
        scan.header.frame_id = "io_base"
        scan.angle_min, scan.angle_increment, scan.angle_max = -0.1, 0.01, 0.1
        scan.range_min, scan.range_max = 0.05, 3.0
        scan.ranges = [OBSTACLE[0] - ROBOT[0]] * 21
        deadline = rospy.get_time() + WAIT_S
        marked = None
        while marked is None and rospy.get_time() < deadline:
            scan.header.stamp = rospy.Time.now() - rospy.Duration(0.1)
            scans.publish(scan)
            marked = costmap.wait_for(lambda m: cell_value(m, *OBSTACLE) == 100, timeout_s=0.3,
                                      after=costmap.count())
        self.assertIsNotNone(marked, "the scan did not mark the obstacle")
        self.assertEqual(cell_value(marked, OBSTACLE[0] + 0.15, OBSTACLE[1] + 0.5), 0)
        self.assertGreater(cell_value(marked, OBSTACLE[0] - 0.1, OBSTACLE[1]), 0)  # inflated around it
        scans.unregister()

        clear = ActionClientProxy("get_path_server/clear_costmap", ClearCostmapAction)
        self.assertTrue(clear.is_available(WAIT_S))
        mark = costmap.count()
        clear.send_goal(ClearCostmapGoal())
        self.assertTrue(clear.wait_for_result(5.0))
        self.assertEqual(clear.result().code, ClearCostmapResult.SUCCESS)
        cleared = costmap.wait_for(lambda m: cell_value(m, *OBSTACLE) == 0, after=mark)
        self.assertIsNotNone(cleared, "clear_costmap did not clear the scan mark")
        # the static map survives a clear
        self.assertEqual(cell_value(cleared, 4.05, 1.0), 100)

        bumps = rospy.Publisher("io_bumper", PointStamped, queue_size=1)
        hit = PointStamped()
        hit.header.frame_id = "io_base"
        hit.point.x = 0.2  # in front of the robot
        marked = None
        deadline = rospy.get_time() + WAIT_S
        while marked is None and rospy.get_time() < deadline:
            hit.header.stamp = rospy.Time.now() - rospy.Duration(0.1)
            bumps.publish(hit)
            marked = costmap.wait_for(lambda m: cell_value(m, ROBOT[0] + 0.2, ROBOT[1]) == 100, timeout_s=0.3,
                                      after=costmap.count())
        self.assertIsNotNone(marked, "the bumper hit was not marked")

    def test_obstacle_memory_keeps_a_heavy_obstacle_through_clear_costmap_until_the_operator_clears_it(self):
        costmap = Latest("get_path_server/global_costmap/costmap", OccupancyGrid)
        remembered = Latest("get_path_server/global_costmap/obstacle_memory", MarkerArray)
        empty = remembered.wait_for(lambda m: True)  # latched once the map came: nothing remembered yet
        self.assertIsNotNone(empty, "no obstacle_memory markers latched")
        self.assertEqual([m.action for m in empty.markers], [Marker.DELETEALL])
        self.assertIsNotNone(costmap.wait_for(lambda m: True), "no costmap published")
        heavy = (2.65, 1.0)  # free on the map, 1.65 m ahead of io_base
        self.assertEqual(cell_value(costmap.wait_for(lambda m: True), *heavy), 0)
        marks = rospy.Publisher("obstacle_memory/mark", PolygonStamped, queue_size=1)
        footprint = PolygonStamped()
        footprint.header.frame_id = "io_base"  # the robot's frame, as RememberObstacleState sends it
        footprint.polygon.points = [Point32(x=x, y=y) for x, y in ((1.5, -0.15), (1.8, -0.15), (1.8, 0.15),
                                                                      (1.5, 0.15))]
        marked = None
        deadline = rospy.get_time() + WAIT_S
        while marked is None and rospy.get_time() < deadline:
            footprint.header.stamp = rospy.Time.now() - rospy.Duration(0.1)
            marks.publish(footprint)
            marked = costmap.wait_for(lambda m: cell_value(m, *heavy) == 100, timeout_s=0.3, after=costmap.count())
        self.assertIsNotNone(marked, "the remembered footprint was not marked")
        marks.unregister()
        shown = remembered.wait_for(lambda m: len(m.markers) > 1)
        self.assertIsNotNone(shown, "the remembered obstacle was not published as markers")
        self.assertEqual([(m.action, m.type, m.ns) for m in shown.markers],
                         [(Marker.DELETEALL, 0, ""), (Marker.ADD, Marker.LINE_STRIP, "footprint"),
                          (Marker.ADD, Marker.TEXT_VIEW_FACING, "text")])
        self.assertTrue(all(m.header.frame_id == "map" for m in shown.markers))
        corners = [(round(p.x, 2), round(p.y, 2)) for p in shown.markers[1].points]
        self.assertEqual(corners, [(2.5, 0.85), (2.8, 0.85), (2.8, 1.15), (2.5, 1.15), (2.5, 0.85)])  # in the map
        self.assertRegex(shown.markers[2].text, r"^#1 heavy at \(2\.65, 1\.00\) m, 0\.30 x 0\.30 m, found at ")
        clear = ActionClientProxy("get_path_server/clear_costmap", ClearCostmapAction)
        self.assertTrue(clear.is_available(WAIT_S))
        mark = costmap.count()
        clear.send_goal(ClearCostmapGoal())
        self.assertTrue(clear.wait_for_result(5.0))
        after_clear = costmap.wait_for(lambda m: True, after=mark + 1)  # a publication after the clear
        self.assertIsNotNone(after_clear)
        self.assertEqual(cell_value(after_clear, *heavy), 100, "clear_costmap forgot the remembered obstacle")
        rospy.wait_for_service("get_path_server/global_costmap/clear_obstacle_memory", WAIT_S)
        answer = rospy.ServiceProxy("get_path_server/global_costmap/clear_obstacle_memory", Trigger)()
        self.assertTrue(answer.success)
        self.assertIn("1 remembered obstacle(s) forgotten", answer.message)
        forgotten = costmap.wait_for(lambda m: cell_value(m, *heavy) == 0, after=costmap.count())
        self.assertIsNotNone(forgotten, "the operator's clear did not forget it")
        cleared = remembered.wait_for(lambda m: len(m.markers) == 1)
        self.assertIsNotNone(cleared, "the operator's clear was not published as markers")
        self.assertEqual(cleared.markers[0].action, Marker.DELETEALL)

        # marked again, then a scan sees through it (no return behind it): forgotten at once, and published so
        marks = rospy.Publisher("obstacle_memory/mark", PolygonStamped, queue_size=1)
        again = publish_until_forwarded(marks, footprint, remembered, lambda m: len(m.markers) == 3, restamp=True)
        self.assertIsNotNone(again, "the second mark was not published as markers")
        marks.unregister()
        scans = rospy.Publisher("io_scan", LaserScan, queue_size=1)
        scan = LaserScan()
        scan.header.frame_id = "io_base"
        scan.angle_min, scan.angle_increment, scan.angle_max = -0.1, 0.01, 0.1  # 21 beams across the footprint
        scan.range_min, scan.range_max = 0.05, 3.0
        scan.ranges = [math.inf] * 21
        seen_gone = publish_until_forwarded(scans, scan, remembered, lambda m: len(m.markers) == 1, restamp=True)
        scans.unregister()
        self.assertIsNotNone(seen_gone, "a scan through the remembered obstacle did not forget it (markers)")
        self.assertEqual(seen_gone.markers[0].action, Marker.DELETEALL)

    def test_rolling_costmap_snapshot_matches_the_newest_scan(self):
        """A controller reads its local costmap through snapshot(): right after a scan, with no timer update in
        between, the obstacle must be in the copied costs where the geometry says (the window follows the base,
        not the lidar)."""
        ns = "~rolling_io/"
        for key, value in (("rolling_window", True), ("static_map", False), ("scan_topic", "io_scan_rolling"),
                           ("bumper_topic", ""), ("robot_base_frame", "io_base"), ("width", 3.0), ("height", 3.0),
                           ("inflation_radius", 0.2), ("robot_radius", 0.1),
                           ("update_frequency", 0.1), ("publish_frequency", 0.0)):  # the timer stays out of it
            rospy.set_param(ns + key, value)
        buffer = tf2_ros.Buffer()
        listener = tf2_ros.TransformListener(buffer)
        local = CostmapROS("rolling_io", buffer, rolling_default=True)
        scans = rospy.Publisher("io_scan_rolling", LaserScan, queue_size=1)
        try:
            scan = LaserScan()
            scan.header.frame_id = "io_lidar"
            scan.angle_min, scan.angle_increment, scan.angle_max = -0.1, 0.01, 0.1
            scan.range_min, scan.range_max = 0.05, 3.0
            scan.ranges = [OBSTACLE[0] - ROBOT[0] - LIDAR_X] * 21  # the same point as the node's scan above
            deadline = rospy.get_time() + WAIT_S
            while local.last_scan_received_s is None and rospy.get_time() < deadline:
                scan.header.stamp = rospy.Time.now() - rospy.Duration(0.1)
                scans.publish(scan)
                rospy.sleep(0.2)
            self.assertIsNotNone(local.last_scan_received_s, "the rolling costmap took no scan")
            snapshot = local.snapshot()
            self.assertIsNotNone(snapshot)
            costs, geometry = snapshot
            half_cell = geometry.resolution / 2.0
            centre_x = geometry.origin_x + geometry.width * geometry.resolution / 2.0
            centre_y = geometry.origin_y + geometry.height * geometry.resolution / 2.0
            self.assertLessEqual(abs(centre_x - ROBOT[0]), geometry.resolution + half_cell,
                                 f"window centred at x={centre_x:.3f}, the base is at {ROBOT[0]}")
            self.assertLessEqual(abs(centre_y - ROBOT[1]), geometry.resolution + half_cell)
            row, col = geometry.world_to_cell(*OBSTACLE)  # the hit lies on a cell edge: it may mark either side
            self.assertEqual(int(costs[row - 1:row + 2, col - 1:col + 2].max()), LETHAL,
                             "the scanned obstacle is not in the snapshot's costs")
            row, col = geometry.world_to_cell(OBSTACLE[0] - 0.5, OBSTACLE[1])
            self.assertEqual(int(costs[row, col]), FREE, "free space between robot and obstacle is not free")
        finally:
            scans.unregister()
            listener.unregister()


if __name__ == "__main__":
    init_node("test_nodes_io", master_timeout_s=WAIT_S)
    rostest.rosrun("flex_nav", "test_nodes_io", TestNodesIO, sys.argv)
