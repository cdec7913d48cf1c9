"""The held-out models of the classifier's dataset: twelve sets of people, pushable objects and furniture
(``HELD_OUT`` .. ``HELD_OUT_12``, the ``unseen`` .. ``unseen12`` splits), each defined, rendered and measured
before the training data that followed it, and never used in a training or selection split
(``test/unit/perception/test_dataset_tools.py``). Frozen: changing a builder here changes a stored held-out
split, so a new held-out set is a new table, new builders and an entry in :data:`HELD_OUT_SETS`.
"""

from __future__ import annotations

import math
import os
from typing import Dict, Tuple

import numpy as np

from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from flex_nav_sim.world import DEFAULT_COLORS
from tools.perception.scene_base import (
    BOXES,
    CLOTHES,
    DATA,
    FRAMES,
    FURNITURE,
    LIGHT_BOXES,
    METAL,
    SHOES,
    SKIN,
    UPHOLSTERY,
    WALLS,
    Builder,
    Rgba,
    Scene,
    Vec3,
    arms_forward,
    box_color,
    castor_star,
    clothing_colors,
    color_links,
    furniture_color,
    jitter,
    limb,
    local,
    person_walker,
    pick,
    quiet_output,
    random_color,
    ring,
    round_or_square_top,
    seated_figure,
    stand_on_floor,
)

HELD_OUT: Dict[str, Tuple[str, ...]] = {
    PERSON: ("deepmimic_humanoid", "dress_walker"),
    MOVABLE: ("crate", "textured_cube", "taped_parcel"),
    CLEAR: ("urdf_table", "bench", "bed", "door_frame"),
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

HELD_OUT_7: Dict[str, Tuple[str, ...]] = {  # the ``unseen7`` split: defined before a height-channel model was measured
    PERSON: ("iv_patient", "mop_cleaner", "floor_sitter"),
    MOVABLE: ("exercise_ball", "cushion_pile", "toy_car"),
    CLEAR: ("patient_hoist", "upright_piano", "aquarium"),
}

HELD_OUT_8: Dict[str, Tuple[str, ...]] = {  # the ``unseen8`` split: defined before an extra6 model was measured
    PERSON: ("reaching_up", "dog_walker", "bench_sleeper"),
    MOVABLE: ("pet_carrier", "bean_bag", "toolbox"),
    CLEAR: ("step_ladder", "pedestal_fan", "kiosk"),
}
HELD_OUT_9: Dict[str, Tuple[str, ...]] = {  # the ``unseen9`` split: defined before the extra7 data was written
    PERSON: ("bending_picker", "box_sitter", "hooded_coat"),
    MOVABLE: ("bucket_stack", "drawer_unit", "dolly_parcel"),
    CLEAR: ("washing_machine", "treadmill", "easel"),
}
HELD_OUT_10: Dict[str, Tuple[str, ...]] = {  # the ``unseen10`` split: defined before an extra7 model was measured
    PERSON: ("shoulder_carry", "cane_elder", "bike_walker"),
    MOVABLE: ("hamper", "tray_stack", "tube_bundle"),
    CLEAR: ("grandfather_clock", "water_cooler", "ironing_board"),
}
HELD_OUT_11: Dict[str, Tuple[str, ...]] = {  # the ``unseen11`` split: defined before the extra8 data was written
    PERSON: ("stretcher_patient", "panel_carrier", "knee_scooter_rider"),
    MOVABLE: ("wet_floor_sign", "pedal_bin", "kick_stool"),
    CLEAR: ("ultrasound_cart", "lectern", "structural_pillar"),  # (the seen "pillar" is a plain column)
}
HELD_OUT_12: Dict[str, Tuple[str, ...]] = {  # the ``unseen12`` split: defined after extra8 was written, before training
    PERSON: ("umbrella_holder", "ladder_carrier", "tricycle_child"),
    MOVABLE: ("watering_can", "gift_box", "ball_bag"),
    CLEAR: ("ticket_barrier", "bollards", "overbed_table"),
}


# -- the first held-out set (``HELD_OUT``: the ``unseen`` split only) -------------------------------------
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


# -- the fourth held-out set (``HELD_OUT_4``: the ``unseen4`` split only) ------------------------------------
# Defined before any model was trained with seated people, castor poles or tall appliances (``ASSISTIVE``):
# new instances of those families, and new pushable objects.
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
    arms_forward(sc, x, y, yaw, fx=0.17, z=handle_z, scale=s, length=0.22)


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


# -- the seventh held-out set (``HELD_OUT_7``: the ``unseen7`` split only) ----------------------------------
# Defined, rendered and measured with the shipped model before any model trained with a height channel was
# looked at: a patient walking with a drip pole, a cleaner bent over a mop, a person sitting on the floor; an
# exercise ball, a pile of cushions, a ride-on toy car; a patient hoist, an upright piano, an aquarium on a stand.
PLASTIC: Tuple[Vec3, ...] = ((0.9, 0.15, 0.15), (0.15, 0.35, 0.85), (0.95, 0.8, 0.1), (0.2, 0.65, 0.3),
                             (0.6, 0.25, 0.7), (0.95, 0.5, 0.1))


def person_iv_patient(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A patient in a gown walking beside a drip pole on a castor star, one hand on the pole."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw, dress=rng.random() < 0.7)
    side = 1.0 if rng.random() < 0.5 else -1.0
    px, py = local(x, y, yaw, rng.uniform(0.0, 0.25), side * rng.uniform(0.35, 0.45) * s)
    metal = jitter(rng, pick(rng, METAL))
    castor_star(sc, px, py, rng.uniform(0.0, math.pi), feet=5, reach=0.28, arm_z=0.06, arm_half=(0.02, 0.015),
                color=metal)
    top = rng.uniform(1.7, 2.0)
    sc.cylinder((px, py, top / 2.0), 0.013, top, metal)
    for k in range(int(rng.integers(1, 3))):
        bx, by = local(px, py, yaw, 0.0, (k - 0.5) * 0.12)
        sc.box((bx, by, top - 0.2), (0.02, 0.06, 0.1), (0.9, 0.93, 0.95, 1.0), yaw)
    hand = (x + px) / 2.0, (y + py) / 2.0
    skin = jitter(rng, pick(rng, SKIN), 0.03)
    sc.capsule((hand[0], hand[1], 1.05 * s), 0.04 * s, 0.25 * s, skin, yaw=yaw + side * 1.5, pitch=math.pi / 2.0)


def person_mop_cleaner(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A cleaner bent over a mop: straight legs, the torso leaning forward, both hands on the handle, the mop head
    on the floor ahead and a wheeled mop bucket beside them."""
    rng = sc.rng
    s = rng.uniform(0.9, 1.1)
    trousers, shirt = jitter(rng, pick(rng, CLOTHES)), jitter(rng, pick(rng, CLOTHES))
    skin, shoes = jitter(rng, pick(rng, SKIN), 0.03), jitter(rng, pick(rng, SHOES), 0.03)
    hip_h, hip_w, leg_r = 0.9 * s, 0.1 * s, rng.uniform(0.055, 0.075) * s
    for side in (1.0, -1.0):
        hx, hy = local(x, y, yaw, 0.0, side * hip_w)
        sc.capsule((hx, hy, hip_h / 2.0 + 0.02), leg_r, hip_h - 2.0 * leg_r, trousers, yaw=yaw)
        fx, fy = local(x, y, yaw, 0.06, side * hip_w)
        sc.box((fx, fy, 0.04), (0.13 * s, 0.05 * s, 0.04), shoes, yaw)
    lean = rng.uniform(0.3, 0.8)  # [rad] forward
    torso_h, width, depth = rng.uniform(0.5, 0.6) * s, rng.uniform(0.34, 0.42) * s, rng.uniform(0.2, 0.26) * s
    up = (math.sin(lean), math.cos(lean))
    cx, cy = local(x, y, yaw, up[0] * torso_h / 2.0, 0.0)
    sc.box((cx, cy, hip_h + up[1] * torso_h / 2.0), (depth / 2.0, width / 2.0, torso_h / 2.0), shirt, yaw, lean)
    hx, hy = local(x, y, yaw, up[0] * (torso_h + 0.14 * s), 0.0)
    sc.sphere((hx, hy, hip_h + up[1] * (torso_h + 0.14 * s)), 0.1 * s, skin)
    mop_fx = rng.uniform(0.7, 1.0)  # [m] the mop head ahead of the feet
    grip_fx, grip_z = up[0] * torso_h + 0.2, hip_h + up[1] * torso_h - 0.35
    for side in (1.0, -1.0):
        sx_, sy_ = local(x, y, yaw, (up[0] * (torso_h - 0.05) + grip_fx) / 2.0, side * 0.12 * s)
        sc.capsule((sx_, sy_, (hip_h + up[1] * (torso_h - 0.05) + grip_z) / 2.0), 0.04 * s, 0.3 * s, shirt, yaw=yaw,
                   pitch=0.6)
    tilt = math.atan2(mop_fx - grip_fx, grip_z)
    length = math.hypot(mop_fx - grip_fx, grip_z) + 0.25
    mx, my = local(x, y, yaw, (grip_fx + mop_fx) / 2.0, 0.0)
    sc.capsule((mx, my, grip_z / 2.0 + 0.05), 0.014, length, jitter(rng, pick(rng, METAL)), yaw=yaw, pitch=tilt)
    headx, heady = local(x, y, yaw, mop_fx, 0.0)
    sc.box((headx, heady, 0.03), (0.08, 0.2, 0.03), jitter(rng, (0.85, 0.85, 0.8)), yaw)
    if rng.random() < 0.7:  # the bucket on castors
        bx, by = local(x, y, yaw, 0.3, (1.0 if rng.random() < 0.5 else -1.0) * 0.5)
        bucket = jitter(rng, pick(rng, ((0.95, 0.8, 0.1), (0.2, 0.35, 0.8), (0.85, 0.15, 0.15))))
        sc.box((bx, by, 0.2), (0.2, 0.15, 0.15), bucket, yaw)
        sc.box((bx, by, 0.42), (0.06, 0.12, 0.08), (0.2, 0.2, 0.2, 1.0), yaw)


def person_floor_sitter(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A person sitting on the floor (fallen, or resting against nothing): legs along the floor, the torso upright
    or leaning back, the hands on the lap."""
    rng = sc.rng
    seated_figure(sc, x, y, yaw, seat_h=0.0, foot_z=0.0, hip_fx=0.0, lean=rng.uniform(0.0, 0.5))


def movable_exercise_ball(sc: Scene, x: float, y: float, yaw: float) -> None:
    """An inflated exercise ball (0.45-0.75 m across) on the floor, with a seam around it."""
    rng = sc.rng
    r = rng.uniform(0.22, 0.38)
    color = jitter(rng, pick(rng, (*PLASTIC, (0.5, 0.5, 0.55), (0.1, 0.1, 0.12))))
    sc.sphere((x, y, r), r, color)
    ring(sc, (x, y, r), yaw, radius=r, tube=0.006, color=(color[0] * 0.7, color[1] * 0.7, color[2] * 0.7, 1.0),
         segments=16)


def movable_cushion_pile(sc: Scene, x: float, y: float, yaw: float) -> None:
    """Two to five square cushions or folded blankets piled on the floor, each a little turned and tilted."""
    rng = sc.rng
    z = 0.0
    for _ in range(int(rng.integers(2, 6))):
        half, thick = rng.uniform(0.2, 0.3), rng.uniform(0.05, 0.09)
        cx, cy = local(x, y, yaw, rng.uniform(-0.06, 0.06), rng.uniform(-0.06, 0.06))
        sc.box((cx, cy, z + thick), (half, half * rng.uniform(0.8, 1.0), thick), random_color(rng, 0.25, 0.95),
               yaw + rng.uniform(-0.5, 0.5), rng.uniform(-0.08, 0.08))
        z += 2.0 * thick - 0.01


def movable_toy_car(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A children's ride-on toy car: a moulded plastic body on four wheels, a seat, a steering wheel."""
    rng = sc.rng
    length, width = rng.uniform(0.7, 0.95), rng.uniform(0.38, 0.5)
    body = jitter(rng, pick(rng, PLASTIC))
    wheel_r = rng.uniform(0.07, 0.1)
    sc.box((x, y, wheel_r + 0.12), (length / 2.0, width / 2.0, 0.12), body, yaw)
    bx, by = local(x, y, yaw, length * 0.3, 0.0)
    sc.box((bx, by, wheel_r + 0.28), (length * 0.15, width / 2.0 - 0.02, 0.06), body, yaw, -0.3)  # bonnet
    sx_, sy_ = local(x, y, yaw, -length * 0.15, 0.0)
    sc.box((sx_, sy_, wheel_r + 0.26), (0.1, width / 2.0 - 0.06, 0.03), (0.1, 0.1, 0.1, 1.0), yaw)  # seat
    rx, ry = local(x, y, yaw, -length * 0.3, 0.0)
    sc.box((rx, ry, wheel_r + 0.34), (0.03, width / 2.0 - 0.06, 0.1), body, yaw)  # seat back
    for fx in (length * 0.35, -length * 0.35):
        for side in (1.0, -1.0):
            wx, wy = local(x, y, yaw, fx, side * (width / 2.0 + 0.02))
            sc.cylinder((wx, wy, wheel_r), wheel_r, 0.05, (0.1, 0.1, 0.1, 1.0), yaw=yaw + math.pi / 2.0,
                        roll=math.pi / 2.0)
    hx, hy = local(x, y, yaw, length * 0.1, 0.0)
    ring(sc, (hx, hy, wheel_r + 0.42), yaw + math.pi / 2.0, radius=0.09, tube=0.012, color=(0.15, 0.15, 0.15, 1.0),
         segments=10)


def clear_patient_hoist(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A mobile patient hoist: a U-shaped base on castors, a mast, a boom reaching forward and a spreader bar
    hanging from it (a sling folded on the bar sometimes)."""
    rng = sc.rng
    metal = jitter(rng, pick(rng, (*METAL, (0.95, 0.95, 0.95))))
    leg, gap = rng.uniform(0.9, 1.2), rng.uniform(0.25, 0.35)
    for side in (1.0, -1.0):
        lx, ly = local(x, y, yaw, leg / 2.0, side * gap)
        sc.box((lx, ly, 0.07), (leg / 2.0, 0.03, 0.03), metal, yaw)
        for fx in (0.0, leg):
            cx, cy = local(x, y, yaw, fx, side * gap)
            sc.sphere((cx, cy, 0.035), 0.035, (0.1, 0.1, 0.1, 1.0))
    sc.box((x, y, 0.07), (0.06, gap, 0.04), metal, yaw)
    mast = rng.uniform(1.3, 1.7)
    sc.box((x, y, mast / 2.0), (0.045, 0.045, mast / 2.0), metal, yaw)
    boom = rng.uniform(0.7, 0.9)
    bx, by = local(x, y, yaw, boom / 2.0, 0.0)
    sc.box((bx, by, mast - 0.05), (boom / 2.0, 0.035, 0.035), metal, yaw, -0.15)
    tx, ty = local(x, y, yaw, boom, 0.0)
    drop = rng.uniform(0.2, 0.4)
    sc.cylinder((tx, ty, mast + 0.08 - drop / 2.0), 0.01, drop, (0.2, 0.2, 0.2, 1.0))
    sc.box((tx, ty, mast + 0.08 - drop), (0.03, 0.25, 0.02), metal, yaw)
    sc.box((x, y, 0.9), (0.08, 0.07, 0.12), jitter(rng, pick(rng, ((0.95, 0.95, 0.95), (0.2, 0.35, 0.7)))), yaw)
    if rng.random() < 0.4:
        sc.box((tx, ty, mast + 0.08 - drop - 0.1), (0.04, 0.22, 0.08), jitter(rng, (0.3, 0.5, 0.75)), yaw)


def clear_upright_piano(sc: Scene, x: float, y: float, yaw: float) -> None:
    """An upright piano: a tall case, a keyboard shelf sticking out at 0.7 m with white and black keys, a
    fall board, two front legs under the keys."""
    rng = sc.rng
    wood = jitter(rng, pick(rng, ((0.08, 0.06, 0.05), (0.35, 0.2, 0.12), (0.55, 0.38, 0.22), (0.92, 0.9, 0.86))))
    w, d, h = rng.uniform(1.4, 1.55), rng.uniform(0.5, 0.62), rng.uniform(1.05, 1.3)
    sc.box((x, y, h / 2.0), (d / 2.0, w / 2.0, h / 2.0), wood, yaw)
    kx, ky = local(x, y, yaw, d / 2.0 + 0.14, 0.0)
    sc.box((kx, ky, 0.7), (0.14, w / 2.0 - 0.06, 0.05), wood, yaw)
    keys_x, keys_y = local(x, y, yaw, d / 2.0 + 0.16, 0.0)
    sc.box((keys_x, keys_y, 0.755), (0.08, w / 2.0 - 0.12, 0.008), (0.95, 0.95, 0.92, 1.0), yaw)
    for k in range(24):
        bx, by = local(x, y, yaw, d / 2.0 + 0.12, (k / 23.0 - 0.5) * (w - 0.3))
        sc.box((bx, by, 0.768), (0.04, 0.008, 0.008), (0.05, 0.05, 0.05, 1.0), yaw)
    for side in (1.0, -1.0):
        lx, ly = local(x, y, yaw, d / 2.0 + 0.22, side * (w / 2.0 - 0.1))
        sc.box((lx, ly, 0.33), (0.03, 0.03, 0.33), wood, yaw)
    fx, fy = local(x, y, yaw, d / 2.0 + 0.02, 0.0)
    sc.box((fx, fy, 0.95), (0.02, w / 2.0 - 0.08, 0.18), wood, yaw, -0.1)


def clear_aquarium(sc: Scene, x: float, y: float, yaw: float) -> None:
    """An aquarium on a cabinet stand: the tank's blue-green water, gravel, plants and fish, a dark lid."""
    rng = sc.rng
    w, d = rng.uniform(0.8, 1.3), rng.uniform(0.35, 0.5)
    stand_h, tank_h = rng.uniform(0.65, 0.8), rng.uniform(0.4, 0.6)
    sc.box((x, y, stand_h / 2.0), (d / 2.0, w / 2.0, stand_h / 2.0), furniture_color(rng), yaw)
    water = jitter(rng, pick(rng, ((0.45, 0.7, 0.8), (0.35, 0.6, 0.55), (0.55, 0.75, 0.85))), 0.04)
    sc.box((x, y, stand_h + tank_h / 2.0), (d / 2.0 - 0.01, w / 2.0 - 0.01, tank_h / 2.0), water, yaw)
    gx, gy = local(x, y, yaw, 0.003, 0.0)
    sc.box((gx, gy, stand_h + 0.04), (d / 2.0 - 0.005, w / 2.0 - 0.005, 0.04), jitter(rng, (0.7, 0.6, 0.45)), yaw)
    face = d / 2.0
    for _ in range(int(rng.integers(2, 5))):
        px, py = local(x, y, yaw, face, rng.uniform(-0.4, 0.4) * w)
        ph = rng.uniform(0.15, 0.35)
        sc.capsule((px, py, stand_h + 0.08 + ph / 2.0), 0.02, ph, jitter(rng, (0.2, 0.55, 0.25)))
    for _ in range(int(rng.integers(3, 8))):
        fx, fy = local(x, y, yaw, face, rng.uniform(-0.45, 0.45) * w)
        sc.sphere((fx, fy, stand_h + rng.uniform(0.15, 0.9) * tank_h), rng.uniform(0.015, 0.03),
                  random_color(rng, 0.5, 1.0))
    sc.box((x, y, stand_h + tank_h + 0.03), (d / 2.0, w / 2.0, 0.03), (0.08, 0.08, 0.08, 1.0), yaw)


# -- the eighth held-out set (``HELD_OUT_8``: the ``unseen8`` split only) -----------------------------------
# Defined, rendered and measured with the shipped model while the models trained with ``extra6`` were training,
# before any of them was measured: a person reaching up with both arms, a person walking a dog, a person lying on
# a bench; a pet carrier, a bean bag, a toolbox; a step ladder, a pedestal fan, a ticket kiosk.
def person_reaching_up(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker-built person with both arms raised (reaching for a high shelf), sometimes on tiptoe."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw)
    sleeve = jitter(rng, pick(rng, CLOTHES))
    shoulder = 0.9 * s + 0.55 * s
    for side in (1.0, -1.0):
        ax, ay = local(x, y, yaw, rng.uniform(0.0, 0.15), side * 0.22 * s)
        sc.capsule((ax, ay, shoulder + 0.3 * s), 0.045 * s, 0.55 * s, sleeve, yaw=yaw, pitch=rng.uniform(-0.3, 0.1))
        hx, hy = local(x, y, yaw, 0.05, side * 0.22 * s)
        sc.sphere((hx, hy, shoulder + 0.62 * s), 0.045 * s, jitter(rng, pick(rng, SKIN), 0.03))


def person_dog_walker(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker with a dog on a lead beside or ahead of them (the dog: body, legs, head, tail)."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw)
    side = 1.0 if rng.random() < 0.5 else -1.0
    dx, dy = local(x, y, yaw, rng.uniform(0.2, 0.7), side * rng.uniform(0.4, 0.7))
    size = rng.uniform(0.6, 1.2)
    fur = jitter(rng, pick(rng, ((0.1, 0.08, 0.06), (0.55, 0.4, 0.2), (0.85, 0.75, 0.55), (0.95, 0.95, 0.9),
                                 (0.4, 0.4, 0.42))))
    body_z, length = 0.35 * size, 0.5 * size
    sc.capsule((dx, dy, body_z), 0.1 * size, length, fur, yaw=yaw, pitch=math.pi / 2.0)
    for fx in (length / 2.0, -length / 2.0):
        for fy in (0.06 * size, -0.06 * size):
            lx, ly = local(dx, dy, yaw, fx, fy)
            sc.capsule((lx, ly, body_z / 2.0), 0.025 * size, body_z - 0.05, fur, yaw=yaw)
    hx, hy = local(dx, dy, yaw, length / 2.0 + 0.15 * size, 0.0)
    sc.sphere((hx, hy, body_z + 0.15 * size), 0.09 * size, fur)
    tx, ty = local(dx, dy, yaw, -length / 2.0 - 0.1 * size, 0.0)
    sc.capsule((tx, ty, body_z + 0.08 * size), 0.015 * size, 0.2 * size, fur, yaw=yaw, pitch=-0.6)
    hand_x, hand_y = local(x, y, yaw, 0.1, side * 0.25 * s)
    limb(sc, (hand_x, hand_y, 0.85 * s), (hx, hy, body_z + 0.15 * size), 0.006, jitter(rng, (0.7, 0.1, 0.1)))


def person_bench_sleeper(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A person lying on their back or side along a bench, at least 1.3 m from the camera (at the origin, looking
    along +x: nearer, the camera sees only the bench's side below the person)."""
    rng = sc.rng
    far = math.hypot(x, y)
    if far < 1.3:
        x, y = x * 1.3 / far, y * 1.3 / far
    length, depth, h = rng.uniform(1.7, 2.0), rng.uniform(0.4, 0.5), rng.uniform(0.4, 0.48)
    seat = furniture_color(rng)
    sc.box((x, y, h), (depth / 2.0, length / 2.0, 0.03), seat, yaw)
    for fy in (length / 2.0 - 0.1, -length / 2.0 + 0.1):
        px, py = local(x, y, yaw, 0.0, fy)
        sc.box((px, py, h / 2.0), (depth / 2.0 - 0.03, 0.03, h / 2.0), seat, yaw)
    s = rng.uniform(0.9, 1.05)
    shirt, trousers = jitter(rng, pick(rng, CLOTHES)), jitter(rng, pick(rng, CLOTHES))
    skin, shoes = jitter(rng, pick(rng, SKIN), 0.03), jitter(rng, pick(rng, SHOES), 0.03)
    along = yaw + math.pi / 2.0  # the body lies along the bench
    top = h + 0.03
    thick = rng.uniform(0.2, 0.26) * s if rng.random() < 0.6 else rng.uniform(0.34, 0.4) * s  # back or side
    head_end = 1.0 if rng.random() < 0.5 else -1.0
    tx, ty = local(x, y, yaw, 0.0, head_end * 0.45 * s)
    sc.box((tx, ty, top + thick / 2.0), (0.19 * s, 0.28 * s, thick / 2.0), shirt, yaw)
    hx, hy = local(x, y, yaw, 0.0, head_end * 0.82 * s)
    sc.sphere((hx, hy, top + 0.1 * s), 0.1 * s, skin)
    for side in (1.0, -1.0):
        lx, ly = local(x, y, yaw, side * 0.09 * s, -head_end * 0.3 * s)
        sc.capsule((lx, ly, top + 0.07 * s), 0.07 * s, 0.75 * s, trousers, yaw=along, pitch=math.pi / 2.0)
        fx, fy = local(x, y, yaw, side * 0.09 * s, -head_end * 0.75 * s)
        sc.box((fx, fy, top + 0.1 * s), (0.045 * s, 0.04 * s, 0.1 * s), shoes, yaw)


def movable_pet_carrier(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A plastic pet carrier: a two-tone shell with a handle on top, a wire door at the front and side vents."""
    rng = sc.rng
    length, width, h = rng.uniform(0.45, 0.7), rng.uniform(0.3, 0.45), rng.uniform(0.3, 0.45)
    top = jitter(rng, pick(rng, ((0.85, 0.85, 0.82), (0.2, 0.35, 0.7), (0.6, 0.6, 0.62), (0.75, 0.3, 0.3))))
    base = jitter(rng, pick(rng, ((0.15, 0.15, 0.18), (0.5, 0.5, 0.52), (0.9, 0.9, 0.88))))
    sc.box((x, y, h * 0.25), (length / 2.0, width / 2.0, h * 0.25), base, yaw)
    sc.box((x, y, h * 0.72), (length / 2.0 - 0.01, width / 2.0 - 0.01, h * 0.22), top, yaw)
    sc.box((x, y, h + 0.03), (0.1, 0.02, 0.03), base, yaw)
    dx, dy = local(x, y, yaw, length / 2.0 + 0.003, 0.0)
    for k in range(5):
        gx, gy = local(dx, dy, yaw, 0.0, (k / 4.0 - 0.5) * width * 0.7)
        sc.box((gx, gy, h * 0.5), (0.003, 0.004, h * 0.3), (0.3, 0.3, 0.32, 1.0), yaw)
    for side in (1.0, -1.0):
        for k in range(3):
            vx, vy = local(x, y, yaw, (k - 1) * length * 0.2, side * (width / 2.0 - 0.005))
            sc.box((vx, vy, h * 0.72), (0.04, 0.003, 0.01), (0.1, 0.1, 0.1, 1.0), yaw)


def movable_bean_bag(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A bean bag: a squashed round body of spheres with a dent where one sits, in fabric colours."""
    rng = sc.rng
    r = rng.uniform(0.3, 0.45)
    fabric = random_color(rng, 0.1, 0.9)
    for k in range(7):
        a = 2.0 * math.pi * k / 7.0 + yaw
        sc.sphere((x + 0.45 * r * math.cos(a), y + 0.45 * r * math.sin(a), 0.55 * r), 0.6 * r, fabric)
    bx, by = local(x, y, yaw, -0.3 * r, 0.0)
    sc.sphere((bx, by, 0.95 * r), 0.55 * r, fabric)


def movable_toolbox(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A toolbox or tackle box on the floor: a metal or plastic case with a lid line, latches and a carry handle,
    sometimes two stacked."""
    rng = sc.rng
    z = 0.0
    for _ in range(1 if rng.random() < 0.6 else 2):
        length, width, h = rng.uniform(0.4, 0.65), rng.uniform(0.2, 0.3), rng.uniform(0.18, 0.3)
        case = jitter(rng, pick(rng, ((0.8, 0.1, 0.1), (0.1, 0.2, 0.6), (0.95, 0.75, 0.1), (0.2, 0.2, 0.2),
                                      (0.6, 0.6, 0.62))))
        sc.box((x, y, z + h / 2.0), (length / 2.0, width / 2.0, h / 2.0), case, yaw)
        sc.box((x, y, z + h * 0.7), (length / 2.0 + 0.003, width / 2.0 + 0.003, 0.005), (0.1, 0.1, 0.1, 1.0), yaw)
        for fx in (-length * 0.3, length * 0.3):
            lx, ly = local(x, y, yaw, fx, width / 2.0 + 0.004)
            sc.box((lx, ly, z + h * 0.7), (0.02, 0.004, 0.025), (0.8, 0.8, 0.82, 1.0), yaw)
        z += h
    sc.box((x, y, z + 0.05), (length * 0.25, 0.015, 0.015), (0.1, 0.1, 0.1, 1.0), yaw)
    for fx in (-length * 0.25, length * 0.25):
        hx, hy = local(x, y, yaw, fx, 0.0)
        sc.box((hx, hy, z + 0.025), (0.012, 0.012, 0.025), (0.1, 0.1, 0.1, 1.0), yaw)


def clear_step_ladder(sc: Scene, x: float, y: float, yaw: float) -> None:
    """An A-frame step ladder standing open: two pairs of rails, steps on the front, a top platform."""
    rng = sc.rng
    h, width = rng.uniform(1.0, 1.8), rng.uniform(0.4, 0.55)
    spread = rng.uniform(0.3, 0.4) * h  # [m] between the feet of the front and back rails
    color = jitter(rng, pick(rng, (*METAL, (0.85, 0.65, 0.1), (0.55, 0.38, 0.22))))
    lean = math.atan2(spread / 2.0, h)
    for front in (1.0, -1.0):
        for side in (1.0, -1.0):
            rx, ry = local(x, y, yaw, front * spread / 4.0, side * width / 2.0)
            sc.box((rx, ry, h / 2.0), (0.02, 0.015, h / 2.0 / math.cos(lean)), color, yaw, -front * lean)
    steps = int(h / 0.28)
    for k in range(1, steps + 1):
        z = k * h / (steps + 1)
        fx, fy = local(x, y, yaw, spread / 2.0 * (1.0 - z / h), 0.0)
        sc.box((fx, fy, z), (0.06, width / 2.0, 0.012), color, yaw)
    sc.box((x, y, h), (0.1, width / 2.0 + 0.01, 0.02), color, yaw)


def clear_pedestal_fan(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A pedestal fan: a round or cross base, a telescopic pole and a round guard with the motor behind it."""
    rng = sc.rng
    h = rng.uniform(1.0, 1.4)
    body = jitter(rng, pick(rng, ((0.95, 0.95, 0.95), (0.1, 0.1, 0.1), (0.6, 0.6, 0.62))))
    if rng.random() < 0.5:
        sc.cylinder((x, y, 0.02), 0.2, 0.04, body)
    else:
        for k in range(2):
            sc.box((x, y, 0.02), (0.25, 0.025, 0.02), body, yaw + k * math.pi / 2.0)
    sc.cylinder((x, y, h / 2.0), 0.015, h, body)
    r = rng.uniform(0.2, 0.26)
    gx, gy = local(x, y, yaw, 0.08, 0.0)
    ring(sc, (gx, gy, h + r * 0.6), yaw + math.pi / 2.0, radius=r, tube=0.008, color=body, segments=14)
    sc.cylinder((gx, gy, h + r * 0.6), r * 0.25, 0.02, body, yaw=yaw, roll=math.pi / 2.0, pitch=0.0)
    mx, my = local(x, y, yaw, -0.05, 0.0)
    sc.cylinder((mx, my, h + r * 0.6), 0.08, 0.14, body, yaw=yaw + math.pi / 2.0, roll=math.pi / 2.0)


def clear_kiosk(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A self-service kiosk (check-in, tickets): a tall slim cabinet with a tilted touch screen, a card slot and a
    printed header."""
    rng = sc.rng
    w, d, h = rng.uniform(0.45, 0.7), rng.uniform(0.35, 0.5), rng.uniform(1.4, 1.8)
    shell = jitter(rng, pick(rng, ((0.95, 0.95, 0.95), (0.15, 0.15, 0.18), (0.2, 0.4, 0.7), (0.7, 0.72, 0.75))))
    sc.box((x, y, h / 2.0), (d / 2.0, w / 2.0, h / 2.0), shell, yaw)
    sx_, sy_ = local(x, y, yaw, d / 2.0 + 0.01, 0.0)
    sc.box((sx_, sy_, h * 0.68), (0.01, w / 2.0 - 0.06, 0.2), jitter(rng, (0.1, 0.2, 0.35)), yaw, -0.25)
    cx, cy = local(x, y, yaw, d / 2.0 + 0.005, w * 0.2)
    sc.box((cx, cy, h * 0.45), (0.005, 0.05, 0.01), (0.05, 0.05, 0.05, 1.0), yaw)
    hx, hy = local(x, y, yaw, d / 2.0 + 0.003, 0.0)
    sc.box((hx, hy, h - 0.1), (0.003, w / 2.0 - 0.03, 0.07), jitter(rng, pick(rng, LIGHT_BOXES)), yaw)


# -- the ninth held-out set (``HELD_OUT_9``: the ``unseen9`` split only) ------------------------------------
# Defined, rendered and measured with the shipped model before the procedural people and objects (``extra7``)
# were written: a person bent over picking something up, a person sitting on a cardboard box, a person in an
# ankle-length hooded coat; a stack of nested buckets, a plastic drawer unit on castors, a parcel on a flat dolly;
# a washing machine, a treadmill, a painter's easel.
def person_bending_picker(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A person bent forward at the hips (60-100 degrees), knees a little bent, one or both hands near the floor."""
    rng = sc.rng
    s = rng.uniform(0.85, 1.1)
    colors = clothing_colors(sc)
    hip_z, hip_w = 0.82 * s, 0.1 * s
    knee_fx = rng.uniform(0.02, 0.12) * s
    for side in (1.0, -1.0):
        hip = (*local(x, y, yaw, -0.05 * s, side * hip_w), hip_z)
        knee = (*local(x, y, yaw, knee_fx, side * hip_w), 0.45 * s)
        ankle = (*local(x, y, yaw, 0.0, side * hip_w), 0.08)
        limb(sc, hip, knee, 0.07 * s, colors["trousers"])
        limb(sc, knee, ankle, 0.06 * s, colors["trousers"])
        fx, fy = local(x, y, yaw, 0.06, side * hip_w)
        sc.box((fx, fy, 0.04), (0.12 * s, 0.05 * s, 0.04), colors["shoes"], yaw)
    bend = rng.uniform(1.05, 1.75)  # [rad] from upright
    torso_h = rng.uniform(0.5, 0.6) * s
    ux, uz = math.sin(bend), math.cos(bend)
    cx, cy = local(x, y, yaw, -0.05 * s + ux * torso_h / 2.0, 0.0)
    sc.box((cx, cy, hip_z + uz * torso_h / 2.0), (0.12 * s, 0.2 * s, torso_h / 2.0), colors["shirt"], yaw, bend)
    shoulder_fx, shoulder_z = -0.05 * s + ux * torso_h, hip_z + uz * torso_h
    hx, hy = local(x, y, yaw, shoulder_fx + 0.14 * s * ux, 0.0)
    sc.sphere((hx, hy, shoulder_z + 0.14 * s * uz), 0.1 * s, colors["skin"])
    for side in (1.0, -1.0):
        shoulder = (*local(x, y, yaw, shoulder_fx, side * 0.22 * s), shoulder_z)
        reach = rng.uniform(0.1, 0.35) if side > 0 or rng.random() < 0.5 else rng.uniform(0.4, 0.7)
        hand = (*local(x, y, yaw, shoulder_fx + rng.uniform(0.0, 0.2), side * 0.25 * s), reach)
        limb(sc, shoulder, hand, 0.045 * s, colors["shirt"])
        sc.sphere(hand, 0.045 * s, colors["skin"])


def person_box_sitter(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A person sitting on a cardboard box or a plastic crate 0.3-0.45 m high, hands on the lap."""
    rng = sc.rng
    seat_h = rng.uniform(0.3, 0.45)
    side = rng.uniform(0.35, 0.5)
    sc.box((x, y, seat_h / 2.0), (side / 2.0, side / 2.0, seat_h / 2.0), box_color(rng), yaw)
    if rng.random() < 0.5:  # tape over the top
        sc.box((x, y, seat_h / 2.0), (side / 2.0 + 0.003, 0.03, seat_h / 2.0 + 0.003),
               jitter(rng, (0.6, 0.45, 0.25), 0.03), yaw)
    seated_figure(sc, x, y, yaw, seat_h=seat_h, hip_fx=rng.uniform(-0.05, 0.05), lean=rng.uniform(-0.25, 0.1))


def person_hooded_coat(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A person in an ankle-length coat (a tapered column from shoulders to 10 cm above the floor) with the hood up,
    hands in the pockets; only the shoes and the face show."""
    rng = sc.rng
    s = rng.uniform(0.85, 1.1)
    coat = jitter(rng, pick(rng, ((0.1, 0.1, 0.12), (0.3, 0.25, 0.2), (0.2, 0.3, 0.2), (0.55, 0.5, 0.4),
                                  (0.6, 0.1, 0.1), (0.15, 0.2, 0.4), (0.85, 0.8, 0.6))))
    hem = rng.uniform(0.08, 0.2)
    shoulder = 1.42 * s
    sc.cylinder((x, y, (hem + 0.9 * s) / 2.0), rng.uniform(0.24, 0.3) * s, 0.9 * s - hem, coat)
    sc.box((x, y, (0.85 * s + shoulder) / 2.0), (0.13 * s, 0.21 * s, (shoulder - 0.85 * s) / 2.0), coat, yaw)
    for side in (1.0, -1.0):
        ax, ay = local(x, y, yaw, 0.03, side * 0.23 * s)
        sc.capsule((ax, ay, shoulder - 0.3 * s), 0.055 * s, 0.45 * s, coat, yaw=yaw, pitch=-0.15)
        fx, fy = local(x, y, yaw, 0.05, side * 0.1 * s)
        sc.box((fx, fy, 0.04), (0.12 * s, 0.05 * s, 0.04), jitter(rng, pick(rng, SHOES), 0.03), yaw)
    sc.sphere((x, y, shoulder + 0.16 * s), 0.125 * s, coat)
    face_x, face_y = local(x, y, yaw, 0.06 * s, 0.0)
    sc.sphere((face_x, face_y, shoulder + 0.15 * s), 0.08 * s, jitter(rng, pick(rng, SKIN), 0.03))


def movable_bucket_stack(sc: Scene, x: float, y: float, yaw: float) -> None:
    """Two to five nested plastic buckets (a tapered column of rims), upright or one tipped on its side beside."""
    rng = sc.rng
    color = random_color(rng, 0.1, 0.95)
    r, h = rng.uniform(0.13, 0.18), rng.uniform(0.25, 0.35)
    count = int(rng.integers(2, 6))
    sc.cylinder((x, y, h / 2.0), r * 0.85, h, color)
    for k in range(count):
        sc.cylinder((x, y, h - 0.02 + 0.05 * k), r, 0.03, color)
    if rng.random() < 0.4:
        bx, by = local(x, y, yaw, 0.0, 2.2 * r)
        sc.cylinder((bx, by, r * 0.9), r * 0.9, h, random_color(rng, 0.1, 0.95), yaw=yaw, roll=math.pi / 2.0)


def movable_drawer_unit(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A plastic three- or four-drawer storage tower on castors, 0.5-0.8 m high, translucent-looking fronts."""
    rng = sc.rng
    w, d, h = rng.uniform(0.3, 0.42), rng.uniform(0.35, 0.45), rng.uniform(0.5, 0.8)
    frame = jitter(rng, pick(rng, ((0.95, 0.95, 0.95), (0.2, 0.2, 0.22), (0.6, 0.6, 0.62))))
    front = random_color(rng, 0.3, 0.95)
    wheel = 0.05
    sc.box((x, y, wheel + h / 2.0), (d / 2.0, w / 2.0, h / 2.0), frame, yaw)
    drawers = int(rng.integers(3, 5))
    for k in range(drawers):
        z = wheel + (k + 0.5) * h / drawers
        fx, fy = local(x, y, yaw, d / 2.0 + 0.004, 0.0)
        sc.box((fx, fy, z), (0.004, w / 2.0 - 0.02, h / drawers / 2.0 - 0.015), front, yaw)
        hx, hy = local(x, y, yaw, d / 2.0 + 0.012, 0.0)
        sc.box((hx, hy, z + h / drawers * 0.25), (0.006, 0.05, 0.008), frame, yaw)
    for fx in (d / 2.0 - 0.04, -d / 2.0 + 0.04):
        for fy in (w / 2.0 - 0.04, -w / 2.0 + 0.04):
            cx, cy = local(x, y, yaw, fx, fy)
            sc.cylinder((cx, cy, wheel / 2.0), wheel / 2.0, 0.02, (0.1, 0.1, 0.1, 1.0), yaw=yaw, roll=math.pi / 2.0)


def movable_dolly_parcel(sc: Scene, x: float, y: float, yaw: float) -> None:
    """One or two parcels on a flat four-wheeled furniture dolly (a low board on castors)."""
    rng = sc.rng
    length, width = rng.uniform(0.5, 0.75), rng.uniform(0.35, 0.5)
    deck = 0.1
    sc.box((x, y, deck - 0.015), (length / 2.0, width / 2.0, 0.015),
           jitter(rng, pick(rng, ((0.2, 0.3, 0.7), (0.1, 0.1, 0.1), (0.6, 0.45, 0.3), (0.7, 0.1, 0.1)))), yaw)
    for fx in (length / 2.0 - 0.06, -length / 2.0 + 0.06):
        for fy in (width / 2.0 - 0.05, -width / 2.0 + 0.05):
            cx, cy = local(x, y, yaw, fx, fy)
            sc.cylinder((cx, cy, 0.035), 0.035, 0.025, (0.15, 0.15, 0.15, 1.0), yaw=yaw, roll=math.pi / 2.0)
    z = deck
    for _ in range(int(rng.integers(1, 3))):
        sx, sy, sz = rng.uniform(0.3, length), rng.uniform(0.25, width), rng.uniform(0.15, 0.4)
        sc.box((x, y, z + sz / 2.0), (sx / 2.0, sy / 2.0, sz / 2.0), box_color(rng), yaw + rng.uniform(-0.2, 0.2))
        z += sz


def clear_washing_machine(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A front-loading washing machine or dryer: a 0.6 m white or grey cube 0.85 m high, a round door, a control
    panel strip and a detergent drawer."""
    rng = sc.rng
    w, d, h = rng.uniform(0.58, 0.62), rng.uniform(0.55, 0.65), rng.uniform(0.82, 0.88)
    body = jitter(rng, pick(rng, ((0.95, 0.95, 0.95), (0.9, 0.9, 0.88), (0.6, 0.6, 0.62), (0.2, 0.2, 0.22))), 0.03)
    sc.box((x, y, h / 2.0), (d / 2.0, w / 2.0, h / 2.0), body, yaw)
    dx, dy = local(x, y, yaw, d / 2.0 + 0.01, 0.0)
    r = rng.uniform(0.2, 0.24)
    sc.cylinder((dx, dy, h * 0.45), r, 0.02, jitter(rng, pick(rng, ((0.6, 0.6, 0.62), (0.15, 0.15, 0.18)))),
                yaw=yaw + math.pi / 2.0, roll=math.pi / 2.0)
    gx, gy = local(x, y, yaw, d / 2.0 + 0.022, 0.0)
    sc.cylinder((gx, gy, h * 0.45), r * 0.7, 0.005, (0.2, 0.25, 0.3, 1.0), yaw=yaw + math.pi / 2.0,
                roll=math.pi / 2.0)
    px, py = local(x, y, yaw, d / 2.0 + 0.004, 0.0)
    sc.box((px, py, h - 0.07), (0.004, w / 2.0 - 0.02, 0.05), jitter(rng, (0.85, 0.85, 0.87), 0.05), yaw)
    kx, ky = local(x, y, yaw, d / 2.0 + 0.012, w * 0.15)
    sc.cylinder((kx, ky, h - 0.07), 0.03, 0.02, (0.3, 0.3, 0.32, 1.0), yaw=yaw + math.pi / 2.0, roll=math.pi / 2.0)


def clear_treadmill(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A treadmill: a long low deck with a dark belt, two uprights at the front and a console with handrails."""
    rng = sc.rng
    length, width, deck = rng.uniform(1.5, 1.9), rng.uniform(0.65, 0.8), rng.uniform(0.15, 0.25)
    frame = jitter(rng, pick(rng, ((0.15, 0.15, 0.17), (0.6, 0.6, 0.62), (0.85, 0.85, 0.87))))
    along = yaw + math.pi / 2.0 if rng.random() < 0.5 else yaw  # seen from the side or from an end
    sc.box((x, y, deck / 2.0), (length / 2.0, width / 2.0, deck / 2.0), frame, along)
    sc.box((x, y, deck + 0.005), (length / 2.0 - 0.1, width / 2.0 - 0.08, 0.005), (0.08, 0.08, 0.08, 1.0), along)
    up_h = rng.uniform(1.2, 1.45)
    for side in (1.0, -1.0):
        ux, uy = local(x, y, along, length / 2.0 - 0.1, side * (width / 2.0 - 0.03))
        sc.box((ux, uy, up_h / 2.0), (0.04, 0.03, up_h / 2.0), frame, along, -0.15)
        rx, ry = local(x, y, along, length / 2.0 - 0.35, side * (width / 2.0 - 0.03))
        sc.box((rx, ry, up_h - 0.2), (0.25, 0.02, 0.02), frame, along)
    cx, cy = local(x, y, along, length / 2.0 - 0.15, 0.0)
    sc.box((cx, cy, up_h), (0.12, width / 2.0, 0.08), frame, along, 0.5)


def clear_easel(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A painter's or flip-chart easel: three splayed legs 1.5-1.9 m long, a board or a paper pad on a ledge."""
    rng = sc.rng
    h = rng.uniform(1.5, 1.9)
    wood = jitter(rng, pick(rng, ((0.6, 0.42, 0.25), (0.75, 0.6, 0.4), (0.3, 0.3, 0.32), (0.8, 0.8, 0.82))))
    top = (x, y, h)
    for fx, fy in ((0.25, 0.3), (0.25, -0.3), (-0.45, 0.0)):
        foot = (*local(x, y, yaw, fx, fy), 0.0)
        limb(sc, foot, top, 0.015, wood)
    bw, bh = rng.uniform(0.6, 0.9), rng.uniform(0.6, 1.0)
    bx, by = local(x, y, yaw, 0.17, 0.0)
    ledge_z = rng.uniform(0.7, 0.95)
    sc.box((bx, by, ledge_z), (0.04, bw / 2.0 + 0.03, 0.015), wood, yaw)
    sheet = jitter(rng, pick(rng, ((0.97, 0.97, 0.97), (0.9, 0.88, 0.8))), 0.02) if rng.random() < 0.6 else \
        random_color(rng, 0.1, 0.95)
    lean = math.atan2(0.17, h)
    sc.box((bx, by, ledge_z + bh / 2.0), (0.01, bw / 2.0, bh / 2.0), sheet, yaw, -lean)


# -- the tenth held-out set (``HELD_OUT_10``: the ``unseen10`` split only) -----------------------------------
# Defined, rendered and measured with the shipped model while the models trained with the procedural ``extra7``
# data were training, before any of them was measured: an adult carrying a child on the shoulders, a stooped
# elderly person with a walking cane, a person walking a bicycle; a laundry hamper, a stack of trays, a bundle of
# cardboard tubes; a grandfather clock, a water cooler, an ironing board.
def person_shoulder_carry(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker with a child sitting on the shoulders, the child's legs hanging down the adult's chest."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw)
    c = rng.uniform(0.45, 0.6)  # the child's scale
    base = 0.9 * s + 0.55 * s + 0.2 * s  # [m] where the child sits (on the neck)
    colors = clothing_colors(sc)
    sc.box((x, y, base + 0.25 * c), (0.1 * c, 0.17 * c, 0.25 * c), colors["shirt"], yaw)
    sc.sphere((x, y, base + 0.62 * c), 0.12 * c, colors["skin"])
    for side in (1.0, -1.0):
        knee = (*local(x, y, yaw, 0.18 * c, side * 0.14 * c), base)
        limb(sc, (*local(x, y, yaw, 0.0, side * 0.08 * c), base + 0.02), knee, 0.05 * c, colors["trousers"])
        limb(sc, knee, (*local(x, y, yaw, 0.2 * c, side * 0.15 * c), base - 0.35 * c), 0.045 * c, colors["trousers"])
        hand = (*local(x, y, yaw, 0.05, side * 0.3 * c), base + 0.7 * c)
        limb(sc, (*local(x, y, yaw, 0.0, side * 0.2 * c), base + 0.45 * c), hand, 0.035 * c, colors["shirt"])


def person_cane_elder(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A stooped older person: torso bent 25-45 degrees, head forward, one hand on a walking cane planted ahead."""
    rng = sc.rng
    s = rng.uniform(0.82, 1.0)
    colors = clothing_colors(sc)
    hip_z = 0.85 * s
    for side in (1.0, -1.0):
        step = side * rng.uniform(0.0, 0.12)
        knee = (*local(x, y, yaw, step + 0.05, side * 0.1 * s), 0.46 * s)
        limb(sc, (*local(x, y, yaw, 0.0, side * 0.1 * s), hip_z), knee, 0.07 * s, colors["trousers"])
        limb(sc, knee, (*local(x, y, yaw, step, side * 0.1 * s), 0.08), 0.06 * s, colors["trousers"])
        fx, fy = local(x, y, yaw, step + 0.06, side * 0.1 * s)
        sc.box((fx, fy, 0.04), (0.12 * s, 0.05 * s, 0.04), colors["shoes"], yaw)
    stoop = rng.uniform(0.45, 0.8)
    torso_h = 0.55 * s
    cx, cy = local(x, y, yaw, math.sin(stoop) * torso_h / 2.0, 0.0)
    sc.box((cx, cy, hip_z + math.cos(stoop) * torso_h / 2.0), (0.12 * s, 0.2 * s, torso_h / 2.0), colors["shirt"],
           yaw, stoop)
    top = (math.sin(stoop) * torso_h, hip_z + math.cos(stoop) * torso_h)
    hx, hy = local(x, y, yaw, top[0] + 0.12 * s, 0.0)
    sc.sphere((hx, hy, top[1] + 0.08 * s), 0.1 * s, colors["skin"])
    side = 1.0 if rng.random() < 0.5 else -1.0
    grip = (*local(x, y, yaw, top[0] + 0.25, side * 0.25 * s), 0.85 * s)
    limb(sc, (*local(x, y, yaw, top[0], side * 0.22 * s), top[1] - 0.05), grip, 0.045 * s, colors["shirt"])
    cane = jitter(rng, pick(rng, ((0.35, 0.22, 0.12), (0.1, 0.1, 0.1), (0.7, 0.7, 0.72))))
    limb(sc, grip, (grip[0], grip[1], 0.0), 0.012, cane)
    limb(sc, (*local(x, y, yaw, top[0], -side * 0.22 * s), top[1] - 0.05),
         (*local(x, y, yaw, top[0] + 0.05, -side * 0.24 * s), top[1] - 0.5 * s), 0.045 * s, colors["shirt"])


def person_bike_walker(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker pushing a bicycle along beside them, a hand on the handlebar and one on the saddle."""
    rng = sc.rng
    side = 1.0 if rng.random() < 0.5 else -1.0
    s = person_walker(sc, *local(x, y, yaw, 0.0, side * 0.3), yaw)
    clear_bicycle(sc, *local(x, y, yaw, 0.1, -side * 0.15), yaw)
    for fx, z in ((0.55, 0.98), (-0.15, 0.92)):
        hand = (*local(x, y, yaw, fx, -side * 0.1), z)
        limb(sc, (*local(x, y, yaw, 0.0, side * (0.3 - 0.22 * s)), 1.35 * s), hand, 0.04 * s,
             jitter(rng, pick(rng, CLOTHES)))


def movable_hamper(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A laundry hamper: a woven cylinder or square basket 0.45-0.65 m high with a lid, maybe clothes spilling."""
    rng = sc.rng
    h, r = rng.uniform(0.45, 0.65), rng.uniform(0.18, 0.25)
    weave = jitter(rng, pick(rng, ((0.75, 0.6, 0.4), (0.55, 0.4, 0.25), (0.9, 0.9, 0.88), (0.4, 0.5, 0.6))))
    round_body = rng.random() < 0.5
    if round_body:
        sc.cylinder((x, y, h / 2.0), r, h, weave)
    else:
        sc.box((x, y, h / 2.0), (r, r, h / 2.0), weave, yaw)
    for k in range(1, 5):  # weave bands
        band = jitter(rng, weave[:3], 0.08)
        if round_body:
            sc.cylinder((x, y, h * k / 5.0), r + 0.004, 0.02, band)
        else:
            sc.box((x, y, h * k / 5.0), (r + 0.004, r + 0.004, 0.01), band, yaw)
    if rng.random() < 0.7:  # a lid
        if round_body:
            sc.cylinder((x, y, h + 0.015), r + 0.01, 0.03, weave)
        else:
            sc.box((x, y, h + 0.015), (r + 0.01, r + 0.01, 0.015), weave, yaw)
    else:  # open, clothes showing
        for _ in range(3):
            ox, oy = local(x, y, yaw, rng.uniform(-0.5, 0.5) * r, rng.uniform(-0.5, 0.5) * r)
            sc.sphere((ox, oy, h), rng.uniform(0.05, 0.1), jitter(rng, pick(rng, CLOTHES)))


def movable_tray_stack(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A stack of 6-20 plastic food or instrument trays, each a thin slab with a raised rim."""
    rng = sc.rng
    length, width = rng.uniform(0.35, 0.55), rng.uniform(0.26, 0.38)
    colour = jitter(rng, pick(rng, ((0.85, 0.85, 0.82), (0.2, 0.35, 0.6), (0.6, 0.2, 0.15), (0.25, 0.25, 0.27),
                                    (0.4, 0.6, 0.45))))
    z = 0.0
    for _ in range(int(rng.integers(6, 21))):
        sc.box((x, y, z + 0.012), (length / 2.0, width / 2.0, 0.012), colour, yaw)
        sc.box((x, y, z + 0.022), (length / 2.0 + 0.006, width / 2.0 + 0.006, 0.003), jitter(rng, colour[:3], 0.04),
               yaw)
        z += 0.027


def movable_tube_bundle(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A bundle of 5-12 cardboard or plastic tubes (posters, drawings) lying on the floor, taped together."""
    rng = sc.rng
    length = rng.uniform(0.6, 1.0)
    tube = jitter(rng, pick(rng, ((0.7, 0.55, 0.35), (0.85, 0.85, 0.82), (0.2, 0.3, 0.6), (0.15, 0.15, 0.15))))
    r = rng.uniform(0.035, 0.06)
    count = int(rng.integers(5, 13))
    for k in range(count):
        row, col = divmod(k, 4)
        oy = (col - 1.5) * 2.0 * r + (r if row % 2 else 0.0)
        ox, oy2 = local(x, y, yaw, 0.0, oy)
        sc.cylinder((ox, oy2, r + row * 1.7 * r), r, length * rng.uniform(0.9, 1.0), jitter(rng, tube[:3], 0.04),
                    yaw=yaw, pitch=math.pi / 2.0)
    for fx in (-length * 0.3, length * 0.3):
        tx, ty = local(x, y, yaw, fx, 0.0)
        sc.box((tx, ty, 2.0 * r), (0.02, 4.2 * r, 2.2 * r), jitter(rng, (0.6, 0.45, 0.25), 0.03), yaw)


def clear_grandfather_clock(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A longcase clock: a plinth, a narrow trunk with a glass door and pendulum, a wider hood with a dial."""
    rng = sc.rng
    h = rng.uniform(1.8, 2.1)
    wood = jitter(rng, pick(rng, ((0.35, 0.2, 0.1), (0.5, 0.3, 0.15), (0.2, 0.12, 0.08), (0.6, 0.45, 0.3))))
    sc.box((x, y, 0.15), (0.2, 0.26, 0.15), wood, yaw)
    sc.box((x, y, 0.3 + (h - 0.85) / 2.0), (0.15, 0.19, (h - 0.85) / 2.0), wood, yaw)
    sc.box((x, y, h - 0.275), (0.18, 0.25, 0.275), wood, yaw)
    fx, fy = local(x, y, yaw, 0.155, 0.0)
    sc.box((fx, fy, 0.3 + (h - 0.85) / 2.0), (0.004, 0.1, (h - 0.85) / 2.0 - 0.08), (0.15, 0.15, 0.18, 1.0), yaw)
    sc.cylinder((fx, fy, 0.55), 0.06, 0.01, (0.85, 0.7, 0.2, 1.0), yaw=yaw + math.pi / 2.0, roll=math.pi / 2.0)
    dx, dy = local(x, y, yaw, 0.185, 0.0)
    sc.cylinder((dx, dy, h - 0.28), 0.15, 0.01, (0.95, 0.93, 0.85, 1.0), yaw=yaw + math.pi / 2.0, roll=math.pi / 2.0)


def clear_water_cooler(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A bottled water cooler: a white or grey cabinet ~1 m high, two taps, an upturned blue bottle on top."""
    rng = sc.rng
    h = rng.uniform(0.9, 1.05)
    body = jitter(rng, pick(rng, ((0.95, 0.95, 0.95), (0.7, 0.7, 0.72), (0.2, 0.2, 0.22))), 0.03)
    sc.box((x, y, h / 2.0), (0.16, 0.16, h / 2.0), body, yaw)
    for side in (1.0, -1.0):
        tx, ty = local(x, y, yaw, 0.18, side * 0.05)
        sc.box((tx, ty, h * 0.72), (0.02, 0.015, 0.02), jitter(rng, (0.8, 0.2, 0.2) if side > 0 else (0.2, 0.3, 0.8)),
               yaw)
    tx, ty = local(x, y, yaw, 0.14, 0.0)
    sc.box((tx, ty, h * 0.55), (0.03, 0.1, 0.01), (0.3, 0.3, 0.32, 1.0), yaw)
    bottle = (0.55, 0.75, 0.95, 1.0)
    sc.cylinder((x, y, h + 0.2), 0.14, 0.36, bottle)
    sc.cylinder((x, y, h + 0.02), 0.04, 0.06, bottle)


def clear_ironing_board(sc: Scene, x: float, y: float, yaw: float) -> None:
    """An ironing board standing open: a long narrow padded board 0.75-0.95 m high on crossed legs."""
    rng = sc.rng
    h, length = rng.uniform(0.75, 0.95), rng.uniform(1.1, 1.4)
    cover = random_color(rng, 0.2, 0.95)
    along = yaw + math.pi / 2.0 if rng.random() < 0.5 else yaw
    sc.box((x, y, h), (length / 2.0, 0.19, 0.02), cover, along)
    nx, ny = local(x, y, along, length / 2.0 + 0.05, 0.0)
    sc.cylinder((nx, ny, h), 0.12, 0.04, cover)  # the rounded nose
    leg = jitter(rng, pick(rng, METAL))
    for foot in (-0.4, 0.4):
        for side in (1.0, -1.0):
            limb(sc, (*local(x, y, along, foot * length * 0.6, side * 0.17), 0.0),
                 (*local(x, y, along, -foot * length * 0.3, side * 0.12), h - 0.03), 0.012, leg)


# -- the eleventh held-out set (``HELD_OUT_11``: the ``unseen11`` split only) ---------------------------------
# Defined, rendered and committed before the ``extra8`` training data was written, and measured only as a
# whole until a model trained with it was: a patient lying on a stretcher trolley (back rest flat or raised), a
# person carrying a large flat panel in front of them, a person on a knee scooter; a folding wet-floor sign, a
# pedal bin, a rolling kick stool; an ultrasound cart, a lectern, a structural pillar.
def person_stretcher_patient(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A patient under a blanket on a stretcher trolley 0.55-0.8 m high, the back rest flat or raised 35-70
    degrees with the torso on it; its nearest end at least 1.5 m from the camera (at the origin, looking along +x:
    nearer, it sees only the trolley below the patient)."""
    rng = sc.rng
    raised = rng.random() < 0.5
    h, length = rng.uniform(0.55, 0.8), rng.uniform(1.9, 2.05)
    far = math.hypot(x, y)
    least = 1.5 + length / 2.0 * abs(math.sin(yaw - math.atan2(y, x)))  # the long axis runs along yaw + pi/2
    if far < least:
        x, y = x * least / far, y * least / far
    frame = jitter(rng, pick(rng, METAL))
    sc.box((x, y, h - 0.05), (0.3, length / 2.0, 0.03), frame, yaw)
    sc.box((x, y, 0.2), (0.25, length / 2.0 - 0.15, 0.04), frame, yaw)  # the base
    for fy in (length / 2.0 - 0.25, -length / 2.0 + 0.25):
        cx, cy = local(x, y, yaw, 0.0, fy)
        sc.cylinder((cx, cy, (0.2 + h - 0.05) / 2.0), 0.04, h - 0.25, frame)  # a column
        for side in (1.0, -1.0):
            wx, wy = local(x, y, yaw, side * 0.22, fy)
            sc.cylinder((wx, wy, 0.06), 0.06, 0.04, (0.1, 0.1, 0.1, 1.0), yaw=yaw, roll=math.pi / 2.0)
    for side in (1.0, -1.0):  # side rails
        rx, ry = local(x, y, yaw, side * 0.31, 0.0)
        sc.box((rx, ry, h + 0.12), (0.01, length * 0.3, 0.015), frame, yaw)
    s = rng.uniform(0.9, 1.05)
    blanket = jitter(rng, pick(rng, ((0.95, 0.95, 0.93), (0.55, 0.7, 0.85), (0.7, 0.85, 0.75), (0.9, 0.8, 0.6))))
    skin = jitter(rng, pick(rng, SKIN), 0.03)
    head_end = 1.0 if rng.random() < 0.5 else -1.0
    legs_c = local(x, y, yaw, 0.0, -head_end * 0.35 * s)
    sc.box((*legs_c, h + 0.09), (0.24 * s, 0.5 * s, 0.09), blanket, yaw)  # legs under the blanket
    fx, fy = local(x, y, yaw, 0.0, -head_end * 0.82 * s)
    sc.box((fx, fy, h + 0.16), (0.16 * s, 0.06, 0.08), blanket, yaw)  # the feet lift it at the end
    back = rng.uniform(0.6, 1.2) if raised else 0.0  # [rad] back rest from flat
    torso = 0.6 * s
    dy_c, dz_c = math.cos(back) * torso / 2.0, math.sin(back) * torso / 2.0
    bx, by = local(x, y, yaw, 0.0, head_end * (0.15 * s + dy_c))
    sc.box((bx, by, h + 0.1 + dz_c), (0.22 * s, torso / 2.0, 0.11 * s), blanket if rng.random() < 0.5 else
           jitter(rng, (0.6, 0.75, 0.85)), yaw, -head_end * back)
    reach = 0.15 * s + math.cos(back) * (torso + 0.14 * s)
    hx, hy = local(x, y, yaw, 0.0, head_end * reach)
    sc.sphere((hx, hy, h + 0.12 + math.sin(back) * (torso + 0.14 * s)), 0.1 * s, skin)


def person_panel_carrier(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker carrying a large flat panel (a board, a picture, a door leaf) upright in front of them with both
    hands: the legs show below it, the head above or beside it."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw)
    width, height = rng.uniform(0.7, 1.2), rng.uniform(0.6, 1.0)
    bottom = rng.uniform(0.45, 0.75) * s
    panel = random_color(rng, 0.15, 0.95) if rng.random() < 0.6 else jitter(rng, pick(rng, FURNITURE))
    shift = rng.uniform(-0.2, 0.2)
    px, py = local(x, y, yaw, 0.3 * s, shift)
    sc.box((px, py, bottom + height / 2.0), (0.015, width / 2.0, height / 2.0), panel, yaw)
    if rng.random() < 0.5:  # a frame or a printed face
        fx, fy = local(x, y, yaw, 0.317 * s, shift)
        sc.box((fx, fy, bottom + height / 2.0), (0.002, width / 2.0 - 0.05, height / 2.0 - 0.05),
               random_color(rng, 0.1, 0.95), yaw)
    arms_forward(sc, x, y, yaw, fx=0.18 * s, z=bottom + height * 0.45, scale=s, length=0.2 * s)


def person_knee_scooter_rider(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A person with one knee on the padded deck of a four-wheeled knee scooter (the shin along it), the other
    foot on the floor, the hands on the handlebar of its steering column."""
    rng = sc.rng
    s = rng.uniform(0.88, 1.08)
    colors = clothing_colors(sc)
    frame = jitter(rng, pick(rng, FRAMES))
    deck_z = rng.uniform(0.45, 0.55) * s
    side = 1.0 if rng.random() < 0.5 else -1.0  # the leg on the deck
    hip_z = 0.92 * s
    # the scooter: a deck from under the hip backwards, a column at the front, four small wheels
    dx, dy = local(x, y, yaw, -0.15, side * 0.1 * s)
    sc.box((dx, dy, deck_z - 0.04), (0.22, 0.1, 0.04), (0.12, 0.12, 0.12, 1.0), yaw)
    limb(sc, (*local(x, y, yaw, -0.05, side * 0.1 * s), 0.08), (*local(x, y, yaw, 0.35, side * 0.1 * s), 0.08),
         0.02, frame)
    limb(sc, (*local(x, y, yaw, 0.35, side * 0.1 * s), 0.08), (*local(x, y, yaw, 0.3, side * 0.1 * s), 0.95 * s),
         0.018, frame)
    for fx_w in (-0.3, 0.35):
        for w in (-0.12, 0.12):
            wx, wy = local(x, y, yaw, fx_w, side * 0.1 * s + w)
            sc.cylinder((wx, wy, 0.08), 0.08, 0.04, (0.1, 0.1, 0.1, 1.0), yaw=yaw + math.pi / 2.0, roll=math.pi / 2.0)
    # legs: the kneeling one's thigh down to the deck, its shin back along it; the standing one to the floor
    knee = (*local(x, y, yaw, 0.05, side * 0.1 * s), deck_z + 0.06)
    limb(sc, (*local(x, y, yaw, -0.02, side * 0.1 * s), hip_z), knee, 0.07 * s, colors["trousers"])
    limb(sc, knee, (*local(x, y, yaw, -0.38, side * 0.1 * s), deck_z + 0.06), 0.06 * s, colors["trousers"])
    foot = (*local(x, y, yaw, 0.05, -side * 0.11 * s), 0.08)
    limb(sc, (*local(x, y, yaw, -0.02, -side * 0.1 * s), hip_z), foot, 0.07 * s, colors["trousers"])
    sc.box((foot[0], foot[1], 0.04), (0.12 * s, 0.05 * s, 0.04), colors["shoes"], yaw)
    torso_h = rng.uniform(0.5, 0.6) * s
    lean = rng.uniform(0.05, 0.3)
    cx, cy = local(x, y, yaw, math.sin(lean) * torso_h / 2.0, 0.0)
    sc.box((cx, cy, hip_z + math.cos(lean) * torso_h / 2.0), (0.11 * s, 0.19 * s, torso_h / 2.0), colors["shirt"],
           yaw, lean)
    top = (math.sin(lean) * torso_h, hip_z + math.cos(lean) * torso_h)
    hx, hy = local(x, y, yaw, top[0] + 0.05, 0.0)
    sc.sphere((hx, hy, top[1] + 0.14 * s), 0.1 * s, colors["skin"])
    for arm in (1.0, -1.0):
        limb(sc, (*local(x, y, yaw, top[0], arm * 0.22 * s), top[1] - 0.05),
             (*local(x, y, yaw, 0.3, side * 0.1 * s + arm * 0.2), 0.95 * s), 0.045 * s, colors["shirt"])


def movable_wet_floor_sign(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A folding A-frame caution sign 0.55-0.7 m high: two yellow (or orange) panels leaning together, a black
    warning triangle and text bands on the faces, a handle slot at the top."""
    rng = sc.rng
    h, w = rng.uniform(0.55, 0.7), rng.uniform(0.26, 0.32)
    spread = rng.uniform(0.18, 0.28)  # [rad] each panel from upright
    yellow = jitter(rng, pick(rng, ((0.98, 0.85, 0.05), (0.95, 0.75, 0.1), (1.0, 0.55, 0.05))), 0.03)
    black = (0.08, 0.08, 0.08, 1.0)
    for face in (1.0, -1.0):
        off = face * math.sin(spread) * h / 2.0
        px, py = local(x, y, yaw, off, 0.0)
        sc.box((px, py, math.cos(spread) * h / 2.0), (0.008, w / 2.0, h / 2.0), yellow, yaw, -face * spread)
        tx, ty = local(x, y, yaw, off * 1.08 + face * 0.008, 0.0)
        sc.box((tx, ty, math.cos(spread) * h * 0.62), (0.003, w * 0.3, w * 0.22), black, yaw, -face * spread)
        for band in (0.3, 0.2):
            bx, by = local(x, y, yaw, face * (math.sin(spread) * h * (1 - band) / 2.0 + 0.009), 0.0)
            sc.box((bx, by, math.cos(spread) * h * band), (0.002, w * 0.4, 0.012), black, yaw, -face * spread)


def movable_pedal_bin(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A pedal bin 0.4-0.7 m high: a round or rounded-square body (clinical yellow, white, steel, red, black),
    a wider lid, a pedal at the front foot, maybe a label."""
    rng = sc.rng
    h, r = rng.uniform(0.4, 0.7), rng.uniform(0.15, 0.22)
    body = jitter(rng, pick(rng, ((0.98, 0.85, 0.1), (0.95, 0.95, 0.95), (0.72, 0.73, 0.76), (0.8, 0.1, 0.1),
                                  (0.1, 0.1, 0.1), (0.2, 0.5, 0.3))), 0.03)
    lid = body if rng.random() < 0.6 else jitter(rng, pick(rng, METAL))
    if rng.random() < 0.5:
        sc.cylinder((x, y, h / 2.0), r, h, body)
        sc.cylinder((x, y, h + 0.02), r + 0.01, 0.04, lid)
    else:
        sc.box((x, y, h / 2.0), (r * 0.9, r, h / 2.0), body, yaw)
        sc.box((x, y, h + 0.02), (r * 0.9 + 0.01, r + 0.01, 0.02), lid, yaw)
    px, py = local(x, y, yaw, r + 0.04, 0.0)
    sc.box((px, py, 0.03), (0.05, 0.06, 0.012), jitter(rng, pick(rng, METAL)), yaw)
    if rng.random() < 0.5:
        lx, ly = local(x, y, yaw, r * 0.92, 0.0)
        sc.box((lx, ly, h * 0.6), (0.004, r * 0.5, h * 0.12), random_color(rng, 0.1, 0.95), yaw)


def movable_kick_stool(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A rolling kick step stool (the round library kind): a tapered drum 0.36-0.45 m high, a rubber tread on top
    and a rubber bumper ring at the foot."""
    rng = sc.rng
    h = rng.uniform(0.36, 0.45)
    r_top, r_base = rng.uniform(0.14, 0.17), rng.uniform(0.2, 0.24)
    body = jitter(rng, pick(rng, ((0.5, 0.5, 0.52), (0.85, 0.83, 0.78), (0.1, 0.1, 0.12), (0.2, 0.3, 0.6),
                                  (0.75, 0.15, 0.12), (0.25, 0.5, 0.3))), 0.03)
    steps = 6
    for k in range(steps):  # the taper, in rings
        r = r_base + (r_top - r_base) * (k + 0.5) / steps
        sc.cylinder((x, y, h * (k + 0.5) / steps), r, h / steps + 0.002, body)
    rubber = (0.08, 0.08, 0.08, 1.0)
    sc.cylinder((x, y, h + 0.008), r_top, 0.016, rubber)
    sc.cylinder((x, y, 0.02), r_base + 0.012, 0.04, rubber)
    if rng.random() < 0.6:  # a mid step
        sc.cylinder((x, y, h * 0.5), (r_base + r_top) / 2.0 + 0.03, 0.02, rubber)


def clear_ultrasound_cart(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A mobile ultrasound or monitoring workstation: a base on castors, a column, a console deck at 0.85-0.95 m
    with a keyboard, a monitor above on an arm, a probe holder and a printer shelf."""
    rng = sc.rng
    shell = jitter(rng, pick(rng, ((0.92, 0.92, 0.9), (0.8, 0.82, 0.85), (0.6, 0.65, 0.72), (0.95, 0.93, 0.85))),
                   0.03)
    dark = jitter(rng, (0.15, 0.15, 0.17), 0.03)
    sc.box((x, y, 0.14), (0.32, 0.27, 0.08), shell, yaw)
    for fx in (0.25, -0.25):
        for fy in (0.2, -0.2):
            wx, wy = local(x, y, yaw, fx, fy)
            sc.cylinder((wx, wy, 0.04), 0.04, 0.03, dark, yaw=yaw, roll=math.pi / 2.0)
    deck = rng.uniform(0.85, 0.95)
    body_top = rng.uniform(0.45, deck - 0.1)
    sc.box((x, y, (0.22 + body_top) / 2.0), (0.25, 0.22, (body_top - 0.22) / 2.0), shell, yaw)  # the electronics
    sc.box((x, y, (body_top + deck) / 2.0), (0.08, 0.1, (deck - body_top) / 2.0), dark, yaw)  # the column
    kx, ky = local(x, y, yaw, 0.08, 0.0)
    sc.box((kx, ky, deck), (0.24, 0.3, 0.03), shell, yaw)
    sc.box((kx, ky, deck + 0.035), (0.16, 0.22, 0.006), dark, yaw)  # the keyboard
    arm_top = deck + rng.uniform(0.25, 0.45)
    limb(sc, (x, y, deck), (x, y, arm_top), 0.025, dark)
    mx, my = local(x, y, yaw, 0.05, 0.0)
    sc.box((mx, my, arm_top + 0.18), (0.03, 0.28, 0.19), dark, yaw, -0.15)
    sx_, sy_ = local(x, y, yaw, 0.085, 0.0)
    sc.box((sx_, sy_, arm_top + 0.18), (0.003, 0.25, 0.16), jitter(rng, (0.1, 0.2, 0.3), 0.05), yaw, -0.15)
    for side in (1.0, -1.0):  # probe holders
        px, py = local(x, y, yaw, 0.1, side * 0.33)
        sc.cylinder((px, py, deck - 0.05), 0.03, 0.1, dark)
    if rng.random() < 0.5:  # a printer on a shelf in the body
        px, py = local(x, y, yaw, 0.2, 0.0)
        sc.box((px, py, body_top - 0.1), (0.06, 0.14, 0.06), dark, yaw)


def clear_lectern(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A lectern 1.05-1.25 m high: a plinth, a straight or tapering body, a sloping reading top with a lip, maybe
    a front panel in another colour."""
    rng = sc.rng
    h = rng.uniform(1.05, 1.25)
    w, d = rng.uniform(0.5, 0.65), rng.uniform(0.38, 0.5)
    wood = furniture_color(rng) if rng.random() < 0.5 else jitter(rng, pick(rng, ((0.4, 0.25, 0.12),
                                                                                  (0.6, 0.45, 0.28))))
    sc.box((x, y, 0.04), (d / 2.0 + 0.04, w / 2.0 + 0.05, 0.04), jitter(rng, wood[:3], 0.05), yaw)
    taper = rng.random() < 0.5
    rings = 5 if taper else 1
    body_h = h - 0.15
    for k in range(rings):
        frac = (k + 0.5) / rings
        scale = 1.0 - (0.3 * (1.0 - frac) if taper else 0.0)
        sc.box((x, y, 0.08 + body_h * frac), (d / 2.0, w / 2.0 * scale, body_h / rings / 2.0 + 0.002), wood, yaw)
    slope = rng.uniform(0.2, 0.35)
    sc.box((x, y, h - 0.03), (d / 2.0 + 0.05, w / 2.0 + 0.04, 0.025), wood, yaw, slope)
    lx, ly = local(x, y, yaw, d / 2.0 + 0.04, 0.0)
    sc.box((lx, ly, h - 0.04), (0.01, w / 2.0 + 0.04, 0.03), jitter(rng, wood[:3], 0.05), yaw)
    if rng.random() < 0.5:
        fx, fy = local(x, y, yaw, d / 2.0 + 0.003, 0.0)
        sc.box((fx, fy, 0.08 + body_h * 0.6), (0.003, w * 0.32, body_h * 0.2), random_color(rng, 0.1, 0.95), yaw)


def clear_structural_pillar(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A structural pillar to the ceiling (2.6 m): square 0.3-0.5 m or round, in a wall colour, with steel corner
    guards or a dark skirting, maybe a sign plate at eye height."""
    rng = sc.rng
    h = 2.6
    colour = jitter(rng, pick(rng, WALLS), 0.03)
    size = rng.uniform(0.3, 0.5)
    if rng.random() < 0.6:
        sc.box((x, y, h / 2.0), (size / 2.0, size / 2.0, h / 2.0), colour, yaw)
        if rng.random() < 0.6:  # corner guards
            guard = jitter(rng, pick(rng, METAL))
            for cx_ in (1.0, -1.0):
                for cy_ in (1.0, -1.0):
                    gx, gy = local(x, y, yaw, cx_ * size / 2.0, cy_ * size / 2.0)
                    sc.box((gx, gy, 0.6), (0.02, 0.02, 0.6), guard, yaw)
        else:
            sc.box((x, y, 0.05), (size / 2.0 + 0.01, size / 2.0 + 0.01, 0.05), jitter(rng, (0.2, 0.2, 0.22)), yaw)
    else:
        sc.cylinder((x, y, h / 2.0), size / 2.0, h, colour)
        sc.cylinder((x, y, 0.05), size / 2.0 + 0.01, 0.1, jitter(rng, (0.2, 0.2, 0.22)))
    if rng.random() < 0.5:  # a sign plate facing the camera side
        sx_, sy_ = local(x, y, yaw, size / 2.0 + 0.005, 0.0)
        sc.box((sx_, sy_, 1.6), (0.005, 0.15, 0.1), random_color(rng, 0.1, 0.95), yaw)


# -- the twelfth held-out set (``HELD_OUT_12``: the ``unseen12`` split only) ----------------------------------
# Defined and committed after the ``extra8`` training data was written and before any model was trained on it:
# a person under an open umbrella, a person carrying a step ladder at their side, a child on a tricycle; a watering
# can, a gift-wrapped box with a ribbon, a mesh bag of balls; a ticket barrier, a row of bollards, an overbed
# table.
def person_umbrella_holder(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker holding an open umbrella (a shallow dome 0.9-1.2 m across on a shaft) over the head."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw)
    side = 1.0 if rng.random() < 0.5 else -1.0
    hand = (*local(x, y, yaw, 0.2 * s, side * 0.2 * s), 1.15 * s)
    limb(sc, (*local(x, y, yaw, 0.0, side * 0.24 * s), 1.4 * s), hand, 0.045 * s, jitter(rng, pick(rng, CLOTHES)))
    canopy = random_color(rng, 0.05, 0.95)
    top = (hand[0], hand[1], 1.85 * s + rng.uniform(0.0, 0.15))
    limb(sc, (hand[0], hand[1], hand[2] - 0.1), top, 0.01, (0.2, 0.2, 0.2, 1.0))
    radius = rng.uniform(0.45, 0.6)
    for k in range(8):  # the canopy: panels sloping down from the tip
        ang = yaw + k * math.pi / 4.0
        mid = (top[0] + 0.5 * radius * math.cos(ang), top[1] + 0.5 * radius * math.sin(ang), top[2] - 0.12)
        sc.box(mid, (radius / 2.0, radius * 0.22, 0.006), canopy, ang, 0.45)


def person_ladder_carrier(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker carrying a closed step ladder (1.0-1.5 m) upright at their side by one hand, its feet a hand's
    breadth above the floor, its rails along the walking direction."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw)
    side = 1.0 if rng.random() < 0.5 else -1.0
    length, width = rng.uniform(1.0, 1.5), rng.uniform(0.35, 0.5)
    metal = jitter(rng, pick(rng, METAL)) if rng.random() < 0.7 else jitter(rng, (0.85, 0.6, 0.2))
    grip_z = 0.75 * s
    bottom = rng.uniform(0.05, 0.15)
    cx, cy = local(x, y, yaw, rng.uniform(-0.1, 0.1), side * 0.38 * s)
    for rail in (1.0, -1.0):
        rx, ry = local(cx, cy, yaw, rail * width / 2.0, 0.0)
        sc.box((rx, ry, bottom + length / 2.0), (0.035, 0.02, length / 2.0), metal, yaw)
    for k in range(int(length / 0.25)):
        sc.box((cx, cy, bottom + 0.15 + k * 0.25), (width / 2.0, 0.03, 0.012), metal, yaw)
    hand = (*local(x, y, yaw, 0.0, side * 0.36 * s), grip_z + 0.1)
    limb(sc, (*local(x, y, yaw, 0.0, side * 0.24 * s), 1.4 * s), hand, 0.045 * s, jitter(rng, pick(rng, CLOTHES)))


def person_tricycle_child(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A child of 2-5 years on a tricycle: a big front wheel with pedals, two small back wheels, a saddle, the
    child's feet on the pedals and hands on the bar."""
    rng = sc.rng
    frame = random_color(rng, 0.1, 0.95)
    front_r, back_r = rng.uniform(0.13, 0.18), rng.uniform(0.08, 0.11)
    fx, fy = local(x, y, yaw, 0.3, 0.0)
    sc.cylinder((fx, fy, front_r), front_r, 0.04, (0.1, 0.1, 0.1, 1.0), yaw=yaw + math.pi / 2.0, roll=math.pi / 2.0)
    for side in (1.0, -1.0):
        bx, by = local(x, y, yaw, -0.2, side * 0.2)
        sc.cylinder((bx, by, back_r), back_r, 0.03, (0.1, 0.1, 0.1, 1.0), yaw=yaw + math.pi / 2.0, roll=math.pi / 2.0)
    limb(sc, (*local(x, y, yaw, -0.2, -0.2), back_r), (*local(x, y, yaw, -0.2, 0.2), back_r), 0.015, frame)
    seat_z = rng.uniform(0.33, 0.42)
    limb(sc, (*local(x, y, yaw, -0.2, 0.0), back_r), (*local(x, y, yaw, 0.28, 0.0), front_r + 0.35), 0.025, frame)
    limb(sc, (fx, fy, front_r), (*local(x, y, yaw, 0.27, 0.0), front_r + 0.42), 0.02, frame)
    sc.cylinder((*local(x, y, yaw, 0.26, 0.0), front_r + 0.42), 0.012, 0.36, frame, yaw=yaw, roll=math.pi / 2.0)
    sx_, sy_ = local(x, y, yaw, -0.05, 0.0)
    sc.box((sx_, sy_, seat_z), (0.08, 0.07, 0.025), (0.1, 0.1, 0.1, 1.0), yaw)
    colors = clothing_colors(sc)
    c = rng.uniform(0.45, 0.55)  # the child's scale
    for side in (1.0, -1.0):
        knee = (*local(x, y, yaw, 0.15, side * 0.08), seat_z + 0.12)
        limb(sc, (*local(x, y, yaw, -0.05, side * 0.06), seat_z + 0.05), knee, 0.05 * c + 0.01, colors["trousers"])
        limb(sc, knee, (*local(x, y, yaw, 0.3, side * 0.07), front_r + side * 0.05), 0.045 * c + 0.01,
             colors["trousers"])
    torso_h = 0.62 * c
    sc.box((sx_, sy_, seat_z + 0.05 + torso_h / 2.0), (0.09, 0.13, torso_h / 2.0), colors["shirt"], yaw, 0.1)
    sc.sphere((sx_, sy_, seat_z + 0.05 + torso_h + 0.1), 0.09, colors["skin"])
    for side in (1.0, -1.0):
        limb(sc, (*local(x, y, yaw, -0.03, side * 0.14), seat_z + torso_h - 0.02),
             (*local(x, y, yaw, 0.26, side * 0.16), front_r + 0.42), 0.03, colors["shirt"])


def movable_watering_can(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A plastic or metal watering can: an oval body 0.25-0.4 m high, a long spout with a rose, a top handle."""
    rng = sc.rng
    h, r = rng.uniform(0.25, 0.4), rng.uniform(0.1, 0.15)
    body = jitter(rng, pick(rng, ((0.2, 0.6, 0.3), (0.9, 0.4, 0.1), (0.2, 0.4, 0.8), (0.7, 0.72, 0.75),
                                  (0.85, 0.15, 0.2))))
    for k in (-0.5, 0.5):  # an oval: two overlapping cylinders
        cx, cy = local(x, y, yaw, k * r, 0.0)
        sc.cylinder((cx, cy, h / 2.0), r, h, body)
    spout0 = (*local(x, y, yaw, r * 1.3, 0.0), h * 0.2)
    spout1 = (*local(x, y, yaw, r * 1.3 + 0.3, 0.0), h * 0.2 + 0.3)
    limb(sc, spout0, spout1, 0.018, body)
    sc.sphere(spout1, 0.035, body)
    p0, p1 = local(x, y, yaw, -r * 1.2, 0.0), local(x, y, yaw, r * 0.8, 0.0)
    limb(sc, (*p0, h - 0.02), (*p0, h + 0.1), 0.015, body)
    limb(sc, (*p0, h + 0.1), (*p1, h + 0.05), 0.015, body)


def movable_gift_box(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A box 0.2-0.6 m in patterned wrapping paper, a ribbon crossing it both ways and a bow on top."""
    rng = sc.rng
    a, b, h = rng.uniform(0.2, 0.6), rng.uniform(0.2, 0.5), rng.uniform(0.15, 0.5)
    paper = random_color(rng, 0.15, 0.95)
    sc.box((x, y, h / 2.0), (a / 2.0, b / 2.0, h / 2.0), paper, yaw)
    spot = random_color(rng, 0.05, 0.95)
    for _ in range(int(rng.integers(3, 8))):  # the pattern on the faces towards the camera
        face = 1.0 if rng.random() < 0.5 else -1.0
        px, py = local(x, y, yaw, face * (a / 2.0 + 0.002), rng.uniform(-0.4, 0.4) * b)
        sc.box((px, py, rng.uniform(0.15, 0.85) * h), (0.002, 0.025, 0.025), spot, yaw)
    ribbon = random_color(rng, 0.1, 0.95)
    sc.box((x, y, h / 2.0), (a / 2.0 + 0.004, 0.02, h / 2.0 + 0.004), ribbon, yaw)
    sc.box((x, y, h / 2.0), (0.02, b / 2.0 + 0.004, h / 2.0 + 0.004), ribbon, yaw)
    for side in (1.0, -1.0):  # the bow's loops
        lx, ly = local(x, y, yaw, 0.0, side * 0.05)
        sc.capsule((lx, ly, h + 0.03), 0.025, 0.06, ribbon, yaw=yaw, roll=side * 0.8)


def movable_ball_bag(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A mesh bag of 4-10 sport balls (footballs, basketballs, volleyballs) lying on the floor, tied at the top."""
    rng = sc.rng
    count = int(rng.integers(4, 11))
    r = rng.uniform(0.09, 0.12)
    colours = ((0.95, 0.95, 0.95), (0.85, 0.45, 0.15), (0.95, 0.85, 0.2), (0.2, 0.3, 0.7), (0.1, 0.1, 0.1))
    for k in range(count):
        row = 0 if k < 6 else 1
        ang = k * 1.1
        ox, oy = local(x, y, yaw, 0.9 * r * math.cos(ang) * (1.6 - row), 0.9 * r * math.sin(ang) * (1.6 - row))
        sc.sphere((ox, oy, r + row * 1.5 * r), r, jitter(rng, pick(rng, colours)))
    mesh = jitter(rng, pick(rng, ((0.1, 0.1, 0.1), (0.8, 0.1, 0.1), (0.1, 0.3, 0.7), (0.9, 0.9, 0.9))))
    for k in range(6):  # strands of the net over the heap
        ang = yaw + k * math.pi / 3.0
        limb(sc, (x + 1.6 * r * math.cos(ang), y + 1.6 * r * math.sin(ang), 0.02), (x, y, 3.0 * r + 0.05), 0.004,
             mesh)
    limb(sc, (x, y, 3.0 * r + 0.05), (x, y, 3.0 * r + 0.2), 0.01, mesh)


def clear_ticket_barrier(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A ticket or entry barrier: two or three waist-high cabinets (0.9-1.05 m) with slanted tops and reader
    panels, glass or tripod arms across the lanes between them."""
    rng = sc.rng
    h = rng.uniform(0.9, 1.05)
    shell = jitter(rng, pick(rng, ((0.75, 0.76, 0.78), (0.3, 0.3, 0.32), (0.9, 0.9, 0.88))), 0.03)
    lane = rng.uniform(0.55, 0.7)
    count = int(rng.integers(2, 4))
    glass = rng.random() < 0.5
    for k in range(count):
        cx, cy = local(x, y, yaw, 0.0, (k - (count - 1) / 2.0) * (lane + 0.2))
        sc.box((cx, cy, h / 2.0), (0.45, 0.1, h / 2.0), shell, yaw)
        sc.box((cx, cy, h + 0.02), (0.2, 0.1, 0.02), jitter(rng, (0.15, 0.15, 0.2)), yaw, 0.2)  # the reader
        sc.box((*local(cx, cy, yaw, 0.3, 0.12), h * 0.7), (0.05, 0.004, 0.05), (0.2, 0.7, 0.3, 1.0), yaw)  # a lamp
        if k < count - 1:
            ax, ay = local(cx, cy, yaw, 0.0, (lane + 0.2) / 2.0)
            if glass:
                sc.box((ax, ay, h * 0.6), (0.2, lane / 2.0 - 0.05, 0.3), (0.7, 0.85, 0.9, 1.0), yaw)
            else:
                sc.cylinder((ax, ay, h * 0.8), 0.02, lane - 0.1, jitter(rng, pick(rng, METAL)), yaw=yaw,
                            roll=math.pi / 2.0)


def clear_bollards(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A row of two to four fixed bollards 0.8-1.0 m high, 1.2-1.6 m apart (one of them at (x, y)), steel or
    painted, maybe a reflective band or a chain between them."""
    rng = sc.rng
    h, r = rng.uniform(0.8, 1.0), rng.uniform(0.06, 0.12)
    colour = jitter(rng, pick(rng, (*METAL, (0.9, 0.75, 0.1), (0.15, 0.15, 0.15), (0.2, 0.35, 0.25))))
    count = int(rng.integers(2, 5))
    gap = rng.uniform(1.2, 1.6)
    chain = rng.random() < 0.3
    band = rng.random() < 0.5
    tops = []
    first = -int(rng.integers(count))  # one of them stands at (x, y)
    for k in range(count):
        bx, by = local(x, y, yaw, 0.0, (first + k) * gap)
        sc.cylinder((bx, by, h / 2.0), r, h, colour)
        sc.sphere((bx, by, h), r, colour)
        if band:
            sc.cylinder((bx, by, h * 0.8), r + 0.003, 0.06, (0.95, 0.95, 0.95, 1.0))
        tops.append((bx, by, h * 0.85))
    if chain:
        for a, b in zip(tops, tops[1:]):
            mid = ((a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0, h * 0.65)
            link = jitter(rng, pick(rng, ((0.9, 0.1, 0.1), (0.95, 0.85, 0.1), (0.2, 0.2, 0.2))))
            limb(sc, a, mid, 0.012, link)
            limb(sc, mid, b, 0.012, link)


def clear_overbed_table(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A hospital overbed table: a top 0.8-1.1 m high cantilevered from one column on a C- or H-shaped base with
    castors, maybe a tray and a cup on it."""
    rng = sc.rng
    h = rng.uniform(0.8, 1.1)
    length, depth = rng.uniform(0.7, 0.95), rng.uniform(0.38, 0.45)
    top = jitter(rng, pick(rng, ((0.85, 0.8, 0.7), (0.7, 0.55, 0.4), (0.9, 0.9, 0.9), (0.5, 0.6, 0.7))))
    metal = jitter(rng, pick(rng, METAL))
    end = 1.0 if rng.random() < 0.5 else -1.0
    sc.box((x, y, h), (depth / 2.0, length / 2.0, 0.015), top, yaw)
    cx, cy = local(x, y, yaw, 0.0, end * (length / 2.0 - 0.06))
    sc.box((cx, cy, h / 2.0), (0.04, 0.03, h / 2.0), metal, yaw)
    for fx in (-depth / 2.0 - 0.05, depth / 2.0 + 0.05):  # the base's legs run under the top
        lx, ly = local(cx, cy, yaw, fx, -end * 0.25)
        sc.box((lx, ly, 0.05), (0.025, 0.3, 0.02), metal, yaw)
        for fy in (0.0, -end * 0.5):
            wx, wy = local(cx, cy, yaw, fx, fy)
            sc.sphere((wx, wy, 0.025), 0.025, (0.1, 0.1, 0.1, 1.0))
    sc.box((cx, cy, 0.05), (depth / 2.0 + 0.05, 0.03, 0.02), metal, yaw)
    if rng.random() < 0.5:
        tx, ty = local(x, y, yaw, 0.0, rng.uniform(-0.2, 0.2))
        sc.box((tx, ty, h + 0.025), (0.15, 0.2, 0.01), random_color(rng, 0.1, 0.95), yaw)
        sc.cylinder((tx, ty, h + 0.08), 0.04, 0.1, random_color(rng, 0.1, 0.95))


HELD_OUT_BUILDERS: Dict[str, Builder] = {  # the held-out models' builders, by name
    "dress_walker": lambda sc, x, y, yaw: person_walker(sc, x, y, yaw, dress=True),
    "deepmimic_humanoid": person_deepmimic,
    "crate": movable_crate,
    "textured_cube": movable_textured_cube,
    "taped_parcel": movable_taped_parcel,
    "urdf_table": clear_urdf_table,
    "bench": clear_bench,
    "bed": clear_bed,
    "door_frame": clear_door_frame,
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
    "iv_patient": person_iv_patient,
    "mop_cleaner": person_mop_cleaner,
    "floor_sitter": person_floor_sitter,
    "exercise_ball": movable_exercise_ball,
    "cushion_pile": movable_cushion_pile,
    "toy_car": movable_toy_car,
    "patient_hoist": clear_patient_hoist,
    "upright_piano": clear_upright_piano,
    "aquarium": clear_aquarium,
    "reaching_up": person_reaching_up,
    "dog_walker": person_dog_walker,
    "bench_sleeper": person_bench_sleeper,
    "pet_carrier": movable_pet_carrier,
    "bean_bag": movable_bean_bag,
    "toolbox": movable_toolbox,
    "step_ladder": clear_step_ladder,
    "pedestal_fan": clear_pedestal_fan,
    "kiosk": clear_kiosk,
    "bending_picker": person_bending_picker,
    "box_sitter": person_box_sitter,
    "hooded_coat": person_hooded_coat,
    "bucket_stack": movable_bucket_stack,
    "drawer_unit": movable_drawer_unit,
    "dolly_parcel": movable_dolly_parcel,
    "washing_machine": clear_washing_machine,
    "treadmill": clear_treadmill,
    "easel": clear_easel,
    "shoulder_carry": person_shoulder_carry,
    "cane_elder": person_cane_elder,
    "bike_walker": person_bike_walker,
    "hamper": movable_hamper,
    "tray_stack": movable_tray_stack,
    "tube_bundle": movable_tube_bundle,
    "grandfather_clock": clear_grandfather_clock,
    "water_cooler": clear_water_cooler,
    "ironing_board": clear_ironing_board,
    "stretcher_patient": person_stretcher_patient,
    "panel_carrier": person_panel_carrier,
    "knee_scooter_rider": person_knee_scooter_rider,
    "wet_floor_sign": movable_wet_floor_sign,
    "pedal_bin": movable_pedal_bin,
    "kick_stool": movable_kick_stool,
    "ultrasound_cart": clear_ultrasound_cart,
    "lectern": clear_lectern,
    "structural_pillar": clear_structural_pillar,
    "umbrella_holder": person_umbrella_holder,
    "ladder_carrier": person_ladder_carrier,
    "tricycle_child": person_tricycle_child,
    "watering_can": movable_watering_can,
    "gift_box": movable_gift_box,
    "ball_bag": movable_ball_bag,
    "ticket_barrier": clear_ticket_barrier,
    "bollards": clear_bollards,
    "overbed_table": clear_overbed_table,
}
HELD_OUT_SETS: Dict[str, Dict[str, Tuple[str, ...]]] = {  # held-out split: its models, in the order defined
    "unseen": HELD_OUT, "unseen2": HELD_OUT_2, "unseen3": HELD_OUT_3, "unseen4": HELD_OUT_4,
    "unseen5": HELD_OUT_5, "unseen6": HELD_OUT_6, "unseen7": HELD_OUT_7,
    "unseen8": HELD_OUT_8, "unseen9": HELD_OUT_9, "unseen10": HELD_OUT_10,
    "unseen11": HELD_OUT_11, "unseen12": HELD_OUT_12,
}
