"""The shipped obstacle classifier on the push-or-avoid scenarios' own targets, seen by the simulator's
camera from where the robot stops in front of them (the behavior classifies once it is blocked).

A retrained model once took S4/S5's wide box in its passage (a tall block on one side, a wall on the
other) for clear furniture, so push_or_avoid never tried to push: this checks every scenario's target
at the distances of a blocked stop before the system tests need minutes to find out."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest
from harness import REPO_ROOT

from flex_nav.perception.classifier import ObstacleClassifier
from flex_nav.perception.labels import MOVABLE, PERSON
from flex_nav_sim.readings import ImageReading
from flex_nav_sim.simulation import SensorOptions, Simulation
from flex_nav_sim.world import load_world

ROBOT_RADIUS = 0.17  # [m] TurtleBot 4 (the scenarios' profile), robot centre to its front
GAPS = (0.5, 0.7, 0.9)  # [m] robot front to the target's near face: where a blocked robot stands
# world, x of the target's near face [m], y of the target [m], expected label
TARGETS = (
    ("s1_light_box_door", 5.0 - 0.225, 2.0, MOVABLE),
    ("s2_heavy_box_door", 5.0 - 0.225, 2.0, MOVABLE),
    ("s3_person_in_door", 5.0 - 0.25, 2.0, PERSON),
    ("s4_light_box_short_route", 6.3 - 0.3, 0.5, MOVABLE),
    ("s5_heavy_box_short_route", 6.3 - 0.3, 0.5, MOVABLE),
)


@pytest.fixture(scope="module")
def classifier() -> ObstacleClassifier:
    return ObstacleClassifier()


@pytest.mark.parametrize(("world", "face_x", "y", "expected"), TARGETS, ids=[t[0] for t in TARGETS])
def test_scenario_target_is_classified_from_a_blocked_stop(
    classifier: ObstacleClassifier, world: str, face_x: float, y: float, expected: str
) -> None:
    spec = load_world(REPO_ROOT / "sim" / "worlds" / f"{world}.yaml")
    options = SensorOptions(odometry=False, lidar=False, bumpers=False, camera=True)
    seen = []
    for gap in GAPS:
        spawn = dataclasses.replace(spec.spawns[0], pose=(face_x - gap - ROBOT_RADIUS, y, 0.0))
        with Simulation(dataclasses.replace(spec, spawns=(spawn,)), seed=0, sensors=options) as sim:
            images = [r for r in sim.step() if isinstance(r, ImageReading)]
        assert images, f"{world}: no camera image"
        seen.append((gap, classifier.classify(images[0].rgb, images[0].depth)))
    wrong = [(gap, p.label, round(p.confidence, 2)) for gap, p in seen if p.label != expected]
    assert not wrong, f"{world}: expected {expected}, got (gap [m], label, confidence) {wrong}"


def test_targets_are_where_the_worlds_put_them() -> None:
    for world, face_x, y, _ in TARGETS:
        spec = load_world(Path(REPO_ROOT / "sim" / "worlds" / f"{world}.yaml"))
        xs = [s.pose[0] for s in spec.solids if abs(s.pose[1] - y) < 0.05 and s.pose[0] > face_x]
        xs += [p.pose_after(0.0)[0] for p in spec.people if abs(p.pose_after(0.0)[1] - y) < 0.05]
        assert xs and min(xs) - face_x < 0.4, f"{world}: no target just behind x = {face_x} m at y = {y} m"
