"""The third held-out set: the ``unseen3`` split only, defined before any depth model was trained. A wheelchair
user, a walker on crutches; a linen bag, a trunk, a stack of parcels; an infusion stand, a wardrobe, a vending
machine.
"""

from __future__ import annotations

import math

from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from tools.perception.held_out.registry import held_out
from tools.perception.scene_base import (
    CLOTHES,
    METAL,
    SHOES,
    SKIN,
    Scene,
    box_color,
    furniture_color,
    jitter,
    local,
    person_walker,
    pick,
    random_color,
)

SET = "unseen3"


@held_out(SET, PERSON, "wheelchair_user")
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


@held_out(SET, PERSON, "crutch_walker")
def person_crutch_walker(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker on two forearm crutches planted ahead of the feet."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw)
    metal = jitter(rng, pick(rng, METAL))
    lean = rng.uniform(0.15, 0.35)  # [rad] crutch tips ahead of the hands
    for side in (1.0, -1.0):
        cx, cy = local(x, y, yaw, 0.5 * 0.95 * s * math.sin(lean), side * 0.3 * s)
        sc.capsule((cx, cy, 0.95 * s * math.cos(lean) / 2.0), 0.014, 0.95 * s, metal, yaw=yaw, pitch=lean)


@held_out(SET, MOVABLE, "linen_bag")
def movable_linen_bag(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A full laundry or linen bag: a soft cylinder with a rounded top and a tied neck."""
    rng = sc.rng
    r, h = rng.uniform(0.18, 0.3), rng.uniform(0.3, 0.55)
    cloth = jitter(rng, pick(rng, ((0.9, 0.9, 0.88), (0.3, 0.45, 0.7), (0.75, 0.8, 0.55), (0.85, 0.55, 0.6),
                                   (0.5, 0.5, 0.52))))
    sc.cylinder((x, y, (h - r * 0.4) / 2.0), r, h - r * 0.4, cloth)
    sc.sphere((x, y, h - r * 0.4), r * 0.98, cloth)
    sc.cylinder((x, y, h + r * 0.55), r * 0.25, r * 0.35, cloth)


@held_out(SET, MOVABLE, "trunk")
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


@held_out(SET, MOVABLE, "parcel_stack")
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


@held_out(SET, CLEAR, "iv_stand")
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


@held_out(SET, CLEAR, "wardrobe")
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


@held_out(SET, CLEAR, "vending_machine")
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
