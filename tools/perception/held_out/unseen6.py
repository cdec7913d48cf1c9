"""The sixth held-out set: the ``unseen6`` split only, defined before the extra5 data was designed.

Defined, rendered and measured before the ``extra5`` training data was designed (which answers the fourth and
fifth sets' failures): two people side by side, a worker in high-visibility clothing, a mobility-scooter
rider; a rolled rug, stacked crates, carrier bags; a sanitiser stand, a parked bicycle, a notice board.
"""

from __future__ import annotations

import math
from typing import Tuple

import numpy as np

from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from tools.perception.held_out.common import parked_bicycle
from tools.perception.held_out.registry import held_out
from tools.perception.scene_base import (
    LIGHT_BOXES,
    METAL,
    UPHOLSTERY,
    Scene,
    Vec3,
    jitter,
    local,
    person_walker,
    pick,
    random_color,
    seated_figure,
)

SET = "unseen6"

HI_VIS: Tuple[Vec3, ...] = ((0.85, 0.95, 0.1), (1.0, 0.55, 0.05), (0.7, 0.95, 0.2))


@held_out(SET, PERSON, "person_pair")
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


@held_out(SET, PERSON, "hi_vis_worker")
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


@held_out(SET, PERSON, "scooter_rider")
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


@held_out(SET, MOVABLE, "rolled_rug")
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


@held_out(SET, MOVABLE, "crate_stack")
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


@held_out(SET, MOVABLE, "carrier_bags")
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


@held_out(SET, CLEAR, "sanitiser_stand")
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


@held_out(SET, CLEAR, "bicycle")
def clear_bicycle(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A parked bicycle on its kickstand (:func:`tools.perception.held_out.common.parked_bicycle`)."""
    parked_bicycle(sc, x, y, yaw)


@held_out(SET, CLEAR, "notice_board")
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
