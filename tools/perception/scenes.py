"""Scenes for the obstacle classifier's dataset, rendered with the simulator's camera model.

Each sample is one pybullet scene in front of a robot at the origin facing +x: a floor, background
walls, optional side distractors outside the region of interest, and one *target* that decides the
label: a person (``person``), a low free-standing object that a robot could push (``movable``: boxes,
crates, parcels, bins) or nothing / a wall / furniture (``clear``: tables, chairs, shelves, cabinets,
pillars, benches, beds, door frames).
The camera is one of the robot profiles' (``sim/robots/*.yaml``: OAK-D on the TurtleBot 4, Kinect on
the Kobuki and Create 2) with a little height and pitch jitter, rendered offscreen with
ER_TINY_RENDERER exactly as :class:`flex_nav_sim.sensors.Camera` does, under varied lighting.

Models are split into the ones used for training and the ones held out for evaluation
(``HELD_OUT``): the held-out people, objects and furniture are never seen in training.

People are drawn in the simulator's own way (a capsule, in clothing colours; the simulator's default
person colour included) and as articulated figures (a primitive walker, the MuJoCo humanoid, the
DeepMimic humanoid of pybullet_data) in random walking poses. Note: a single-colour capsule seen from
0.25-0.30 m height looks like a cylinder pillar of the same colour; the dataset keeps pillars in
furniture colours (greys, whites, wood, muted blue), which is what lets the model tell them apart.
"""

from __future__ import annotations

import contextlib
import math
import os
import sys
from dataclasses import dataclass
from typing import Any, Callable, Dict, Iterator, List, Sequence, Tuple

import numpy as np
import pybullet
import pybullet_data

from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from flex_nav_sim.bodies import FLOOR_COLOR
from flex_nav_sim.profiles import CameraSpec, load_profile
from flex_nav_sim.sensors import depth_from_buffer
from flex_nav_sim.world import DEFAULT_COLORS

Rgba = Tuple[float, float, float, float]
Vec3 = Tuple[float, float, float]
DATA = pybullet_data.getDataPath()
PROFILES = ("turtlebot4", "kobuki", "create2")

TRAIN_MODELS: Dict[str, Tuple[str, ...]] = {
    PERSON: ("capsule", "walker", "mjcf_humanoid"),
    MOVABLE: ("box", "box_pair", "bin"),
    CLEAR: ("empty", "wall", "table", "chair", "pillar", "cabinet", "shelf", "coffee_table", "sofa"),
}
TRAIN_ONLY: Dict[str, Tuple[str, ...]] = {  # extra training models, only in the ``extra`` splits
    PERSON: (),
    MOVABLE: ("light_box", "suitcase", "tote", "sack"),
    CLEAR: ("stool", "ottoman", "sideboard", "cart", "radiator", "seat_row", "gurney", "desk", "corridor"),
}
EXTRA_SPLITS = ("extra", "val_extra", "extra2", "val_extra2", "extra3", "val_extra3", "extra4", "val_extra4",
                "extra5", "val_extra5")
PASSAGE: Dict[str, Tuple[str, ...]] = {  # the ``extra2`` splits: boxes in passages against corridors and furniture
    PERSON: TRAIN_MODELS[PERSON],
    MOVABLE: ("passage_box", "passage_box", "box", "light_box"),
    CLEAR: ("corridor", "sideboard", "ottoman", "sofa"),
}
HELD_OUT: Dict[str, Tuple[str, ...]] = {
    PERSON: ("deepmimic_humanoid", "dress_walker"),
    MOVABLE: ("crate", "textured_cube", "taped_parcel"),
    CLEAR: ("urdf_table", "bench", "bed", "door_frame"),
}
PROCEDURAL: Dict[str, Tuple[str, ...]] = {  # the ``extra3`` splits: randomised furniture and marked boxes
    PERSON: TRAIN_MODELS[PERSON],
    MOVABLE: ("marked_box", "marked_box", "box", "bin"),
    CLEAR: ("random_furniture", "random_furniture", "random_furniture", "wall"),
}
HELD_OUT_2: Dict[str, Tuple[str, ...]] = {  # the ``unseen2`` split: defined before the extra3 model was trained
    PERSON: ("child_walker", "bag_walker"),
    MOVABLE: ("cooler", "drum", "wrapped_parcel"),
    CLEAR: ("bookcase", "coat_rack", "pedestal_table", "partition"),
}
HELD_OUT_3: Dict[str, Tuple[str, ...]] = {  # the ``unseen3`` split: defined before any depth model was trained
    PERSON: ("wheelchair_user", "crutch_walker"),
    MOVABLE: ("linen_bag", "trunk", "parcel_stack"),
    CLEAR: ("iv_stand", "wardrobe", "vending_machine"),
}
ASSISTIVE: Dict[str, Tuple[str, ...]] = {  # the ``extra4`` splits: seated people, poles on castors, tall blocks
    PERSON: ("seated_person", "wheelchair_rider", "wheelchair_rider", "frame_walker", "trolley_pusher", "walker"),
    MOVABLE: ("box", "bin", "suitcase", "tote", "sack", "light_box"),
    CLEAR: ("castor_pole", "tall_appliance", "locker", "empty_wheelchair", "random_furniture", "wall"),
}
ENCUMBERED: Dict[str, Tuple[str, ...]] = {  # the ``extra5`` splits: people behind or on things, plants
    PERSON: ("block_pusher", "behind_thing", "behind_thing", "base_rider", "seated_person", "walker"),
    MOVABLE: ("marked_box", "box", "bin", "suitcase", "tote", "sack"),
    CLEAR: ("plant", "plant", "random_furniture", "tall_appliance", "empty_base", "empty_wheelchair"),
}
HELD_OUT_4: Dict[str, Tuple[str, ...]] = {  # the ``unseen4`` split: defined before seated people were trained on
    PERSON: ("power_chair_user", "cart_pusher"),
    MOVABLE: ("lidded_tub", "duffel_bag", "bottle_pack"),
    CLEAR: ("floor_lamp", "fridge", "photocopier"),
}
HELD_OUT_5: Dict[str, Tuple[str, ...]] = {  # the ``unseen5`` split: defined before the extra5 data was designed
    PERSON: ("kneeler", "box_carrier", "stroller_pusher"),
    MOVABLE: ("laundry_basket", "flat_pack", "water_jugs"),
    CLEAR: ("potted_plant", "reception_counter", "chair_stack"),
}
HELD_OUT_6: Dict[str, Tuple[str, ...]] = {  # the ``unseen6`` split: defined before the extra5 data was designed
    PERSON: ("person_pair", "hi_vis_worker", "scooter_rider"),
    MOVABLE: ("rolled_rug", "crate_stack", "carrier_bags"),
    CLEAR: ("sanitiser_stand", "bicycle", "notice_board"),
}

# -- colour palettes ----------------------------------------------------------------------------------
CLOTHES: Tuple[Vec3, ...] = (
    DEFAULT_COLORS["person"][:3], (0.1, 0.15, 0.35), (0.15, 0.15, 0.18), (0.25, 0.35, 0.6), (0.2, 0.5, 0.5),
    (0.55, 0.1, 0.1), (0.1, 0.4, 0.15), (0.45, 0.4, 0.3), (0.9, 0.9, 0.92), (0.5, 0.2, 0.45), (0.85, 0.55, 0.1),
    (0.3, 0.55, 0.75), (0.6, 0.75, 0.85), (0.35, 0.25, 0.2), (0.8, 0.25, 0.45),
)
SKIN: Tuple[Vec3, ...] = ((0.95, 0.8, 0.7), (0.85, 0.65, 0.5), (0.6, 0.42, 0.3), (0.4, 0.27, 0.18))
SHOES: Tuple[Vec3, ...] = ((0.05, 0.05, 0.05), (0.3, 0.2, 0.1), (0.9, 0.9, 0.9), (0.2, 0.2, 0.3))
BOXES: Tuple[Vec3, ...] = (
    DEFAULT_COLORS["box"][:3], (0.75, 0.58, 0.35), (0.65, 0.5, 0.3), (0.85, 0.7, 0.45), (0.9, 0.9, 0.88),
    (0.3, 0.45, 0.75), (0.75, 0.2, 0.2), (0.25, 0.55, 0.3), (0.9, 0.8, 0.2), (0.45, 0.45, 0.45),
    (0.8, 0.8, 0.8), (0.62, 0.62, 0.64), (0.97, 0.97, 0.97),  # grey and white plastic
)
FURNITURE: Tuple[Vec3, ...] = (
    DEFAULT_COLORS["obstacle"][:3], DEFAULT_COLORS["wall"][:3], DEFAULT_COLORS["door"][:3], (0.9, 0.9, 0.9),
    (0.6, 0.6, 0.62), (0.4, 0.4, 0.42), (0.55, 0.4, 0.25), (0.7, 0.55, 0.4), (0.8, 0.8, 0.75), (0.5, 0.55, 0.6),
)
WALLS: Tuple[Vec3, ...] = (
    DEFAULT_COLORS["wall"][:3], (0.85, 0.85, 0.8), (0.75, 0.8, 0.85), (0.9, 0.88, 0.8), (0.6, 0.65, 0.6),
    (0.8, 0.75, 0.7), (0.95, 0.95, 0.95),
)
FLOORS: Tuple[Vec3, ...] = (
    FLOOR_COLOR[:3], (0.7, 0.7, 0.68), (0.6, 0.55, 0.5), (0.5, 0.55, 0.6), (0.85, 0.85, 0.85), (0.55, 0.45, 0.35),
    (0.4, 0.42, 0.45),
)


def jitter(rng: np.random.Generator, color: Vec3, amount: float = 0.06) -> Rgba:
    r, g, b = (float(np.clip(v + rng.uniform(-amount, amount), 0.0, 1.0)) for v in color)
    return r, g, b, 1.0


def pick(rng: np.random.Generator, palette: Sequence[Vec3]) -> Vec3:
    return palette[int(rng.integers(len(palette)))]


def random_color(rng: np.random.Generator, lo: float, hi: float, amount: float = 0.0) -> Rgba:
    """Any colour: each channel uniform in [lo, hi], then :func:`jitter` by ``amount``."""
    r, g, b = (float(v) for v in rng.uniform(lo, hi, 3))
    return jitter(rng, (r, g, b), amount)


@dataclass(frozen=True)
class Sample:
    """One rendered sample: the image and what is in it."""

    rgb: np.ndarray  # uint8 (height, width, 3)
    depth: np.ndarray  # float32 (height, width) [m], registered to rgb; +inf where nothing was rendered
    label: str
    model: str
    profile: str
    distance: float  # [m] camera to target (0 for 'empty')


class Scene:
    """Visual-only primitives in one BulletClient (nothing is simulated, only rendered)."""

    def __init__(self, client: Any, rng: np.random.Generator) -> None:
        self.c = client
        self.rng = rng

    def _body(self, visual: int, pos: Vec3, orn: Sequence[float]) -> int:
        return int(self.c.createMultiBody(0.0, -1, visual, list(pos), list(orn)))

    def box(self, pos: Vec3, half: Vec3, color: Rgba, yaw: float = 0.0, pitch: float = 0.0) -> int:
        visual = self.c.createVisualShape(pybullet.GEOM_BOX, halfExtents=list(half), rgbaColor=list(color))
        return self._body(visual, pos, self.c.getQuaternionFromEuler([0.0, pitch, yaw]))

    def cylinder(self, pos: Vec3, radius: float, length: float, color: Rgba, *, yaw: float = 0.0,
                 pitch: float = 0.0, roll: float = 0.0) -> int:
        """Upright unless turned: ``roll`` = pi/2 lays it on its side across ``yaw`` (a wheel)."""
        visual = self.c.createVisualShape(pybullet.GEOM_CYLINDER, radius=radius, length=length, rgbaColor=list(color))
        upright = roll == 0.0 and pitch == 0.0 and yaw == 0.0
        orn = (0.0, 0.0, 0.0, 1.0) if upright else self.c.getQuaternionFromEuler([roll, pitch, yaw])
        return self._body(visual, pos, orn)

    def capsule(self, pos: Vec3, radius: float, length: float, color: Rgba, *, yaw: float = 0.0,
                pitch: float = 0.0, roll: float = 0.0) -> int:
        visual = self.c.createVisualShape(pybullet.GEOM_CAPSULE, radius=radius, length=length, rgbaColor=list(color))
        return self._body(visual, pos, self.c.getQuaternionFromEuler([roll, pitch, yaw]))

    def sphere(self, pos: Vec3, radius: float, color: Rgba) -> int:
        visual = self.c.createVisualShape(pybullet.GEOM_SPHERE, radius=radius, rgbaColor=list(color))
        return self._body(visual, pos, (0.0, 0.0, 0.0, 1.0))

    def floor(self, color: Rgba) -> None:
        visual = self.c.createVisualShape(pybullet.GEOM_BOX, halfExtents=[30.0, 30.0, 0.005], rgbaColor=list(color))
        self._body(visual, (0.0, 0.0, -0.005), (0.0, 0.0, 0.0, 1.0))

    def wall(self, centre: Tuple[float, float], length: float, height: float, yaw: float, color: Rgba, *,
             thickness: float = 0.1) -> None:
        """A wall segment whose long side runs along ``yaw`` [rad]."""
        self.box((centre[0], centre[1], height / 2.0), (length / 2.0, thickness / 2.0, height / 2.0), color, yaw)


def local(x: float, y: float, yaw: float, fx: float, fy: float) -> Tuple[float, float]:
    """A point (fx forward, fy left) [m] in the frame of an object at (x, y, yaw), in world coordinates."""
    c, s = math.cos(yaw), math.sin(yaw)
    return x + c * fx - s * fy, y + s * fx + c * fy


# -- people ---------------------------------------------------------------------------------------------
def person_capsule(sc: Scene, x: float, y: float, yaw: float) -> None:
    """The simulator's person: a kinematic capsule (flex_nav_sim.bodies.create_person), clothing colour."""
    rng = sc.rng
    radius = rng.uniform(0.17, 0.28)
    height = rng.uniform(1.5, 1.9)
    color = DEFAULT_COLORS["person"] if rng.random() < 0.3 else jitter(rng, pick(rng, CLOTHES))
    sc.capsule((x, y, height / 2.0), radius, height - 2.0 * radius, color, yaw=yaw)


def person_walker(sc: Scene, x: float, y: float, yaw: float, *, dress: bool = False,
                  size: Tuple[float, float] = (0.9, 1.1)) -> float:
    """A figure of primitives: legs in a walking pose, shoes, torso, arms, head (``dress``: a skirt), scaled
    by a factor drawn from ``size``; returns that factor."""
    rng = sc.rng
    s = rng.uniform(*size)
    hip_h, hip_w = 0.9 * s, rng.uniform(0.08, 0.12) * s
    leg_r = rng.uniform(0.05, 0.08) * s
    stride = rng.uniform(-0.45, 0.45)  # [rad] leg swing
    trousers = jitter(rng, pick(rng, CLOTHES))
    shirt = jitter(rng, pick(rng, CLOTHES))
    skin = jitter(rng, pick(rng, SKIN), 0.03)
    shoes = jitter(rng, pick(rng, SHOES), 0.03)
    legs = skin if dress and rng.random() < 0.6 else trousers
    lower = rng.random()  # trousers, shorts (bare lower legs) or a long coat over the thighs
    for side, swing in ((1.0, stride), (-1.0, -stride)):
        hx, hy = local(x, y, yaw, 0.0, side * hip_w)
        length = hip_h / max(math.cos(swing), 0.5)
        fwd = 0.5 * length * math.sin(swing)
        cx, cy = local(hx, hy, yaw, fwd, 0.0)
        sc.capsule((cx, cy, hip_h - 0.5 * length * math.cos(swing) + 0.02), leg_r, length - 2 * leg_r, legs,
                   yaw=yaw, pitch=-swing)
        if not dress and 0.6 <= lower < 0.8:  # shorts: bare lower legs
            kx, ky = local(hx, hy, yaw, 0.75 * length * math.sin(swing), 0.0)
            sc.capsule((kx, ky, hip_h - 0.75 * length * math.cos(swing) + 0.02), leg_r * 1.02, 0.5 * length - 2 * leg_r,
                       skin, yaw=yaw, pitch=-swing)
        foot_fwd = length * math.sin(swing) + 0.06
        fx, fy = local(hx, hy, yaw, foot_fwd, 0.0)
        sc.box((fx, fy, 0.04), (0.13 * s, 0.05 * s, 0.04), shoes, yaw)
    torso_h = rng.uniform(0.5, 0.62) * s
    width, depth = rng.uniform(0.34, 0.44) * s, rng.uniform(0.2, 0.28) * s
    sc.box((x, y, hip_h + torso_h / 2.0), (depth / 2.0, width / 2.0, torso_h / 2.0), shirt, yaw)
    if not dress and lower >= 0.8:  # long coat (lab coat, scrubs gown) down to the knees
        coat = jitter(rng, (0.93, 0.93, 0.93)) if rng.random() < 0.5 else shirt
        half_h = (hip_h - 0.45 * s) / 2.0
        sc.box((x, y, 0.45 * s + half_h + 0.05), (depth / 2.0 + 0.03, width / 2.0 + 0.02, half_h), coat, yaw)
    if dress:
        skirt_bottom = rng.uniform(0.35, 0.6) * s
        sc.cylinder((x, y, (hip_h + 0.05 + skirt_bottom) / 2.0), rng.uniform(0.2, 0.3) * s,
                    hip_h + 0.05 - skirt_bottom, shirt if rng.random() < 0.5 else jitter(rng, pick(rng, CLOTHES)))
    else:
        sc.box((x, y, hip_h), (depth / 2.0 + 0.01, width / 2.0 - 0.02, 0.06), trousers, yaw)  # hips
    shoulder = hip_h + torso_h
    for side in (1.0, -1.0):
        swing = -side * stride * 0.8
        ax, ay = local(x, y, yaw, 0.5 * 0.6 * math.sin(swing), side * (width / 2.0 + 0.05))
        sc.capsule((ax, ay, shoulder - 0.3 * s), 0.045 * s, 0.5 * s, shirt, yaw=yaw, pitch=-swing)
    sc.sphere((x, y, shoulder + 0.15 * s), 0.1 * s, skin)
    return s


@contextlib.contextmanager
def quiet_output() -> Iterator[None]:
    """Silence file descriptors 1 and 2 (pybullet's C code prints its warnings there, around sys.stdout)."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(1), os.dup(2)]
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 1)
        os.dup2(devnull, 2)
        yield
    finally:
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        for fd in (*saved, devnull):
            os.close(fd)


def _color_links(sc: Scene, body: int, colors: Callable[[str], Rgba]) -> None:
    sc.c.changeVisualShape(body, -1, rgbaColor=list(colors("base")))
    for j in range(sc.c.getNumJoints(body)):
        name = sc.c.getJointInfo(body, j)[12].decode()
        sc.c.changeVisualShape(body, j, rgbaColor=list(colors(name)))


def _stand_on_floor(sc: Scene, body: int, x: float, y: float, orn: Sequence[float]) -> None:
    """Move ``body`` so its lowest point touches the floor at (x, y)."""
    pos, _ = sc.c.getBasePositionAndOrientation(body)
    lo_z, lo_xy = math.inf, None
    ranges = [sc.c.getAABB(body, j) for j in range(-1, sc.c.getNumJoints(body))]
    lo = np.min([r[0] for r in ranges], axis=0)
    hi = np.max([r[1] for r in ranges], axis=0)
    lo_z = float(lo[2])
    lo_xy = (float(lo[0] + hi[0]) / 2.0, float(lo[1] + hi[1]) / 2.0)
    sc.c.resetBasePositionAndOrientation(
        body, [pos[0] + x - lo_xy[0], pos[1] + y - lo_xy[1], pos[2] - lo_z], list(orn)
    )


def _clothing(sc: Scene) -> Dict[str, Rgba]:
    rng = sc.rng
    return {
        "trousers": jitter(rng, pick(rng, CLOTHES)),
        "shirt": jitter(rng, pick(rng, CLOTHES)),
        "skin": jitter(rng, pick(rng, SKIN), 0.03),
        "shoes": jitter(rng, pick(rng, SHOES), 0.03),
    }


def person_mjcf(sc: Scene, x: float, y: float, yaw: float) -> None:
    """The MuJoCo humanoid (pybullet_data mjcf/humanoid_symmetric_no_ground.xml) in a random walking pose."""
    rng, c = sc.rng, sc.c
    body = c.loadMJCF(os.path.join(DATA, "mjcf", "humanoid_symmetric_no_ground.xml"))[0]
    stride = rng.uniform(-0.6, 0.6)
    angles = {
        "right_hip_y": -stride, "left_hip_y": stride,
        "right_knee": -rng.uniform(0.0, 0.8), "left_knee": -rng.uniform(0.0, 0.8),
        "right_shoulder1": rng.uniform(-0.5, 0.5), "left_shoulder1": rng.uniform(-0.5, 0.5),
        "right_elbow": -rng.uniform(0.2, 1.2), "left_elbow": -rng.uniform(0.2, 1.2),
    }
    for j in range(c.getNumJoints(body)):
        name = c.getJointInfo(body, j)[1].decode()
        if name in angles:
            c.resetJointState(body, j, angles[name])
    wear = _clothing(sc)

    def colour(link: str) -> Rgba:
        if "foot" in link:
            return wear["shoes"]
        if any(k in link for k in ("thigh", "shin", "pelvis")):
            return wear["trousers"]
        if "lower_arm" in link or link in ("head", "base"):
            return wear["skin"] if link != "base" else wear["shirt"]
        return wear["shirt"]

    _color_links(sc, body, colour)
    _stand_on_floor(sc, body, x, y, c.getQuaternionFromEuler([0.0, 0.0, yaw]))


def person_deepmimic(sc: Scene, x: float, y: float, yaw: float) -> None:
    """The DeepMimic humanoid (pybullet_data humanoid/humanoid.urdf, y-up, rotated upright), random pose."""
    rng, c = sc.rng, sc.c
    scale = rng.uniform(0.22, 0.27)
    orn = c.getQuaternionFromEuler([math.pi / 2.0, 0.0, yaw])
    with quiet_output():  # the URDF parser warns about every joint without an axis
        body = c.loadURDF(os.path.join(DATA, "humanoid", "humanoid.urdf"), [x, y, 1.0], orn, globalScaling=scale,
                          useFixedBase=True)
    stride = rng.uniform(-0.6, 0.6)
    for j in range(c.getNumJoints(body)):
        name = c.getJointInfo(body, j)[1].decode()
        if name in ("right_hip", "left_hip"):
            sign = 1.0 if name == "right_hip" else -1.0
            c.resetJointStateMultiDof(body, j, list(c.getQuaternionFromEuler([0.0, 0.0, sign * stride])))
        elif name in ("right_knee", "left_knee"):
            c.resetJointState(body, j, -rng.uniform(0.0, 0.9))
        elif name in ("right_shoulder", "left_shoulder"):
            c.resetJointStateMultiDof(body, j, list(c.getQuaternionFromEuler([rng.uniform(-0.3, 0.3), 0.0,
                                                                               rng.uniform(-0.5, 0.5)])))
        elif name in ("right_elbow", "left_elbow"):
            c.resetJointState(body, j, rng.uniform(0.0, 1.2))
    wear = _clothing(sc)

    def colour(link: str) -> Rgba:
        if "ankle" in link:
            return wear["shoes"]
        if "hip" in link or "knee" in link or link == "base":
            return wear["trousers"]
        if "wrist" in link or "neck" in link:
            return wear["skin"]
        return wear["shirt"]

    _color_links(sc, body, colour)
    _stand_on_floor(sc, body, x, y, orn)


# -- movable objects ------------------------------------------------------------------------------------
def box_color(rng: np.random.Generator) -> Rgba:
    return jitter(rng, BOXES[0] if rng.random() < 0.35 else pick(rng, BOXES))


def movable_box(sc: Scene, x: float, y: float, yaw: float) -> None:
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.2, 0.7), rng.uniform(0.2, 0.7), rng.uniform(0.15, 0.65)
    sc.box((x, y, sz / 2.0), (sx / 2.0, sy / 2.0, sz / 2.0), box_color(rng), yaw)


def movable_box_pair(sc: Scene, x: float, y: float, yaw: float) -> None:
    """Two boxes: stacked, or side by side."""
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.25, 0.6), rng.uniform(0.25, 0.6), rng.uniform(0.15, 0.32)
    sc.box((x, y, sz / 2.0), (sx / 2.0, sy / 2.0, sz / 2.0), box_color(rng), yaw)
    tx, ty, tz = sx * rng.uniform(0.5, 0.9), sy * rng.uniform(0.5, 0.9), rng.uniform(0.12, 0.3)
    if rng.random() < 0.6:
        sc.box((x, y, sz + tz / 2.0), (tx / 2.0, ty / 2.0, tz / 2.0), box_color(rng), yaw + rng.uniform(-0.4, 0.4))
    else:
        px, py = local(x, y, yaw, 0.0, (sy + ty) / 2.0 + 0.02)
        sc.box((px, py, tz / 2.0), (tx / 2.0, ty / 2.0, tz / 2.0), box_color(rng), yaw + rng.uniform(-0.3, 0.3))


def movable_crate(sc: Scene, x: float, y: float, yaw: float) -> None:
    """An open-top plastic crate: a floor panel and four thin walls."""
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.3, 0.6), rng.uniform(0.25, 0.45), rng.uniform(0.2, 0.4)
    t = 0.015
    color = jitter(rng, pick(rng, ((0.2, 0.3, 0.7), (0.8, 0.2, 0.15), (0.15, 0.15, 0.15), (0.9, 0.6, 0.1),
                                   (0.2, 0.55, 0.3))))
    sc.box((x, y, t), (sx / 2.0, sy / 2.0, t), color, yaw)
    for fx, fy, hx, hy in ((sx / 2.0, 0.0, t, sy / 2.0), (-sx / 2.0, 0.0, t, sy / 2.0),
                           (0.0, sy / 2.0, sx / 2.0, t), (0.0, -sy / 2.0, sx / 2.0, t)):
        px, py = local(x, y, yaw, fx, fy)
        sc.box((px, py, sz / 2.0), (hx, hy, sz / 2.0), color, yaw)


def movable_textured_cube(sc: Scene, x: float, y: float, yaw: float) -> None:
    """pybullet_data's textured cube.urdf, scaled to 0.25-0.55 m."""
    rng, c = sc.rng, sc.c
    size = rng.uniform(0.25, 0.55)
    c.loadURDF(os.path.join(DATA, "cube.urdf"), [x, y, size / 2.0], c.getQuaternionFromEuler([0.0, 0.0, yaw]),
               globalScaling=size, useFixedBase=True)


def movable_taped_parcel(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A cardboard box with a tape band around it and a white label."""
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.25, 0.6), rng.uniform(0.25, 0.6), rng.uniform(0.2, 0.55)
    sc.box((x, y, sz / 2.0), (sx / 2.0, sy / 2.0, sz / 2.0), jitter(rng, BOXES[int(rng.integers(4))]), yaw)
    tape = jitter(rng, pick(rng, ((0.6, 0.45, 0.25), (0.2, 0.2, 0.2), (0.85, 0.85, 0.8), (0.8, 0.2, 0.1))), 0.03)
    sc.box((x, y, sz / 2.0), (0.03, sy / 2.0 + 0.003, sz / 2.0 + 0.003), tape, yaw)
    lx, ly = local(x, y, yaw, -sx / 2.0 - 0.002, sy * 0.2)
    sc.box((lx, ly, sz * 0.55), (0.002, sy * 0.12, sz * 0.12), (0.95, 0.95, 0.95, 1.0), yaw)


# -- clear: nothing, walls and furniture -------------------------------------------------------------------
def furniture_color(rng: np.random.Generator) -> Rgba:
    return jitter(rng, pick(rng, FURNITURE))


def clear_wall(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A wall across the view (x, y = its point straight ahead): long, ending in view, or a corner."""
    rng = sc.rng
    height = rng.uniform(0.5, 2.5)
    color = jitter(rng, pick(rng, WALLS))
    along = math.atan2(y, x) + math.pi / 2.0 + rng.uniform(-0.6, 0.6)  # wall direction
    kind = rng.random()
    if kind < 0.5:
        sc.wall((x, y), rng.uniform(8.0, 16.0), height, along, color)
    else:
        end = rng.uniform(-1.0, 1.0)  # [m] where the wall ends, along it from the point ahead
        side = 1.0 if rng.random() < 0.5 else -1.0
        length = 8.0
        cx, cy = x + math.cos(along) * (end + side * length / 2.0), y + math.sin(along) * (end + side * length / 2.0)
        sc.wall((cx, cy), length, height, along, color)
        if kind < 0.8:  # a corner: a second wall going away from the robot at the end
            ex, ey = x + math.cos(along) * end, y + math.sin(along) * end
            away = along + side * math.pi / 2.0
            if math.cos(away - math.atan2(ey, ex)) < 0.0:
                away += math.pi
            sc.wall((ex + math.cos(away) * 4.0, ey + math.sin(away) * 4.0), 8.0, height, away,
                    jitter(rng, pick(rng, WALLS)))
    if height >= 1.9 and rng.random() < 0.3:  # a closed door in a full-height wall
        sc.box((x - 0.06 * math.cos(along - math.pi / 2.0), y - 0.06 * math.sin(along - math.pi / 2.0), 1.0),
               (0.45, 0.02, 1.0), jitter(rng, DEFAULT_COLORS["door"][:3]), along)


def clear_table(sc: Scene, x: float, y: float, yaw: float) -> None:
    rng = sc.rng
    w, d, h = rng.uniform(0.8, 1.6), rng.uniform(0.6, 0.9), rng.uniform(0.7, 0.78)
    top, legs = furniture_color(rng), furniture_color(rng)
    sc.box((x, y, h - 0.02), (d / 2.0, w / 2.0, 0.02), top, yaw)
    leg = rng.uniform(0.02, 0.04)
    for fx in (d / 2.0 - 0.05, -d / 2.0 + 0.05):
        for fy in (w / 2.0 - 0.05, -w / 2.0 + 0.05):
            px, py = local(x, y, yaw, fx, fy)
            sc.box((px, py, (h - 0.04) / 2.0), (leg, leg, (h - 0.04) / 2.0), legs, yaw)


def clear_chair(sc: Scene, x: float, y: float, yaw: float) -> None:
    rng = sc.rng
    s, h = rng.uniform(0.4, 0.5), rng.uniform(0.42, 0.48)
    seat, legs = furniture_color(rng), furniture_color(rng)
    sc.box((x, y, h), (s / 2.0, s / 2.0, 0.025), seat, yaw)
    for fx in (s / 2.0 - 0.03, -s / 2.0 + 0.03):
        for fy in (s / 2.0 - 0.03, -s / 2.0 + 0.03):
            px, py = local(x, y, yaw, fx, fy)
            sc.box((px, py, h / 2.0), (0.02, 0.02, h / 2.0), legs, yaw)
    bx, by = local(x, y, yaw, -s / 2.0, 0.0)
    sc.box((bx, by, h + 0.25), (0.02, s / 2.0, 0.25), seat, yaw)


def clear_coffee_table(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A low table (0.35-0.5 m) on four legs."""
    rng = sc.rng
    w, d, h = rng.uniform(0.8, 1.4), rng.uniform(0.5, 0.8), rng.uniform(0.35, 0.5)
    top, legs = furniture_color(rng), furniture_color(rng)
    sc.box((x, y, h - 0.025), (d / 2.0, w / 2.0, 0.025), top, yaw)
    for fx in (d / 2.0 - 0.05, -d / 2.0 + 0.05):
        for fy in (w / 2.0 - 0.05, -w / 2.0 + 0.05):
            px, py = local(x, y, yaw, fx, fy)
            sc.box((px, py, (h - 0.05) / 2.0), (0.025, 0.025, (h - 0.05) / 2.0), legs, yaw)


def clear_sofa(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A sofa or waiting-room seat row: a wide seat block, a back and arms."""
    rng = sc.rng
    w, d, seat = rng.uniform(1.4, 2.2), rng.uniform(0.7, 0.9), rng.uniform(0.38, 0.45)
    color = jitter(rng, pick(rng, (*FURNITURE, (0.3, 0.35, 0.5), (0.45, 0.3, 0.25))))
    sc.box((x, y, seat / 2.0), (d / 2.0, w / 2.0, seat / 2.0), color, yaw)
    bx, by = local(x, y, yaw, -d / 2.0 + 0.1, 0.0)
    sc.box((bx, by, 0.42), (0.1, w / 2.0, 0.42), color, yaw)
    for side in (1.0, -1.0):
        ax, ay = local(x, y, yaw, 0.0, side * (w / 2.0 - 0.08))
        sc.box((ax, ay, 0.3), (d / 2.0, 0.08, 0.3), color, yaw)


def clear_pillar(sc: Scene, x: float, y: float, yaw: float) -> None:
    rng = sc.rng
    h = rng.uniform(2.0, 3.0)
    if rng.random() < 0.6:
        sc.cylinder((x, y, h / 2.0), rng.uniform(0.15, 0.4), h, furniture_color(rng))
    else:
        half = rng.uniform(0.15, 0.35)
        sc.box((x, y, h / 2.0), (half, half, h / 2.0), furniture_color(rng), yaw)


def movable_bin(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A low cylinder: waste bin, bucket (the simulator's lab has bins and cones as low cylinders)."""
    rng = sc.rng
    h = rng.uniform(0.3, 0.6)
    color = box_color(rng) if rng.random() < 0.5 else furniture_color(rng)
    sc.cylinder((x, y, h / 2.0), rng.uniform(0.12, 0.25), h, color)


def clear_cabinet(sc: Scene, x: float, y: float, yaw: float) -> None:
    rng = sc.rng
    w, d, h = rng.uniform(0.5, 1.2), rng.uniform(0.4, 0.6), rng.uniform(0.9, 2.0)
    sc.box((x, y, h / 2.0), (d / 2.0, w / 2.0, h / 2.0), furniture_color(rng), yaw)
    if rng.random() < 0.5:  # door gap line
        fx, fy = local(x, y, yaw, -d / 2.0 - 0.002, 0.0)
        sc.box((fx, fy, h / 2.0), (0.002, 0.005, h / 2.0 - 0.05), (0.2, 0.2, 0.2, 1.0), yaw)


def clear_shelf(sc: Scene, x: float, y: float, yaw: float) -> None:
    rng = sc.rng
    w, d, h = rng.uniform(0.6, 1.2), rng.uniform(0.3, 0.45), rng.uniform(1.2, 2.0)
    color = furniture_color(rng)
    for fy in (w / 2.0, -w / 2.0):
        px, py = local(x, y, yaw, 0.0, fy)
        sc.box((px, py, h / 2.0), (d / 2.0, 0.015, h / 2.0), color, yaw)
    levels = int(rng.integers(3, 6))
    for k in range(levels):
        z = 0.08 + k * (h - 0.1) / (levels - 1)
        sc.box((x, y, z), (d / 2.0, w / 2.0, 0.012), color, yaw)


def clear_urdf_table(sc: Scene, x: float, y: float, yaw: float) -> None:
    """pybullet_data's textured table.urdf (0.6 m high), scaled 0.9-1.3."""
    c = sc.c
    c.loadURDF(os.path.join(DATA, "table", "table.urdf"), [x, y, 0.0], c.getQuaternionFromEuler([0.0, 0.0, yaw]),
               globalScaling=float(sc.rng.uniform(0.9, 1.3)), useFixedBase=True)


def clear_bench(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A long bench on two slab legs."""
    rng = sc.rng
    length, depth, h = rng.uniform(1.2, 1.8), rng.uniform(0.35, 0.45), rng.uniform(0.42, 0.48)
    color = furniture_color(rng)
    sc.box((x, y, h), (depth / 2.0, length / 2.0, 0.03), color, yaw)
    for fy in (length / 2.0 - 0.1, -length / 2.0 + 0.1):
        px, py = local(x, y, yaw, 0.0, fy)
        sc.box((px, py, h / 2.0), (depth / 2.0 - 0.02, 0.03, h / 2.0), color, yaw)


def clear_bed(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A hospital bed: a mattress on a frame with four legs and a headboard."""
    rng = sc.rng
    length, width = rng.uniform(1.9, 2.1), rng.uniform(0.85, 1.0)
    frame_z, top_z = rng.uniform(0.25, 0.35), rng.uniform(0.5, 0.65)
    frame = furniture_color(rng)
    mattress = jitter(rng, pick(rng, ((0.9, 0.9, 0.9), (0.6, 0.75, 0.85), (0.6, 0.8, 0.7))))
    sc.box((x, y, (frame_z + top_z) / 2.0), (width / 2.0, length / 2.0, (top_z - frame_z) / 2.0), mattress, yaw)
    sc.box((x, y, frame_z - 0.03), (width / 2.0 + 0.02, length / 2.0 + 0.02, 0.03), frame, yaw)
    for fx in (width / 2.0 - 0.04, -width / 2.0 + 0.04):
        for fy in (length / 2.0 - 0.04, -length / 2.0 + 0.04):
            px, py = local(x, y, yaw, fx, fy)
            sc.box((px, py, (frame_z - 0.06) / 2.0), (0.025, 0.025, (frame_z - 0.06) / 2.0), frame, yaw)
    hx, hy = local(x, y, yaw, 0.0, length / 2.0)
    sc.box((hx, hy, 0.5), (width / 2.0, 0.02, 0.5), frame, yaw)


def clear_door_frame(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A wall with an open door straight ahead: the way is clear."""
    rng = sc.rng
    height, gap = rng.uniform(0.6, 2.2), rng.uniform(0.8, 1.2)
    color = jitter(rng, pick(rng, WALLS))
    for side in (1.0, -1.0):
        px, py = local(x, y, yaw, 0.0, side * (gap / 2.0 + 1.5))
        sc.wall((px, py), 3.0, height, yaw + math.pi / 2.0, color)
    if rng.random() < 0.5:  # door panel swung open against the wall
        px, py = local(x, y, yaw, -0.45, gap / 2.0)
        sc.box((px, py, min(height, 2.0) / 2.0), (0.42, 0.02, min(height, 2.0) / 2.0),
               jitter(rng, DEFAULT_COLORS["door"][:3]), yaw)


# -- training-only models (``TRAIN_ONLY``: the ``extra`` and ``val_extra`` splits) ----------------------------
# More hard negatives of the shapes the model confused with boxes (low, long or raised furniture; walls
# alongside the way) and more kinds of pushable objects. None of them is a held-out model (``HELD_OUT``).
METAL: Tuple[Vec3, ...] = ((0.75, 0.75, 0.78), (0.55, 0.56, 0.6), (0.35, 0.36, 0.4), (0.92, 0.92, 0.92),
                           (0.3, 0.45, 0.7))
LIGHT_BOXES: Tuple[Vec3, ...] = (
    (0.97, 0.97, 0.97), (0.9, 0.9, 0.88), (0.8, 0.8, 0.8), (0.68, 0.68, 0.7), (0.55, 0.55, 0.57),
    (0.85, 0.9, 0.95), (0.95, 0.9, 0.8), (0.8, 0.85, 0.8), (0.78, 0.72, 0.65),
)


def legs4(sc: Scene, x: float, y: float, yaw: float, *, dx: float, dy: float, height: float, half: float,
          color: Rgba) -> None:
    """Four square legs of ``height`` [m] at (+-dx, +-dy) in the object's frame."""
    for fx in (dx, -dx):
        for fy in (dy, -dy):
            px, py = local(x, y, yaw, fx, fy)
            sc.box((px, py, height / 2.0), (half, half, height / 2.0), color, yaw)


def round_or_square_top(sc: Scene, x: float, y: float, yaw: float, *, z: float, radius: float, thickness: float,
                        color: Rgba, round_chance: float) -> None:
    """A seat or table top centred at height ``z`` [m]: a disc of ``radius`` [m] (with ``round_chance``) or a
    square of the same half-width."""
    if sc.rng.random() < round_chance:
        sc.cylinder((x, y, z), radius, thickness, color)
    else:
        sc.box((x, y, z), (radius, radius, thickness / 2.0), color, yaw)


def clear_stool(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A stool: a round or square seat on three or four thin legs, sometimes a foot rest."""
    rng = sc.rng
    h, r = rng.uniform(0.4, 0.78), rng.uniform(0.15, 0.22)
    seat, legs = furniture_color(rng), jitter(rng, pick(rng, (*METAL, *FURNITURE)))
    round_or_square_top(sc, x, y, yaw, z=h - 0.03, radius=r, thickness=0.06, color=seat, round_chance=0.5)
    n = 3 if rng.random() < 0.4 else 4
    for k in range(n):
        a = yaw + 2.0 * math.pi * k / n
        sc.cylinder((x + 0.8 * r * math.cos(a), y + 0.8 * r * math.sin(a), (h - 0.06) / 2.0), 0.015, h - 0.06, legs)
    if rng.random() < 0.5:
        sc.box((x, y, h * 0.35), (0.8 * r, 0.8 * r, 0.01), legs, yaw)


def clear_ottoman(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A padded footstool: a low block raised on short legs (the gap under it shows)."""
    rng = sc.rng
    sx, sy, body, leg = rng.uniform(0.4, 0.9), rng.uniform(0.4, 1.2), rng.uniform(0.2, 0.35), rng.uniform(0.12, 0.22)
    color = jitter(rng, pick(rng, (*FURNITURE, (0.3, 0.35, 0.5), (0.45, 0.3, 0.25), (0.6, 0.2, 0.2))))
    sc.box((x, y, leg + body / 2.0), (sx / 2.0, sy / 2.0, body / 2.0), color, yaw)
    legs4(sc, x, y, yaw, dx=sx / 2.0 - 0.05, dy=sy / 2.0 - 0.05, height=leg, half=0.02,
          color=jitter(rng, pick(rng, FURNITURE)))


def clear_sideboard(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A long low cabinet (sideboard, bedside row, lab bench base) on legs, with door lines and handles."""
    rng = sc.rng
    length, depth = rng.uniform(1.0, 2.2), rng.uniform(0.4, 0.55)
    leg, body = rng.uniform(0.08, 0.25), rng.uniform(0.4, 0.75)
    color = furniture_color(rng)
    sc.box((x, y, leg + body / 2.0), (depth / 2.0, length / 2.0, body / 2.0), color, yaw)
    legs4(sc, x, y, yaw, dx=depth / 2.0 - 0.04, dy=length / 2.0 - 0.04, height=leg, half=0.025,
          color=jitter(rng, pick(rng, METAL)))
    doors = int(rng.integers(2, 5))
    dark = (0.15, 0.15, 0.15, 1.0)
    for k in range(doors):
        fy = -length / 2.0 + (k + 0.5) * length / doors
        for side in (1.0, -1.0):  # handles on both faces (the robot sees either)
            hx, hy = local(x, y, yaw, side * (depth / 2.0 + 0.01), fy + 0.06)
            sc.box((hx, hy, leg + body * 0.75), (0.01, 0.01, 0.05), dark, yaw)
        if k:
            for side in (1.0, -1.0):
                gx, gy = local(x, y, yaw, side * (depth / 2.0 + 0.002), -length / 2.0 + k * length / doors)
                sc.box((gx, gy, leg + body / 2.0), (0.002, 0.004, body / 2.0 - 0.02), dark, yaw)


def clear_cart(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A service trolley: two or three shelves on four posts, castors and a push handle."""
    rng = sc.rng
    length, width, h = rng.uniform(0.6, 1.0), rng.uniform(0.4, 0.6), rng.uniform(0.8, 1.0)
    frame, shelf = jitter(rng, pick(rng, METAL)), jitter(rng, pick(rng, (*METAL, *FURNITURE)))
    wheel = 0.06
    for fx in (length / 2.0 - 0.03, -length / 2.0 + 0.03):
        for fy in (width / 2.0 - 0.03, -width / 2.0 + 0.03):
            px, py = local(x, y, yaw, fx, fy)
            sc.cylinder((px, py, wheel + (h - wheel) / 2.0), 0.015, h - wheel, frame)
            sc.sphere((px, py, wheel / 2.0), wheel / 2.0, (0.1, 0.1, 0.1, 1.0))
    levels = int(rng.integers(2, 4))
    for k in range(levels):
        z = wheel + 0.1 + k * (h - wheel - 0.12) / (levels - 1)
        sc.box((x, y, z), (length / 2.0, width / 2.0, 0.015), shelf, yaw)
    hx, hy = local(x, y, yaw, length / 2.0 + 0.05, 0.0)
    sc.box((hx, hy, h + 0.05), (0.015, width / 2.0, 0.015), frame, yaw)


def clear_radiator(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A ribbed radiator on brackets in front of a wall across the view."""
    rng = sc.rng
    along = math.atan2(y, x) + math.pi / 2.0 + rng.uniform(-0.3, 0.3)
    normal = along - math.pi / 2.0  # from the wall towards the robot
    wx, wy = x - 0.12 * math.cos(normal), y - 0.12 * math.sin(normal)
    sc.wall((wx, wy), rng.uniform(6.0, 12.0), rng.uniform(1.0, 2.5), along, jitter(rng, pick(rng, WALLS)))
    length, body, lift = rng.uniform(0.6, 1.6), rng.uniform(0.35, 0.7), rng.uniform(0.08, 0.2)
    color = jitter(rng, pick(rng, ((0.95, 0.95, 0.95), (0.85, 0.85, 0.83), (0.6, 0.6, 0.62), (0.3, 0.3, 0.32))), 0.03)
    sc.box((x, y, lift + body / 2.0), (length / 2.0, 0.03, body / 2.0), color, along)
    ribs = int(length / rng.uniform(0.05, 0.09))
    shade = (*(0.8 * v for v in color[:3]), 1.0)
    for k in range(ribs):
        t = -length / 2.0 + (k + 0.5) * length / ribs
        px, py = x + math.cos(along) * t + 0.035 * math.cos(normal), y + math.sin(along) * t + 0.035 * math.sin(normal)
        sc.box((px, py, lift + body / 2.0), (0.006, 0.008, body / 2.0 - 0.01), shade, along)  # type: ignore[arg-type]
    for t in (-length / 2.0 + 0.1, length / 2.0 - 0.1):
        px, py = x + math.cos(along) * t, y + math.sin(along) * t
        sc.box((px, py, lift / 2.0), (0.015, 0.015, lift / 2.0), color, along)


def clear_seat_row(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A waiting-room seat row: two to four seats with backs on a beam carried by two T legs."""
    rng = sc.rng
    seats, h = int(rng.integers(2, 5)), rng.uniform(0.42, 0.47)
    pitch_w = rng.uniform(0.5, 0.6)
    seat, frame = furniture_color(rng), jitter(rng, pick(rng, METAL))
    length = seats * pitch_w
    sc.box((x, y, h - 0.08), (0.03, length / 2.0, 0.03), frame, yaw)  # beam
    for fy in (length / 2.0 - 0.25, -length / 2.0 + 0.25):
        px, py = local(x, y, yaw, 0.0, fy)
        sc.box((px, py, (h - 0.1) / 2.0), (0.025, 0.025, (h - 0.1) / 2.0), frame, yaw)
        sc.box((px, py, 0.015), (0.25, 0.03, 0.015), frame, yaw)
    for k in range(seats):
        fy = -length / 2.0 + (k + 0.5) * pitch_w
        px, py = local(x, y, yaw, 0.0, fy)
        sc.box((px, py, h), (0.22, pitch_w / 2.0 - 0.03, 0.03), seat, yaw)
        bx, by = local(x, y, yaw, -0.22, fy)
        sc.box((bx, by, h + 0.25), (0.02, pitch_w / 2.0 - 0.03, 0.22), seat, yaw, pitch=-0.15)


def clear_gurney(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A stretcher trolley: a thin pad on a frame at 0.55-0.9 m, on castor legs or a central column."""
    rng = sc.rng
    length, width, h = rng.uniform(1.8, 2.1), rng.uniform(0.55, 0.75), rng.uniform(0.55, 0.9)
    frame = jitter(rng, pick(rng, METAL))
    pad = jitter(rng, pick(rng, ((0.9, 0.9, 0.9), (0.3, 0.4, 0.6), (0.2, 0.2, 0.22), (0.6, 0.75, 0.85))))
    sc.box((x, y, h - 0.04), (width / 2.0, length / 2.0, 0.04), frame, yaw)
    sc.box((x, y, h + 0.04), (width / 2.0 - 0.02, length / 2.0 - 0.02, 0.05), pad, yaw)
    if rng.random() < 0.5:
        legs4(sc, x, y, yaw, dx=width / 2.0 - 0.05, dy=length / 2.0 - 0.1, height=h - 0.08, half=0.02, color=frame)
    else:
        for fy in (length / 4.0, -length / 4.0):
            px, py = local(x, y, yaw, 0.0, fy)
            sc.box((px, py, (h - 0.08) / 2.0), (0.06, 0.08, (h - 0.08) / 2.0), frame, yaw)
        sc.box((x, y, 0.06), (width / 2.0 - 0.05, length / 2.0 - 0.1, 0.03), frame, yaw)
    if rng.random() < 0.5:  # side rails
        for side in (1.0, -1.0):
            px, py = local(x, y, yaw, side * width / 2.0, 0.0)
            sc.box((px, py, h + 0.2), (0.01, length / 3.0, 0.01), frame, yaw)


def clear_desk(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A desk whose top rests on two side panels, sometimes a back panel and a drawer pedestal."""
    rng = sc.rng
    length, depth, h = rng.uniform(1.0, 1.8), rng.uniform(0.6, 0.8), rng.uniform(0.7, 0.78)
    top, panel = furniture_color(rng), furniture_color(rng)
    sc.box((x, y, h - 0.015), (depth / 2.0, length / 2.0, 0.015), top, yaw)
    for fy in (length / 2.0 - 0.02, -length / 2.0 + 0.02):
        px, py = local(x, y, yaw, 0.0, fy)
        sc.box((px, py, (h - 0.03) / 2.0), (depth / 2.0 - 0.02, 0.02, (h - 0.03) / 2.0), panel, yaw)
    if rng.random() < 0.5:
        px, py = local(x, y, yaw, -depth / 2.0 + 0.05, 0.0)
        sc.box((px, py, h * 0.6), (0.01, length / 2.0 - 0.04, h * 0.25), panel, yaw)
    if rng.random() < 0.4:
        px, py = local(x, y, yaw, 0.0, length / 2.0 - 0.25)
        sc.box((px, py, (h - 0.03) / 2.0), (depth / 2.0 - 0.05, 0.2, (h - 0.03) / 2.0), panel, yaw)


def clear_corridor(sc: Scene, x: float, y: float, yaw: float) -> None:
    """Walls along both sides of the way ahead (a corridor), maybe an end wall far away: the way is clear."""
    rng = sc.rng
    heading = math.atan2(y, x) + rng.uniform(-0.25, 0.25)
    color = jitter(rng, pick(rng, WALLS))
    height = rng.uniform(0.8, 2.5)
    for side in (1.0, -1.0):
        offset = rng.uniform(0.7, 1.4)
        cx = math.cos(heading) * 4.5 - side * math.sin(heading) * offset
        cy = math.sin(heading) * 4.5 + side * math.cos(heading) * offset
        sc.wall((cx, cy), 7.0, height, heading, color if rng.random() < 0.7 else jitter(rng, pick(rng, WALLS)))
    if rng.random() < 0.5:
        d = rng.uniform(3.0, 7.0)
        sc.wall((d * math.cos(heading), d * math.sin(heading)), 4.0, height, heading + math.pi / 2.0,
                jitter(rng, pick(rng, WALLS)))


def movable_light_box(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A plain box in white, grey or pastel (the colours of walls), often large."""
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.3, 0.7), rng.uniform(0.3, 0.7), rng.uniform(0.2, 0.65)
    sc.box((x, y, sz / 2.0), (sx / 2.0, sy / 2.0, sz / 2.0), jitter(rng, pick(rng, LIGHT_BOXES), 0.04), yaw)


def movable_passage_box(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A box, often wide and low, in a passage: walls or tall blocks alongside the way on both sides."""
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.3, 0.7), rng.uniform(0.3, 0.8), rng.uniform(0.2, 0.5)
    box_yaw = math.atan2(y, x) + rng.uniform(-0.3, 0.3)
    sc.box((x, y, sz / 2.0), (sx / 2.0, sy / 2.0, sz / 2.0), box_color(rng), box_yaw)
    heading = math.atan2(y, x) + rng.uniform(-0.15, 0.15)
    for side in (1.0, -1.0):
        offset = max(sx, sy) / 2.0 + rng.uniform(0.1, 0.5)  # [m] from the box centre to the side's face
        color = jitter(rng, pick(rng, WALLS if rng.random() < 0.5 else FURNITURE))
        height, thickness = rng.uniform(0.5, 2.5), rng.uniform(0.1, 3.0)
        along = rng.uniform(1.0, 5.0)  # [m] how far the side runs on past the box
        centre_fwd = (along - 0.4) / 2.0  # from 0.4 m before the box centre (never around the camera)
        lateral = side * (offset + thickness / 2.0)
        cx = x + math.cos(heading) * centre_fwd - math.sin(heading) * lateral
        cy = y + math.sin(heading) * centre_fwd + math.cos(heading) * lateral
        sc.wall((cx, cy), along + 0.4, height, heading, color, thickness=thickness)


def movable_suitcase(sc: Scene, x: float, y: float, yaw: float) -> None:
    """An upright suitcase on small castors with a pulled-out handle (or a flat one)."""
    rng = sc.rng
    w, d, h = rng.uniform(0.35, 0.5), rng.uniform(0.2, 0.3), rng.uniform(0.45, 0.75)
    color = jitter(rng, pick(rng, ((0.1, 0.1, 0.12), (0.2, 0.25, 0.45), (0.6, 0.1, 0.15), (0.5, 0.5, 0.52),
                                   (0.85, 0.85, 0.85), (0.2, 0.45, 0.4), (0.8, 0.5, 0.2))))
    wheel = 0.035
    sc.box((x, y, wheel * 2 + h / 2.0), (d / 2.0, w / 2.0, h / 2.0), color, yaw)
    for fy in (w / 2.0 - 0.04, -w / 2.0 + 0.04):
        for fx in (d / 2.0 - 0.03, -d / 2.0 + 0.03):
            px, py = local(x, y, yaw, fx, fy)
            sc.sphere((px, py, wheel), wheel, (0.08, 0.08, 0.08, 1.0))
    if rng.random() < 0.6:
        top = wheel * 2 + h
        ext = rng.uniform(0.1, 0.4)
        for fy in (0.1, -0.1):
            px, py = local(x, y, yaw, -d / 2.0 + 0.02, fy)
            sc.box((px, py, top + ext / 2.0), (0.008, 0.008, ext / 2.0), (0.3, 0.3, 0.3, 1.0), yaw)
        px, py = local(x, y, yaw, -d / 2.0 + 0.02, 0.0)
        sc.box((px, py, top + ext), (0.015, 0.12, 0.015), (0.1, 0.1, 0.1, 1.0), yaw)


def movable_tote(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A lidded plastic storage tote: a body narrowing to the bottom and a wider lid."""
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.35, 0.7), rng.uniform(0.3, 0.5), rng.uniform(0.2, 0.45)
    body = jitter(rng, pick(rng, ((0.2, 0.3, 0.7), (0.15, 0.15, 0.15), (0.55, 0.55, 0.58), (0.85, 0.85, 0.85),
                                  (0.75, 0.2, 0.2), (0.2, 0.55, 0.3))))
    lid = body if rng.random() < 0.5 else jitter(rng, pick(rng, ((0.9, 0.8, 0.1), (0.2, 0.3, 0.7), (0.1, 0.1, 0.1))))
    sc.box((x, y, sz * 0.25), (sx / 2.0 - 0.02, sy / 2.0 - 0.02, sz * 0.25), body, yaw)
    sc.box((x, y, sz * 0.75), (sx / 2.0, sy / 2.0, sz * 0.25), body, yaw)
    sc.box((x, y, sz + 0.015), (sx / 2.0 + 0.015, sy / 2.0 + 0.015, 0.015), lid, yaw)


def movable_sack(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A bag lying on the floor (duffel bag, laundry or rubbish sack): a lying capsule or a squat blob."""
    rng = sc.rng
    color = jitter(rng, pick(rng, ((0.1, 0.1, 0.1), (0.2, 0.25, 0.45), (0.85, 0.85, 0.8), (0.3, 0.4, 0.25),
                                   (0.6, 0.15, 0.15), (0.55, 0.45, 0.3))))
    r = rng.uniform(0.12, 0.22)
    if rng.random() < 0.6:
        sc.capsule((x, y, r), r, rng.uniform(0.25, 0.55), color, yaw=yaw, pitch=math.pi / 2.0)
    else:
        sc.sphere((x, y, r), r * 1.3, color)
        sc.sphere((x, y, 2.2 * r), r * 0.8, color)


# -- randomised models (``PROCEDURAL``: the ``extra3`` and ``val_extra3`` splits) ---------------------------
# Domain randomisation instead of one more hand-made model: furniture as a board on a random support (legs,
# end slabs, end frames, a trestle) with random proportions and extras, and boxes with random markings.
def clear_random_furniture(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A board 0.3-1.1 m high on a random support, maybe a lower shelf, an apron or a back; random sizes."""
    rng = sc.rng
    length, depth, h = rng.uniform(0.4, 2.2), rng.uniform(0.3, 0.9), rng.uniform(0.3, 1.1)
    t = rng.uniform(0.02, 0.07)  # [m] board thickness
    top = furniture_color(rng)
    frame = top if rng.random() < 0.5 else jitter(rng, pick(rng, (*METAL, *FURNITURE)))
    inset = rng.uniform(0.0, min(0.15, depth / 4.0))  # [m] supports from the board's edges
    leg_h = h - t
    sc.box((x, y, h - t / 2.0), (depth / 2.0, length / 2.0, t / 2.0), top, yaw)
    ends = (length / 2.0 - inset - 0.03, -length / 2.0 + inset + 0.03)
    support = int(rng.integers(4))
    if support == 0:  # four legs
        half = rng.uniform(0.012, 0.04)
        legs4(sc, x, y, yaw, dx=depth / 2.0 - inset - half, dy=length / 2.0 - inset - half, height=leg_h, half=half,
              color=frame)
    elif support == 1:  # a slab at each end
        slab = rng.uniform(0.015, 0.05)
        for fy in ends:
            px, py = local(x, y, yaw, 0.0, fy)
            sc.box((px, py, leg_h / 2.0), (depth / 2.0 - inset, slab, leg_h / 2.0), frame, yaw)
    elif support == 2:  # a frame at each end: two posts on a foot bar
        for fy in ends:
            for fx in (depth / 2.0 - inset - 0.02, -depth / 2.0 + inset + 0.02):
                px, py = local(x, y, yaw, fx, fy)
                sc.box((px, py, leg_h / 2.0), (0.02, 0.02, leg_h / 2.0), frame, yaw)
            px, py = local(x, y, yaw, 0.0, fy)
            sc.box((px, py, 0.02), (depth / 2.0 - inset, 0.025, 0.02), frame, yaw)
    else:  # a trestle: a post at each end joined by a low stretcher
        for fy in ends:
            px, py = local(x, y, yaw, 0.0, fy)
            sc.box((px, py, leg_h / 2.0), (0.04, 0.04, leg_h / 2.0), frame, yaw)
            sc.box((px, py, 0.02), (depth / 2.0 - inset, 0.03, 0.02), frame, yaw)
        stretcher_z = rng.uniform(0.1, max(0.12, leg_h * 0.5))
        sc.box((x, y, stretcher_z), (0.025, length / 2.0 - inset - 0.03, 0.025), frame, yaw)
    if h > 0.45 and rng.random() < 0.35:  # a lower shelf
        sc.box((x, y, rng.uniform(0.08, h * 0.45)), (depth / 2.0 - inset, length / 2.0 - inset, 0.012), top, yaw)
    if rng.random() < 0.3:  # an apron board under the top along both long sides
        apron = rng.uniform(0.05, min(0.2, leg_h * 0.5))
        for side in (1.0, -1.0):
            px, py = local(x, y, yaw, side * (depth / 2.0 - inset), 0.0)
            sc.box((px, py, h - t - apron / 2.0), (0.01, length / 2.0 - inset, apron / 2.0), frame, yaw)
    if rng.random() < 0.3:  # a back rest
        back = rng.uniform(0.1, 0.3)
        px, py = local(x, y, yaw, -depth / 2.0 + 0.02, 0.0)
        sc.box((px, py, h + back), (0.02, length / 2.0, back), top, yaw, pitch=rng.uniform(-0.2, 0.0))


def movable_marked_box(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A box of a random colour with random markings on its sides: patches (labels, print, handle holes),
    tape bands over the top, maybe a lid rim."""
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.2, 0.7), rng.uniform(0.2, 0.7), rng.uniform(0.15, 0.6)
    base = box_color(rng) if rng.random() < 0.6 else random_color(rng, 0.05, 0.95, 0.06)
    sc.box((x, y, sz / 2.0), (sx / 2.0, sy / 2.0, sz / 2.0), base, yaw)
    for fx, fy, across in ((sx / 2.0, 0.0, sy), (-sx / 2.0, 0.0, sy), (0.0, sy / 2.0, sx), (0.0, -sy / 2.0, sx)):
        for _ in range(int(rng.integers(0, 3))):
            color = random_color(rng, 0.0, 1.0)
            w, hh = rng.uniform(0.05, 0.45) * across, rng.uniform(0.05, 0.45) * sz
            u, v = rng.uniform(-0.5, 0.5) * (across - w), rng.uniform(hh, sz - hh)
            px, py = local(x, y, yaw, fx * 1.01 + (0.0 if fx else u), fy * 1.01 + (u if fx else 0.0))
            half = (0.002, w / 2.0, hh / 2.0) if fx else (w / 2.0, 0.002, hh / 2.0)
            sc.box((px, py, v), half, color, yaw)
    for _ in range(int(rng.integers(0, 3))):  # tape bands over the top, along x or y
        tape = jitter(rng, pick(rng, ((0.6, 0.45, 0.25), (0.2, 0.2, 0.2), (0.85, 0.85, 0.8), (0.8, 0.2, 0.1),
                                      (0.2, 0.4, 0.8))), 0.03)
        w = rng.uniform(0.03, 0.07)
        if rng.random() < 0.5:
            sc.box((x, y, sz / 2.0), (sx / 2.0 + 0.003, w, sz / 2.0 + 0.003), tape, yaw)
        else:
            sc.box((x, y, sz / 2.0), (w, sy / 2.0 + 0.003, sz / 2.0 + 0.003), tape, yaw)
    if rng.random() < 0.3:  # a lid rim
        lid = base if rng.random() < 0.5 else box_color(rng)
        rim = rng.uniform(0.03, 0.08)
        sc.box((x, y, sz - rim / 2.0 + 0.005), (sx / 2.0 + 0.01, sy / 2.0 + 0.01, rim / 2.0), lid, yaw)


# -- the second held-out set (``HELD_OUT_2``: the ``unseen2`` split only) -----------------------------------
def person_child(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A child: the walker at 0.6-0.75 scale (1.0-1.3 m tall)."""
    person_walker(sc, x, y, yaw, size=(0.6, 0.75))


def person_with_bag(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker with a backpack or a shoulder bag at the hip."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw)
    color = jitter(rng, pick(rng, ((0.1, 0.1, 0.1), (0.2, 0.25, 0.45), (0.55, 0.1, 0.1), (0.45, 0.35, 0.2),
                                   (0.3, 0.45, 0.3))))
    if rng.random() < 0.5:  # backpack
        px, py = local(x, y, yaw, -0.2 * s, 0.0)
        sc.box((px, py, 1.25 * s), (0.08, 0.15 * s, 0.2 * s), color, yaw)
    else:
        side = 1.0 if rng.random() < 0.5 else -1.0
        px, py = local(x, y, yaw, 0.0, side * 0.3 * s)
        sc.box((px, py, 0.85 * s), (0.14 * s, 0.05, 0.12 * s), color, yaw)


def movable_cooler(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A cool box: a body, a wider lid of another colour, a handle block on each end."""
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.4, 0.7), rng.uniform(0.3, 0.45), rng.uniform(0.3, 0.45)
    body = jitter(rng, pick(rng, ((0.2, 0.35, 0.75), (0.8, 0.15, 0.15), (0.2, 0.55, 0.35), (0.9, 0.9, 0.9))))
    lid = jitter(rng, pick(rng, ((0.95, 0.95, 0.95), (0.3, 0.3, 0.32), (0.85, 0.75, 0.2))))
    sc.box((x, y, sz * 0.42), (sx / 2.0, sy / 2.0, sz * 0.42), body, yaw)
    sc.box((x, y, sz * 0.92), (sx / 2.0 + 0.015, sy / 2.0 + 0.015, sz * 0.08), lid, yaw)
    for side in (1.0, -1.0):
        px, py = local(x, y, yaw, side * (sx / 2.0 + 0.02), 0.0)
        sc.box((px, py, sz * 0.7), (0.02, sy * 0.25, 0.025), lid, yaw)


def movable_drum(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A fibre or plastic drum: a cylinder with two rolling rings and a lid."""
    rng = sc.rng
    r, h = rng.uniform(0.18, 0.28), rng.uniform(0.35, 0.6)
    color = jitter(rng, pick(rng, ((0.15, 0.3, 0.65), (0.1, 0.1, 0.1), (0.55, 0.42, 0.28), (0.25, 0.5, 0.3),
                                   (0.85, 0.85, 0.85))))
    ring = jitter(rng, pick(rng, METAL))
    sc.cylinder((x, y, h / 2.0), r, h, color)
    for z in (h / 3.0, 2.0 * h / 3.0):
        sc.cylinder((x, y, z), r + 0.012, 0.02, ring)
    sc.cylinder((x, y, h + 0.01), r + 0.01, 0.02, ring if rng.random() < 0.5 else color)


def movable_wrapped_parcel(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A parcel in brown or coloured paper tied with a string both ways."""
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.25, 0.55), rng.uniform(0.25, 0.55), rng.uniform(0.15, 0.4)
    paper = jitter(rng, pick(rng, ((0.62, 0.48, 0.32), (0.7, 0.58, 0.4), (0.3, 0.45, 0.7), (0.75, 0.3, 0.35))))
    string = jitter(rng, pick(rng, ((0.9, 0.88, 0.8), (0.15, 0.15, 0.15), (0.8, 0.1, 0.1))), 0.03)
    sc.box((x, y, sz / 2.0), (sx / 2.0, sy / 2.0, sz / 2.0), paper, yaw)
    sc.box((x, y, sz / 2.0), (sx / 2.0 + 0.003, 0.008, sz / 2.0 + 0.003), string, yaw)
    sc.box((x, y, sz / 2.0), (0.008, sy / 2.0 + 0.003, sz / 2.0 + 0.003), string, yaw)


def clear_bookcase(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A bookcase with a back panel, shelves and rows of books."""
    rng = sc.rng
    w, d, h = rng.uniform(0.6, 1.2), rng.uniform(0.25, 0.4), rng.uniform(1.0, 2.0)
    color = furniture_color(rng)
    for fy in (w / 2.0, -w / 2.0):
        px, py = local(x, y, yaw, 0.0, fy)
        sc.box((px, py, h / 2.0), (d / 2.0, 0.015, h / 2.0), color, yaw)
    bx, by = local(x, y, yaw, -d / 2.0 + 0.01, 0.0)
    sc.box((bx, by, h / 2.0), (0.01, w / 2.0, h / 2.0), color, yaw)
    levels = int(rng.integers(3, 6))
    gap = (h - 0.05) / levels
    for k in range(levels + 1):
        sc.box((x, y, 0.03 + k * gap), (d / 2.0, w / 2.0, 0.012), color, yaw)
    for k in range(levels):
        fy = -w / 2.0 + 0.03
        while fy < w / 2.0 - 0.05:
            bw, bh = rng.uniform(0.02, 0.05), rng.uniform(0.5, 0.85) * gap
            px, py = local(x, y, yaw, 0.0, fy + bw / 2.0)
            book = random_color(rng, 0.1, 0.9)
            sc.box((px, py, 0.045 + k * gap + bh / 2.0), (d / 2.0 - 0.03, bw / 2.0, bh / 2.0), book, yaw)
            fy += bw + rng.uniform(0.0, 0.02)


def clear_coat_rack(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A coat stand: a pole on three or four feet with hooks, sometimes a coat hanging from it."""
    rng = sc.rng
    h = rng.uniform(1.6, 1.85)
    color = jitter(rng, pick(rng, (*METAL, (0.45, 0.3, 0.18), (0.1, 0.1, 0.1))))
    sc.cylinder((x, y, h / 2.0), 0.018, h, color)
    feet = int(rng.integers(3, 5))
    for k in range(feet):
        a = yaw + 2.0 * math.pi * k / feet
        fx, fy = x + 0.16 * math.cos(a), y + 0.16 * math.sin(a)
        sc.box((fx, fy, 0.02), (0.16, 0.015, 0.015), color, a)
        hx, hy = x + 0.08 * math.cos(a), y + 0.08 * math.sin(a)
        sc.box((hx, hy, h - 0.08), (0.08, 0.01, 0.01), color, a)
    if rng.random() < 0.5:
        coat = jitter(rng, pick(rng, CLOTHES))
        cx, cy = local(x, y, yaw, 0.1, 0.0)
        sc.box((cx, cy, h - 0.5), (0.05, 0.22, 0.4), coat, yaw)


def clear_pedestal_table(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A round or square table on a single central column and a base disc or cross."""
    rng = sc.rng
    h, r = rng.uniform(0.45, 0.76), rng.uniform(0.3, 0.5)
    top, stand = furniture_color(rng), jitter(rng, pick(rng, (*METAL, *FURNITURE)))
    round_or_square_top(sc, x, y, yaw, z=h - 0.02, radius=r, thickness=0.04, color=top, round_chance=0.6)
    sc.cylinder((x, y, h / 2.0), rng.uniform(0.03, 0.06), h - 0.04, stand)
    if rng.random() < 0.5:
        sc.cylinder((x, y, 0.015), r * 0.6, 0.03, stand)
    else:
        for a in (yaw, yaw + math.pi / 2.0):
            sc.box((x, y, 0.02), (r * 0.7, 0.025, 0.02), stand, a)


def clear_partition(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A free-standing screen (room divider) raised on two feet: the floor shows under it."""
    rng = sc.rng
    w, h, lift = rng.uniform(0.8, 1.8), rng.uniform(1.2, 1.7), rng.uniform(0.05, 0.2)
    panel = jitter(rng, pick(rng, ((0.85, 0.85, 0.8), (0.6, 0.7, 0.8), (0.45, 0.55, 0.45), (0.7, 0.65, 0.55))))
    feet = jitter(rng, pick(rng, METAL))
    sc.box((x, y, lift + h / 2.0), (0.025, w / 2.0, h / 2.0), panel, yaw)
    for fy in (w / 2.0 - 0.1, -w / 2.0 + 0.1):
        px, py = local(x, y, yaw, 0.0, fy)
        sc.box((px, py, (lift + 0.1) / 2.0), (0.2, 0.02, (lift + 0.1) / 2.0), feet, yaw)


# -- the third held-out set (``HELD_OUT_3``: the ``unseen3`` split only) ------------------------------------
def person_wheelchair_user(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A person seated in a wheelchair: big rear wheels, small castors, a seat and a back; thighs level,
    shins down to the footrest, torso, arms on the armrests, head."""
    rng = sc.rng
    s = rng.uniform(0.85, 1.05)
    frame = jitter(rng, pick(rng, (*METAL, (0.1, 0.1, 0.1), (0.2, 0.25, 0.5))))
    tyre = jitter(rng, (0.08, 0.08, 0.08), 0.03)
    seat_h, half_w = 0.5, rng.uniform(0.22, 0.28)
    for side in (1.0, -1.0):  # rear wheels (0.3 m radius) beside the seat, castors in front
        wx, wy = local(x, y, yaw, -0.12, side * (half_w + 0.04))
        sc.cylinder((wx, wy, 0.3), 0.3, 0.03, tyre, yaw=yaw, roll=math.pi / 2.0)
        sc.cylinder((wx, wy, 0.3), 0.27, 0.035, frame, yaw=yaw, roll=math.pi / 2.0)
        cx, cy = local(x, y, yaw, 0.3, side * (half_w - 0.03))
        sc.cylinder((cx, cy, 0.07), 0.07, 0.03, tyre, yaw=yaw, roll=math.pi / 2.0)
        fx, fy = local(x, y, yaw, 0.3, side * (half_w - 0.03))
        sc.box((fx, fy, 0.3), (0.012, 0.012, 0.2), frame, yaw)
    sc.box((x, y, seat_h), (0.23, half_w, 0.03), frame, yaw)
    bx, by = local(x, y, yaw, -0.22, 0.0)
    sc.box((bx, by, seat_h + 0.25), (0.02, half_w, 0.25), frame, yaw)
    trousers = jitter(rng, pick(rng, CLOTHES))
    shirt = jitter(rng, pick(rng, CLOTHES))
    skin = jitter(rng, pick(rng, SKIN), 0.03)
    for side in (1.0, -1.0):
        tx, ty = local(x, y, yaw, 0.05, side * 0.1 * s)
        sc.capsule((tx, ty, seat_h + 0.09), 0.07 * s, 0.3 * s, trousers, yaw=yaw, pitch=math.pi / 2.0)
        kx, ky = local(x, y, yaw, 0.27, side * 0.1 * s)
        sc.capsule((kx, ky, seat_h - 0.17), 0.055 * s, 0.3 * s, trousers, yaw=yaw)
        sx_, sy_ = local(x, y, yaw, 0.33, side * 0.1 * s)
        sc.box((sx_, sy_, 0.12), (0.12 * s, 0.05 * s, 0.04), jitter(rng, pick(rng, SHOES), 0.03), yaw)
        ax, ay = local(x, y, yaw, -0.02, side * (half_w + 0.02))
        sc.capsule((ax, ay, seat_h + 0.35), 0.045 * s, 0.3 * s, shirt, yaw=yaw, pitch=0.3)
    torso_h = rng.uniform(0.5, 0.6) * s
    px, py = local(x, y, yaw, -0.1, 0.0)
    sc.box((px, py, seat_h + 0.05 + torso_h / 2.0), (0.11 * s, 0.19 * s, torso_h / 2.0), shirt, yaw)
    sc.sphere((px, py, seat_h + 0.05 + torso_h + 0.15 * s), 0.1 * s, skin)


def person_crutch_walker(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker on two forearm crutches planted ahead of the feet."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw)
    metal = jitter(rng, pick(rng, METAL))
    lean = rng.uniform(0.15, 0.35)  # [rad] crutch tips ahead of the hands
    for side in (1.0, -1.0):
        cx, cy = local(x, y, yaw, 0.5 * 0.95 * s * math.sin(lean), side * 0.3 * s)
        sc.capsule((cx, cy, 0.95 * s * math.cos(lean) / 2.0), 0.014, 0.95 * s, metal, yaw=yaw, pitch=lean)


def movable_linen_bag(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A full laundry or linen bag: a soft cylinder with a rounded top and a tied neck."""
    rng = sc.rng
    r, h = rng.uniform(0.18, 0.3), rng.uniform(0.3, 0.55)
    cloth = jitter(rng, pick(rng, ((0.9, 0.9, 0.88), (0.3, 0.45, 0.7), (0.75, 0.8, 0.55), (0.85, 0.55, 0.6),
                                   (0.5, 0.5, 0.52))))
    sc.cylinder((x, y, (h - r * 0.4) / 2.0), r, h - r * 0.4, cloth)
    sc.sphere((x, y, h - r * 0.4), r * 0.98, cloth)
    sc.cylinder((x, y, h + r * 0.55), r * 0.25, r * 0.35, cloth)


def movable_trunk(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A storage trunk: a body with a curved lid (a half-buried cylinder), metal corners and two straps."""
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.5, 0.8), rng.uniform(0.35, 0.5), rng.uniform(0.25, 0.4)
    body = jitter(rng, pick(rng, ((0.45, 0.28, 0.15), (0.15, 0.25, 0.45), (0.2, 0.2, 0.2), (0.55, 0.15, 0.15),
                                  (0.3, 0.45, 0.3))))
    metal = jitter(rng, pick(rng, METAL))
    sc.box((x, y, sz / 2.0), (sy / 2.0, sx / 2.0, sz / 2.0), body, yaw)
    sc.cylinder((x, y, sz - sy * 0.25), sy * 0.5, sx, body, yaw=yaw, roll=math.pi / 2.0)
    for fy in (-sx / 3.0, sx / 3.0):
        px, py = local(x, y, yaw, 0.0, fy)
        sc.box((px, py, sz / 2.0), (sy / 2.0 + 0.004, 0.02, sz / 2.0 + 0.004), metal, yaw)
    for fx in (sy / 2.0, -sy / 2.0):
        for fy in (sx / 2.0, -sx / 2.0):
            px, py = local(x, y, yaw, fx, fy)
            sc.box((px, py, 0.04), (0.025, 0.025, 0.04), metal, yaw)


def movable_parcel_stack(sc: Scene, x: float, y: float, yaw: float) -> None:
    """Two or three parcels of different sizes and colours stacked, each turned a little."""
    rng = sc.rng
    z = 0.0
    sx, sy = rng.uniform(0.35, 0.6), rng.uniform(0.35, 0.6)
    for _ in range(int(rng.integers(2, 4))):
        sz = rng.uniform(0.1, 0.22)
        color = random_color(rng, 0.2, 0.95) if rng.random() < 0.5 else box_color(rng)
        sc.box((x, y, z + sz / 2.0), (sx / 2.0, sy / 2.0, sz / 2.0), color, yaw + rng.uniform(-0.3, 0.3))
        z += sz
        sx, sy = sx * rng.uniform(0.6, 0.95), sy * rng.uniform(0.6, 0.95)


def clear_iv_stand(sc: Scene, x: float, y: float, yaw: float) -> None:
    """An infusion stand: a pole on five castor feet, a hook bar on top, sometimes a bag and a pump."""
    rng = sc.rng
    h = rng.uniform(1.5, 2.0)
    metal = jitter(rng, pick(rng, METAL))
    sc.cylinder((x, y, h / 2.0), 0.015, h, metal)
    for k in range(5):
        a = yaw + 2.0 * math.pi * k / 5.0
        sc.box((x + 0.14 * math.cos(a), y + 0.14 * math.sin(a), 0.06), (0.14, 0.015, 0.012), metal, a)
        sc.sphere((x + 0.27 * math.cos(a), y + 0.27 * math.sin(a), 0.03), 0.03, (0.1, 0.1, 0.1, 1.0))
    sc.box((x, y, h), (0.01, 0.15, 0.01), metal, yaw)
    if rng.random() < 0.7:
        bx, by = local(x, y, yaw, 0.0, 0.12)
        sc.box((bx, by, h - 0.15), (0.02, 0.07, 0.11), (0.85, 0.9, 0.95, 1.0), yaw)
    if rng.random() < 0.5:
        px, py = local(x, y, yaw, 0.06, 0.0)
        sc.box((px, py, rng.uniform(0.9, 1.2)), (0.06, 0.08, 0.1), jitter(rng, (0.85, 0.85, 0.82)), yaw)


def clear_wardrobe(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A tall wardrobe on a plinth: two doors with a gap between them and two handles."""
    rng = sc.rng
    w, d, h = rng.uniform(0.8, 1.4), rng.uniform(0.5, 0.65), rng.uniform(1.7, 2.1)
    color = furniture_color(rng)
    plinth = jitter(rng, pick(rng, ((0.1, 0.1, 0.1), (0.4, 0.4, 0.42))))
    sc.box((x, y, 0.05), (d / 2.0 - 0.02, w / 2.0 - 0.02, 0.05), plinth, yaw)
    sc.box((x, y, 0.1 + (h - 0.1) / 2.0), (d / 2.0, w / 2.0, (h - 0.1) / 2.0), color, yaw)
    fx, fy = local(x, y, yaw, -d / 2.0 - 0.003, 0.0)
    sc.box((fx, fy, 0.1 + (h - 0.1) / 2.0), (0.003, 0.006, (h - 0.1) / 2.0 - 0.03), (0.15, 0.15, 0.15, 1.0), yaw)
    handle = jitter(rng, pick(rng, METAL))
    for side in (1.0, -1.0):
        hx, hy = local(x, y, yaw, -d / 2.0 - 0.015, side * 0.05)
        sc.box((hx, hy, h * 0.55), (0.012, 0.008, 0.1), handle, yaw)


def clear_vending_machine(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A vending machine: a tall block in a bright colour with a dark glass front, a keypad and a flap."""
    rng = sc.rng
    w, d, h = rng.uniform(0.7, 1.0), rng.uniform(0.7, 0.85), rng.uniform(1.75, 1.95)
    body = jitter(rng, pick(rng, ((0.8, 0.1, 0.1), (0.1, 0.3, 0.7), (0.95, 0.95, 0.95), (0.15, 0.15, 0.15),
                                  (0.9, 0.6, 0.1))))
    sc.box((x, y, h / 2.0), (d / 2.0, w / 2.0, h / 2.0), body, yaw)
    gx, gy = local(x, y, yaw, -d / 2.0 - 0.003, -w * 0.12)
    sc.box((gx, gy, h * 0.6), (0.003, w * 0.33, h * 0.3), jitter(rng, (0.15, 0.2, 0.25), 0.05), yaw)
    kx, ky = local(x, y, yaw, -d / 2.0 - 0.005, w * 0.36)
    sc.box((kx, ky, h * 0.6), (0.005, w * 0.08, h * 0.1), (0.7, 0.7, 0.72, 1.0), yaw)
    fx, fy = local(x, y, yaw, -d / 2.0 - 0.004, -w * 0.12)
    sc.box((fx, fy, 0.3), (0.004, w * 0.3, 0.08), (0.1, 0.1, 0.1, 1.0), yaw)


# -- seated people (the fourth held-out set and the ``extra4`` training splits share the figure) ------------
def seated_figure(sc: Scene, x: float, y: float, yaw: float, *, seat_h: float, foot_z: float = 0.0,
                  hip_fx: float = 0.0, lean: float = 0.0, armrest_h: float | None = None) -> float:
    """A person seated with the hips ``hip_fx`` [m] ahead of (x, y) on a seat ``seat_h`` [m] high: thighs
    forward, shins down to the feet at ``foot_z`` [m], the torso leaning back by ``lean`` [rad], the forearms
    on armrests ``armrest_h`` [m] high (None: on the lap). Returns the figure's scale."""
    rng = sc.rng
    s = rng.uniform(0.85, 1.1)
    trousers, shirt = jitter(rng, pick(rng, CLOTHES)), jitter(rng, pick(rng, CLOTHES))
    skin, shoes = jitter(rng, pick(rng, SKIN), 0.03), jitter(rng, pick(rng, SHOES), 0.03)
    legs = skin if rng.random() < 0.15 else trousers  # a skirt or shorts: bare shins
    thigh_r, thigh_len = rng.uniform(0.06, 0.08) * s, 0.4 * s
    hip_w = rng.uniform(0.09, 0.13) * s
    knee_fx, knee_z = hip_fx + thigh_len, seat_h + thigh_r
    ankle_z = foot_z + 0.08
    for side in (1.0, -1.0):
        tx, ty = local(x, y, yaw, hip_fx + thigh_len / 2.0, side * hip_w)
        sc.capsule((tx, ty, knee_z), thigh_r, thigh_len - thigh_r, trousers, yaw=yaw, pitch=math.pi / 2.0)
        ahead = rng.uniform(-0.08, 0.15)  # [m] feet tucked back or stretched out
        tilt = math.atan2(-ahead, knee_z - ankle_z)
        shin = math.hypot(ahead, knee_z - ankle_z)
        sx_, sy_ = local(x, y, yaw, knee_fx + ahead / 2.0, side * hip_w)
        sc.capsule((sx_, sy_, (knee_z + ankle_z) / 2.0), thigh_r * 0.8, max(shin - thigh_r, 0.05),
                   legs, yaw=yaw, pitch=tilt)
        fx, fy = local(x, y, yaw, knee_fx + ahead + 0.06 * s, side * hip_w)
        sc.box((fx, fy, foot_z + 0.04), (0.12 * s, 0.05 * s, 0.04), shoes, yaw)
    torso_h = rng.uniform(0.5, 0.6) * s
    width, depth = rng.uniform(0.34, 0.42) * s, rng.uniform(0.2, 0.26) * s
    up = (-math.sin(lean), math.cos(lean))  # (forward, up) along the spine
    base_fx, base_z = hip_fx - 0.04, seat_h + 0.04
    cx, cy = local(x, y, yaw, base_fx + up[0] * torso_h / 2.0, 0.0)
    sc.box((cx, cy, base_z + up[1] * torso_h / 2.0), (depth / 2.0, width / 2.0, torso_h / 2.0), shirt, yaw, -lean)
    hx, hy = local(x, y, yaw, base_fx + up[0] * (torso_h + 0.14 * s), 0.0)
    sc.sphere((hx, hy, base_z + up[1] * (torso_h + 0.14 * s)), 0.1 * s, skin)
    shoulder_fx, shoulder_z = base_fx + up[0] * (torso_h - 0.06), base_z + up[1] * (torso_h - 0.06)
    elbow_z = armrest_h + 0.05 if armrest_h is not None else seat_h + 0.16
    for side in (1.0, -1.0):
        arm_y = side * (width / 2.0 + 0.05 * s)
        ux, uy = local(x, y, yaw, shoulder_fx, arm_y)
        sc.capsule((ux, uy, (shoulder_z + elbow_z) / 2.0), 0.045 * s, max(shoulder_z - elbow_z - 0.05, 0.05), shirt,
                   yaw=yaw)
        fore_y = arm_y if armrest_h is not None else side * (hip_w + 0.04)
        ex, ey = local(x, y, yaw, shoulder_fx + 0.14 * s, fore_y)
        sc.capsule((ex, ey, elbow_z), 0.04 * s, 0.22 * s, skin if rng.random() < 0.3 else shirt, yaw=yaw,
                   pitch=math.pi / 2.0)
    return s


# -- the fourth held-out set (``HELD_OUT_4``: the ``unseen4`` split only) ------------------------------------
# Defined before any model was trained with seated people, castor poles or tall appliances (``ASSISTIVE``):
# new instances of those families, and new pushable objects.
UPHOLSTERY: Tuple[Vec3, ...] = ((0.1, 0.1, 0.1), (0.2, 0.25, 0.45), (0.35, 0.2, 0.15), (0.4, 0.4, 0.42),
                                (0.15, 0.35, 0.3))


def person_power_chair_user(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A person in a powered wheelchair: a long low base on six small wheels, a padded captain's seat on a
    column, a high back with a headrest, armrests, a joystick box and a footplate."""
    rng = sc.rng
    base = jitter(rng, pick(rng, ((0.1, 0.1, 0.1), (0.25, 0.25, 0.28), (0.55, 0.1, 0.1), (0.15, 0.25, 0.5))))
    pad = jitter(rng, pick(rng, UPHOLSTERY))
    length, half_w, base_h = rng.uniform(0.85, 1.0), rng.uniform(0.27, 0.32), rng.uniform(0.18, 0.26)
    sc.box((x, y, 0.1 + base_h / 2.0), (length / 2.0, half_w, base_h / 2.0), base, yaw)
    tyre = jitter(rng, (0.07, 0.07, 0.07), 0.02)
    drive_r = rng.uniform(0.15, 0.18)
    for side in (1.0, -1.0):
        wx, wy = local(x, y, yaw, 0.0, side * (half_w + 0.04))
        sc.cylinder((wx, wy, drive_r), drive_r, 0.07, tyre, yaw=yaw, roll=math.pi / 2.0)
        for fx in (length / 2.0 - 0.08, -length / 2.0 + 0.08):
            cx, cy = local(x, y, yaw, fx, side * (half_w - 0.05))
            sc.cylinder((cx, cy, 0.06), 0.06, 0.04, tyre, yaw=yaw, roll=math.pi / 2.0)
    seat_h = rng.uniform(0.55, 0.62)
    sc.cylinder((x, y, (0.1 + base_h + seat_h) / 2.0), 0.05, seat_h - 0.1 - base_h, base)
    sc.box((x, y, seat_h - 0.05), (0.24, half_w - 0.02, 0.05), pad, yaw)
    bx, by = local(x, y, yaw, -0.24, 0.0)
    back_h = rng.uniform(0.55, 0.7)
    sc.box((bx, by, seat_h + back_h / 2.0), (0.05, half_w - 0.03, back_h / 2.0), pad, yaw, 0.12)
    hx, hy = local(x, y, yaw, -0.3, 0.0)
    sc.box((hx, hy, seat_h + back_h + 0.1), (0.04, 0.13, 0.08), pad, yaw, 0.12)
    armrest_h = seat_h + rng.uniform(0.2, 0.26)
    for side in (1.0, -1.0):
        ax, ay = local(x, y, yaw, 0.0, side * (half_w - 0.01))
        sc.box((ax, ay, armrest_h), (0.2, 0.04, 0.03), pad, yaw)
    jx, jy = local(x, y, yaw, 0.22, (half_w + 0.02) * (1.0 if rng.random() < 0.5 else -1.0))
    sc.box((jx, jy, armrest_h + 0.03), (0.05, 0.035, 0.04), base, yaw)
    sc.sphere((jx, jy, armrest_h + 0.1), 0.02, (0.05, 0.05, 0.05, 1.0))
    px, py = local(x, y, yaw, length / 2.0 + 0.08, 0.0)
    sc.box((px, py, 0.14), (0.1, half_w - 0.05, 0.012), base, yaw)
    seated_figure(sc, x, y, yaw, seat_h=seat_h, foot_z=0.15, hip_fx=-0.12, lean=rng.uniform(0.0, 0.18),
                  armrest_h=armrest_h)


def person_cart_pusher(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker pushing a closed medication cart (drawers, a top and a handle), the hands on the handle."""
    rng = sc.rng
    length, width, h = rng.uniform(0.55, 0.75), rng.uniform(0.42, 0.55), rng.uniform(0.9, 1.05)
    body = jitter(rng, pick(rng, ((0.92, 0.92, 0.9), (0.7, 0.8, 0.9), (0.85, 0.88, 0.8), (0.6, 0.6, 0.62))))
    front = jitter(rng, pick(rng, ((0.3, 0.45, 0.75), (0.85, 0.3, 0.3), (0.95, 0.95, 0.95), (0.4, 0.6, 0.4))))
    gap = 0.3  # [m] between the walker's centre and the cart's back
    s = person_walker(sc, x - 0.5 * (length / 2.0 + gap) * math.cos(yaw),
                      y - 0.5 * (length / 2.0 + gap) * math.sin(yaw), yaw)
    cx, cy = local(x, y, yaw, 0.5 * (length / 2.0 + gap), 0.0)
    sc.box((cx, cy, 0.08 + (h - 0.08) / 2.0), (length / 2.0, width / 2.0, (h - 0.08) / 2.0), body, yaw)
    sc.box((cx, cy, h + 0.015), (length / 2.0 + 0.02, width / 2.0 + 0.02, 0.015), front, yaw)
    drawers = int(rng.integers(3, 6))
    for k in range(drawers):
        z = 0.12 + (k + 0.5) * (h - 0.16) / drawers
        for side in (1.0, -1.0):
            dx, dy = local(cx, cy, yaw, 0.0, side * (width / 2.0 + 0.003))
            sc.box((dx, dy, z), (length / 2.0 - 0.03, 0.003, (h - 0.16) / drawers / 2.0 - 0.012), front, yaw)
    for fx in (length / 2.0 - 0.05, -length / 2.0 + 0.05):
        for fy in (width / 2.0 - 0.05, -width / 2.0 + 0.05):
            wx, wy = local(cx, cy, yaw, fx, fy)
            sc.sphere((wx, wy, 0.04), 0.04, (0.1, 0.1, 0.1, 1.0))
    handle_fx, handle_z = -length / 2.0 - 0.05, h + 0.05
    hx, hy = local(cx, cy, yaw, handle_fx, 0.0)
    sc.box((hx, hy, handle_z), (0.015, width / 2.0 - 0.03, 0.015), jitter(rng, pick(rng, METAL)), yaw)
    reach = gap + handle_fx + length / 2.0  # [m] from the walker's centre to the handle, forward
    for side in (1.0, -1.0):
        ax, ay = local(x, y, yaw, -0.5 * (length / 2.0 + gap) + reach / 2.0, side * 0.18 * s)
        sc.capsule((ax, ay, handle_z), 0.04 * s, max(reach - 0.08, 0.05), (0.9, 0.75, 0.65, 1.0), yaw=yaw,
                   pitch=math.pi / 2.0)


def movable_lidded_tub(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A plastic storage tub: a body narrower at the bottom, a lid with a lip, a handle recess on each end."""
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.4, 0.7), rng.uniform(0.3, 0.45), rng.uniform(0.22, 0.4)
    body = jitter(rng, pick(rng, ((0.85, 0.87, 0.9), (0.6, 0.7, 0.85), (0.2, 0.2, 0.22), (0.55, 0.6, 0.5),
                                  (0.9, 0.85, 0.75))))
    lid = jitter(rng, pick(rng, ((0.2, 0.4, 0.8), (0.15, 0.15, 0.15), (0.9, 0.2, 0.2), (0.95, 0.95, 0.95),
                                 (0.3, 0.7, 0.4))))
    sc.box((x, y, sz * 0.25), (sx / 2.0 - 0.02, sy / 2.0 - 0.02, sz * 0.25), body, yaw)
    sc.box((x, y, sz * 0.7), (sx / 2.0, sy / 2.0, sz * 0.22), body, yaw)
    sc.box((x, y, sz * 0.95), (sx / 2.0 + 0.015, sy / 2.0 + 0.015, sz * 0.05), lid, yaw)
    for side in (1.0, -1.0):
        px, py = local(x, y, yaw, side * (sx / 2.0 + 0.002), 0.0)
        sc.box((px, py, sz * 0.75), (0.002, sy * 0.2, sz * 0.05), (0.1, 0.1, 0.1, 1.0), yaw)


def movable_duffel_bag(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A holdall lying on the floor: a long cylinder with darker ends, a zip along the top and two handles."""
    rng = sc.rng
    r, length = rng.uniform(0.13, 0.2), rng.uniform(0.5, 0.8)
    cloth = jitter(rng, pick(rng, ((0.1, 0.1, 0.12), (0.15, 0.25, 0.5), (0.45, 0.1, 0.1), (0.3, 0.35, 0.25),
                                   (0.6, 0.5, 0.35), (0.85, 0.5, 0.1))))
    trim = jitter(rng, pick(rng, ((0.05, 0.05, 0.05), (0.9, 0.9, 0.9), (0.5, 0.5, 0.5))))
    sc.cylinder((x, y, r), r, length, cloth, yaw=yaw, roll=math.pi / 2.0)
    for side in (1.0, -1.0):
        ex, ey = local(x, y, yaw, 0.0, side * length / 2.0)
        sc.cylinder((ex, ey, r), r * 1.01, 0.02, trim, yaw=yaw, roll=math.pi / 2.0)
    sc.box((x, y, 2.0 * r), (0.012, length / 2.0 - 0.03, 0.006), trim, yaw)
    for fy in (-length * 0.15, length * 0.15):
        hx, hy = local(x, y, yaw, 0.0, fy)
        sc.box((hx, hy, 2.0 * r + 0.05), (0.012, 0.012, 0.05), trim, yaw)
    hx, hy = local(x, y, yaw, 0.0, 0.0)
    sc.box((hx, hy, 2.0 * r + 0.1), (0.012, length * 0.15 + 0.012, 0.01), trim, yaw)


def movable_bottle_pack(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A shrink-wrapped pack of water bottles: rows of bottles with caps, a printed band round the middle."""
    rng = sc.rng
    rows, cols = int(rng.integers(2, 5)), int(rng.integers(3, 7))
    r, h = rng.uniform(0.035, 0.045), rng.uniform(0.2, 0.3)
    water = jitter(rng, pick(rng, ((0.7, 0.8, 0.9), (0.6, 0.75, 0.85), (0.85, 0.9, 0.92))), 0.04)
    cap = jitter(rng, pick(rng, ((0.1, 0.3, 0.8), (0.9, 0.9, 0.9), (0.1, 0.6, 0.3), (0.8, 0.1, 0.1))))
    band = jitter(rng, pick(rng, ((0.1, 0.35, 0.75), (0.9, 0.9, 0.9), (0.2, 0.6, 0.8), (0.85, 0.2, 0.2))))
    for i in range(rows):
        for j in range(cols):
            bx, by = local(x, y, yaw, (i - (rows - 1) / 2.0) * 2.0 * r, (j - (cols - 1) / 2.0) * 2.0 * r)
            sc.cylinder((bx, by, h * 0.4), r, h * 0.8, water)
            sc.cylinder((bx, by, h * 0.9), r * 0.45, h * 0.2, water)
            sc.cylinder((bx, by, h + 0.01), r * 0.4, 0.02, cap)
    sc.box((x, y, h * 0.45), (rows * r + 0.004, cols * r + 0.004, h * 0.15), band, yaw)


def clear_floor_lamp(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A standard lamp: a heavy round base, a thin pole and a shade at the top."""
    rng = sc.rng
    h = rng.uniform(1.4, 1.8)
    metal = jitter(rng, pick(rng, (*METAL, (0.1, 0.1, 0.1), (0.7, 0.55, 0.3))))
    shade = jitter(rng, pick(rng, ((0.95, 0.92, 0.85), (0.9, 0.9, 0.9), (0.75, 0.65, 0.5), (0.2, 0.2, 0.22))))
    r_base = rng.uniform(0.13, 0.18)
    sc.cylinder((x, y, 0.015), r_base, 0.03, metal)
    sc.cylinder((x, y, h / 2.0), rng.uniform(0.01, 0.016), h, metal)
    r_shade = rng.uniform(0.16, 0.24)
    sc.cylinder((x, y, h), r_shade, rng.uniform(0.2, 0.3), shade)


def clear_fridge(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A tall fridge-freezer: two doors one above the other, long vertical handles, a grille at the foot."""
    rng = sc.rng
    w, d, h = rng.uniform(0.55, 0.75), rng.uniform(0.6, 0.7), rng.uniform(1.6, 1.95)
    body = jitter(rng, pick(rng, ((0.95, 0.95, 0.95), (0.75, 0.76, 0.78), (0.15, 0.15, 0.16), (0.9, 0.88, 0.8))),
                  0.03)
    sc.box((x, y, h / 2.0), (d / 2.0, w / 2.0, h / 2.0), body, yaw)
    split = h * rng.uniform(0.3, 0.7)
    gx, gy = local(x, y, yaw, -d / 2.0 - 0.003, 0.0)
    sc.box((gx, gy, split), (0.003, w / 2.0, 0.006), (0.2, 0.2, 0.2, 1.0), yaw)
    sc.box((gx, gy, 0.05), (0.003, w / 2.0 - 0.02, 0.04), (0.1, 0.1, 0.1, 1.0), yaw)
    handle = jitter(rng, pick(rng, METAL))
    side = 1.0 if rng.random() < 0.5 else -1.0
    hx, hy = local(x, y, yaw, -d / 2.0 - 0.03, side * (w / 2.0 - 0.06))
    sc.box((hx, hy, split + 0.25), (0.015, 0.012, 0.2), handle, yaw)
    sc.box((hx, hy, split - 0.2), (0.015, 0.012, 0.15), handle, yaw)


def clear_photocopier(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A floor-standing copier: paper drawers in a base cabinet, the scanner unit with a sloped panel on top,
    an output tray on one side."""
    rng = sc.rng
    w, d = rng.uniform(0.55, 0.7), rng.uniform(0.55, 0.7)
    base_h, top_h = rng.uniform(0.55, 0.7), rng.uniform(0.3, 0.4)
    light = jitter(rng, pick(rng, ((0.92, 0.92, 0.9), (0.85, 0.85, 0.85), (0.75, 0.76, 0.78))), 0.03)
    dark = jitter(rng, pick(rng, ((0.25, 0.25, 0.27), (0.4, 0.4, 0.42))), 0.03)
    sc.box((x, y, base_h / 2.0 + 0.03), (d / 2.0, w / 2.0, base_h / 2.0), light, yaw)
    for k in range(int(rng.integers(2, 5))):
        fx, fy = local(x, y, yaw, -d / 2.0 - 0.003, 0.0)
        z = 0.03 + base_h - (k + 0.5) * 0.14
        if z > 0.08:
            sc.box((fx, fy, z), (0.003, w / 2.0 - 0.03, 0.004), dark, yaw)
    sc.box((x, y, 0.03 + base_h + top_h / 2.0), (d / 2.0 - 0.02, w / 2.0, top_h / 2.0), light, yaw)
    px, py = local(x, y, yaw, -d / 2.0 + 0.05, w * 0.15)
    sc.box((px, py, 0.03 + base_h + top_h), (0.08, w * 0.3, 0.015), dark, yaw, 0.3)
    tx, ty = local(x, y, yaw, 0.0, (w / 2.0 + 0.12) * (1.0 if rng.random() < 0.5 else -1.0))
    sc.box((tx, ty, 0.03 + base_h + 0.05), (d / 2.0 - 0.1, 0.12, 0.01), dark, yaw)
    for fx in (d / 2.0 - 0.05, -d / 2.0 + 0.05):
        for fy in (w / 2.0 - 0.05, -w / 2.0 + 0.05):
            cx, cy = local(x, y, yaw, fx, fy)
            sc.sphere((cx, cy, 0.025), 0.025, (0.1, 0.1, 0.1, 1.0))


# -- seated people and what stands on thin supports (``ASSISTIVE``: the ``extra4`` and ``val_extra4`` splits) --
# Chosen from the RGB-D model's failures on ``unseen3``: people who sit (on chairs, stools, in wheelchairs of
# random build, empty wheelchairs as the furniture they are), walkers with a frame or pushing a trolley, poles on
# castor bases and tall appliances and lockers. None of them is a held-out model (``HELD_OUT_4`` included).
FRAMES: Tuple[Vec3, ...] = (*METAL, (0.1, 0.1, 0.1), (0.7, 0.1, 0.1), (0.1, 0.45, 0.25), (0.15, 0.2, 0.55))


def ring(sc: Scene, centre: Tuple[float, float, float], yaw: float, *, radius: float, tube: float, color: Rgba,
         segments: int = 12) -> None:
    """A wheel's tyre seen from the side: ``segments`` capsules round a circle of ``radius`` [m] in the vertical
    plane across ``yaw`` (the hub and the spokes stay see-through)."""
    chord = 2.0 * radius * math.sin(math.pi / segments)
    for k in range(segments):
        a = 2.0 * math.pi * (k + 0.5) / segments
        px, py = local(centre[0], centre[1], yaw, radius * math.cos(a), 0.0)
        sc.capsule((px, py, centre[2] + radius * math.sin(a)), tube, chord, color, yaw=yaw, pitch=-a)


def wheelchair(sc: Scene, x: float, y: float, yaw: float) -> Tuple[float, float, float]:
    """A manual wheelchair of random build facing +x: rear wheels (self-propelling, spoked or solid) or small
    transit wheels, castors, a sling seat and back, push handles, maybe armrests, footplates.
    Returns (seat height, footplate height, armrest height or 0) [m]."""
    rng = sc.rng
    frame = jitter(rng, pick(rng, FRAMES))
    cloth = jitter(rng, pick(rng, UPHOLSTERY))
    tyre = jitter(rng, (0.07, 0.07, 0.07), 0.02)
    seat_h, half_w = rng.uniform(0.44, 0.52), rng.uniform(0.2, 0.27)
    rear_r = rng.uniform(0.24, 0.33) if rng.random() < 0.75 else rng.uniform(0.1, 0.16)
    spoked = rng.random() < 0.6
    for side in (1.0, -1.0):
        wx, wy = local(x, y, yaw, -0.12, side * (half_w + 0.05))
        if spoked and rear_r > 0.2:
            ring(sc, (wx, wy, rear_r), yaw, radius=rear_r - 0.015, tube=0.015, color=tyre)
            ring(sc, (wx, wy, rear_r), yaw, radius=rear_r - 0.05, tube=0.006, color=jitter(rng, pick(rng, METAL)))
            sc.cylinder((wx, wy, rear_r), 0.04, 0.05, frame, yaw=yaw, roll=math.pi / 2.0)
        else:
            sc.cylinder((wx, wy, rear_r), rear_r, 0.03, tyre, yaw=yaw, roll=math.pi / 2.0)
            sc.cylinder((wx, wy, rear_r), rear_r * 0.8, 0.035, frame, yaw=yaw, roll=math.pi / 2.0)
        castor_r = rng.uniform(0.05, 0.1)
        cx, cy = local(x, y, yaw, 0.28, side * (half_w - 0.02))
        sc.cylinder((cx, cy, castor_r), castor_r, 0.03, tyre, yaw=yaw, roll=math.pi / 2.0)
        sc.box((cx, cy, (castor_r + seat_h) / 2.0), (0.012, 0.012, (seat_h - castor_r) / 2.0), frame, yaw)
        rx, ry = local(x, y, yaw, 0.0, side * half_w)
        sc.box((rx, ry, seat_h), (0.25, 0.012, 0.012), frame, yaw)  # seat rail
        px, py = local(x, y, yaw, -0.22, side * half_w)
        top = seat_h + rng.uniform(0.42, 0.52)
        sc.box((px, py, (seat_h - 0.1 + top) / 2.0), (0.012, 0.012, (top - seat_h + 0.1) / 2.0), frame, yaw, -0.1)
        hx, hy = local(x, y, yaw, -0.3, side * half_w)
        sc.box((hx, hy, top), (0.07, 0.018, 0.018), (0.1, 0.1, 0.1, 1.0), yaw)
        fx, fy = local(x, y, yaw, 0.4, side * (half_w * 0.5))
        sc.box((fx, fy, 0.12), (0.07, half_w * 0.45, 0.01), frame, yaw)
    sc.box((x, y, seat_h), (0.23, half_w, 0.02), cloth, yaw)
    bx, by = local(x, y, yaw, -0.23, 0.0)
    sc.box((bx, by, seat_h + 0.24), (0.015, half_w, 0.2), cloth, yaw, -0.1)
    armrest_h = 0.0
    if rng.random() < 0.6:
        armrest_h = seat_h + rng.uniform(0.18, 0.25)
        for side in (1.0, -1.0):
            ax, ay = local(x, y, yaw, -0.02, side * (half_w + 0.01))
            sc.box((ax, ay, armrest_h), (0.17, 0.025, 0.02), cloth, yaw)
    return seat_h, 0.13, armrest_h


def castor_star(sc: Scene, x: float, y: float, yaw: float, *, feet: int, reach: float, arm_z: float,
                arm_half: Tuple[float, float], color: Rgba) -> None:
    """A star base: ``feet`` arms ``reach`` [m] long from (x, y) at height ``arm_z`` [m] (half width and
    height ``arm_half`` [m]), a castor at the end of each."""
    for k in range(feet):
        a = yaw + 2.0 * math.pi * k / feet
        sc.box((x + reach / 2.0 * math.cos(a), y + reach / 2.0 * math.sin(a), arm_z), (reach / 2.0, *arm_half), color,
               a)
        sc.sphere((x + reach * math.cos(a), y + reach * math.sin(a), 0.03), 0.03, (0.1, 0.1, 0.1, 1.0))


def person_wheelchair_rider(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A person seated in a manual wheelchair of random build (:func:`wheelchair`), leaning back a little."""
    seat_h, foot_z, armrest_h = wheelchair(sc, x, y, yaw)
    seated_figure(sc, x, y, yaw, seat_h=seat_h + 0.02, foot_z=foot_z, hip_fx=-0.12,
                  lean=sc.rng.uniform(0.0, 0.25), armrest_h=armrest_h or None)


def clear_empty_wheelchair(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A wheelchair with nobody in it (furniture: the robot goes round it)."""
    wheelchair(sc, x, y, yaw)


def person_seated(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A person on a chair (four legs and a back), an office chair (castor star, column, back) or a high
    stool (no back, feet on a ring or on the floor)."""
    rng = sc.rng
    kind = int(rng.integers(3))
    seat_c, frame = furniture_color(rng), jitter(rng, pick(rng, (*METAL, *FURNITURE)))
    if kind == 0:  # chair
        h, half = rng.uniform(0.42, 0.5), rng.uniform(0.2, 0.25)
        sc.box((x, y, h - 0.02), (half, half, 0.02), seat_c, yaw)
        legs4(sc, x, y, yaw, dx=half - 0.03, dy=half - 0.03, height=h - 0.04, half=0.018, color=frame)
        bx, by = local(x, y, yaw, -half, 0.0)
        sc.box((bx, by, h + 0.25), (0.02, half, 0.25), seat_c, yaw, -0.1)
        seated_figure(sc, x, y, yaw, seat_h=h, hip_fx=-0.1, lean=rng.uniform(0.0, 0.2))
    elif kind == 1:  # office chair
        h = rng.uniform(0.45, 0.55)
        castor_star(sc, x, y, yaw, feet=5, reach=0.3, arm_z=0.08, arm_half=(0.02, 0.015), color=frame)
        sc.cylinder((x, y, (0.08 + h) / 2.0), 0.03, h - 0.08, frame)
        sc.box((x, y, h - 0.04), (0.24, 0.24, 0.04), seat_c, yaw)
        bx, by = local(x, y, yaw, -0.25, 0.0)
        sc.box((bx, by, h + 0.32), (0.03, 0.22, 0.25), seat_c, yaw, -0.15)
        armrest = h + 0.22 if rng.random() < 0.6 else None
        if armrest is not None:
            for side in (1.0, -1.0):
                ax, ay = local(x, y, yaw, 0.0, side * 0.25)
                sc.box((ax, ay, armrest), (0.12, 0.025, 0.02), (0.1, 0.1, 0.1, 1.0), yaw)
        seated_figure(sc, x, y, yaw, seat_h=h, hip_fx=-0.12, lean=rng.uniform(0.0, 0.3), armrest_h=armrest)
    else:  # high stool
        h, r = rng.uniform(0.6, 0.78), rng.uniform(0.16, 0.2)
        round_or_square_top(sc, x, y, yaw, z=h - 0.03, radius=r, thickness=0.06, color=seat_c, round_chance=0.7)
        for k in range(4):
            a = yaw + math.pi / 4.0 + math.pi * k / 2.0
            sc.cylinder((x + 0.85 * r * math.cos(a), y + 0.85 * r * math.sin(a), (h - 0.06) / 2.0), 0.014, h - 0.06,
                        frame)
        foot_z = 0.25 if rng.random() < 0.5 else 0.0
        if foot_z:
            sc.box((x, y, foot_z - 0.01), (0.9 * r, 0.9 * r, 0.01), frame, yaw)
        seated_figure(sc, x, y, yaw, seat_h=h, foot_z=foot_z, hip_fx=-0.05, lean=rng.uniform(-0.1, 0.1))


def person_frame_walker(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker with a walking frame ahead (four legs and side rails; a rollator: front wheels, a seat, a bag)."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw)
    metal = jitter(rng, pick(rng, FRAMES))
    h, half_w, depth = rng.uniform(0.8, 0.92) * s, rng.uniform(0.26, 0.32), rng.uniform(0.35, 0.5)
    front = 0.3 + depth
    rollator = rng.random() < 0.4
    for fx in (0.3, front):
        for side in (1.0, -1.0):
            lx, ly = local(x, y, yaw, fx, side * half_w)
            sc.capsule((lx, ly, h / 2.0), 0.013, h, metal, yaw=yaw)
            if rollator:
                sc.cylinder((lx, ly, 0.1), 0.1, 0.03, (0.08, 0.08, 0.08, 1.0), yaw=yaw, roll=math.pi / 2.0)
    for side in (1.0, -1.0):
        rx, ry = local(x, y, yaw, (0.3 + front) / 2.0, side * half_w)
        sc.capsule((rx, ry, h), 0.015, depth, metal, yaw=yaw, pitch=math.pi / 2.0)
    fx, fy = local(x, y, yaw, front, 0.0)
    sc.capsule((fx, fy, h * 0.8), 0.013, 2.0 * half_w, metal, yaw=yaw, roll=math.pi / 2.0)
    if rollator:
        cx, cy = local(x, y, yaw, (0.3 + front) / 2.0, 0.0)
        sc.box((cx, cy, h * 0.6), (depth / 2.0, half_w, 0.015), jitter(rng, pick(rng, UPHOLSTERY)), yaw)
        bx, by = local(x, y, yaw, front + 0.05, 0.0)
        sc.box((bx, by, h * 0.7), (0.05, half_w * 0.7, 0.1), jitter(rng, pick(rng, UPHOLSTERY)), yaw)
    for side in (1.0, -1.0):  # forearms to the grips
        ax, ay = local(x, y, yaw, 0.15, side * 0.2 * s)
        sc.capsule((ax, ay, h + 0.05), 0.04 * s, 0.2, jitter(rng, pick(rng, SKIN), 0.03), yaw=yaw, pitch=1.3)


def person_trolley_pusher(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker pushing something on wheels ahead: a service trolley, an empty wheelchair or a linen trolley
    (a frame with a bag); the hands on its back."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw)
    kind = int(rng.integers(3))
    ahead = rng.uniform(0.6, 0.8)  # [m] from the walker's centre to the pushed thing's centre
    tx, ty = local(x, y, yaw, ahead, 0.0)
    if kind == 0:
        clear_cart(sc, tx, ty, yaw)
        grip_z = 0.95
    elif kind == 1:
        wheelchair(sc, tx, ty, yaw)
        grip_z = 0.95
    else:
        frame = jitter(rng, pick(rng, METAL))
        bag = jitter(rng, pick(rng, ((0.9, 0.9, 0.88), (0.3, 0.45, 0.7), (0.75, 0.3, 0.3), (0.4, 0.6, 0.4))))
        grip_z = rng.uniform(0.85, 1.0)
        for fx in (-0.25, 0.25):
            for side in (1.0, -1.0):
                px, py = local(tx, ty, yaw, fx, side * 0.25)
                sc.cylinder((px, py, grip_z / 2.0 + 0.03), 0.012, grip_z - 0.06, frame)
                sc.sphere((px, py, 0.03), 0.03, (0.1, 0.1, 0.1, 1.0))
        sc.box((tx, ty, grip_z * 0.55), (0.22, 0.22, grip_z * 0.35), bag, yaw)
    for side in (1.0, -1.0):
        ax, ay = local(x, y, yaw, 0.2, side * 0.18 * s)
        sc.capsule((ax, ay, grip_z), 0.04 * s, 0.25, jitter(rng, pick(rng, SKIN), 0.03), yaw=yaw, pitch=math.pi / 2.0)


def clear_castor_pole(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A pole on a castor star (drip pole, coat stand or monitor stand): random height, four or five feet,
    something at the top (hooks, a cross bar, a monitor, a basket) or nothing."""
    rng = sc.rng
    h = rng.uniform(1.0, 2.1)
    metal = jitter(rng, pick(rng, FRAMES))
    r_pole = rng.uniform(0.012, 0.03)
    sc.cylinder((x, y, h / 2.0), r_pole, h, metal)
    feet, reach = int(rng.integers(4, 6)), rng.uniform(0.2, 0.32)
    castor_star(sc, x, y, yaw, feet=feet, reach=reach, arm_z=0.07, arm_half=(0.016, 0.014), color=metal)
    top = int(rng.integers(4))
    if top == 0:  # hooks
        for k in range(4):
            a = yaw + math.pi * k / 2.0
            sc.capsule((x + 0.06 * math.cos(a), y + 0.06 * math.sin(a), h - 0.05), 0.008, 0.1, metal, yaw=a,
                       pitch=0.8)
    elif top == 1:  # cross bar, maybe with a bag
        sc.box((x, y, h), (0.01, rng.uniform(0.1, 0.2), 0.01), metal, yaw)
        if rng.random() < 0.5:
            bx, by = local(x, y, yaw, 0.0, 0.1)
            sc.box((bx, by, h - 0.15), (0.02, 0.06, 0.1), (0.85, 0.9, 0.95, 1.0), yaw)
    elif top == 2:  # a monitor
        sc.box((x, y, h), (0.03, rng.uniform(0.18, 0.3), rng.uniform(0.12, 0.2)), (0.08, 0.08, 0.1, 1.0), yaw)
    if rng.random() < 0.4:  # a basket or a pump half-way up
        sc.box((x, y, rng.uniform(0.6, 1.0)), (0.08, 0.1, 0.07), jitter(rng, pick(rng, (*METAL, *FURNITURE))), yaw)


def clear_tall_appliance(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A tall appliance or cupboard 1.3-2.1 m: a block with one to three doors (horizontal gaps), handles on
    one side, maybe a display and a grille; white, steel, black, cream or a colour."""
    rng = sc.rng
    w, d, h = rng.uniform(0.5, 1.0), rng.uniform(0.5, 0.8), rng.uniform(1.3, 2.1)
    body = jitter(rng, pick(rng, ((0.95, 0.95, 0.95), (0.75, 0.76, 0.78), (0.12, 0.12, 0.13), (0.9, 0.87, 0.78),
                                  (0.6, 0.15, 0.15), (0.2, 0.35, 0.6))), 0.04)
    dark = jitter(rng, pick(rng, ((0.1, 0.1, 0.1), (0.3, 0.3, 0.32))), 0.02)
    sc.box((x, y, h / 2.0), (d / 2.0, w / 2.0, h / 2.0), body, yaw)
    fx, fy = local(x, y, yaw, -d / 2.0 - 0.003, 0.0)
    edges = sorted(rng.uniform(0.2, 0.85, int(rng.integers(0, 3))) * h)
    for z in edges:
        sc.box((fx, fy, z), (0.003, w / 2.0, 0.005), dark, yaw)
    side = 1.0 if rng.random() < 0.5 else -1.0
    handle = jitter(rng, pick(rng, METAL))
    for lo, hi in zip([0.0, *edges], [*edges, h]):
        hx, hy = local(x, y, yaw, -d / 2.0 - 0.02, side * (w / 2.0 - 0.05))
        length = min(0.4, (hi - lo) * 0.5)
        sc.box((hx, hy, (lo + hi) / 2.0), (0.01, 0.01, length / 2.0), handle, yaw)
    if rng.random() < 0.4:
        dx, dy = local(x, y, yaw, -d / 2.0 - 0.004, -side * 0.1)
        sc.box((dx, dy, h * 0.7), (0.004, 0.08, 0.05), (0.05, 0.1, 0.15, 1.0), yaw)
    if rng.random() < 0.5:
        sc.box((fx, fy, 0.05), (0.003, w / 2.0 - 0.02, 0.04), dark, yaw)


def clear_locker(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A bank of two to four tall steel lockers: narrow doors, vents at the top, a lock on each door."""
    rng = sc.rng
    n, door_w = int(rng.integers(2, 5)), rng.uniform(0.3, 0.4)
    d, h = rng.uniform(0.4, 0.55), rng.uniform(1.6, 1.95)
    body = jitter(rng, pick(rng, ((0.6, 0.62, 0.65), (0.3, 0.4, 0.6), (0.85, 0.85, 0.82), (0.25, 0.45, 0.3),
                                  (0.7, 0.3, 0.2))), 0.04)
    w = n * door_w
    sc.box((x, y, h / 2.0), (d / 2.0, w / 2.0, h / 2.0), body, yaw)
    for k in range(n):
        fy = -w / 2.0 + (k + 0.5) * door_w
        if k:
            gx, gy = local(x, y, yaw, -d / 2.0 - 0.003, fy - door_w / 2.0)
            sc.box((gx, gy, h / 2.0), (0.003, 0.004, h / 2.0 - 0.03), (0.15, 0.15, 0.15, 1.0), yaw)
        vx, vy = local(x, y, yaw, -d / 2.0 - 0.003, fy)
        for z in (h - 0.12, h - 0.16, h - 0.2):
            sc.box((vx, vy, z), (0.003, door_w * 0.3, 0.006), (0.15, 0.15, 0.15, 1.0), yaw)
        lx, ly = local(x, y, yaw, -d / 2.0 - 0.01, fy + door_w * 0.35)
        sc.box((lx, ly, h * 0.55), (0.01, 0.012, 0.03), jitter(rng, pick(rng, METAL)), yaw)


# -- the fifth held-out set (``HELD_OUT_5``: the ``unseen5`` split only) ------------------------------------
# Defined, rendered and measured before the ``extra5`` training data was designed (which answers the fourth set's
# failures): people kneeling, carrying a box in front of them or pushing a pushchair; new pushable things; a
# potted plant, a reception counter and a stack of chairs as furniture.
FOLIAGE: Tuple[Vec3, ...] = ((0.15, 0.45, 0.15), (0.25, 0.55, 0.2), (0.1, 0.3, 0.12), (0.35, 0.5, 0.2))


def person_kneeler(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A person kneeling on one knee or both (cleaning, tying a shoe, talking to a child): thighs down to the
    knees on the floor, shins back along it, the torso upright or bent forward, the arms down or reaching."""
    rng = sc.rng
    s = rng.uniform(0.85, 1.1)
    trousers, shirt = jitter(rng, pick(rng, CLOTHES)), jitter(rng, pick(rng, CLOTHES))
    skin, shoes = jitter(rng, pick(rng, SKIN), 0.03), jitter(rng, pick(rng, SHOES), 0.03)
    leg_r, thigh, hip_w = rng.uniform(0.06, 0.08) * s, 0.45 * s, rng.uniform(0.09, 0.12) * s
    hip_z = thigh + leg_r
    both = rng.random() < 0.4
    for k, side in enumerate((1.0, -1.0)):
        hx, hy = local(x, y, yaw, 0.0, side * hip_w)
        if both or k == 0:  # thigh down to the knee on the floor, shin and foot back along it
            sc.capsule((hx, hy, hip_z / 2.0 + leg_r / 2.0), leg_r, thigh - leg_r, trousers, yaw=yaw)
            sx_, sy_ = local(x, y, yaw, -0.2 * s, side * hip_w)
            sc.capsule((sx_, sy_, leg_r), leg_r * 0.85, 0.32 * s, trousers, yaw=yaw, pitch=math.pi / 2.0)
            fx, fy = local(x, y, yaw, -0.45 * s, side * hip_w)
            sc.box((fx, fy, 0.05), (0.04, 0.05 * s, 0.05), shoes, yaw)
        else:  # thigh forward, shin down to the foot flat on the floor
            tx, ty = local(x, y, yaw, thigh / 2.0, side * hip_w)
            sc.capsule((tx, ty, hip_z), leg_r, thigh - leg_r, trousers, yaw=yaw, pitch=math.pi / 2.0)
            kx, ky = local(x, y, yaw, thigh, side * hip_w)
            sc.capsule((kx, ky, hip_z / 2.0 + 0.04), leg_r * 0.85, max(hip_z - 0.1, 0.05), trousers, yaw=yaw)
            fx, fy = local(x, y, yaw, thigh + 0.06, side * hip_w)
            sc.box((fx, fy, 0.04), (0.13 * s, 0.05 * s, 0.04), shoes, yaw)
    lean = rng.uniform(0.0, 0.7)  # [rad] forward
    torso_h = rng.uniform(0.5, 0.6) * s
    width, depth = rng.uniform(0.34, 0.42) * s, rng.uniform(0.2, 0.26) * s
    up = (math.sin(lean), math.cos(lean))  # (forward, up) along the spine
    cx, cy = local(x, y, yaw, up[0] * torso_h / 2.0, 0.0)
    sc.box((cx, cy, hip_z + up[1] * torso_h / 2.0), (depth / 2.0, width / 2.0, torso_h / 2.0), shirt, yaw, lean)
    hx, hy = local(x, y, yaw, up[0] * (torso_h + 0.14 * s), 0.0)
    sc.sphere((hx, hy, hip_z + up[1] * (torso_h + 0.14 * s)), 0.1 * s, skin)
    shoulder_fx, shoulder_z = up[0] * (torso_h - 0.05), hip_z + up[1] * (torso_h - 0.05)
    reach = rng.uniform(0.0, 1.2)  # [rad] arms forward from hanging
    for side in (1.0, -1.0):
        ax, ay = local(x, y, yaw, shoulder_fx + 0.3 * s * math.sin(reach), side * (width / 2.0 + 0.05 * s))
        sc.capsule((ax, ay, shoulder_z - 0.3 * s * math.cos(reach)), 0.045 * s, 0.5 * s, shirt, yaw=yaw,
                   pitch=reach)
    if rng.random() < 0.5:  # a bucket beside them
        bx, by = local(x, y, yaw, 0.25, (width / 2.0 + 0.25) * (1.0 if rng.random() < 0.5 else -1.0))
        sc.cylinder((bx, by, 0.13), rng.uniform(0.12, 0.16), 0.26, jitter(rng, pick(rng, BOXES)))


def person_box_carrier(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker carrying a box in front of them with both hands, between the waist and the chin."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw, size=(0.9, 1.05))
    bx_, by_, bz_ = rng.uniform(0.2, 0.35), rng.uniform(0.3, 0.5), rng.uniform(0.2, 0.4)
    z = rng.uniform(0.95, 1.25) * s
    cx, cy = local(x, y, yaw, 0.15 * s + bx_ / 2.0, 0.0)
    sc.box((cx, cy, z), (bx_ / 2.0, by_ / 2.0, bz_ / 2.0), box_color(rng), yaw)
    skin = jitter(rng, pick(rng, SKIN), 0.03)
    for side in (1.0, -1.0):
        ax, ay = local(x, y, yaw, 0.15 * s + bx_ * 0.4, side * (by_ / 2.0 + 0.03))
        sc.capsule((ax, ay, z - bz_ / 2.0 + 0.03), 0.04 * s, max(bx_ * 0.7, 0.05), skin, yaw=yaw, pitch=math.pi / 2.0)


def person_stroller_pusher(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker pushing a pushchair: four small wheels, a frame rising back to the handle, a fabric seat and
    a hood."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw)
    frame = jitter(rng, pick(rng, ((0.1, 0.1, 0.1), (0.75, 0.75, 0.78), (0.35, 0.35, 0.38))))
    cloth = jitter(rng, pick(rng, ((0.15, 0.2, 0.4), (0.1, 0.1, 0.12), (0.6, 0.15, 0.2), (0.55, 0.55, 0.5),
                                   (0.2, 0.45, 0.4))))
    ahead, half_w = rng.uniform(0.6, 0.8), rng.uniform(0.2, 0.27)
    handle_z = rng.uniform(0.95, 1.1)
    for fx in (-0.25, 0.25):
        for side in (1.0, -1.0):
            wx, wy = local(x, y, yaw, ahead + fx, side * half_w)
            sc.cylinder((wx, wy, 0.08), 0.08, 0.03, (0.08, 0.08, 0.08, 1.0), yaw=yaw, roll=math.pi / 2.0)
    for side in (1.0, -1.0):  # side tubes from the front wheel up to the handle
        ax, ay = local(x, y, yaw, ahead + 0.25, side * half_w)
        hx, hy = local(x, y, yaw, 0.3, side * half_w)
        mx, my = (ax + hx) / 2.0, (ay + hy) / 2.0
        dx, dz = ahead - 0.05, handle_z - 0.08
        sc.capsule((mx, my, (0.08 + handle_z) / 2.0), 0.012, math.hypot(dx, dz), frame, yaw=yaw,
                   pitch=-(math.pi / 2.0 - math.atan2(dz, dx)))
    hx, hy = local(x, y, yaw, 0.3, 0.0)
    sc.box((hx, hy, handle_z), (0.02, half_w, 0.02), frame, yaw)
    seat_fx = ahead + rng.uniform(-0.05, 0.1)
    sx_, sy_ = local(x, y, yaw, seat_fx, 0.0)
    sc.box((sx_, sy_, 0.5), (0.22, half_w - 0.03, 0.18), cloth, yaw, -0.3)
    if rng.random() < 0.7:  # the hood
        kx, ky = local(x, y, yaw, seat_fx - 0.1, 0.0)
        sc.cylinder((kx, ky, 0.72), 0.2, 2.0 * half_w - 0.04, cloth, yaw=yaw + math.pi / 2.0, roll=math.pi / 2.0)
    for side in (1.0, -1.0):
        ax, ay = local(x, y, yaw, 0.17, side * 0.18 * s)
        sc.capsule((ax, ay, handle_z), 0.04 * s, 0.22, jitter(rng, pick(rng, SKIN), 0.03), yaw=yaw,
                   pitch=math.pi / 2.0)


def movable_laundry_basket(sc: Scene, x: float, y: float, yaw: float) -> None:
    """An open plastic laundry basket: slotted walls, a rim, clothes heaped inside above the rim or not."""
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.45, 0.65), rng.uniform(0.32, 0.45), rng.uniform(0.25, 0.4)
    plastic = jitter(rng, pick(rng, ((0.95, 0.95, 0.95), (0.3, 0.5, 0.85), (0.9, 0.4, 0.6), (0.4, 0.75, 0.45),
                                     (0.2, 0.2, 0.22))))
    shade = (plastic[0] * 0.4, plastic[1] * 0.4, plastic[2] * 0.4, 1.0)
    t = 0.012
    for fx, fy, hx, hy in ((sx / 2.0, 0.0, t, sy / 2.0), (-sx / 2.0, 0.0, t, sy / 2.0),
                           (0.0, sy / 2.0, sx / 2.0, t), (0.0, -sy / 2.0, sx / 2.0, t)):
        wx, wy = local(x, y, yaw, fx, fy)
        sc.box((wx, wy, sz / 2.0), (hx, hy, sz / 2.0), plastic, yaw)
        for z in np.linspace(0.3, 0.75, int(rng.integers(2, 5))) * sz:  # slots, a little proud of the wall
            ox, oy = local(x, y, yaw, fx * 1.01, fy * 1.01)
            sc.box((ox, oy, z), (hx * 0.8 if hx > t else t * 1.2, hy * 0.8 if hy > t else t * 1.2, 0.012), shade, yaw)
    sc.box((x, y, sz), (sx / 2.0 + 0.015, sy / 2.0 + 0.015, 0.012), plastic, yaw)  # the rim (hollow inside seen
    sc.box((x, y, sz * 0.5), (sx / 2.0 - t, sy / 2.0 - t, sz * 0.45), shade, yaw)  # as the shadowed inside)
    for _ in range(int(rng.integers(0, 6))):
        cx, cy = local(x, y, yaw, rng.uniform(-0.3, 0.3) * sx, rng.uniform(-0.3, 0.3) * sy)
        sc.sphere((cx, cy, sz + rng.uniform(-0.04, 0.06)), rng.uniform(0.07, 0.12), jitter(rng, pick(rng, CLOTHES)))


def movable_flat_pack(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A flat-pack carton lying on the floor: long, wide and low, with tape across it and a printed label."""
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.8, 1.3), rng.uniform(0.4, 0.75), rng.uniform(0.08, 0.2)
    sc.box((x, y, sz / 2.0), (sx / 2.0, sy / 2.0, sz / 2.0), box_color(rng), yaw)
    tape = jitter(rng, pick(rng, ((0.85, 0.75, 0.5), (0.9, 0.9, 0.9), (0.2, 0.2, 0.2), (0.8, 0.3, 0.2))), 0.03)
    for fx in (-sx * 0.35, sx * 0.35):
        tx, ty = local(x, y, yaw, fx, 0.0)
        sc.box((tx, ty, sz / 2.0), (0.025, sy / 2.0 + 0.003, sz / 2.0 + 0.003), tape, yaw)
    lx, ly = local(x, y, yaw, rng.uniform(-0.2, 0.2) * sx, rng.uniform(-0.2, 0.2) * sy)
    sc.box((lx, ly, sz + 0.002), (0.1, 0.07, 0.002), jitter(rng, pick(rng, LIGHT_BOXES)), yaw)


def movable_water_jugs(sc: Scene, x: float, y: float, yaw: float) -> None:
    """One to three 19 l water-cooler bottles standing on the floor: a ribbed body, a shoulder, a neck, a cap."""
    rng = sc.rng
    water = jitter(rng, pick(rng, ((0.55, 0.7, 0.9), (0.45, 0.6, 0.85), (0.75, 0.85, 0.95))), 0.04)
    cap = jitter(rng, pick(rng, ((0.1, 0.3, 0.8), (0.9, 0.9, 0.9), (0.1, 0.6, 0.3))))
    n = int(rng.integers(1, 4))
    for k in range(n):
        bx, by = local(x, y, yaw, rng.uniform(-0.05, 0.05), (k - (n - 1) / 2.0) * 0.29)
        r, h = rng.uniform(0.13, 0.14), rng.uniform(0.36, 0.42)
        sc.cylinder((bx, by, h / 2.0), r, h, water)
        for z in (h * 0.3, h * 0.6):
            sc.cylinder((bx, by, z), r * 1.02, 0.015, water)
        sc.cylinder((bx, by, h + 0.03), r * 0.7, 0.06, water)
        sc.cylinder((bx, by, h + 0.09), 0.03, 0.06, water)
        sc.cylinder((bx, by, h + 0.125), 0.035, 0.02, cap)


def clear_potted_plant(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A large potted plant 0.9-1.9 m: a pot, a trunk or stems, foliage as clusters of leaves."""
    rng = sc.rng
    pot = jitter(rng, pick(rng, ((0.7, 0.35, 0.2), (0.95, 0.95, 0.95), (0.12, 0.12, 0.12), (0.5, 0.5, 0.5),
                                 (0.6, 0.55, 0.45))))
    r_pot, h_pot = rng.uniform(0.15, 0.25), rng.uniform(0.3, 0.5)
    sc.cylinder((x, y, h_pot / 2.0), r_pot, h_pot, pot)
    sc.cylinder((x, y, h_pot), r_pot * 0.95, 0.01, (0.25, 0.17, 0.1, 1.0))
    h = rng.uniform(0.9, 1.9)
    trunk = rng.random() < 0.6
    if trunk:
        sc.cylinder((x, y, (h_pot + h * 0.75) / 2.0), rng.uniform(0.02, 0.04), h * 0.75 - h_pot,
                    jitter(rng, (0.35, 0.25, 0.15), 0.05))
    leaf = pick(rng, FOLIAGE)
    for _ in range(int(rng.integers(6, 14))):
        lo = h * 0.55 if trunk else h_pot + 0.1
        z = rng.uniform(lo, h)
        spread = rng.uniform(0.1, 0.35)
        a = rng.uniform(-math.pi, math.pi)
        sc.sphere((x + spread * math.cos(a), y + spread * math.sin(a), z), rng.uniform(0.08, 0.18),
                  jitter(rng, leaf, 0.06))


def clear_reception_counter(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A reception counter: a long desk 1.5-2.5 m with a raised front ledge, panels and a kick plate."""
    rng = sc.rng
    w, d = rng.uniform(1.5, 2.5), rng.uniform(0.6, 0.8)
    h, ledge_h = rng.uniform(0.72, 0.78), rng.uniform(1.05, 1.2)
    body = jitter(rng, pick(rng, (*FURNITURE, (0.95, 0.95, 0.95), (0.2, 0.3, 0.5))), 0.04)
    accent = jitter(rng, pick(rng, ((0.9, 0.9, 0.9), (0.15, 0.15, 0.15), (0.7, 0.55, 0.35), (0.3, 0.55, 0.7))))
    sc.box((x, y, h / 2.0), (d / 2.0, w / 2.0, h / 2.0), body, yaw)
    fx, fy = local(x, y, yaw, -d / 2.0 + 0.06, 0.0)
    sc.box((fx, fy, ledge_h / 2.0), (0.06, w / 2.0, ledge_h / 2.0), body, yaw)
    tx, ty = local(x, y, yaw, -d / 2.0 + 0.04, 0.0)
    sc.box((tx, ty, ledge_h + 0.015), (0.12, w / 2.0 + 0.02, 0.015), accent, yaw)
    px, py = local(x, y, yaw, -d / 2.0 - 0.003, 0.0)
    for k in range(int(rng.integers(1, 4))):
        z = ledge_h * (k + 1) / 4.0
        sc.box((px, py, z), (0.003, w / 2.0 - 0.02, 0.01), accent, yaw)
    sc.box((px, py, 0.04), (0.004, w / 2.0, 0.04), (0.1, 0.1, 0.1, 1.0), yaw)


def clear_chair_stack(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A stack of four to eight plastic or steel-framed chairs, each seat a few centimetres above the last."""
    rng = sc.rng
    shell = jitter(rng, pick(rng, (*FURNITURE, (0.85, 0.3, 0.2), (0.2, 0.4, 0.7), (0.95, 0.95, 0.95))))
    legs = jitter(rng, pick(rng, (*METAL, (0.1, 0.1, 0.1))))
    n, step = int(rng.integers(4, 9)), rng.uniform(0.04, 0.07)
    seat, half = 0.45, rng.uniform(0.2, 0.24)
    for fx in (-half, half):
        for fy in (-half, half):
            lx, ly = local(x, y, yaw, fx, fy)
            sc.cylinder((lx, ly, seat / 2.0), 0.012, seat, legs)
    for k in range(n):
        z = seat + k * step
        sc.box((x, y, z), (half, half, 0.015), shell, yaw, 0.05)
        bx, by = local(x, y, yaw, -half - 0.02 + 0.01 * k, 0.0)
        sc.box((bx, by, z + 0.22), (0.015, half, 0.2), shell, yaw, 0.15)
    top = seat + (n - 1) * step
    for fy in (-half, half):  # the top chair's front legs above the stack
        lx, ly = local(x, y, yaw, half, fy)
        sc.cylinder((lx, ly, top - 0.05), 0.012, 0.1, legs)


# -- the sixth held-out set (``HELD_OUT_6``: the ``unseen6`` split only) ------------------------------------
# Defined, rendered and measured before the ``extra5`` training data was designed (which answers the fourth and
# fifth sets' failures): two people side by side, a worker in high-visibility clothing, a mobility-scooter
# rider; a rolled rug, stacked crates, carrier bags; a sanitiser stand, a parked bicycle, a notice board.
HI_VIS: Tuple[Vec3, ...] = ((0.85, 0.95, 0.1), (1.0, 0.55, 0.05), (0.7, 0.95, 0.2))


def person_pair(sc: Scene, x: float, y: float, yaw: float) -> None:
    """Two walkers side by side or one a little behind the other, facing the same way or each other."""
    rng = sc.rng
    gap = rng.uniform(0.45, 0.7)  # [m] between their centres
    back = rng.uniform(-0.3, 0.3)
    turn = 0.0 if rng.random() < 0.6 else rng.uniform(2.4, 3.9)  # [rad] the second one faces back
    ax, ay = local(x, y, yaw, -back / 2.0, gap / 2.0)
    bx, by = local(x, y, yaw, back / 2.0, -gap / 2.0)
    person_walker(sc, ax, ay, yaw)
    person_walker(sc, bx, by, yaw + turn, dress=rng.random() < 0.3)


def person_hi_vis_worker(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker in work clothes: a high-visibility vest with reflective bands over the torso, a hard hat."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw)
    vest = jitter(rng, pick(rng, HI_VIS), 0.03)
    hip_h = 0.9 * s
    sc.box((x, y, hip_h + 0.27 * s), (0.14 * s, 0.215 * s, 0.25 * s), vest, yaw)
    for z in (hip_h + 0.1 * s, hip_h + 0.3 * s):
        sc.box((x, y, z), (0.142 * s, 0.217 * s, 0.02), (0.85, 0.85, 0.85, 1.0), yaw)
    if rng.random() < 0.7:
        sc.cylinder((x, y, hip_h + 0.84 * s), 0.13 * s, 0.08 * s, jitter(rng, pick(rng, ((1.0, 1.0, 1.0),
                                                                                          *HI_VIS)), 0.03))


def person_scooter_rider(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A person on a mobility scooter: a low deck on four small wheels, a front shroud with a tiller and
    handlebars, a seat on a post with armrests, a basket at the front."""
    rng = sc.rng
    body = jitter(rng, pick(rng, ((0.6, 0.1, 0.1), (0.1, 0.25, 0.55), (0.75, 0.75, 0.78), (0.1, 0.1, 0.1))))
    length, half_w = rng.uniform(1.0, 1.25), rng.uniform(0.26, 0.3)
    sc.box((x, y, 0.13), (length / 2.0, half_w, 0.05), body, yaw)
    for fx in (length / 2.0 - 0.12, -length / 2.0 + 0.12):
        for side in (1.0, -1.0):
            wx, wy = local(x, y, yaw, fx, side * (half_w - 0.02))
            sc.cylinder((wx, wy, 0.11), 0.11, 0.07, (0.07, 0.07, 0.07, 1.0), yaw=yaw, roll=math.pi / 2.0)
    fx_, fy_ = local(x, y, yaw, length / 2.0 - 0.15, 0.0)
    sc.box((fx_, fy_, 0.3), (0.15, half_w - 0.03, 0.14), body, yaw, -0.3)
    tx, ty = local(x, y, yaw, length / 2.0 - 0.3, 0.0)
    sc.box((tx, ty, 0.6), (0.03, 0.05, 0.3), (0.15, 0.15, 0.15, 1.0), yaw, -0.35)
    hx, hy = local(x, y, yaw, length / 2.0 - 0.4, 0.0)
    sc.box((hx, hy, 0.88), (0.03, 0.25, 0.02), (0.1, 0.1, 0.1, 1.0), yaw)
    if rng.random() < 0.7:
        bx, by = local(x, y, yaw, length / 2.0 - 0.05, 0.0)
        sc.box((bx, by, 0.6), (0.12, 0.18, 0.1), jitter(rng, pick(rng, METAL)), yaw)
    seat_fx, seat_h = -length / 2.0 + 0.3, rng.uniform(0.55, 0.65)
    sx_, sy_ = local(x, y, yaw, seat_fx, 0.0)
    sc.cylinder((sx_, sy_, (0.18 + seat_h) / 2.0), 0.035, seat_h - 0.18, (0.2, 0.2, 0.2, 1.0))
    pad = jitter(rng, pick(rng, UPHOLSTERY))
    sc.box((sx_, sy_, seat_h - 0.04), (0.22, 0.24, 0.05), pad, yaw)
    kx, ky = local(x, y, yaw, seat_fx - 0.22, 0.0)
    sc.box((kx, ky, seat_h + 0.25), (0.05, 0.22, 0.25), pad, yaw, -0.1)
    seated_figure(sc, sx_, sy_, yaw, seat_h=seat_h, foot_z=0.18, hip_fx=-0.05, lean=rng.uniform(-0.1, 0.15))


def movable_rolled_rug(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A rolled rug or mat lying on the floor, maybe tied with cord, the spiral visible at the ends."""
    rng = sc.rng
    r, length = rng.uniform(0.08, 0.16), rng.uniform(0.8, 1.6)
    cloth = random_color(rng, 0.15, 0.85)
    sc.cylinder((x, y, r), r, length, cloth, yaw=yaw, roll=math.pi / 2.0)
    for side in (1.0, -1.0):
        ex, ey = local(x, y, yaw, 0.0, side * length / 2.0)
        sc.cylinder((ex, ey, r), r * 0.6, 0.01, (cloth[0] * 0.6, cloth[1] * 0.6, cloth[2] * 0.6, 1.0), yaw=yaw,
                    roll=math.pi / 2.0)
    if rng.random() < 0.6:
        cord = jitter(rng, (0.8, 0.75, 0.6))
        for fy in (-length * 0.3, length * 0.3):
            cx, cy = local(x, y, yaw, 0.0, fy)
            sc.cylinder((cx, cy, r), r * 1.03, 0.015, cord, yaw=yaw, roll=math.pi / 2.0)


def movable_crate_stack(sc: Scene, x: float, y: float, yaw: float) -> None:
    """One to three open-top plastic stacking crates with hand holes and ribbed sides, maybe with goods inside."""
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.4, 0.6), rng.uniform(0.3, 0.4), rng.uniform(0.15, 0.3)
    plastic = jitter(rng, pick(rng, ((0.2, 0.35, 0.7), (0.8, 0.15, 0.15), (0.2, 0.55, 0.3), (0.3, 0.3, 0.3),
                                     (0.95, 0.75, 0.1))))
    dark = (plastic[0] * 0.5, plastic[1] * 0.5, plastic[2] * 0.5, 1.0)
    for k in range(int(rng.integers(1, 4))):
        z0 = k * (sz - 0.01)
        sc.box((x, y, z0 + sz / 2.0), (sx / 2.0, sy / 2.0, sz / 2.0), plastic, yaw)
        for side in (1.0, -1.0):
            hx, hy = local(x, y, yaw, side * (sx / 2.0 + 0.002), 0.0)
            sc.box((hx, hy, z0 + sz * 0.8), (0.002, 0.06, 0.02), (0.05, 0.05, 0.05, 1.0), yaw)
            rx, ry = local(x, y, yaw, 0.0, side * (sy / 2.0 + 0.002))
            for fx in np.linspace(-0.35, 0.35, 5) * sx:
                px, py = local(rx, ry, yaw, fx, 0.0)
                sc.box((px, py, z0 + sz * 0.45), (0.01, 0.002, sz * 0.3), dark, yaw)


def movable_carrier_bags(sc: Scene, x: float, y: float, yaw: float) -> None:
    """Two to four carrier bags standing on the floor: paper or plastic bodies, two handles each, goods at the top."""
    rng = sc.rng
    n = int(rng.integers(2, 5))
    for k in range(n):
        bx, by = local(x, y, yaw, rng.uniform(-0.1, 0.1), (k - (n - 1) / 2.0) * 0.22)
        w, d, h = rng.uniform(0.25, 0.4), rng.uniform(0.12, 0.2), rng.uniform(0.3, 0.45)
        bag = jitter(rng, pick(rng, ((0.7, 0.55, 0.35), (0.95, 0.95, 0.95), (0.15, 0.15, 0.15), (0.8, 0.2, 0.2),
                                     (0.2, 0.5, 0.3))))
        turn = yaw + math.pi / 2.0 + rng.uniform(-0.4, 0.4)
        sc.box((bx, by, h / 2.0), (w / 2.0, d / 2.0, h / 2.0), bag, turn)
        for side in (1.0, -1.0):
            hx, hy = local(bx, by, turn, 0.0, side * d * 0.3)
            sc.box((hx, hy, h + 0.06), (w * 0.2, 0.006, 0.06), bag, turn)
        if rng.random() < 0.6:
            sc.sphere((bx, by, h), min(w, d) * 0.45, random_color(rng, 0.2, 0.9))


def clear_sanitiser_stand(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A hand-sanitiser stand: a flat heavy base plate, a post, a dispenser box with a drip tray and a sign."""
    rng = sc.rng
    metal = jitter(rng, pick(rng, (*METAL, (0.1, 0.1, 0.1), (0.95, 0.95, 0.95))))
    h = rng.uniform(1.1, 1.5)
    sc.box((x, y, 0.01), (0.17, 0.17, 0.01), metal, yaw)
    sc.box((x, y, h / 2.0), (0.025, 0.04, h / 2.0), metal, yaw)
    dx, dy = local(x, y, yaw, -0.07, 0.0)
    sc.box((dx, dy, h - 0.2), (0.05, 0.07, 0.12), jitter(rng, pick(rng, ((0.95, 0.95, 0.95), (0.1, 0.1, 0.1)))), yaw)
    sc.box((dx, dy, h - 0.45), (0.05, 0.07, 0.01), metal, yaw)
    sx_, sy_ = local(x, y, yaw, -0.03, 0.0)
    sc.box((sx_, sy_, h + 0.12), (0.005, 0.12, 0.12), jitter(rng, pick(rng, LIGHT_BOXES)), yaw)


def clear_bicycle(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A parked bicycle on its kickstand: two spoked wheels, a diamond frame, a saddle and handlebars."""
    rng = sc.rng
    frame = random_color(rng, 0.05, 0.9)
    r, base = rng.uniform(0.3, 0.35), rng.uniform(0.5, 0.55)  # [m] wheel radius, half wheelbase
    for fx in (-base, base):
        cx, cy = local(x, y, yaw, fx, 0.0)
        ring(sc, (cx, cy, r), yaw + math.pi / 2.0, radius=r - 0.015, tube=0.015, color=(0.06, 0.06, 0.06, 1.0))
        sc.cylinder((cx, cy, r), 0.03, 0.06, jitter(rng, pick(rng, METAL)), yaw=yaw + math.pi / 2.0, roll=math.pi / 2.0)
    crank = (0.0, 0.3)
    seat = (-0.15, r + 0.55)
    head = (base - 0.12, r + 0.5)
    rear, front = (-base, r), (base, r)
    for (ax, az), (bx, bz) in ((rear, crank), (crank, seat), (seat, head), (crank, head), (rear, seat), (head, front)):
        mx, my = local(x, y, yaw, (ax + bx) / 2.0, 0.0)
        length = math.hypot(bx - ax, bz - az)
        sc.capsule((mx, my, (az + bz) / 2.0), 0.017, length, frame, yaw=yaw,
                   pitch=math.pi / 2.0 - math.atan2(bz - az, bx - ax))
    sx_, sy_ = local(x, y, yaw, seat[0] - 0.02, 0.0)
    sc.box((sx_, sy_, seat[1] + 0.05), (0.12, 0.07, 0.03), (0.08, 0.08, 0.08, 1.0), yaw)
    hx, hy = local(x, y, yaw, head[0] - 0.03, 0.0)
    sc.cylinder((hx, hy, head[1] + 0.12), 0.014, 0.5, (0.1, 0.1, 0.1, 1.0), yaw=yaw + math.pi / 2.0, roll=math.pi / 2.0)


def clear_notice_board(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A notice board on two legs with feet: a framed cork or white board with papers pinned on it."""
    rng = sc.rng
    w, h, bottom = rng.uniform(0.8, 1.3), rng.uniform(0.6, 1.0), rng.uniform(0.5, 0.8)
    frame = jitter(rng, pick(rng, (*METAL, (0.1, 0.1, 0.1), (0.5, 0.35, 0.2))))
    board = jitter(rng, pick(rng, ((0.7, 0.55, 0.35), (0.95, 0.95, 0.95), (0.2, 0.3, 0.5))), 0.03)
    for side in (1.0, -1.0):
        lx, ly = local(x, y, yaw, 0.0, side * (w / 2.0 - 0.03))
        sc.box((lx, ly, (bottom + h) / 2.0), (0.02, 0.02, (bottom + h) / 2.0), frame, yaw)
        sc.box((lx, ly, 0.02), (0.2, 0.03, 0.02), frame, yaw)
    sc.box((x, y, bottom + h / 2.0), (0.02, w / 2.0, h / 2.0), board, yaw)
    for _ in range(int(rng.integers(2, 8))):
        px, py = local(x, y, yaw, -0.022, rng.uniform(-0.4, 0.4) * w)
        sc.box((px, py, bottom + rng.uniform(0.15, 0.85) * h), (0.002, 0.08, 0.1), random_color(rng, 0.6, 1.0), yaw)


# -- people with something in front of them or under them, plants (``ENCUMBERED``: the ``extra5`` splits) -----
# Chosen from the failures on ``unseen4`` (a person behind a cart taken for a movable object, a powered-wheelchair
# user taken for furniture) and ``unseen5`` (a potted plant taken for a person or a box), generalised: a walker
# pushing a random wheeled block, a person standing behind any object (the rule: a person anywhere in the region
# means "person"), a person on a random powered base, the same bases empty, and random plants. Nothing from
# ``unseen6`` was looked at; none of them is a held-out model.
def wheeled_block(sc: Scene, x: float, y: float, yaw: float) -> float:
    """A block of random size and colour on castors (a cart, a cabinet on wheels, a laundry trolley), with
    random panels; returns its height [m]."""
    rng = sc.rng
    length, width, h = rng.uniform(0.4, 1.0), rng.uniform(0.35, 0.7), rng.uniform(0.5, 1.2)
    body = random_color(rng, 0.05, 0.95, 0.04) if rng.random() < 0.5 else furniture_color(rng)
    sc.box((x, y, 0.1 + (h - 0.1) / 2.0), (length / 2.0, width / 2.0, (h - 0.1) / 2.0), body, yaw)
    for _ in range(int(rng.integers(0, 5))):  # drawers, doors, labels, bins on the sides
        side = 1.0 if rng.random() < 0.5 else -1.0
        px, py = local(x, y, yaw, rng.uniform(-0.3, 0.3) * length, side * (width / 2.0 + 0.003))
        sc.box((px, py, rng.uniform(0.2, 0.9) * h), (rng.uniform(0.05, 0.45) * length, 0.003, rng.uniform(0.03, 0.2)),
               random_color(rng, 0.0, 1.0), yaw)
    for fx in (length / 2.0 - 0.05, -length / 2.0 + 0.05):
        for fy in (width / 2.0 - 0.05, -width / 2.0 + 0.05):
            wx, wy = local(x, y, yaw, fx, fy)
            sc.sphere((wx, wy, 0.045), 0.045, (0.1, 0.1, 0.1, 1.0))
    return h


def person_block_pusher(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker pushing a :func:`wheeled_block` ahead, the hands on its back edge or on a handle."""
    rng = sc.rng
    ahead = rng.uniform(0.55, 0.9)  # [m] walker's centre to the block's centre; (x, y) half-way between
    s = person_walker(sc, *local(x, y, yaw, -ahead / 2.0, 0.0), yaw)
    h = wheeled_block(sc, *local(x, y, yaw, ahead / 2.0, 0.0), yaw)
    grip_z = min(h + 0.05, 1.1)
    for side in (1.0, -1.0):
        ax, ay = local(x, y, yaw, 0.2 - ahead / 2.0, side * 0.18 * s)
        sc.capsule((ax, ay, grip_z), 0.04 * s, 0.25, jitter(rng, pick(rng, SKIN), 0.03), yaw=yaw, pitch=math.pi / 2.0)


BEHIND_THINGS = ("marked_box", "bin", "suitcase", "tote", "sack", "light_box", "random_furniture", "stool")


def person_behind_thing(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A person (walker, dress walker or capsule) standing 0.3-0.7 m behind an object or a piece of furniture
    as seen from the camera (at the origin, looking along +x), the object at least 1 m away and 0.1-0.35 m to one
    side of the line of sight so that it hides part of the person, not all."""
    rng = sc.rng
    bearing, distance = math.atan2(y, x), math.hypot(x, y)
    gap = rng.uniform(0.3, 0.7)  # [m] along the line of sight
    aside = rng.uniform(0.1, 0.35) * (1.0 if rng.random() < 0.5 else -1.0)  # [m] across it
    near = max(distance - gap / 2.0, 1.0)  # [m] the object no nearer than this: it must not fill the picture
    builder = (person_walker, lambda *a: person_walker(*a, dress=True), person_capsule)[int(rng.integers(3))]
    builder(sc, *local(0.0, 0.0, bearing, near + gap, 0.0), yaw)
    thing = BEHIND_THINGS[int(rng.integers(len(BEHIND_THINGS)))]
    BUILDERS[thing](sc, *local(0.0, 0.0, bearing, near, aside), rng.uniform(-math.pi, math.pi))


def powered_base(sc: Scene, x: float, y: float, yaw: float) -> Tuple[float, float]:
    """A random powered base with a seat (power chair, scooter, ride-on machine): a low deck on four to six
    wheels, a seat on a column or a box, maybe a back, armrests, a tiller or a joystick; facing +x.
    Returns (seat height, deck height) [m]."""
    rng = sc.rng
    body = random_color(rng, 0.05, 0.9, 0.04)
    pad = jitter(rng, pick(rng, UPHOLSTERY))
    length, half_w = rng.uniform(0.6, 1.3), rng.uniform(0.22, 0.34)
    deck_z, deck_h = rng.uniform(0.08, 0.2), rng.uniform(0.05, 0.25)
    sc.box((x, y, deck_z + deck_h / 2.0), (length / 2.0, half_w, deck_h / 2.0), body, yaw)
    wheel_r = rng.uniform(0.06, 0.2)
    axles = (length / 2.0 - 0.1, -length / 2.0 + 0.1) + ((0.0,) if rng.random() < 0.4 else ())
    for fx in axles:
        for side in (1.0, -1.0):
            wx, wy = local(x, y, yaw, fx, side * (half_w + 0.03))
            r = wheel_r if fx == 0.0 or rng.random() < 0.5 else min(wheel_r, 0.08)
            sc.cylinder((wx, wy, r), r, 0.06, (0.07, 0.07, 0.07, 1.0), yaw=yaw, roll=math.pi / 2.0)
    seat_h = rng.uniform(0.5, 0.68)
    top = deck_z + deck_h
    if rng.random() < 0.5:
        sc.cylinder((x, y, (top + seat_h) / 2.0), 0.04, max(seat_h - top, 0.02), body)
    else:
        sc.box((x, y, (top + seat_h) / 2.0), (0.18, half_w - 0.03, max(seat_h - top, 0.02) / 2.0), body, yaw)
    sc.box((x, y, seat_h - 0.04), (0.22, half_w - 0.02, 0.05), pad, yaw)
    if rng.random() < 0.8:
        back_h = rng.uniform(0.2, 0.7)
        bx, by = local(x, y, yaw, -0.24, 0.0)
        sc.box((bx, by, seat_h + back_h / 2.0), (0.05, half_w - 0.04, back_h / 2.0), pad, yaw, -rng.uniform(0.0, 0.2))
    if rng.random() < 0.6:
        for side in (1.0, -1.0):
            ax, ay = local(x, y, yaw, 0.0, side * (half_w - 0.01))
            sc.box((ax, ay, seat_h + 0.22), (0.18, 0.035, 0.025), pad, yaw)
    if rng.random() < 0.5:  # a tiller with handlebars at the front
        tx, ty = local(x, y, yaw, length / 2.0 - 0.2, 0.0)
        sc.box((tx, ty, top + 0.35), (0.03, 0.05, 0.35), body, yaw, -0.3)
        hx, hy = local(x, y, yaw, length / 2.0 - 0.32, 0.0)
        sc.box((hx, hy, top + 0.7), (0.03, 0.22, 0.02), (0.1, 0.1, 0.1, 1.0), yaw)
    return seat_h, top


def person_base_rider(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A person seated on a :func:`powered_base`, feet on the deck."""
    seat_h, top = powered_base(sc, x, y, yaw)
    seated_figure(sc, x, y, yaw, seat_h=seat_h, foot_z=top, hip_fx=-0.1, lean=sc.rng.uniform(-0.05, 0.2),
                  armrest_h=None)


def clear_empty_base(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A :func:`powered_base` with nobody on it (furniture: the robot goes round it)."""
    powered_base(sc, x, y, yaw)


def clear_plant(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A random plant 0.4-2.1 m: a round or square pot (or none: a planter bed), a trunk, stems or nothing,
    foliage as clusters of spheres and leaf-like capsules of random greens, maybe flowers."""
    rng = sc.rng
    pot_h = rng.uniform(0.2, 0.7) if rng.random() < 0.85 else 0.0
    r_pot = rng.uniform(0.12, 0.35)
    if pot_h:
        pot = random_color(rng, 0.05, 0.95, 0.04)
        if rng.random() < 0.6:
            sc.cylinder((x, y, pot_h / 2.0), r_pot, pot_h, pot)
        else:
            sc.box((x, y, pot_h / 2.0), (r_pot, r_pot, pot_h / 2.0), pot, yaw)
    h = pot_h + rng.uniform(0.3, 1.5)
    stems = int(rng.integers(0, 5))
    trunk_top = pot_h + (h - pot_h) * rng.uniform(0.3, 0.8)
    wood = jitter(rng, pick(rng, ((0.35, 0.25, 0.15), (0.25, 0.2, 0.12), (0.3, 0.45, 0.2))), 0.05)
    for _ in range(stems):
        lean = rng.uniform(-0.4, 0.4)
        a = rng.uniform(-math.pi, math.pi)
        length = trunk_top - pot_h
        sc.capsule((x + 0.5 * length * math.sin(lean) * math.cos(a), y + 0.5 * length * math.sin(lean) * math.sin(a),
                    pot_h + 0.5 * length * math.cos(lean)), rng.uniform(0.01, 0.04), length, wood, yaw=a, pitch=lean)
    green = (float(rng.uniform(0.05, 0.4)), float(rng.uniform(0.25, 0.65)), float(rng.uniform(0.05, 0.3)))
    lo = trunk_top if stems else pot_h
    for _ in range(int(rng.integers(5, 25))):
        a, spread = rng.uniform(-math.pi, math.pi), rng.uniform(0.0, 0.45) * (h - pot_h + 0.3)
        px, py, z = x + spread * math.cos(a), y + spread * math.sin(a), rng.uniform(lo, h)
        color = jitter(rng, green, 0.08)
        if rng.random() < 0.5:
            sc.sphere((px, py, z), rng.uniform(0.04, 0.2), color)
        else:
            sc.capsule((px, py, z), rng.uniform(0.015, 0.05), rng.uniform(0.1, 0.4), color,
                       yaw=rng.uniform(-math.pi, math.pi), pitch=rng.uniform(0.3, 1.5))
    if rng.random() < 0.25:  # flowers
        bloom = random_color(rng, 0.5, 1.0)
        for _ in range(int(rng.integers(3, 10))):
            a, spread = rng.uniform(-math.pi, math.pi), rng.uniform(0.0, 0.3)
            sc.sphere((x + spread * math.cos(a), y + spread * math.sin(a), rng.uniform(lo, h + 0.05)), 0.04, bloom)


def clear_empty(sc: Scene, x: float, y: float, yaw: float) -> None:
    """Nothing in front (only the background)."""


Builder = Callable[[Scene, float, float, float], object]  # what a builder returns is not used
BUILDERS: Dict[str, Builder] = {
    "capsule": person_capsule,
    "walker": person_walker,
    "dress_walker": lambda sc, x, y, yaw: person_walker(sc, x, y, yaw, dress=True),
    "mjcf_humanoid": person_mjcf,
    "deepmimic_humanoid": person_deepmimic,
    "box": movable_box,
    "box_pair": movable_box_pair,
    "crate": movable_crate,
    "textured_cube": movable_textured_cube,
    "taped_parcel": movable_taped_parcel,
    "empty": clear_empty,
    "wall": clear_wall,
    "table": clear_table,
    "chair": clear_chair,
    "pillar": clear_pillar,
    "coffee_table": clear_coffee_table,
    "sofa": clear_sofa,
    "bin": movable_bin,
    "cabinet": clear_cabinet,
    "shelf": clear_shelf,
    "urdf_table": clear_urdf_table,
    "bench": clear_bench,
    "bed": clear_bed,
    "door_frame": clear_door_frame,
    "stool": clear_stool,
    "ottoman": clear_ottoman,
    "sideboard": clear_sideboard,
    "cart": clear_cart,
    "radiator": clear_radiator,
    "seat_row": clear_seat_row,
    "gurney": clear_gurney,
    "desk": clear_desk,
    "corridor": clear_corridor,
    "light_box": movable_light_box,
    "suitcase": movable_suitcase,
    "passage_box": movable_passage_box,
    "tote": movable_tote,
    "sack": movable_sack,
    "random_furniture": clear_random_furniture,
    "marked_box": movable_marked_box,
    "child_walker": person_child,
    "bag_walker": person_with_bag,
    "cooler": movable_cooler,
    "drum": movable_drum,
    "wrapped_parcel": movable_wrapped_parcel,
    "bookcase": clear_bookcase,
    "coat_rack": clear_coat_rack,
    "pedestal_table": clear_pedestal_table,
    "partition": clear_partition,
    "wheelchair_user": person_wheelchair_user,
    "crutch_walker": person_crutch_walker,
    "linen_bag": movable_linen_bag,
    "trunk": movable_trunk,
    "parcel_stack": movable_parcel_stack,
    "iv_stand": clear_iv_stand,
    "wardrobe": clear_wardrobe,
    "vending_machine": clear_vending_machine,
    "power_chair_user": person_power_chair_user,
    "cart_pusher": person_cart_pusher,
    "lidded_tub": movable_lidded_tub,
    "duffel_bag": movable_duffel_bag,
    "bottle_pack": movable_bottle_pack,
    "floor_lamp": clear_floor_lamp,
    "fridge": clear_fridge,
    "photocopier": clear_photocopier,
    "seated_person": person_seated,
    "wheelchair_rider": person_wheelchair_rider,
    "frame_walker": person_frame_walker,
    "trolley_pusher": person_trolley_pusher,
    "castor_pole": clear_castor_pole,
    "tall_appliance": clear_tall_appliance,
    "locker": clear_locker,
    "empty_wheelchair": clear_empty_wheelchair,
    "kneeler": person_kneeler,
    "box_carrier": person_box_carrier,
    "stroller_pusher": person_stroller_pusher,
    "laundry_basket": movable_laundry_basket,
    "flat_pack": movable_flat_pack,
    "water_jugs": movable_water_jugs,
    "potted_plant": clear_potted_plant,
    "reception_counter": clear_reception_counter,
    "chair_stack": clear_chair_stack,
    "person_pair": person_pair,
    "hi_vis_worker": person_hi_vis_worker,
    "scooter_rider": person_scooter_rider,
    "rolled_rug": movable_rolled_rug,
    "crate_stack": movable_crate_stack,
    "carrier_bags": movable_carrier_bags,
    "sanitiser_stand": clear_sanitiser_stand,
    "bicycle": clear_bicycle,
    "notice_board": clear_notice_board,
    "block_pusher": person_block_pusher,
    "behind_thing": person_behind_thing,
    "base_rider": person_base_rider,
    "empty_base": clear_empty_base,
    "plant": clear_plant,
}
DISTANCES: Dict[str, Tuple[float, float]] = {  # [m] camera to target centre
    PERSON: (0.5, 2.2),
    MOVABLE: (0.55, 1.8),
    CLEAR: (0.5, 2.5),
}
SIDE_DISTRACTORS = ("capsule", "walker", "box", "table", "chair", "pillar", "bin", "cabinet")


class Renderer:
    """Renders samples in one DIRECT BulletClient, reset between samples."""

    def __init__(self, rng: np.random.Generator) -> None:
        from pybullet_utils import bullet_client

        self.client = bullet_client.BulletClient(connection_mode=pybullet.DIRECT)
        self.rng = rng
        self.cameras = {name: load_profile(name).camera for name in PROFILES}

    def close(self) -> None:
        self.client.disconnect()

    def render(self, label: str, model: str) -> Sample:
        rng, c = self.rng, self.client
        c.resetSimulation()
        sc = Scene(c, rng)
        profile = PROFILES[int(rng.integers(len(PROFILES)))]
        spec = self.cameras[profile]
        assert spec is not None
        eye_z = spec.mount[2] + rng.uniform(-0.03, 0.03)
        pitch = spec.pitch + math.radians(rng.uniform(-3.0, 3.0))
        eye = (spec.mount[0], 0.0, eye_z)
        sc.floor(jitter(rng, pick(rng, FLOORS), 0.05))
        self._background(sc, spec)
        roi_half = math.atan(0.6 * math.tan(spec.hfov / 2.0))  # [rad] half-angle of the default ROI
        distance = 0.0
        if model != "empty":
            lo, hi = DISTANCES[label]
            distance = rng.uniform(lo, hi)
            bearing = rng.uniform(-0.5, 0.5) * roi_half
            x, y = eye[0] + distance * math.cos(bearing), distance * math.sin(bearing)
            BUILDERS[model](sc, x, y, rng.uniform(-math.pi, math.pi))
        self._side_distractors(sc, roi_half, spec)
        rgb, depth = self._shoot(spec, eye, pitch)
        return Sample(rgb, depth, label, model, profile, distance)

    def _background(self, sc: Scene, spec: CameraSpec) -> None:
        rng = sc.rng
        for _ in range(int(rng.integers(0, 4))):  # room walls: long enough that their ends rarely show
            d = rng.uniform(2.8, 7.0)
            b = rng.uniform(-1.2, 1.2)
            sc.wall((d * math.cos(b), d * math.sin(b)), rng.uniform(10.0, 20.0), rng.uniform(0.6, 2.5),
                    b + math.pi / 2.0 + rng.uniform(-0.5, 0.5), jitter(rng, pick(rng, WALLS)))

    def _side_distractors(self, sc: Scene, roi_half: float, spec: CameraSpec) -> None:
        rng = sc.rng
        for _ in range(int(rng.integers(0, 3))):
            model = SIDE_DISTRACTORS[int(rng.integers(len(SIDE_DISTRACTORS)))]
            d = rng.uniform(1.2, 4.0)
            margin = math.asin(min(0.9 / d, 1.0))  # [rad] keeps objects up to 0.9 m wide out of the ROI
            side = 1.0 if rng.random() < 0.5 else -1.0
            b = side * rng.uniform(roi_half + margin, roi_half + margin + 0.5)
            BUILDERS[model](sc, d * math.cos(b), d * math.sin(b), rng.uniform(-math.pi, math.pi))

    def _shoot(self, spec: CameraSpec, eye: Vec3, pitch: float) -> Tuple[np.ndarray, np.ndarray]:
        rng, c = self.rng, self.client
        cp, sp = math.cos(pitch), math.sin(pitch)
        view = c.computeViewMatrix(list(eye), [eye[0] + cp, eye[1], eye[2] - sp], [sp, 0.0, cp])
        projection = c.computeProjectionMatrixFOV(math.degrees(spec.vfov), spec.width / spec.height, spec.near,
                                                  spec.far)
        light: Dict[str, Any] = {}
        if rng.random() < 0.7:  # else the simulator's default lighting
            az, el = rng.uniform(-math.pi, math.pi), rng.uniform(0.3, 1.4)
            light = {
                "lightDirection": [math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)],
                "lightColor": [float(v) for v in rng.uniform(0.85, 1.0, 3)],
                "lightAmbientCoeff": float(rng.uniform(0.3, 0.8)),
                "lightDiffuseCoeff": float(rng.uniform(0.3, 0.8)),
                "lightSpecularCoeff": float(rng.uniform(0.0, 0.3)),
            }
        _, _, rgba, depth, _ = c.getCameraImage(
            spec.width, spec.height, view, projection, renderer=pybullet.ER_TINY_RENDERER,
            flags=pybullet.ER_NO_SEGMENTATION_MASK, shadow=0, **light,
        )
        image = np.asarray(rgba, dtype=np.uint8).reshape(spec.height, spec.width, 4)
        metric = depth_from_buffer(depth, spec.width, spec.height, spec.near, spec.far)
        return np.ascontiguousarray(image[:, :, :3]), metric


HELD_OUT_SETS: Dict[str, Dict[str, Tuple[str, ...]]] = {  # held-out split: its models, in the order defined
    "unseen": HELD_OUT, "unseen2": HELD_OUT_2, "unseen3": HELD_OUT_3, "unseen4": HELD_OUT_4,
    "unseen5": HELD_OUT_5, "unseen6": HELD_OUT_6,
}
OWN_MODELS: Dict[str, Dict[str, Tuple[str, ...]]] = {  # splits with models of their own (the others: models_for)
    **HELD_OUT_SETS,
    "extra2": PASSAGE, "val_extra2": PASSAGE,
    "extra3": PROCEDURAL, "val_extra3": PROCEDURAL,
    "extra4": ASSISTIVE, "val_extra4": ASSISTIVE,
    "extra5": ENCUMBERED, "val_extra5": ENCUMBERED,
}


def models_for(split: str) -> Dict[str, Tuple[str, ...]]:
    """The models of each label used in a split: ``train``/``val``/``test`` (seen), ``unseen`` (held out),
    ``extra``/``val_extra`` (the seen ones and the training-only ones, :data:`TRAIN_ONLY`), ``extra2``/``val_extra2``
    (:data:`PASSAGE`), ``extra3``/``val_extra3`` (:data:`PROCEDURAL`), ``extra4``/``val_extra4``
    (:data:`ASSISTIVE`), ``extra5``/``val_extra5`` (:data:`ENCUMBERED`), ``unseen2`` (:data:`HELD_OUT_2`),
    ``unseen3`` (:data:`HELD_OUT_3`), ``unseen4`` (:data:`HELD_OUT_4`), ``unseen5`` (:data:`HELD_OUT_5`),
    ``unseen6`` (:data:`HELD_OUT_6`)."""
    if split in OWN_MODELS:
        return OWN_MODELS[split]
    if split in EXTRA_SPLITS:
        return {label: TRAIN_MODELS[label] + TRAIN_ONLY[label] for label in TRAIN_MODELS}
    return TRAIN_MODELS


def plan(labels: Sequence[str], per_label: int, split: str, rng: np.random.Generator,
         offset: int = 0) -> List[Tuple[str, str]]:
    """(label, model) pairs: ``per_label`` per label, models cycled evenly from ``offset``, shuffled."""
    pairs: List[Tuple[str, str]] = []
    for label in labels:
        models = models_for(split)[label]
        pairs.extend((label, models[(i + offset) % len(models)]) for i in range(per_label))
    order = rng.permutation(len(pairs))
    return [pairs[i] for i in order]
