"""Message conversions and tf-based frame changes, without a master (tf2 buffer filled by hand)."""

import io
import math

import numpy as np
import pytest
import rospy
import tf2_ros
from geometry_msgs.msg import PoseStamped, TransformStamped
from nav_msgs.msg import OccupancyGrid, Path

from flex_nav.exceptions import ConfigError, NotReadyError
from flex_nav.nav.costmap.grid_map import GridMap
from flex_nav.ros.conversions import grid_map_of, map_msg, occupancy_grid_msg, path_msg, path_points
from flex_nav.ros.frames import frame_pose, goal_in_frame, path_in_frame


def test_numpy_occupancy_grid_serializes_like_genpy():
    occ = (np.arange(37 * 23) % 102 - 1).astype(np.int8).reshape(23, 37)
    msg = occupancy_grid_msg(occ, 0.05, 1.0, -2.0, frame_id="map", stamp=rospy.Time(7, 5))
    fast, slow = io.BytesIO(), io.BytesIO()
    msg.serialize(fast)
    OccupancyGrid(header=msg.header, info=msg.info, data=occ.ravel().tolist()).serialize(slow)
    assert fast.getvalue() == slow.getvalue()
    back = OccupancyGrid()
    back.deserialize(fast.getvalue())
    grid = grid_map_of(back)
    np.testing.assert_array_equal(grid.occupancy, occ)
    assert grid.origin == (1.0, -2.0, 0.0)


def test_map_msg_keeps_origin_yaw():
    grid = GridMap(np.zeros((3, 4), dtype=np.int8), 0.1, (1.0, 2.0, 0.5))
    msg = map_msg(grid, frame_id="world", stamp=rospy.Time(1))
    buff = io.BytesIO()
    msg.serialize(buff)
    back = OccupancyGrid()
    back.deserialize(buff.getvalue())
    assert back.header.frame_id == "world"
    assert grid_map_of(back).origin == pytest.approx((1.0, 2.0, 0.5))


def test_grid_map_of_rejects_wrong_size():
    msg = OccupancyGrid()
    msg.info.width, msg.info.height, msg.info.resolution = 3, 2, 0.1
    msg.data = [0] * 5
    with pytest.raises(ConfigError, match="5 cells but info says 3 x 2"):
        grid_map_of(msg)


def buffer_with_odom(x=1.0, y=2.0, yaw=math.pi / 2):
    buffer = tf2_ros.Buffer(debug=False)
    tf = TransformStamped()
    tf.header.frame_id, tf.child_frame_id = "map", "odom"
    tf.transform.translation.x, tf.transform.translation.y = x, y
    tf.transform.rotation.z, tf.transform.rotation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    buffer.set_transform_static(tf, "test")
    return buffer


def stamped(frame, x, y, q=(0.0, 0.0, 0.0, 1.0)):
    msg = PoseStamped()
    msg.header.frame_id = frame
    msg.pose.position.x, msg.pose.position.y = x, y
    o = msg.pose.orientation
    o.x, o.y, o.z, o.w = q
    return msg


def test_goal_in_frame_transforms_and_checks():
    buffer = buffer_with_odom()
    goal = goal_in_frame(buffer, stamped("odom", 1.0, 0.0), "map", 0.0)
    np.testing.assert_allclose(goal, [1.0, 3.0, math.pi / 2], atol=1e-9)
    same = goal_in_frame(buffer, stamped("/map", 4.0, 5.0), "map", 0.0)
    np.testing.assert_allclose(same, [4.0, 5.0, 0.0])
    with pytest.raises(ConfigError, match="frame_id is empty"):
        goal_in_frame(buffer, stamped("", 1.0, 0.0), "map", 0.0)
    with pytest.raises(NotReadyError, match="'mars' cannot be transformed into 'map'"):
        goal_in_frame(buffer, stamped("mars", 1.0, 0.0), "map", 0.0)
    with pytest.raises(ConfigError, match="not normalised"):
        goal_in_frame(buffer, stamped("map", 1.0, 0.0, (0.0, 0.0, 0.0, 0.5)), "map", 0.0)
    with pytest.raises(ConfigError, match="not finite"):
        goal_in_frame(buffer, stamped("map", math.nan, 0.0), "map", 0.0)


def test_path_in_frame_and_round_trip():
    buffer = buffer_with_odom(0.0, 0.0, 0.0)
    points = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]])
    msg = path_msg(points, "odom", rospy.Time(0), final_yaw=0.3)
    np.testing.assert_array_equal(path_points(msg), points)
    poses = path_in_frame(buffer, msg, "map", 0.0)
    np.testing.assert_allclose(poses, np.array([[0, 0, 0], [1, 0, math.pi / 2], [1, 1, 0.3]]), atol=1e-12)


def test_path_in_frame_zero_quaternions_face_along_the_path():
    msg = Path()
    msg.header.frame_id = "map"
    for x, y in ((0.0, 0.0), (0.0, 1.0), (-1.0, 1.0)):
        msg.poses.append(stamped("map", x, y, (0.0, 0.0, 0.0, 0.0)))
    poses = path_in_frame(tf2_ros.Buffer(debug=False), msg, "map", 0.0)
    np.testing.assert_allclose(poses[:, 2], [math.pi / 2, math.pi, math.pi])


def test_path_in_frame_rejects_bad_paths():
    buffer = tf2_ros.Buffer(debug=False)
    with pytest.raises(ConfigError, match="empty"):
        path_in_frame(buffer, Path(), "map", 0.0)
    msg = path_msg(np.array([[0.0, 0.0], [1.0, 0.0]]), "map", rospy.Time(0))
    msg.poses[1].pose.position.y = math.inf
    with pytest.raises(ConfigError, match="path pose 1: position"):
        path_in_frame(buffer, msg, "map", 0.0)
    msg = path_msg(np.array([[0.0, 0.0], [1.0, 0.0]]), "nowhere", rospy.Time(0))
    with pytest.raises(NotReadyError, match="'nowhere'"):
        path_in_frame(buffer, msg, "map", 0.0)


def test_frame_pose_refuses_an_old_transform_but_not_a_static_one(monkeypatch):
    monkeypatch.setattr(rospy.Time, "now", staticmethod(lambda: rospy.Time(100, 0)))
    static = buffer_with_odom(1.0, 2.0, 0.0)  # stamp 0 in the message: tf2 keeps static transforms ageless
    assert frame_pose(static, "map", "odom", 0.0, max_age_s=1.0) == pytest.approx((1.0, 2.0, 0.0))
    static_stamped = tf2_ros.Buffer(debug=False)
    tf = TransformStamped()
    tf.header.stamp = rospy.Time(3)  # sent long ago by a static broadcaster: still no age
    tf.header.frame_id, tf.child_frame_id = "map", "odom"
    tf.transform.rotation.w = 1.0
    static_stamped.set_transform_static(tf, "test")
    assert frame_pose(static_stamped, "map", "odom", 0.0, max_age_s=1.0) == pytest.approx((0.0, 0.0, 0.0))

    localized = tf2_ros.Buffer(debug=False)
    tf.header.stamp = rospy.Time(98, 500_000_000)  # the localizer's last map -> odom, 1.5 s ago
    tf.transform.translation.x = 4.0
    localized.set_transform(tf, "test")
    with pytest.raises(NotReadyError, match=r"'map' -> 'odom' is 1\.50 s old \(more than 1\.00 s\)"):
        frame_pose(localized, "map", "odom", 0.0, max_age_s=1.0)
    assert frame_pose(localized, "map", "odom", 0.0, max_age_s=2.0)[0] == pytest.approx(4.0)
    assert frame_pose(localized, "map", "odom", 0.0)[0] == pytest.approx(4.0)  # 0: no age check
