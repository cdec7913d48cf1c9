"""The robots parameter: world defaults, text and list forms, errors naming the entry."""

from __future__ import annotations

import math

import pytest

from flex_nav.exceptions import ConfigError
from flex_nav_sim.spawn_spec import resolve_spawns
from flex_nav_sim.world import Spawn, load_world


def test_default_is_the_worlds_robots() -> None:
    world = load_world("lab")
    assert resolve_spawns(world, "") == list(world.spawns)
    assert resolve_spawns(world, None) == list(world.spawns)


def test_text_forms() -> None:
    world = load_world("lab")
    base = world.spawns[0]
    spawns = resolve_spawns(world, "robot1:create2, robot2:turtlebot4:3:1:90  robot3:kobuki:5:1")
    assert spawns == [
        Spawn("robot1", "create2", base.pose),
        Spawn("robot2", "turtlebot4", (3.0, 1.0, math.radians(90.0))),
        Spawn("robot3", "kobuki", (5.0, 1.0, 0.0)),
    ]
    assert resolve_spawns(world, "robot1:") == [base]  # empty profile: the world's


def test_list_form() -> None:
    world = load_world("lab")
    spawns = resolve_spawns(world, [{"name": "robot1"}, {"name": "r2", "profile": "create2", "pose": [2, 1, 180]}])
    assert spawns == [world.spawns[0], Spawn("r2", "create2", (2.0, 1.0, math.pi))]


def test_unknown_robot_without_pose() -> None:
    with pytest.raises(ConfigError, match=r"robot 'robot7' is not valid \(valid: robot1\) in world lab"):
        resolve_spawns(load_world("lab"), "robot7")


def test_bad_numbers_and_shapes() -> None:
    world = load_world("lab")
    with pytest.raises(ConfigError, match="must be numbers"):
        resolve_spawns(world, "r:kobuki:one:2")
    with pytest.raises(ConfigError, match="is not NAME, NAME:PROFILE or NAME:PROFILE:X:Y"):
        resolve_spawns(world, "r:kobuki:1")
    message = r"robots\[0\]\.pos: unknown field 'pos' is not valid \(valid: name, pose, profile\)"
    with pytest.raises(ConfigError, match=message):
        resolve_spawns(world, [{"name": "robot1", "pos": [1, 1]}])
    with pytest.raises(ConfigError, match="must be text"):
        resolve_spawns(world, 42)
