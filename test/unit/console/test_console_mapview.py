"""The map view's translation without ROS or a browser: the grid as a PNG a decoder reads back, patches of what
changed, overlays in the map frame and thinned, the throttle, goals checked; and through the aiohttp server: the
map and overlays in a new page's snapshot, a goal from the page to the sender, a refused one with the reason."""

from __future__ import annotations

import asyncio
import base64
import io
import math
from typing import Any, Dict, List, Tuple

import numpy as np
import pytest
from PIL import Image
from unit.console.test_console_server import ROBOT, console, origin, page, run, served, until

from flex_nav.console.errors import CommandRefused, MapViewError
from flex_nav.console.mapview import (
    FREE,
    MAX_FOOTPRINT_POINTS,
    MAX_POINTS,
    MAX_REMEMBERED,
    MAX_REMEMBERED_TEXT,
    MIN_PERIOD_S,
    OCCUPIED,
    UNKNOWN,
    GoalRequest,
    GridGeometry,
    MapPicture,
    Throttle,
    check_goal,
    memory_overlay,
    path_overlay,
    pose_overlay,
    poses_overlay,
    robot_namespace,
    scan_overlay,
)
from flex_nav.exceptions import NotReadyError

GEOMETRY = GridGeometry("map", 0.05, 4, 3, (-1.0, -2.0, 0.0))


def decoded(png64: str) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(base64.b64decode(png64))))


def test_the_grid_is_a_png_with_its_top_row_first_and_map_server_shades() -> None:
    data = [0, 100, -1, 50,   0, 0, 0, 0,   -1, -1, -1, 100]  # rows from the origin (bottom row first)
    event = MapPicture().update(GEOMETRY, data)
    assert event is not None and event["type"] == "map"
    assert (event["width"], event["height"], event["origin"], event["resolution"]) == (4, 3, [-1.0, -2.0, 0.0], 0.05)
    image = decoded(event["png"])
    assert image.shape == (3, 4) and image.dtype == np.uint8
    assert image[0].tolist() == [UNKNOWN, UNKNOWN, UNKNOWN, OCCUPIED]  # the last row of data is the picture's top
    assert image[2].tolist() == [FREE, OCCUPIED, UNKNOWN, FREE - 127]


def test_a_changed_map_sends_only_the_changed_rectangle_and_nothing_when_unchanged() -> None:
    picture = MapPicture()
    data = np.zeros(12, dtype=np.int8)
    picture.update(GEOMETRY, data)
    assert picture.update(GEOMETRY, data) is None and picture.version == 1
    data[5] = 100  # row 1 (from the bottom), column 1: picture row 1
    data[6] = -1
    patch = picture.update(GEOMETRY, data)
    assert patch is not None and patch["type"] == "map_patch" and patch["version"] == 2
    assert (patch["x"], patch["y"], patch["width"], patch["height"]) == (1, 1, 2, 1)
    assert decoded(patch["png"]).tolist() == [[OCCUPIED, UNKNOWN]]
    whole = picture.whole_event()  # a later page: whole
    assert whole is not None and decoded(whole["png"])[1, 1] == OCCUPIED
    moved = GridGeometry("map", 0.05, 4, 3, (0.0, 0.0, 0.0))
    again = picture.update(moved, data)
    assert again is not None and again["type"] == "map"  # new geometry: the whole map again


def test_maps_that_are_not_shown_say_why() -> None:
    with pytest.raises(MapViewError, match="has 5 cells, not width x height = 4 x 3"):
        MapPicture().update(GEOMETRY, [0] * 5)
    with pytest.raises(MapViewError, match=r"resolution 0\.0 is not a positive number"):
        MapPicture().update(GridGeometry("map", 0.0, 4, 3, (0.0, 0.0, 0.0)), [0] * 12)
    with pytest.raises(MapViewError, match="a map of 0 x 3 cells is not shown"):
        MapPicture().update(GridGeometry("map", 0.05, 0, 3, (0.0, 0.0, 0.0)), [])


def test_overlays_are_in_the_map_frame_rounded_and_thinned() -> None:
    pose = pose_overlay(ROBOT, 1.5, (1.23456, -2.0, 0.5), 0.177)
    assert pose == {"type": "overlay", "robot": ROBOT, "kind": "pose", "stamp": 1.5, "x": 1.235, "y": -2.0,
                    "yaw": 0.5, "radius": 0.177}
    square = np.array([[0.2, 0.2], [-0.2, 0.2], [-0.2, -0.2], [0.2, -0.20004]])
    with_polygon = pose_overlay(ROBOT, 1.5, (0.0, 0.0, 0.0), 0.2, square)
    assert with_polygon["footprint"] == [[0.2, 0.2], [-0.2, 0.2], [-0.2, -0.2], [0.2, -0.2]]
    assert "footprint" not in pose_overlay(ROBOT, 1.5, (0.0, 0.0, 0.0), 0.2, square[:2])  # not a polygon
    # a laser at (1, 2) facing +y: a reading of 1 m straight ahead ends at (1, 3); out of range / inf dropped
    scan = scan_overlay(ROBOT, 2.0, ranges=[1.0, float("inf"), 9.0, 0.01], angle_min=0.0, angle_increment=0.1,
                        range_min=0.05, range_max=5.0, laser_pose=(1.0, 2.0, math.pi / 2))
    assert scan["points"] == [[1.0, 3.0]]
    long_plan = np.stack([np.linspace(0, 10, 5000), np.zeros(5000)], axis=1)
    plan = path_overlay(ROBOT, "global_plan", 3.0, long_plan)
    assert len(plan["points"]) == MAX_POINTS["global_plan"]
    assert plan["points"][0] == [0.0, 0.0] and plan["points"][-1] == [10.0, 0.0]  # both ends kept
    with pytest.raises(MapViewError, match="'scan' is not a plan"):
        path_overlay(ROBOT, "scan", 3.0, long_plan)
    cloud = poses_overlay(ROBOT, "particles", 4.0, np.zeros((2000, 3)))
    assert len(cloud["points"]) == MAX_POINTS["particles"] and len(cloud["points"][0]) == 3
    people = poses_overlay(ROBOT, "people", 4.0, np.array([[1.0, 2.0, 0.5]]))
    assert people["kind"] == "people" and people["points"] == [[1.0, 2.0, 0.5]]
    with pytest.raises(MapViewError, match="'scan' is not a set of poses"):
        poses_overlay(ROBOT, "scan", 4.0, np.zeros((1, 3)))


def test_remembered_obstacles_are_rounded_bounded_and_checked() -> None:
    square = np.array([[1.00049, 2.0], [1.5, 2.0], [1.5, 2.5], [1.0, 2.5]])
    event = memory_overlay(ROBOT, 3.0, [(4, square, "#4 heavy at (1.25, 2.25) m")])
    assert event == {"type": "overlay", "robot": ROBOT, "kind": "memory", "stamp": 3.0, "truncated": 0,
                     "obstacles": [{"id": 4, "footprint": [[1.0, 2.0], [1.5, 2.0], [1.5, 2.5], [1.0, 2.5]],
                                    "text": "#4 heavy at (1.25, 2.25) m"}]}
    assert memory_overlay(ROBOT, 3.0, [])["obstacles"] == []  # nothing remembered (the operator cleared it)
    circle = np.column_stack((np.cos(np.linspace(0, 6, 500)), np.sin(np.linspace(0, 6, 500))))
    bad = [(1, square[:2], "a line"), (2, np.array([[0.0, 0.0], [1.0, math.nan], [0.0, 1.0]]), "not finite"),
           (3, circle, "x" * 1000)]
    (kept,) = memory_overlay(ROBOT, 3.0, bad)["obstacles"]
    assert kept["id"] == 3 and len(kept["footprint"]) == MAX_FOOTPRINT_POINTS
    assert kept["text"] == "x" * MAX_REMEMBERED_TEXT
    many = memory_overlay(ROBOT, 3.0, [(i, square, f"#{i}") for i in range(MAX_REMEMBERED + 7)])
    assert len(many["obstacles"]) == MAX_REMEMBERED and many["truncated"] == 7
    assert MIN_PERIOD_S["memory"] > 0  # throttled like the other overlays (the node holds the newest back)


def test_the_throttle_lets_one_overlay_of_a_kind_through_per_period() -> None:
    now = [0.0]
    throttle = Throttle(clock=lambda: now[0])
    assert throttle.due(ROBOT, "scan") and not throttle.due(ROBOT, "scan")
    assert throttle.due(ROBOT, "pose") and throttle.due("/robot2/behavior_runner", "scan")
    now[0] = 0.25
    assert throttle.due(ROBOT, "scan")


def test_goals_are_checked_against_the_robots_and_the_map() -> None:
    goal = {"robot": ROBOT, "kind": "goal", "x": -0.9, "y": -1.9, "yaw": 3 * math.pi}
    request = check_goal(goal, [ROBOT], GEOMETRY)
    assert (request.robot, request.kind, request.x, request.y) == (ROBOT, "goal", -0.9, -1.9)
    assert request.yaw == pytest.approx(math.pi)
    cases: List[Tuple[Dict[str, Any], str, str]] = [
             ({"robot": "/robot9/behavior_runner"}, "robot", "is not valid (valid: /robot1/behavior_runner)"),
             ({"kind": "teleport"}, "kind", "valid: goal, initial_pose"),
             ({"x": float("nan")}, "x", "x must be a finite number, got nan"),
             ({"yaw": "north"}, "yaw", "yaw must be a finite number"),
             ({"y": True}, "y", "y must be a finite number, got True"),
             ({"x": -0.8 + 4 * 0.05}, "x", "is off the map")]  # one cell beyond the last column
    for change, field, reason in cases:
        with pytest.raises(CommandRefused, match=reason.replace("(", r"\(").replace(")", r"\)")) as err:
            check_goal({**goal, **change}, [ROBOT], GEOMETRY)
        assert err.value.field == field
    with pytest.raises(CommandRefused, match="no map yet"):
        check_goal(goal, [ROBOT], None)
    assert GridGeometry("map", 1.0, 2, 1, (0.0, 0.0, math.pi / 2)).contains(-0.5, 1.5)  # a rotated origin
    assert robot_namespace(ROBOT) == "/robot1" and robot_namespace("/behavior_runner") == ""


def test_a_page_gets_the_map_and_overlays_and_its_goals_reach_the_sender() -> None:
    async def check() -> None:
        made, _ = console(port=0)
        goals: List[GoalRequest] = []

        def send_goal(request: GoalRequest) -> None:
            if request.kind == "initial_pose":
                raise NotReadyError("nothing listens on /robot1/initialpose (yet); try again")
            goals.append(request)

        made.send_goal = send_goal
        async with served(made) as client:
            first = await page(client)
            await asyncio.to_thread(made.submit_robots, [ROBOT])
            await asyncio.to_thread(made.submit_map, GEOMETRY, [0] * 12)
            assert (await until(first, lambda e: e["type"] == "map"))["width"] == 4
            await asyncio.to_thread(made.submit_overlay, pose_overlay(ROBOT, 1.0, (0.0, 0.0, 0.0), 0.2))
            await until(first, lambda e: e["type"] == "overlay")
            await asyncio.to_thread(made.submit_map, GEOMETRY, [0] * 11 + [100])
            assert (await until(first, lambda e: e["type"] == "map_patch"))["y"] == 0
            second = await client.ws_connect("/ws", headers={"Origin": origin(client)})
            seen: List[Dict[str, Any]] = []
            await until(second, lambda e: e["type"] == "snapshot_done", seen)
            assert [e["type"] for e in seen] == ["hello", "snapshot", "robots", "map", "overlay", "snapshot_done"]
            assert decoded(seen[3]["png"])[0, 3] == OCCUPIED  # the map as patched
            await second.send_json({"type": "goal", "id": 7, "robot": ROBOT, "kind": "goal", "x": -0.9, "y": -1.9,
                                    "yaw": 0.5})
            sent = await until(second, lambda e: e["type"] in ("goal_sent", "refused"))
            assert sent == {"type": "goal_sent", "ref": "2:7", "robot": ROBOT, "kind": "goal", "x": -0.9, "y": -1.9,
                            "yaw": 0.5}
            assert goals == [GoalRequest(ROBOT, "goal", -0.9, -1.9, 0.5)]
            await second.send_json({"type": "goal", "id": 8, "robot": ROBOT, "kind": "goal", "x": 50.0, "y": 0.0,
                                    "yaw": 0.0})
            refused = await until(second, lambda e: e["type"] in ("goal_sent", "refused"))
            assert refused["ref"] == "2:8" and "(50.00, 0.00) m is off the map" in refused["reason"]
            await second.send_json({"type": "goal", "id": 9, "robot": ROBOT, "kind": "initial_pose", "x": -0.9,
                                    "y": -1.9, "yaw": 0.0})
            refused = await until(second, lambda e: e["type"] in ("goal_sent", "refused"))
            assert "nothing listens on /robot1/initialpose" in refused["reason"] and len(goals) == 1
            await first.close()
            await second.close()
    run(check())
