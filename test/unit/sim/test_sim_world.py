"""World files: the shipped worlds load; walls, doors, low obstacles, people and events are interpreted;
bad files, bad spawns and duplicate namespaces are rejected with messages naming the field."""

from __future__ import annotations

import math
from pathlib import Path

import cv2
import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
from flex_nav_sim.world import Spawn, available_worlds, check_spawns, load_world, occupied_rectangles


def test_shipped_worlds() -> None:
    assert set(available_worlds()) >= {"lab", "two_rooms", "open_room", "corridor"}
    for name in available_worlds():
        world = load_world(name)
        assert world.name == name
        assert world.spawns, name
        check_spawns(world, world.spawns, {s.name: 0.18 for s in world.spawns})


def test_lab_low_obstacle_lies_on_the_first_leg() -> None:
    lab = load_world("lab")
    low = [s for s in lab.solids if s.kind == "obstacle" and s.height < lab.map.min_height]
    assert [s.name for s in low] == ["low_step"]
    assert not low[0].in_map
    start, g1 = lab.goals["start"], lab.goals["g1"]
    fp = low[0].footprint()
    # the straight line start -> g1 crosses the low step
    samples = [(start[0] + f * (g1[0] - start[0]), start[1] + f * (g1[1] - start[1])) for f in np.linspace(0, 1, 101)]
    assert any(fp.distance_to(x, y) == 0.0 for x, y in samples)
    assert set(lab.goals) == {"start", "g1", "g2", "g3"}


def test_two_rooms_door_cuts_the_divider() -> None:
    world = load_world("two_rooms")
    names = {s.name for s in world.solids}
    assert "divider" not in names and {"divider_a", "divider_b", "door"} <= names
    door = world.solid("door")
    assert door.kind == "door" and not door.present and not door.in_map  # open
    gap_top = world.solid("divider_a").footprint().bounds()[3]
    gap_bottom = world.solid("divider_b").footprint().bounds()[1]
    assert gap_bottom - gap_top == pytest.approx(0.9)


def test_open_room_people_and_events() -> None:
    world = load_world("open_room")
    walker = next(p for p in world.people if p.name == "walker")
    assert walker.walks and walker.loop and walker.start_time == 0.0
    late = next(p for p in world.people if p.name == "late_walker")
    assert late.start_time is None
    assert [(e.time, e.action, e.target) for e in world.events] == [
        (10.0, "start_walking", "late_walker"),
        (40.0, "remove", "temporary_barrier"),
    ]
    boxes = {s.name: s for s in world.solids if s.kind == "box"}
    assert boxes["light_box"].mass == 0.5 and boxes["heavy_box"].mass == 30.0


def test_person_pose_along_waypoints() -> None:
    walker = next(p for p in load_world("open_room").people if p.name == "walker")
    assert walker.path_length() == pytest.approx(24.0)
    x, y, yaw = walker.pose_after(2.5)  # 2 m along the first side at 0.8 m/s
    assert (x, y) == pytest.approx((4.0, 8.0))
    assert yaw == pytest.approx(0.0)
    x, y, yaw = walker.pose_after(10.0)  # 8 m: 2 m down the second side
    assert (x, y) == pytest.approx((8.0, 6.0))
    assert yaw == pytest.approx(-math.pi / 2)
    assert walker.pose_after(30.0)[:2] == pytest.approx(walker.pose_after(0.0)[:2])  # one lap = 24 m


def _world(tmp_path: Path, body: str) -> Path:
    path = tmp_path / "w.yaml"
    path.write_text("name: w\nrooms:\n  - {name: r, min: [0, 0], max: [4, 4]}\n" + body)
    return path


def test_unknown_world_lists_valid_names() -> None:
    with pytest.raises(ConfigError, match=r"world 'moon' is not valid \(valid: .*lab.*\)"):
        load_world("moon")


def test_malformed_world_yaml(tmp_path: Path) -> None:
    path = tmp_path / "w.yaml"
    path.write_text("name: w\nrooms: [{name: r, min: [0, 0]\n")
    with pytest.raises(ConfigError, match="malformed YAML"):
        load_world(path)


BAD_WORLD_FILES = {  # test id: (what the file adds to a valid world, the error it must give)
    "bad_shape_lists_choices": (
        "obstacles:\n  - {name: o, shape: cube, size: [1, 1, 1], pose: [2, 2]}\n",
        r"obstacles\[0\]\.shape 'cube' is not valid \(valid: box, cylinder\)",
    ),
    "unknown_world_field": ("obstacle:\n  - {name: o}\n", "unknown field 'obstacle'"),
    "duplicate_names_rejected": (
        "obstacles:\n"
        "  - {name: o, size: [0.2, 0.2, 1], pose: [1, 1]}\n"
        "  - {name: o, size: [0.2, 0.2, 1], pose: [2, 2]}\n",
        "'o' is already used",
    ),
    "event_target_must_exist": (
        "events:\n  - {at: 4, action: remove, target: ghost}\n",
        r"events\[0\]\.target for action remove 'ghost' is not valid",
    ),
    "event_cannot_remove_walls": ("events:\n  - {at: 4, action: remove, target: r_south}\n", "'r_south' is not valid"),
    "door_must_sit_on_a_wall": ("doors:\n  - {name: d, at: [2, 2]}\n", "does not lie on any wall"),
    "unknown_robot_profile_in_world": (
        "robots:\n  - {name: r1, profile: roomba, pose: [1, 1]}\n",
        r"robots\[0\]\.profile 'roomba' is not valid \(valid: create2, kobuki",
    ),
}


@pytest.mark.parametrize(("extra", "match"), BAD_WORLD_FILES.values(), ids=BAD_WORLD_FILES.keys())
def test_bad_world_file_is_rejected_naming_the_field(tmp_path: Path, extra: str, match: str) -> None:
    with pytest.raises(ConfigError, match=match):
        load_world(_world(tmp_path, extra))


def test_spawn_inside_wall_rejected() -> None:
    world = load_world("two_rooms")
    with pytest.raises(ConfigError, match=r"robot 'robot1' spawned at .* overlaps wall 'divider_a'"):
        check_spawns(world, [Spawn("robot1", "kobuki", (5.0, 1.0, 0.0))], {"robot1": 0.18})


def test_spawn_on_low_obstacle_rejected() -> None:
    world = load_world("lab")
    with pytest.raises(ConfigError, match="overlaps obstacle 'low_step'"):
        check_spawns(world, [Spawn("robot1", "kobuki", (4.0, 1.0, 0.0))], {"robot1": 0.18})


def test_two_robots_one_namespace_rejected() -> None:
    world = load_world("open_room")
    spawns = [Spawn("robot1", "kobuki", (1.0, 1.0, 0.0)), Spawn("robot1", "create2", (3.0, 1.0, 0.0))]
    with pytest.raises(ConfigError, match="two robots share the namespace 'robot1'"):
        check_spawns(world, spawns, {"robot1": 0.18})


def test_robots_on_top_of_each_other_rejected() -> None:
    world = load_world("open_room")
    spawns = [Spawn("a", "kobuki", (1.0, 1.0, 0.0)), Spawn("b", "kobuki", (1.2, 1.0, 0.0))]
    with pytest.raises(ConfigError, match="robots 'a' and 'b' are spawned on top of each other"):
        check_spawns(world, spawns, {"a": 0.18, "b": 0.18})


def test_bad_robot_name_rejected() -> None:
    world = load_world("open_room")
    with pytest.raises(ConfigError, match="not a valid ROS namespace"):
        check_spawns(world, [Spawn("1robot", "kobuki", (1.0, 1.0, 0.0))], {"1robot": 0.18})


def test_walls_from_image(tmp_path: Path) -> None:
    image = np.full((40, 60), 254, dtype=np.uint8)  # 3 x 2 m at 0.05 m/px, free
    image[0, :] = image[-1, :] = 0  # top and bottom rows occupied
    image[:, 0] = image[:, -1] = 0
    image[10:30, 30] = 0  # a 1 m wall in the middle
    cv2.imwrite(str(tmp_path / "walls.png"), image)
    path = tmp_path / "img.yaml"
    path.write_text(
        "name: img\nwall_images:\n  - {file: walls.png, resolution: 0.05, origin: [1.0, 2.0], height: 0.5}\n"
    )
    world = load_world(path)
    walls = [s for s in world.solids if s.kind == "wall"]
    assert 4 <= len(walls) <= 6  # merged into a few rectangles, not 300 pixels
    assert world.bounds() == pytest.approx((1.0, 2.0, 4.0, 4.0))
    middle = [w for w in walls if w.size[0] == pytest.approx(0.05) and w.size[1] == pytest.approx(1.0)]
    assert len(middle) == 1
    # image row 10..29 from the top -> y from 2 + (40 - 30) * 0.05 = 2.5 to 3.5
    assert middle[0].pose[:2] == pytest.approx((1.0 + 30.5 * 0.05, 3.0))


def test_occupied_rectangles_cover_exactly() -> None:
    rng = np.random.default_rng(3)
    mask = rng.random((23, 31)) < 0.3
    covered = np.zeros_like(mask)
    for r0, c0, r1, c1 in occupied_rectangles(mask):
        assert not covered[r0:r1, c0:c1].any()  # no overlaps
        covered[r0:r1, c0:c1] = True
    assert (covered == mask).all()
