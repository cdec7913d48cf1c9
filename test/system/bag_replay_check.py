#!/usr/bin/env python3
"""Replays a demo bag as a user would into RViz, and checks what RViz's displays would need.

Usage: bag_replay_check.py BAG ROBOT SECONDS. Against the master in the environment: sets ``/use_sim_time``,
plays the first SECONDS of BAG with ``rosbag play`` (the bag's own /clock drives time), and checks, as RViz's
LaserScan display does, that each scan can be placed in the ``map`` frame through /tf and /tf_static at its stamp;
and that the robot's global costmap, global plan and footprint arrive. Prints the counts and ``REPLAY PASSED``
(exit 0), or what was missing (exit 1).
"""

from __future__ import annotations

import subprocess
import sys
import threading
from typing import Any, Dict, List

import rospy
import tf2_ros
from geometry_msgs.msg import PolygonStamped
from nav_msgs.msg import OccupancyGrid, Path
from sensor_msgs.msg import LaserScan

from flex_nav.ros.node import init_node

TF_WAIT_S = 1.0  # [s] of ROS time a scan's transform may take to arrive (RViz's tf filter queue does the same)
MIN_SCANS_PLACED = 20


def main() -> int:
    bag, robot, seconds = sys.argv[1], sys.argv[2], float(sys.argv[3])
    rospy.set_param("/use_sim_time", True)
    init_node("bag_replay_check")
    tf_buffer = tf2_ros.Buffer(cache_time=rospy.Duration(30.0))
    tf2_ros.TransformListener(tf_buffer)
    lock = threading.Lock()
    scans: List[LaserScan] = []
    seen: Dict[str, int] = {"costmap": 0, "plan": 0, "footprint": 0}

    def count(name: str) -> Any:
        def on_message(_msg: Any) -> None:
            with lock:
                seen[name] += 1
        return on_message

    def on_scan(msg: LaserScan) -> None:
        with lock:
            scans.append(msg)

    subscribers = [
        rospy.Subscriber(f"/{robot}/scan", LaserScan, on_scan, queue_size=100),
        rospy.Subscriber(f"/{robot}/get_path_server/global_costmap/costmap", OccupancyGrid, count("costmap")),
        rospy.Subscriber(f"/{robot}/get_path_server/plan", Path, count("plan")),
        rospy.Subscriber(f"/{robot}/footprint", PolygonStamped, count("footprint")),
    ]
    player = subprocess.run(["rosbag", "play", "--quiet", "-u", str(seconds), bag], capture_output=True, text=True,
                            timeout=seconds * 4 + 60.0, check=False)
    placed = unplaced = 0
    with lock:
        received = list(scans)
    for scan in received[len(received) // 4:]:  # once the static frames and the localizer's map -> odom are in
        try:
            tf_buffer.lookup_transform("map", scan.header.frame_id, scan.header.stamp)
            placed += 1
        except (tf2_ros.LookupException, tf2_ros.ConnectivityException, tf2_ros.ExtrapolationException):
            unplaced += 1
    for subscriber in subscribers:
        subscriber.unregister()
    print(f"rosbag play exit {player.returncode}; scans {len(received)}, placed in map {placed}, not {unplaced}; "
          f"{seen}", flush=True)
    failures = []
    if player.returncode != 0:
        failures.append(f"rosbag play failed: {player.stderr[-2000:]}")
    if placed < MIN_SCANS_PLACED or unplaced > placed // 10:
        failures.append(f"scans placed in map: {placed} (not: {unplaced})")
    failures += [f"no {name} message" for name, n in seen.items() if n == 0]
    for failure in failures:
        print(f"REPLAY FAILED: {failure}", flush=True)
    if not failures:
        print("REPLAY PASSED", flush=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
