"""The obstacle memory as RViz markers (visualization_msgs/MarkerArray), and back.

:func:`memory_markers` makes the array a costmap with an obstacle memory latches on ``~<costmap>/obstacle_memory``
after every change: a DELETEALL first (so forgotten obstacles vanish), then per remembered obstacle a closed
LINE_STRIP of its footprint (namespace ``footprint``) and a view-facing text of its
:meth:`~flex_nav.nav.costmap.memory_layer.RememberedObstacle.describe` above its centre (namespace ``text``), both
with the obstacle's id as marker id, in the costmap's frame. :func:`remembered_of_markers` reads such an array
back into (id, footprint, text) rows (the operator console draws them); markers of other namespaces or types are
ignored, an obstacle without a footprint is dropped.
"""

from __future__ import annotations

from typing import Dict, List, Sequence, Tuple

import numpy as np
import rospy
from geometry_msgs.msg import Point
from visualization_msgs.msg import Marker, MarkerArray

from flex_nav.nav.costmap.memory_layer import RememberedObstacle

FOOTPRINT_NS = "footprint"
TEXT_NS = "text"
LINE_WIDTH_M = 0.04  # [m] the footprint's line
TEXT_HEIGHT_M = 0.15  # [m] height of a capital letter
TEXT_ABOVE_M = 0.3  # [m] the text's height above the footprint's centre
COLOUR = (0.55, 0.0, 0.0, 1.0)  # RGBA [0..1]: dark red, as the console draws them

Remembered = Tuple[int, np.ndarray, str]  # (obstacle id, (N, 2) footprint [m] in the array's frame, its text)


def _marker(frame: str, stamp: rospy.Time, ns: str, marker_id: int, kind: int) -> Marker:
    marker = Marker()
    marker.header.frame_id = frame
    marker.header.stamp = stamp
    marker.ns = ns
    marker.id = marker_id
    marker.type = kind
    marker.action = Marker.ADD
    marker.pose.orientation.w = 1.0
    marker.color.r, marker.color.g, marker.color.b, marker.color.a = COLOUR
    return marker


def memory_markers(obstacles: Sequence[RememberedObstacle], frame: str, stamp: rospy.Time) -> MarkerArray:
    """DELETEALL, then a footprint LINE_STRIP and a describe() text per obstacle, in ``frame``."""
    clear_all = Marker()
    clear_all.header.frame_id = frame
    clear_all.header.stamp = stamp
    clear_all.action = Marker.DELETEALL
    markers = [clear_all]
    for obstacle in obstacles:
        line = _marker(frame, stamp, FOOTPRINT_NS, obstacle.obstacle_id, Marker.LINE_STRIP)
        line.scale.x = LINE_WIDTH_M
        corners = [Point(x=float(x), y=float(y)) for x, y in obstacle.footprint]
        line.points = [*corners, corners[0]]  # closed
        text = _marker(frame, stamp, TEXT_NS, obstacle.obstacle_id, Marker.TEXT_VIEW_FACING)
        text.pose.position.x, text.pose.position.y = obstacle.centre
        text.pose.position.z = TEXT_ABOVE_M
        text.scale.z = TEXT_HEIGHT_M
        text.text = obstacle.describe()
        markers += [line, text]
    return MarkerArray(markers=markers)


def remembered_of_markers(msg: MarkerArray) -> List[Remembered]:
    """The (id, footprint, text) rows of a :func:`memory_markers` array, in its markers' order (the closing corner
    of a footprint dropped); a DELETEALL forgets the rows before it, a DELETE the obstacle's."""
    footprints: Dict[int, np.ndarray] = {}
    texts: Dict[int, str] = {}
    for marker in msg.markers:
        if marker.action == Marker.DELETEALL:
            footprints.clear()
            texts.clear()
        elif marker.action == Marker.DELETE:
            footprints.pop(marker.id, None)
            texts.pop(marker.id, None)
        elif marker.ns == FOOTPRINT_NS and marker.type == Marker.LINE_STRIP:
            rows = np.array([(p.x, p.y) for p in marker.points], dtype=float).reshape(-1, 2)
            if len(rows) > 1 and np.array_equal(rows[0], rows[-1]):
                rows = rows[:-1]
            footprints[marker.id] = rows
        elif marker.ns == TEXT_NS and marker.type == Marker.TEXT_VIEW_FACING:
            texts[marker.id] = marker.text
    return [(obstacle_id, rows, texts.get(obstacle_id, f"#{obstacle_id}"))
            for obstacle_id, rows in footprints.items() if len(rows) >= 3]
