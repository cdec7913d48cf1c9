"""The fifth held-out set: the ``unseen5`` split only, defined before the extra5 data was designed.

Defined, rendered and measured before the ``extra5`` training data was designed (which answers the fourth set's
failures): people kneeling, carrying a box in front of them or pushing a pushchair; new pushable things; a
potted plant, a reception counter and a stack of chairs as furniture.
"""

from __future__ import annotations

import math
from typing import Tuple

import numpy as np

from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from tools.perception.held_out.registry import held_out
from tools.perception.scene_base import (
    BOXES,
    CLOTHES,
    FURNITURE,
    LIGHT_BOXES,
    METAL,
    SHOES,
    SKIN,
    Scene,
    Vec3,
    arms_forward,
    box_color,
    jitter,
    local,
    person_walker,
    pick,
)

SET = "unseen5"

FOLIAGE: Tuple[Vec3, ...] = ((0.15, 0.45, 0.15), (0.25, 0.55, 0.2), (0.1, 0.3, 0.12), (0.35, 0.5, 0.2))


@held_out(SET, PERSON, "kneeler")
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


@held_out(SET, PERSON, "box_carrier")
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


@held_out(SET, PERSON, "stroller_pusher")
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


@held_out(SET, MOVABLE, "laundry_basket")
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


@held_out(SET, MOVABLE, "flat_pack")
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


@held_out(SET, MOVABLE, "water_jugs")
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


@held_out(SET, CLEAR, "potted_plant")
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


@held_out(SET, CLEAR, "reception_counter")
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


@held_out(SET, CLEAR, "chair_stack")
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
