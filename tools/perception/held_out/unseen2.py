"""The second held-out set: the ``unseen2`` split only, defined before the extra3 model was trained. A child, a
walker with a bag; a cool box, a drum, a wrapped parcel; a bookcase, a coat stand, a pedestal table, a partition.
"""

from __future__ import annotations

import math

from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from tools.perception.held_out.registry import held_out
from tools.perception.scene_base import (
    CLOTHES,
    FURNITURE,
    METAL,
    Scene,
    furniture_color,
    jitter,
    local,
    person_walker,
    pick,
    random_color,
    round_or_square_top,
)

SET = "unseen2"


@held_out(SET, PERSON, "child_walker")
def person_child(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A child: the walker at 0.6-0.75 scale (1.0-1.3 m tall)."""
    person_walker(sc, x, y, yaw, size=(0.6, 0.75))


@held_out(SET, PERSON, "bag_walker")
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


@held_out(SET, MOVABLE, "cooler")
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


@held_out(SET, MOVABLE, "drum")
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


@held_out(SET, MOVABLE, "wrapped_parcel")
def movable_wrapped_parcel(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A parcel in brown or coloured paper tied with a string both ways."""
    rng = sc.rng
    sx, sy, sz = rng.uniform(0.25, 0.55), rng.uniform(0.25, 0.55), rng.uniform(0.15, 0.4)
    paper = jitter(rng, pick(rng, ((0.62, 0.48, 0.32), (0.7, 0.58, 0.4), (0.3, 0.45, 0.7), (0.75, 0.3, 0.35))))
    string = jitter(rng, pick(rng, ((0.9, 0.88, 0.8), (0.15, 0.15, 0.15), (0.8, 0.1, 0.1))), 0.03)
    sc.box((x, y, sz / 2.0), (sx / 2.0, sy / 2.0, sz / 2.0), paper, yaw)
    sc.box((x, y, sz / 2.0), (sx / 2.0 + 0.003, 0.008, sz / 2.0 + 0.003), string, yaw)
    sc.box((x, y, sz / 2.0), (0.008, sy / 2.0 + 0.003, sz / 2.0 + 0.003), string, yaw)


@held_out(SET, CLEAR, "bookcase")
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


@held_out(SET, CLEAR, "coat_rack")
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


@held_out(SET, CLEAR, "pedestal_table")
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


@held_out(SET, CLEAR, "partition")
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
