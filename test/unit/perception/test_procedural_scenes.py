"""The procedural dataset models (tools/perception/procedural_scenes.py): the shapes they place, recorded without
rendering, obey what each label promises (people rest on the floor or a support, objects are small enough to push,
structures are too big to)."""

from __future__ import annotations

import math
import sys
from typing import Any, List, Sequence, Tuple

import numpy as np
import pybullet
import pytest
from harness import REPO_ROOT

if str(REPO_ROOT) not in sys.path:  # ``tools`` is imported as a package from the repository root
    sys.path.insert(0, str(REPO_ROOT))

from tools.perception import procedural_scenes
from tools.perception.scene_base import Scene

Shape = Tuple[int, dict[str, Any]]


class RecordingClient:
    """Stands in for a BulletClient: records every visual shape and where it was placed."""

    def __init__(self) -> None:
        self.shapes: List[Shape] = []
        self.bodies: List[Tuple[Shape, Sequence[float], Sequence[float]]] = []

    def createVisualShape(self, kind: int, **kwargs: Any) -> int:
        self.shapes.append((kind, kwargs))
        return len(self.shapes) - 1

    def createMultiBody(self, mass: float, collision: int, visual: int, pos: Sequence[float],
                        orn: Sequence[float]) -> int:
        assert mass == 0.0 and collision == -1
        self.bodies.append((self.shapes[visual], pos, orn))
        return len(self.bodies) - 1

    @staticmethod
    def getQuaternionFromEuler(euler: Sequence[float]) -> Sequence[float]:
        quaternion: Sequence[float] = pybullet.getQuaternionFromEuler(euler)
        return quaternion

    def extent(self) -> Tuple[np.ndarray, np.ndarray]:
        """(lowest, highest) corner [m] over all shapes."""
        points = []
        for (kind, kw), pos, orn in self.bodies:
            centre = np.asarray(pos, dtype=float)
            rot = np.asarray(pybullet.getMatrixFromQuaternion(orn)).reshape(3, 3)
            if kind == pybullet.GEOM_BOX:
                half = np.asarray(kw["halfExtents"])
                for sx in (-1, 1):
                    for sy in (-1, 1):
                        for sz in (-1, 1):
                            points.append(centre + rot @ (half * (sx, sy, sz)))
                continue
            radius = float(kw["radius"])
            normal = rot[:, 2]
            axis = normal * kw.get("length", 0.0) / 2.0
            # a capsule's or a sphere's ends are balls; a cylinder's are discs across its axis
            reach = radius * np.sqrt(np.clip(1.0 - normal**2, 0.0, 1.0)) if kind == pybullet.GEOM_CYLINDER \
                else np.full(3, radius)
            for end in (centre + axis, centre - axis):
                points += [end - reach, end + reach]
        stacked = np.array(points)
        return stacked.min(axis=0), stacked.max(axis=0)


def _build(builder: Any, seed: int, x: float = 1.5, y: float = 0.0, yaw: float = 0.3) -> RecordingClient:
    client = RecordingClient()
    builder(Scene(client, np.random.default_rng(seed)), x, y, yaw)
    assert client.bodies, "the builder placed nothing"
    return client


@pytest.mark.parametrize("stance", procedural_scenes.STANCES)
def test_a_random_person_rests_on_the_floor_in_every_stance(stance: str, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(procedural_scenes, "STANCES", (stance,))
    for seed in range(12):
        low, high = _build(procedural_scenes.person_random_pose, seed, x=0.9).extent()  # near: never hidden
        # the contact points are balls (the pelvis one as deep as the chest) and joints are kept above the floor,
        # not the limbs' surfaces: the lowest shape may float or sink a few cm, never more
        assert -0.06 <= low[2] <= 0.06, f"{stance} seed {seed}: lowest point {low[2]:.3f} m"
        assert high[2] < 2.3, f"{stance} seed {seed}: {high[2]:.2f} m tall"
        if stance in ("standing", "walking"):
            assert high[2] > 0.85
        if stance in ("all_fours", "sitting_floor", "squatting"):  # a raised arm included
            assert high[2] < 1.7, f"{stance} seed {seed}: {high[2]:.2f} m tall"
        if stance == "lying":  # on the floor or on a support up to 0.7 m, an arm raised
            assert high[2] < 1.6, f"{stance} seed {seed}: {high[2]:.2f} m tall"


def test_the_stances_differ_in_height_as_people_do() -> None:
    pose = {stance: procedural_scenes._Pose(np.random.default_rng(0), stance) for stance in procedural_scenes.STANCES}
    assert pose["lying"].body_pitch in (-math.pi / 2.0, math.pi / 2.0)
    assert pose["all_fours"].body_pitch > 1.0
    assert pose["standing"].body_pitch == 0.0 and pose["bending"].spine > 0.5
    for knee, hip in zip(pose["sitting_floor"].knee, pose["sitting_floor"].hip):
        assert 0.0 <= hip - knee <= math.pi / 2.0 + 1e-9  # the shin goes forward-down to the floor


def test_random_objects_are_small_enough_to_push() -> None:
    for seed in range(60):
        low, high = _build(procedural_scenes.movable_random_object, seed).extent()
        assert low[2] >= -0.08  # blobs of spheres are squashed into the floor
        assert high[2] <= 0.9, f"seed {seed}: {high[2]:.2f} m high"
        assert max(high[0] - low[0], high[1] - low[1]) <= 1.15, f"seed {seed}: {high - low} m"


def test_random_structures_are_too_big_to_push() -> None:
    heights = []
    for seed in range(60):
        _, high = _build(procedural_scenes.clear_random_structure, seed).extent()
        heights.append(high[2])
    assert min(heights) >= 0.8  # every structure stands at least 0.8 m high
    assert max(heights) > 1.6  # and some are taller than a person's shoulder


def test_a_pusher_holds_a_handle_ahead_of_it_and_rests_on_the_floor() -> None:
    for seed in range(30):
        client = RecordingClient()
        sc = Scene(client, np.random.default_rng(seed))
        hands = procedural_scenes.person_random_pose(sc, 1.5, 0.0, 0.0, stances=("standing",), reach=True)
        for hand in hands:  # facing +x from x = 1.5: the hands are ahead of the figure, between hip and head
            assert hand[0] > 1.5 + 0.1 and 0.5 < hand[2] < 1.7, f"seed {seed}: hand at {hand}"
        low, high = _build(procedural_scenes.person_pushing_thing, seed).extent()
        # a bent-over child pushing a toy is ~0.7 m high
        assert -0.06 <= low[2] <= 0.06 and 0.6 < high[2] < 2.3, f"seed {seed}: {low[2]:.3f}..{high[2]:.2f} m"


@pytest.mark.parametrize("builder", [procedural_scenes.clear_random_machine, procedural_scenes.clear_random_appliance,
                                     procedural_scenes.clear_legged_frame])
def test_machines_appliances_and_frames_are_too_big_to_push(builder: Any) -> None:
    for seed in range(40):
        low, high = _build(builder, seed).extent()
        assert low[2] >= -0.05, f"seed {seed}: lowest point {low[2]:.3f} m"
        assert high[2] >= 0.8, f"{builder.__name__} seed {seed}: {high[2]:.2f} m high"
        assert high[2] < 2.3
