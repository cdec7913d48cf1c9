"""``map_server`` and ``map_saver``: a map_server-format map on the ``map`` topic, and back to a file.

``rosrun flex_nav map_server MAP.yaml`` loads the map (any problem with the file: exit status 1 and the
map_io error, before contacting the master), then publishes it latched on ``map`` (nav_msgs/OccupancyGrid)
and ``map_metadata`` (nav_msgs/MapMetaData) and serves ``static_map`` (nav_msgs/GetMap), as ROS map_server
does. Parameter ``~frame_id`` (str, "map"): the frame the map is published in.

``rosrun flex_nav map_saver -f NAME`` waits at most ``--timeout`` [s] for one message on ``map`` and writes
NAME.yaml + NAME.pgm (map_saver's format, see :func:`flex_nav.nav.costmap.map_io.save_map`); exit status 1 with
the reason when no map arrives or the file cannot be written.
"""

from __future__ import annotations

import argparse
import sys
import threading
from pathlib import Path
from typing import List, Optional, Sequence

import rospy
from nav_msgs.msg import MapMetaData, OccupancyGrid
from nav_msgs.srv import GetMap, GetMapRequest, GetMapResponse

from flex_nav.exceptions import ConfigError
from flex_nav.nav.costmap.map_io import load_map, save_map
from flex_nav.ros.conversions import grid_map_of, map_msg
from flex_nav.ros.node import init_node
from flex_nav.ros.params import param_str, reject_unknown

EXIT_OK = 0
EXIT_FAILED = 1
SAVER_TIMEOUT_S = 10.0  # [s] default bound on waiting for the map


class MapServer:
    """Publishes one loaded map (latched) and answers ``static_map`` with it."""

    def __init__(self, yaml_path: str) -> None:
        reject_unknown("~", ("frame_id",))
        grid = load_map(yaml_path)
        frame_id = param_str("~frame_id", "map")
        if not frame_id:
            raise ConfigError("parameter ~frame_id is empty; give the frame the map is published in")
        self.map = map_msg(grid, frame_id=frame_id, stamp=rospy.Time.now())
        self.metadata_publisher = rospy.Publisher("map_metadata", MapMetaData, queue_size=1, latch=True)
        self.map_publisher = rospy.Publisher("map", OccupancyGrid, queue_size=1, latch=True)
        self.service = rospy.Service("static_map", GetMap, self._on_get_map)
        self.metadata_publisher.publish(self.map.info)
        self.map_publisher.publish(self.map)
        rospy.loginfo(
            "map_server: %s: %d x %d cells at %.3f m/cell in frame '%s'",
            yaml_path, self.map.info.width, self.map.info.height, self.map.info.resolution, frame_id,
        )

    def _on_get_map(self, _request: GetMapRequest) -> GetMapResponse:
        return GetMapResponse(map=self.map)


def map_server_main(argv: Optional[Sequence[str]] = None) -> int:
    args = list(rospy.myargv(list(argv) if argv is not None else sys.argv))[1:]
    if len(args) != 1:
        print("usage: rosrun flex_nav map_server MAP.yaml", file=sys.stderr)
        return EXIT_FAILED
    try:
        load_map(args[0])  # fail before the master is contacted
    except ConfigError as err:
        print(f"map_server: {err}", file=sys.stderr)
        return EXIT_FAILED
    init_node("map_server")
    try:
        MapServer(args[0])
    except ConfigError as err:
        rospy.logfatal("map_server: %s", err)
        return EXIT_FAILED
    rospy.spin()
    return EXIT_OK


def _saver_arguments(argv: List[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="map_saver", description="Save the map on topic 'map' as YAML + PGM.")
    parser.add_argument("-f", dest="name", default="map", help="output name without suffix (default: map)")
    parser.add_argument("--occ", type=int, default=65, help="occupied threshold 0..100 (default 65)")
    parser.add_argument("--free", type=int, default=25, help="free threshold 0..100 (default 25)")
    parser.add_argument("--timeout", type=float, default=SAVER_TIMEOUT_S, help="[s] wait for the map (default 10)")
    return parser.parse_args(argv)


def map_saver_main(argv: Optional[Sequence[str]] = None) -> int:
    args = _saver_arguments(list(rospy.myargv(list(argv) if argv is not None else sys.argv))[1:])
    if not 0.0 < args.timeout < 3600.0:
        print(f"map_saver: --timeout {args.timeout} must be in (0, 3600) s", file=sys.stderr)
        return EXIT_FAILED
    yaml_path = Path(args.name + ".yaml")
    init_node("map_saver", anonymous=True)
    received: List[OccupancyGrid] = []
    arrived = threading.Event()

    def on_map(msg: OccupancyGrid) -> None:
        if not received:
            received.append(msg)
            arrived.set()

    topic = rospy.resolve_name("map")
    subscriber = rospy.Subscriber("map", OccupancyGrid, on_map, queue_size=1)
    rospy.loginfo("map_saver: waiting up to %.1f s for a map on %s", args.timeout, topic)
    if not arrived.wait(args.timeout):
        subscriber.unregister()
        print(f"map_saver: no map arrived on {topic} within {args.timeout:.1f} s", file=sys.stderr)
        return EXIT_FAILED
    subscriber.unregister()
    try:
        grid = grid_map_of(received[0])
        image = save_map(grid, yaml_path, occupied_threshold=args.occ, free_threshold=args.free)
    except (ConfigError, OSError) as err:
        print(f"map_saver: {err}", file=sys.stderr)
        return EXIT_FAILED
    rospy.loginfo("map_saver: wrote %s and %s (%d x %d cells)", yaml_path, image, grid.width, grid.height)
    return EXIT_OK
