"""The arrival bound of a scenario world: the earliest arrival along a route that keeps a distance from the
scripted people while moving, checked against the people's own replay (metrics.person_position) and against
cases with a known answer."""

import math
from pathlib import Path

import numpy as np
import pytest

from flex_nav.apps.eval.arrival_bound import check_route, earliest_arrival, main
from flex_nav.apps.eval.metrics import ROBOT_RADIUS_M, person_position, walking_intervals
from flex_nav.exceptions import ConfigError
from flex_nav_sim.static_map import static_map
from flex_nav_sim.world import load_world

ROUTE = np.array([[0.8, 4.0], [8.2, 4.0]])
H6 = Path(__file__).resolve().parents[2] / "data" / "issue28" / "variants" / "h6_people_crossing.yaml"


def _world(tmp_path: Path, people: str) -> Path:
    path = tmp_path / "bound_world.yaml"
    path.write_text(
        "name: bound_world\n"
        "map: {resolution: 0.05, min_height: 0.12, padding: 0.5}\n"
        "defaults: {wall_height: 0.8, wall_thickness: 0.1}\n"
        "rooms:\n  - {name: room, min: [0.0, 0.0], max: [9.0, 8.0]}\n"
        f"people:\n{people}"
        "robots:\n  - {name: robot1, profile: turtlebot4, pose: [0.8, 4.0, 0]}\n"
        "goals:\n  start: [0.8, 4.0, 0]\n  goal: [8.2, 4.0, 0]\n")
    return path


def _closest_while_moving(world, profile, start_world_s: float, step_s: float = 0.1) -> float:
    """The smallest gap to any person at the two ends of every step that moves, replayed from the world file."""
    x = np.interp(profile, [0.0, 7.4], ROUTE[:, 0])
    worst = math.inf
    for person in world.people:
        intervals = walking_intervals(person, world.events)
        for k in range(len(profile) - 1):
            if profile[k + 1] == profile[k]:
                continue
            for j in (k, k + 1):
                px, py = person_position(person, intervals, start_world_s + j * step_s)
                worst = min(worst, math.hypot(x[j] - px, 4.0 - py) - person.radius - ROBOT_RADIUS_M)
    return worst


def test_without_people_it_drives_at_full_speed(tmp_path):
    world = load_world(_world(tmp_path, "  []\n"))
    result = earliest_arrival(world, ROUTE, start_world_s=4.0, speed_mps=0.26)
    assert result.arrival_s is not None
    assert result.arrival_s == pytest.approx(math.ceil(7.4 / 0.026 - 1e-9) * 0.1)
    assert result.profile_m[0] == 0.0 and result.profile_m[-1] == pytest.approx(7.4)
    assert len(result.profile_m) == round(result.arrival_s / 0.1) + 1


def test_h6_profile_keeps_the_distance_while_moving_and_waits_for_the_walkers():
    world = load_world(H6)
    free_s = 7.4 / 0.26
    result = earliest_arrival(world, ROUTE, start_world_s=4.0, moving_gap_m=0.3)
    assert result.arrival_s is not None and result.arrival_s > free_s + 1.0  # it had to wait
    assert _closest_while_moving(world, result.profile_m, 4.0) >= 0.3 - 1e-9
    steps = np.diff(result.profile_m)
    assert steps.min() >= 0.0 and steps.max() <= 0.026 + 1e-9  # forward only, never faster than 0.26 m/s
    closer = earliest_arrival(world, ROUTE, start_world_s=4.0, moving_gap_m=0.1)
    assert closer.arrival_s is not None and closer.arrival_s <= result.arrival_s  # less distance: never later


def test_a_person_standing_on_the_route_cannot_be_passed(tmp_path):
    world = load_world(_world(tmp_path, "  - {name: still, waypoints: [[4.0, 4.0], [4.0, 7.0]], speed: 0.5, "
                                        "loop: false, start: null}\n"))
    result = earliest_arrival(world, ROUTE, start_world_s=4.0, limit_s=20.0)
    assert result.arrival_s is None and result.profile_m == ()
    radius = world.people[0].radius
    assert result.farthest_m <= (4.0 - 0.8) - radius - ROBOT_RADIUS_M - 0.3 + 0.01
    assert result.farthest_m >= (4.0 - 0.8) - radius - ROBOT_RADIUS_M - 0.3 - 0.01
    assert "no speed profile keeps 0.3 m" in result.line(0.3)


def test_bad_inputs_are_named(tmp_path):
    world = load_world(_world(tmp_path, "  []\n"))
    with pytest.raises(ConfigError, match="route"):
        earliest_arrival(world, np.array([[0.0, 0.0]]), start_world_s=0.0)
    with pytest.raises(ConfigError, match="speed_mps"):
        earliest_arrival(world, ROUTE, start_world_s=0.0, speed_mps=-0.1)
    with pytest.raises(ConfigError, match="moving_gap_m"):
        earliest_arrival(world, ROUTE, start_world_s=0.0, moving_gap_m=math.nan)


def test_a_route_through_a_wall_is_refused():
    h3 = load_world(H6.parent / "h3_person_in_door.yaml")  # its door is off the straight line
    start, goal = h3.goals["start"], h3.goals["goal"]
    with pytest.raises(ConfigError, match="wall at"):
        check_route(static_map(h3), np.array([start[:2], goal[:2]]), ROBOT_RADIUS_M)
    s3 = load_world("s3_person_in_door")
    start, goal = s3.goals["start"], s3.goals["goal"]
    check_route(static_map(s3), np.array([start[:2], goal[:2]]), ROBOT_RADIUS_M)  # straight through its door


def test_command_line(tmp_path, capsys):
    assert main(["--world", str(H6)]) == 0
    assert "earliest arrival" in capsys.readouterr().out
    assert main(["--world", str(H6), "--route", "1,4;x"]) == 2
    assert "--route must be" in capsys.readouterr().err
    assert main(["--world", str(_world(tmp_path, "  - {name: still, waypoints: [[4.0, 4.0], [4.0, 7.0]], "
                                                 "speed: 0.5, loop: false, start: null}\n")), "--limit", "5"]) == 1
