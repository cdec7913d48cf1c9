"""Planar transforms of poses and headings along polylines."""

import math

import numpy as np
import pytest

from flex_nav.nav.angles import wrap_angle
from flex_nav.nav.planar import compose_poses, heading_along, inverse_pose, transform_poses


def test_wrap_angle():
    assert wrap_angle(3 * math.pi / 2) == pytest.approx(-math.pi / 2)
    assert wrap_angle(-3 * math.pi / 2) == pytest.approx(math.pi / 2)
    assert wrap_angle(0.3) == pytest.approx(0.3)


def test_transform_poses_rotates_translates_and_wraps_yaw():
    poses = np.array([[1.0, 0.0, 0.0], [0.0, 2.0, math.pi * 0.75]])
    out = transform_poses(poses, 10.0, 20.0, math.pi / 2)
    np.testing.assert_allclose(out[:, :2], [[10.0, 21.0], [8.0, 20.0]], atol=1e-12)
    assert out[0, 2] == pytest.approx(math.pi / 2)
    assert out[1, 2] == pytest.approx(-math.pi * 0.75)  # 1.25 pi wrapped
    np.testing.assert_array_equal(poses[0], [1.0, 0.0, 0.0])  # input untouched


def test_transform_points_only():
    out = transform_poses(np.array([[1.0, 1.0]]), 0.0, 0.0, math.pi)
    np.testing.assert_allclose(out, [[-1.0, -1.0]], atol=1e-12)


def test_heading_along_faces_next_distinct_point():
    points = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [1.0, 1.0], [1.0, 1.0]])
    yaw = heading_along(points)
    np.testing.assert_allclose(yaw, [0.0, math.pi / 2, math.pi / 2, math.pi / 2, math.pi / 2])


def test_heading_along_degenerate():
    np.testing.assert_array_equal(heading_along(np.zeros((3, 2))), [0.0, 0.0, 0.0])
    np.testing.assert_array_equal(heading_along(np.zeros((1, 2))), [0.0])
    yaw = heading_along(np.array([[0.0, 0.0], [-1.0, 0.0]]))
    np.testing.assert_allclose(yaw, [math.pi, math.pi])


def test_compose_and_inverse_poses() -> None:
    a = (1.0, 2.0, math.pi / 2)
    b = (0.5, 0.0, math.pi / 4)
    assert compose_poses(a, b) == pytest.approx((1.0, 2.5, 3 * math.pi / 4))
    for p in (a, b, (-3.0, 0.2, -2.5)):
        assert compose_poses(p, inverse_pose(p)) == pytest.approx((0.0, 0.0, 0.0), abs=1e-12)
        assert compose_poses(inverse_pose(p), p) == pytest.approx((0.0, 0.0, 0.0), abs=1e-12)
    # yaw wraps into (-pi, pi]
    assert compose_poses((0.0, 0.0, 3.0), (0.0, 0.0, 1.0))[2] == pytest.approx(4.0 - 2 * math.pi)
