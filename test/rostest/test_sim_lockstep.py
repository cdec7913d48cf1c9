#!/usr/bin/env python3
"""rostest node: the simulator's lockstep mode through a real master (see sim_lockstep.test)."""

import contextlib
import sys
import threading
import time
import unittest

import actionlib
import rospy
import rostest
import tf2_ros
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import PoseStamped, PoseWithCovarianceStamped, Twist, TwistStamped
from message_log import MessageLog
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock, Log
from sensor_msgs.msg import LaserScan
from std_srvs.srv import Trigger

from flex_nav.msg import ClearCostmapAction, ClearCostmapResult, LockstepHold, SimEvent
from flex_nav.ros.lockstep import LockstepParticipant
from flex_nav.ros.node import init_node
from flex_nav.ros.proxies import ActionClientProxy, RosProxies, Subscription

WAIT_S = 20.0  # [s] wall-time bound on every wait
TIMEOUT_S = 2.0  # [s] wall: the simulator's ~lockstep_timeout (sim_lockstep.test)
STEP_S = 1.0 / 240.0  # [s] one physics step
LATE_WALKER_AT_S = 10.0  # [s] open_room's start_walking event, in the world's time
LEAD_S = 5.0  # [s] simulated: a hold this far ahead arrives before the simulation (rtf 0) gets there


class WallLog(MessageLog):
    """A topic's messages, waited on in wall time (simulated time stands while the test holds it)."""

    def __init__(self, topic, msg_type, queue_size=None):
        super().__init__(topic, msg_type, queue_size=queue_size, wait_s=WAIT_S, poll_s=0.005)

    def now_s(self):
        return time.monotonic()


def clock_s(msg):
    return msg.clock.to_sec()


@contextlib.contextmanager
def topic_hold_renewed(hold, topic):
    """Hold ``topic`` from its first message after time 0, renewed (a new, still reached stamp) before the simulator's
    timeout would drop it: a test whose view of /clock lags on a loaded machine still finds time standing."""
    done = threading.Event()

    def renew():
        renewals = 1
        while not done.wait(TIMEOUT_S / 4.0):
            renewals += 1
            hold.hold_topic(topic, renewals * 1e-9)

    hold.hold_topic(topic, 1e-9)
    renewer = threading.Thread(target=renew, daemon=True)
    renewer.start()
    try:
        yield
    finally:
        done.set()
        renewer.join()


class TestSimLockstep(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        init_node("test_sim_lockstep")
        # only the newest clock counts: a bounded queue keeps this node's view from lagging far behind on a loaded
        # machine (at rtf 0 the simulator sends thousands of clock messages a second)
        cls.clock = WallLog("/clock", Clock, queue_size=1)
        cls.scan = WallLog("/robot1/scan", LaserScan)
        cls.events = WallLog("/sim_events", SimEvent)
        cls.rosout = WallLog("/rosout", Log)
        cls.holds = WallLog("/lockstep/holds", LockstepHold)
        cls.poses = WallLog("/robot1/initialpose", PoseWithCovarianceStamped)
        cls.tf_buffer = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf_buffer)
        cls.clock.newest(lambda m: clock_s(m) > 0.5)

    def now(self):
        return clock_s(self.clock.newest(lambda m: True))

    def stands_at(self, stamp_s, wall_s):
        """Simulated time reaches ``stamp_s`` and stays within a step of it for ``wall_s`` of wall time (reached
        within 1 µs: /clock carries whole nanoseconds, and a sum of two times in floats may lie a nanosecond above
        the step the simulator stands at)."""
        self.clock.newest(lambda m: clock_s(m) >= stamp_s - 1e-6)
        time.sleep(wall_s)
        self.assertLess(self.now(), stamp_s + STEP_S + 1e-6)

    def frozen_at(self, hold):
        """Hold simulated time where it is when the hold arrives (this node's view of /clock may lag behind on a
        loaded machine, so a hold 'a little ahead' could already be passed) and return where it stands. The hold is
        renewed (a new stamp, still passed) before the simulator's timeout would drop it, so a view that lags by
        more than the timeout still finds time standing."""
        deadline = time.monotonic() + WAIT_S
        renewals = 0
        hold.hold_clock(0.0)
        renewed_at = time.monotonic()
        before = self.now()
        while time.monotonic() < deadline:
            time.sleep(0.2)
            if time.monotonic() - renewed_at > TIMEOUT_S / 4.0:
                renewals += 1
                hold.hold_clock(renewals * 1e-6)
                renewed_at = time.monotonic()
            now = self.now()
            if now == before:
                return now
            before = now
        self.fail(f"simulated time did not stand still within {WAIT_S} s (at {before:.3f} s)")

    def test_1_a_clock_hold_stops_simulated_time_until_replaced(self):
        hold = LockstepParticipant("clock_hold", enabled=True)
        self.assertTrue(hold.wait_connected(WAIT_S))
        stop_s = self.frozen_at(hold) + 1.0
        hold.hold_clock(stop_s)  # replaced while the simulation stands: it goes on to there
        self.stands_at(stop_s, TIMEOUT_S / 2.0)
        hold.hold_clock(stop_s + 1.0)  # replaced: on to the next
        self.stands_at(stop_s + 1.0, TIMEOUT_S / 2.0)
        hold.release()
        self.clock.newest(lambda m: clock_s(m) > stop_s + 3.0)

    def test_2_a_topic_hold_stops_after_the_scan_and_its_transform_is_there(self):
        hold = LockstepParticipant("scan_hold", enabled=True)
        self.assertTrue(hold.wait_connected(WAIT_S))
        after_s = self.now() + LEAD_S
        hold.hold_topic("/robot1/scan", after_s)
        scan = self.scan.newest(lambda m: m.header.stamp.to_sec() >= after_s)
        time.sleep(TIMEOUT_S / 2.0)
        newest = self.scan.newest(lambda m: True)
        self.assertEqual(newest.header.stamp, scan.header.stamp)  # nothing after it while held
        # the scan went out with the odometry at (or after) its stamp: tf places it without a later step
        self.assertTrue(self.tf_buffer.can_transform("robot1/odom", "robot1/base_footprint", scan.header.stamp))
        hold.release()
        self.scan.newest(lambda m: m.header.stamp > scan.header.stamp)

    def test_3_a_hold_nobody_replaces_is_dropped_after_the_timeout(self):
        hold = LockstepParticipant("forgotten_hold", enabled=True)
        self.assertTrue(hold.wait_connected(WAIT_S))
        stop_s = self.now() + LEAD_S
        hold.hold_clock(stop_s)
        self.clock.newest(lambda m: clock_s(m) >= stop_s)
        held_from = time.monotonic()
        self.clock.newest(lambda m: clock_s(m) > stop_s + 0.5)  # it goes on: the hold was dropped
        held_wall_s = time.monotonic() - held_from
        self.assertGreater(held_wall_s, TIMEOUT_S * 0.7)
        report = self.rosout.wait_for(lambda m: "forgotten_hold" in m.msg and "dropped" in m.msg)
        self.assertEqual(report.level, Log.WARN)

    def test_4_the_worlds_script_starts_on_request_and_only_once(self):
        self.assertEqual([e for e in self.events.since(0) if e.kind == SimEvent.WORLD_EVENT], [])
        rospy.wait_for_service("/sim/start_world", timeout=WAIT_S)
        start = rospy.ServiceProxy("/sim/start_world", Trigger)
        hold = LockstepParticipant("world_start", enabled=True)
        self.assertTrue(hold.wait_connected(WAIT_S))
        pose_hold = LockstepParticipant("localizer_like", enabled=True)  # as the localizer holds for a world start
        self.assertTrue(pose_hold.wait_connected(WAIT_S))
        with topic_hold_renewed(pose_hold, "/robot1/initialpose"):
            start_s = self.now() + LEAD_S
            hold.hold_clock(start_s)  # so the start falls on a known step
            self.stands_at(start_s, 0.2)
            answer = start()
            self.assertTrue(answer.success, answer.message)
            held_at_s = self.now()
            hold.release()
            # the initial pose goes out again, stamped at the start, and the simulation waits for its taker
            pose = self.poses.newest(lambda m: m.header.stamp.to_sec() > 0.0)
            self.assertAlmostEqual(pose.header.stamp.to_sec(), held_at_s, delta=STEP_S / 2.0)
            self.stands_at(held_at_s + STEP_S, TIMEOUT_S / 2.0)
        pose_hold.release()
        event = self.events.newest(lambda e: e.kind == SimEvent.WORLD_EVENT)
        self.assertEqual(event.other, "late_walker")
        self.assertAlmostEqual(event.header.stamp.to_sec(), held_at_s + LATE_WALKER_AT_S, delta=2 * STEP_S)
        again = start()
        self.assertFalse(again.success)
        self.assertIn("started already", again.message)

    def test_5_a_sent_command_is_waited_for_and_drives_the_robot_from_the_next_step(self):
        commands = rospy.Publisher("/robot1/cmd_vel_stamped", TwistStamped, queue_size=10)
        relay_copies = rospy.Publisher("/robot1/cmd_vel", Twist, queue_size=10)
        odom = WallLog("/robot1/odom", Odometry)
        hold = LockstepParticipant("controller", enabled=True)
        self.assertTrue(hold.wait_connected(WAIT_S))
        deadline = time.monotonic() + WAIT_S
        while commands.get_num_connections() == 0 and time.monotonic() < deadline:
            time.sleep(0.01)
        self.assertGreater(commands.get_num_connections(), 0, "the simulator takes no stamped commands")
        stop_s = self.now() + LEAD_S
        hold.hold_clock(stop_s)
        self.stands_at(stop_s, 0.1)
        stamp = self.clock.newest(lambda m: True).clock
        hold.sent("/robot1/cmd_vel_stamped", stamp.to_sec())  # announced, not published yet
        hold.release()
        self.stands_at(stamp.to_sec(), TIMEOUT_S / 2.0)  # it waits for the command, not for the released hold
        command = TwistStamped()
        command.header.stamp = stamp
        command.twist.linear.x = 0.2
        commands.publish(command)
        moving = odom.newest(lambda m: m.twist.twist.linear.x > 0.01)
        self.assertLess(moving.header.stamp.to_sec(), stamp.to_sec() + 0.5)
        self.assertFalse([m for m in self.rosout.since(0) if "/controller" in m.msg and "dropped" in m.msg],
                         "the announced command was dropped, not received")
        # stopped by a later stamped zero; twist_relay's Twist copies do not drive a lockstep simulation
        command.header.stamp = self.clock.newest(lambda m: True).clock
        command.twist.linear.x = 0.0
        commands.publish(command)
        stopped = odom.newest(lambda m: abs(m.twist.twist.linear.x) < 1e-3)
        relay_copies.publish(Twist())
        later = Twist()
        later.linear.x = 0.3
        relay_copies.publish(later)
        after_s = stopped.header.stamp.to_sec() + 1.0
        self.assertLess(abs(odom.newest(lambda m: m.header.stamp.to_sec() >= after_s).twist.twist.linear.x), 1e-3)

    def test_6_a_result_sent_while_the_simulation_stands_is_seen_only_once_it_goes_on(self):
        server = actionlib.SimpleActionServer(
            "/instant_server", ClearCostmapAction, lambda _goal: server.set_succeeded(ClearCostmapResult()),
            auto_start=False)
        server.start()
        client = ActionClientProxy("/instant_server", ClearCostmapAction)
        self.assertTrue(client.is_available(WAIT_S))
        hold = LockstepParticipant("behavior_tick", enabled=True)
        self.assertTrue(hold.wait_connected(WAIT_S))
        tick_s = self.now() + LEAD_S
        hold.hold_clock(tick_s)
        self.stands_at(tick_s, 0.1)
        client.send_goal(ClearCostmapAction().action_goal.goal)
        self.assertTrue(client.wait_for_result(WAIT_S))  # it has arrived (a wall-time wait) ...
        self.assertFalse(client.has_result())  # ... but a tick at the time it was sent does not see it
        hold.release()
        self.clock.newest(lambda m: clock_s(m) > tick_s + 0.05)
        self.assertTrue(client.has_result())
        self.assertEqual(client.state(), GoalStatus.SUCCEEDED)

    def test_7_a_behaviors_velocity_commands_are_announced_with_its_hold(self):
        hold = LockstepParticipant("announcing_behavior", enabled=True)
        self.assertTrue(hold.wait_connected(WAIT_S))
        proxies = RosProxies(lockstep=hold)
        try:
            commands = proxies.publisher("/robot1/cmd_vel_stamped", TwistStamped)
            deadline = time.monotonic() + WAIT_S
            while commands.get_num_connections() == 0 and time.monotonic() < deadline:
                time.sleep(0.01)
            tick_s = self.now() + LEAD_S
            hold.hold_clock(tick_s)
            self.stands_at(tick_s, 0.05)
            stop = TwistStamped()
            stop.header.stamp = self.clock.newest(lambda m: True).clock
            commands.publish(stop)
            announced = self.holds.newest(lambda m: m.participant == hold.name and m.sent_topic)
            self.assertEqual(announced.sent_topic, "/robot1/cmd_vel_stamped")
            self.assertEqual(announced.sent_stamp_s, stop.header.stamp.to_sec())
            self.assertTrue(announced.holding)  # with the behavior's current hold, which it keeps
            self.assertEqual(announced.stamp_s, tick_s)
            hold.release()
            self.clock.newest(lambda m: clock_s(m) > tick_s + 0.05)  # received: the simulation goes on
        finally:
            proxies.shutdown()

    def test_8_a_message_stamped_at_the_standing_time_is_seen_only_once_time_has_passed_it(self):
        publisher = rospy.Publisher("/gated_goal", PoseStamped, queue_size=10)
        gated = Subscription("/gated_goal", PoseStamped, buffer_size=5, lockstep=True)
        try:
            deadline = time.monotonic() + WAIT_S
            while publisher.get_num_connections() == 0 and time.monotonic() < deadline:
                time.sleep(0.01)
            hold = LockstepParticipant("gated_reader", enabled=True)
            self.assertTrue(hold.wait_connected(WAIT_S))
            tick_s = self.now() + LEAD_S
            hold.hold_clock(tick_s)
            self.stands_at(tick_s, 0.05)
            now = self.clock.newest(lambda m: True).clock
            current, older = PoseStamped(), PoseStamped()
            current.header.stamp = now
            older.header.stamp = now - rospy.Duration(1.0)
            publisher.publish(current)
            publisher.publish(older)
            deadline = time.monotonic() + WAIT_S
            while gated.last() is None and time.monotonic() < deadline:
                time.sleep(0.01)
            time.sleep(0.2)  # the message stamped now has arrived as well, surely
            self.assertEqual(gated.last().header.stamp, older.header.stamp)  # only the one from before now
            self.assertEqual(gated.pop_buffered().header.stamp, older.header.stamp)
            self.assertIsNone(gated.pop_buffered())
            hold.release()
            self.clock.newest(lambda m: clock_s(m) > tick_s + 0.05)
            self.assertEqual(gated.last().header.stamp, now)  # time has passed its stamp
            self.assertEqual(gated.pop_buffered().header.stamp, now)
        finally:
            gated.unregister()


if __name__ == "__main__":
    rostest.rosrun("flex_nav", "sim_lockstep", TestSimLockstep, sys.argv)
