#!/usr/bin/env python3
"""Controller latency through ROS: odometry in -> TwistStamped out, and cancel -> zero twist.

A private roscore, a real ``pure_pursuit_path`` node (20 Hz, no scan) following a long straight path, and
this process as the robot: it publishes ``odom`` (with tf odom -> base_footprint, and a static map -> odom)
70 ms apart -- slower than the
control period, so every message starts a control tick -- and times each message until the controller's
TwistStamped arrives (TCP_NODELAY both ways, one clock). Reference in the same run: a plain rospy node
that answers each Odometry with a TwistStamped (the transport floor); ratio = controller / relay.
Target (issue 3): median <= 5 ms.

Also timed: cancel of a running goal -> zero twist received (target: within one control period, 50 ms),
and one SafeFollower.tick in-process (pure pursuit plus the safety wrapper; bench_pure_pursuit.py times
the bare step).
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any, List, Tuple

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "src"))

import numpy as np  # noqa: E402
import rospy  # noqa: E402
import tf2_ros  # noqa: E402
from geometry_msgs.msg import PoseStamped, TransformStamped, TwistStamped  # noqa: E402
from nav_msgs.msg import Odometry  # noqa: E402
from nav_msgs.msg import Path as PathMsg  # noqa: E402

from flex_nav.msg import FollowPathAction, FollowPathGoal  # noqa: E402
from flex_nav.nav.control.controller import Pose2D, SafeFollower  # noqa: E402
from flex_nav.nav.control.pure_pursuit import PurePursuitParams  # noqa: E402
from flex_nav.nav.costmap.costmap_grid import CostmapGeometry  # noqa: E402
from flex_nav.ros.proxies import ActionClientProxy  # noqa: E402
from flex_nav.testing.private_master import PrivateMaster  # noqa: E402

SAMPLES = 200  # odometry messages timed per node
ODOM_PERIOD_S = 0.07  # [s] between odometry messages (> control period: each one starts a tick)
CONTROL_PERIOD_S = 0.05  # [s] controller_frequency 20 Hz
CANCELS = 20
TARGET_MS = 5.0


def relay_main() -> None:
    """The reference node: every Odometry on ``odom`` answered at once with a TwistStamped on ``cmd``."""
    rospy.init_node("latency_relay")
    pub = rospy.Publisher("cmd", TwistStamped, queue_size=1, tcp_nodelay=True)

    def on_odom(msg: Odometry) -> None:
        out = TwistStamped()
        out.header.stamp = rospy.Time.now()
        out.twist.linear.x = msg.twist.twist.linear.x
        pub.publish(out)

    rospy.Subscriber("odom", Odometry, on_odom, queue_size=1, tcp_nodelay=True)
    rospy.spin()


class Probe:
    """Publishes Odometry and waits for the next TwistStamped on a topic; all times from time.monotonic()."""

    def __init__(self, odom_topic: str, cmd_topic: str) -> None:
        self.cond = threading.Condition()
        self.received: List[Tuple[float, Any]] = []  # (monotonic time, msg)
        self.pub = rospy.Publisher(odom_topic, Odometry, queue_size=1, tcp_nodelay=True)
        self.tf = tf2_ros.TransformBroadcaster()
        self.sub = rospy.Subscriber(cmd_topic, TwistStamped, self.on_cmd, queue_size=10, tcp_nodelay=True)

    def on_cmd(self, msg: TwistStamped) -> None:
        now = time.monotonic()
        with self.cond:
            self.received.append((now, msg))
            self.cond.notify_all()

    def wait_connected(self, timeout_s: float = 30.0) -> None:
        deadline = time.monotonic() + timeout_s
        while self.pub.get_num_connections() == 0 or self.sub.get_num_connections() == 0:
            if time.monotonic() > deadline:
                raise SystemExit("bench: the node under test did not connect")
            time.sleep(0.05)

    def odom(self, v: float = 0.0) -> Odometry:
        msg = Odometry()
        msg.header.stamp = rospy.Time.now()
        msg.header.frame_id, msg.child_frame_id = "odom", "base_footprint"
        msg.pose.pose.orientation.w = 1.0
        msg.twist.twist.linear.x = v
        return msg

    def round_trip(self, v: float = 0.0, timeout_s: float = 1.0) -> float | None:
        """[s] from publishing one odometry message to the next command, or None."""
        with self.cond:
            mark = len(self.received)
        msg = self.odom(v)
        tf = TransformStamped()  # as a driver does: odom -> base_footprint with every odometry message
        tf.header = msg.header
        tf.child_frame_id = msg.child_frame_id
        tf.transform.rotation.w = 1.0
        self.tf.sendTransform(tf)
        sent = time.monotonic()
        self.pub.publish(msg)
        deadline = sent + timeout_s
        with self.cond:
            while len(self.received) == mark:
                left = deadline - time.monotonic()
                if left <= 0:
                    return None
                self.cond.wait(left)
            return self.received[mark][0] - sent

    def measure(self, count: int) -> list:
        times, v = [], 0.0
        for _ in range(count):
            latency = self.round_trip(v)
            if latency is not None:
                times.append(latency)
                v = float(self.received[-1][1].twist.linear.x)
            time.sleep(ODOM_PERIOD_S)
        return times


def figures(times: list) -> str:
    ms = np.array(times) * 1e3
    return (f"median {np.median(ms):.2f} ms, p90 {np.percentile(ms, 90):.2f} ms, max {ms.max():.2f} ms "
            f"({len(ms)} samples)")


def tick_time() -> float:
    """[s] median of SafeFollower.tick on a 60x60 local costmap along a straight path."""
    follower = SafeFollower(PurePursuitParams(), sensors=["odom"], sensor_timeout_s=1e9, collision_timeout_s=1.0,
                            nominal_period_s=CONTROL_PERIOD_S, start_s=0.0)
    path = np.column_stack([np.arange(0.0, 50.0, 0.05), np.zeros(1000), np.zeros(1000)])
    geometry = CostmapGeometry(60, 60, 0.05, -1.5, -1.5)
    snapshot = (np.zeros(geometry.shape, dtype=np.uint8), geometry)
    follower.set_path(path)
    times, x, v = [], 0.0, 0.0
    for k in range(2000):
        t = time.perf_counter()

        def pose(x: float = x) -> Pose2D:  # x bound at this step, as the lambda default `x=x` did
            return (x, 0.0, 0.0)

        d = follower.tick(0.05 * (k + 1), pose, (v, 0.0), lambda: snapshot)
        times.append(time.perf_counter() - t)
        v = d.v
        x += v * CONTROL_PERIOD_S
        geometry.origin_x = x - 1.5
    return statistics.median(times[10:])


def main() -> int:
    with tempfile.TemporaryDirectory() as home:
        master = PrivateMaster(ros_home=Path(home) / "ros_home").start()
        os.environ.update(master.env)
        procs = []
        try:
            rospy.init_node("bench_controller_latency")
            rospy.set_param("/pure_pursuit_path", {
                "controller_frequency": 1.0 / CONTROL_PERIOD_S, "sensor_timeout": 2.0,
                "local_costmap": {"scan_topic": "", "bumper_topic": "", "publish_frequency": 0.0},
            })
            controller = subprocess.Popen(
                ["rosrun", "flex_nav", "pure_pursuit_path", "cmd_vel_stamped:=cmd_ctl", "odom:=odom_ctl"],
                env=master.env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True,
            )
            procs.append(controller)
            relay = subprocess.Popen(
                [sys.executable, __file__, "--relay", "cmd:=cmd_ref", "odom:=odom_ref"],
                env=master.env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True,
            )
            procs.append(relay)

            static = tf2_ros.StaticTransformBroadcaster()
            tf = TransformStamped()
            tf.header.stamp = rospy.Time.now()
            tf.header.frame_id, tf.child_frame_id = "map", "odom"
            tf.transform.rotation.w = 1.0
            static.sendTransform(tf)

            ctl_probe = Probe("odom_ctl", "cmd_ctl")
            ref_probe = Probe("odom_ref", "cmd_ref")
            client = ActionClientProxy("pure_pursuit_path", FollowPathAction)
            if not client.is_available(60.0):
                print("FAIL: pure_pursuit_path did not come up")
                return 1
            ctl_probe.wait_connected()
            ref_probe.wait_connected()
            path = PathMsg()
            path.header.frame_id = "map"
            for k in range(2001):
                pose = PoseStamped()
                pose.pose.position.x = 0.05 * k
                pose.pose.orientation.w = 1.0
                path.poses.append(pose)
            goal = FollowPathGoal(path=path)

            # feed odometry while the goal starts, then time
            client.send_goal(goal)
            for _ in range(10):
                ctl_probe.round_trip()
                time.sleep(ODOM_PERIOD_S)
            ref_probe.measure(10)
            ctl_times = ctl_probe.measure(SAMPLES)
            ref_times = ref_probe.measure(SAMPLES)
            print(f"odom -> cmd through pure_pursuit_path: {figures(ctl_times)}")
            print(f"odom -> cmd through a plain rospy relay (reference): {figures(ref_times)}")
            ctl_med, ref_med = statistics.median(ctl_times) * 1e3, statistics.median(ref_times) * 1e3
            print(f"controller / relay: {ctl_med / ref_med:.2f}x; controller / {TARGET_MS:.0f} ms target: "
                  f"{ctl_med / TARGET_MS:.2f}x")

            # cancel -> zero twist
            cancel_times = []
            for _ in range(CANCELS):
                client.send_goal(goal)
                for _ in range(3):
                    ctl_probe.round_trip(0.2)
                    time.sleep(ODOM_PERIOD_S)
                with ctl_probe.cond:
                    mark = len(ctl_probe.received)
                sent = time.monotonic()
                client.cancel()
                zero_at = None
                deadline = sent + 2.0
                with ctl_probe.cond:
                    while zero_at is None and time.monotonic() < deadline:
                        for at, msg in ctl_probe.received[mark:]:
                            if msg.twist.linear.x == 0.0 and msg.twist.angular.z == 0.0:
                                zero_at = at
                                break
                        else:
                            ctl_probe.cond.wait(0.05)
                client.wait_for_result(2.0)
                if zero_at is None:
                    print("FAIL: no zero twist after a cancel")
                    return 1
                cancel_times.append(zero_at - sent)
            cancel_max = max(cancel_times) * 1e3
            print(f"cancel -> zero twist: {figures(cancel_times)}; max / control period "
                  f"{cancel_max / (CONTROL_PERIOD_S * 1e3):.2f}x")

            tick_ms = tick_time() * 1e3
            print(f"SafeFollower.tick (pure pursuit + safety, in-process): median {tick_ms:.4f} ms")

            ok = ctl_med <= TARGET_MS and cancel_max <= CONTROL_PERIOD_S * 1e3
            print("PASS" if ok else "FAIL")
            return 0 if ok else 1
        finally:
            for proc in procs:
                try:
                    os.killpg(proc.pid, 2)
                    proc.wait(timeout=10)
                except (ProcessLookupError, subprocess.TimeoutExpired):
                    os.killpg(proc.pid, 9)
            master.stop()


if __name__ == "__main__":
    if "--relay" in sys.argv:
        relay_main()
        sys.exit(0)
    sys.exit(main())
