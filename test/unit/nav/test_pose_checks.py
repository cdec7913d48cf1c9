from __future__ import annotations

import math

import pytest

from flex_nav.nav.pose_checks import frame_problem, pose_problem, quaternion_of_yaw, yaw_of_quaternion


def test_good_pose_passes() -> None:
    assert pose_problem((1.0, 2.0, 0.0), (0.0, 0.0, 0.0, 1.0)) is None


@pytest.mark.parametrize(
    ("position", "orientation", "expected"),
    [
        ((math.nan, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0), "position"),
        ((0.0, math.inf, 0.0), (0.0, 0.0, 0.0, 1.0), "position"),
        ((0.0, 0.0, 0.0), (0.0, 0.0, math.nan, 1.0), "orientation"),
        ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 0.0), "not normalised"),
        ((0.0, 0.0, 0.0), (0.0, 0.0, 1.0, 1.0), "not normalised"),
    ],
)
def test_bad_poses_have_reasons(position: tuple[float, ...], orientation: tuple[float, ...], expected: str) -> None:
    reason = pose_problem(position, orientation)
    assert reason is not None and expected in reason


def test_frames() -> None:
    assert frame_problem("map", "map") is None
    assert frame_problem("/map", "map") is None
    assert "empty" in (frame_problem("", "map") or "")
    assert "'odom' is not the planning frame 'map'" in (frame_problem("odom", "map") or "")


@pytest.mark.parametrize("yaw", [0.0, 0.5, -1.2, math.pi - 1e-9, -math.pi + 1e-3])
def test_yaw_round_trip(yaw: float) -> None:
    assert yaw_of_quaternion(*quaternion_of_yaw(yaw)) == pytest.approx(yaw, abs=1e-9)
