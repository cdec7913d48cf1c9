#!/usr/bin/env python3
"""Robot-side recorder of the two-host system test: the simulator's ground truth and the base's commands.

Usage: two_hosts_observer.py ROBOT OUT_CSV. Runs on the robot's computer (its namespace in the test), so it
keeps recording while the link to the operator's computer is down. One line per message, flushed at once:

    gt,<wall [s]>,<sim [s]>,<x [m]>,<y [m]>,<v [m/s]>,<w [rad/s]>     ROBOT/ground_truth (stamp = simulated time)
    cmd,<wall [s]>,<sim [s]>,<v [m/s]>,<w [rad/s]>                   ROBOT/cmd_vel, what the base is told

wall is ``time.monotonic()`` at reception (one clock for every process of the machine), sim the ground
truth's stamp or this node's ROS time. Stops on SIGINT or SIGTERM.
"""

from __future__ import annotations

import signal
import sys
import threading
import time
from pathlib import Path
from typing import Any

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

from flex_nav.ros.node import init_node


def main() -> int:
    robot, out = sys.argv[1], Path(sys.argv[2])
    init_node("two_hosts_observer")
    lock = threading.Lock()
    with out.open("w", buffering=1) as sink:

        def write(line: str) -> None:
            with lock:
                sink.write(line + "\n")

        def on_truth(msg: Odometry) -> None:
            p, t = msg.pose.pose.position, msg.twist.twist
            write(f"gt,{time.monotonic():.4f},{msg.header.stamp.to_sec():.4f},{p.x:.4f},{p.y:.4f},"
                  f"{t.linear.x:.4f},{t.angular.z:.4f}")

        def on_command(msg: Twist) -> None:
            write(f"cmd,{time.monotonic():.4f},{rospy.get_time():.4f},{msg.linear.x:.4f},{msg.angular.z:.4f}")

        subscribers: list[Any] = [
            rospy.Subscriber(f"/{robot}/ground_truth", Odometry, on_truth, queue_size=100, tcp_nodelay=True),
            rospy.Subscriber(f"/{robot}/cmd_vel", Twist, on_command, queue_size=100, tcp_nodelay=True),
        ]
        signal.signal(signal.SIGTERM, lambda *_: rospy.signal_shutdown("SIGTERM"))
        rospy.spin()
        del subscribers
    return 0


if __name__ == "__main__":
    sys.exit(main())
