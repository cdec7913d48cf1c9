"""The obstacle classifier's class as an RViz text marker (``obstacle_class_marker``, visualization_msgs/Marker).

RViz cannot show a flex_nav/ObstacleClass; the ``obstacle_classifier`` node therefore also publishes, after every
classified frame, a view-facing text such as ``movable 0.93 (5/5)`` (the smoothed label, its confidence and its
votes in the window) above the robot: in the frame of the scan it fuses (the robot's, z up), or at the camera's
frame before a scan has come. The text is coloured by label and disappears ``LIFETIME_S`` after the last frame,
so a stopped classifier leaves no stale class on the screen. Stamp 0: RViz places it with the newest transform.
"""

from __future__ import annotations

from typing import Dict, Optional, Tuple

import rospy
from visualization_msgs.msg import Marker

from flex_nav.msg import ObstacleClass

TOPIC = "obstacle_class_marker"
ABOVE_M = 0.6  # [m] the text's height above the origin of the robot's frame
TEXT_HEIGHT_M = 0.25  # [m] height of a capital letter
LIFETIME_S = 2.0  # [s] the marker's lifetime after the frame that set it
LABEL_COLOURS: Dict[str, Tuple[float, float, float]] = {  # RGB [0..1]
    "person": (1.0, 0.35, 0.35),
    "movable": (0.35, 1.0, 0.35),
    "clear": (0.85, 0.85, 0.85),
}
UNKNOWN_COLOUR = (1.0, 0.85, 0.2)


def class_text(msg: ObstacleClass) -> str:
    """``label confidence (votes/window)`` of an ObstacleClass."""
    return f"{msg.label} {msg.confidence:.2f} ({msg.votes}/{msg.window})"


def class_marker(msg: ObstacleClass, robot_frame: Optional[str]) -> Marker:
    """The text marker of ``msg``: above the origin of ``robot_frame``, or at the image's frame when None."""
    marker = Marker()
    marker.header.frame_id = robot_frame or msg.header.frame_id
    marker.ns = "obstacle_class"
    marker.id = 0
    marker.type = Marker.TEXT_VIEW_FACING
    marker.action = Marker.ADD
    marker.pose.position.z = ABOVE_M if robot_frame else 0.0
    marker.pose.orientation.w = 1.0
    marker.scale.z = TEXT_HEIGHT_M
    marker.color.r, marker.color.g, marker.color.b = LABEL_COLOURS.get(msg.label, UNKNOWN_COLOUR)
    marker.color.a = 1.0
    marker.lifetime = rospy.Duration(LIFETIME_S)
    marker.text = class_text(msg)
    return marker


class ClassMarkerPublisher:
    """Publishes :func:`class_marker` of each ObstacleClass on ``obstacle_class_marker`` (relative name)."""

    def __init__(self, topic: str = TOPIC) -> None:
        self.publisher = rospy.Publisher(topic, Marker, queue_size=2)

    def publish(self, msg: ObstacleClass, robot_frame: Optional[str]) -> None:
        self.publisher.publish(class_marker(msg, robot_frame))
