"""The seventh held-out set: the ``unseen7`` split only, defined before a height-channel model was measured.

Defined, rendered and measured with the shipped model before any model trained with a height channel was
looked at: a patient walking with a drip pole, a cleaner bent over a mop, a person sitting on the floor; an
exercise ball, a pile of cushions, a ride-on toy car; a patient hoist, an upright piano, an aquarium on a stand.
"""

from __future__ import annotations

import math
from typing import Tuple

from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from tools.perception.held_out.registry import held_out
from tools.perception.scene_base import (
    CLOTHES,
    METAL,
    SHOES,
    SKIN,
    Scene,
    Vec3,
    castor_star,
    furniture_color,
    jitter,
    local,
    person_walker,
    pick,
    random_color,
    ring,
    seated_figure,
)

SET = "unseen7"

PLASTIC: Tuple[Vec3, ...] = ((0.9, 0.15, 0.15), (0.15, 0.35, 0.85), (0.95, 0.8, 0.1), (0.2, 0.65, 0.3),
                             (0.6, 0.25, 0.7), (0.95, 0.5, 0.1))


@held_out(SET, PERSON, "iv_patient")
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


@held_out(SET, PERSON, "mop_cleaner")
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


@held_out(SET, PERSON, "floor_sitter")
def person_floor_sitter(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A person sitting on the floor (fallen, or resting against nothing): legs along the floor, the torso upright
    or leaning back, the hands on the lap."""
    rng = sc.rng
    seated_figure(sc, x, y, yaw, seat_h=0.0, foot_z=0.0, hip_fx=0.0, lean=rng.uniform(0.0, 0.5))


@held_out(SET, MOVABLE, "exercise_ball")
def movable_exercise_ball(sc: Scene, x: float, y: float, yaw: float) -> None:
    """An inflated exercise ball (0.45-0.75 m across) on the floor, with a seam around it."""
    rng = sc.rng
    r = rng.uniform(0.22, 0.38)
    color = jitter(rng, pick(rng, (*PLASTIC, (0.5, 0.5, 0.55), (0.1, 0.1, 0.12))))
    sc.sphere((x, y, r), r, color)
    ring(sc, (x, y, r), yaw, radius=r, tube=0.006, color=(color[0] * 0.7, color[1] * 0.7, color[2] * 0.7, 1.0),
         segments=16)


@held_out(SET, MOVABLE, "cushion_pile")
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


@held_out(SET, MOVABLE, "toy_car")
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


@held_out(SET, CLEAR, "patient_hoist")
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


@held_out(SET, CLEAR, "upright_piano")
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


@held_out(SET, CLEAR, "aquarium")
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
