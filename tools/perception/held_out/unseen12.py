"""The twelfth held-out set: the ``unseen12`` split only, defined after extra8 was written, before training.

Defined and committed after the ``extra8`` training data was written and before any model was trained on it:
a person under an open umbrella, a person carrying a step ladder at their side, a child on a tricycle; a watering
can, a gift-wrapped box with a ribbon, a mesh bag of balls; a ticket barrier, a row of bollards, an overbed
table.
"""

from __future__ import annotations

import math

from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from tools.perception.held_out.registry import held_out
from tools.perception.scene_base import (
    CLOTHES,
    METAL,
    Scene,
    clothing_colors,
    jitter,
    limb,
    local,
    person_walker,
    pick,
    random_color,
)

SET = "unseen12"


@held_out(SET, PERSON, "umbrella_holder")
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


@held_out(SET, PERSON, "ladder_carrier")
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


@held_out(SET, PERSON, "tricycle_child")
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


@held_out(SET, MOVABLE, "watering_can")
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


@held_out(SET, MOVABLE, "gift_box")
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


@held_out(SET, MOVABLE, "ball_bag")
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


@held_out(SET, CLEAR, "ticket_barrier")
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


@held_out(SET, CLEAR, "bollards")
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


@held_out(SET, CLEAR, "overbed_table")
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
