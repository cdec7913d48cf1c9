"""The first held-out set: the ``unseen`` split only. The DeepMimic humanoid of pybullet_data and a walker in a
dress; an open-top crate, pybullet_data's textured cube, a taped parcel; pybullet_data's table, a bench, a hospital
bed, a door frame with the way through it clear.
"""

from __future__ import annotations

import math
import os

from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from flex_nav_sim.world import DEFAULT_COLORS
from tools.perception.held_out.registry import held_out
from tools.perception.scene_base import (
    BOXES,
    DATA,
    WALLS,
    Rgba,
    Scene,
    clothing_colors,
    color_links,
    furniture_color,
    jitter,
    local,
    person_walker,
    pick,
    quiet_output,
    stand_on_floor,
)

SET = "unseen"


@held_out(SET, PERSON, "deepmimic_humanoid")
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
    wear = clothing_colors(sc)

    def colour(link: str) -> Rgba:
        if "ankle" in link:
            return wear["shoes"]
        if "hip" in link or "knee" in link or link == "base":
            return wear["trousers"]
        if "wrist" in link or "neck" in link:
            return wear["skin"]
        return wear["shirt"]

    color_links(sc, body, colour)
    stand_on_floor(sc, body, x, y, orn)


@held_out(SET, PERSON, "dress_walker")
def person_dress_walker(sc: Scene, x: float, y: float, yaw: float) -> None:
    """The walker in a dress."""
    person_walker(sc, x, y, yaw, dress=True)


@held_out(SET, MOVABLE, "crate")
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


@held_out(SET, MOVABLE, "textured_cube")
def movable_textured_cube(sc: Scene, x: float, y: float, yaw: float) -> None:
    """pybullet_data's textured cube.urdf, scaled to 0.25-0.55 m."""
    rng, c = sc.rng, sc.c
    size = rng.uniform(0.25, 0.55)
    c.loadURDF(os.path.join(DATA, "cube.urdf"), [x, y, size / 2.0], c.getQuaternionFromEuler([0.0, 0.0, yaw]),
               globalScaling=size, useFixedBase=True)


@held_out(SET, MOVABLE, "taped_parcel")
def movable_taped_parcel(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A cardboard box with a tape band around it and a white label."""
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.25, 0.6), rng.uniform(0.25, 0.6), rng.uniform(0.2, 0.55)
    sc.box((x, y, sz / 2.0), (sx / 2.0, sy / 2.0, sz / 2.0), jitter(rng, BOXES[int(rng.integers(4))]), yaw)
    tape = jitter(rng, pick(rng, ((0.6, 0.45, 0.25), (0.2, 0.2, 0.2), (0.85, 0.85, 0.8), (0.8, 0.2, 0.1))), 0.03)
    sc.box((x, y, sz / 2.0), (0.03, sy / 2.0 + 0.003, sz / 2.0 + 0.003), tape, yaw)
    lx, ly = local(x, y, yaw, -sx / 2.0 - 0.002, sy * 0.2)
    sc.box((lx, ly, sz * 0.55), (0.002, sy * 0.12, sz * 0.12), (0.95, 0.95, 0.95, 1.0), yaw)


@held_out(SET, CLEAR, "urdf_table")
def clear_urdf_table(sc: Scene, x: float, y: float, yaw: float) -> None:
    """pybullet_data's textured table.urdf (0.6 m high), scaled 0.9-1.3."""
    c = sc.c
    c.loadURDF(os.path.join(DATA, "table", "table.urdf"), [x, y, 0.0], c.getQuaternionFromEuler([0.0, 0.0, yaw]),
               globalScaling=float(sc.rng.uniform(0.9, 1.3)), useFixedBase=True)


@held_out(SET, CLEAR, "bench")
def clear_bench(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A long bench on two slab legs."""
    rng = sc.rng
    length, depth, h = rng.uniform(1.2, 1.8), rng.uniform(0.35, 0.45), rng.uniform(0.42, 0.48)
    color = furniture_color(rng)
    sc.box((x, y, h), (depth / 2.0, length / 2.0, 0.03), color, yaw)
    for fy in (length / 2.0 - 0.1, -length / 2.0 + 0.1):
        px, py = local(x, y, yaw, 0.0, fy)
        sc.box((px, py, h / 2.0), (depth / 2.0 - 0.02, 0.03, h / 2.0), color, yaw)


@held_out(SET, CLEAR, "bed")
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


@held_out(SET, CLEAR, "door_frame")
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
