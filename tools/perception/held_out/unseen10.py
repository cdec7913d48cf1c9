"""The tenth held-out set: the ``unseen10`` split only, defined before an extra7 model was measured.

Defined, rendered and measured with the shipped model while the models trained with the procedural ``extra7``
data were training, before any of them was measured: an adult carrying a child on the shoulders, a stooped
elderly person with a walking cane, a person walking a bicycle; a laundry hamper, a stack of trays, a bundle of
cardboard tubes; a grandfather clock, a water cooler, an ironing board.
"""

from __future__ import annotations

import math

from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from tools.perception.held_out.common import parked_bicycle
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

SET = "unseen10"


@held_out(SET, PERSON, "shoulder_carry")
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


@held_out(SET, PERSON, "cane_elder")
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


@held_out(SET, PERSON, "bike_walker")
def person_bike_walker(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker pushing a bicycle along beside them, a hand on the handlebar and one on the saddle."""
    rng = sc.rng
    side = 1.0 if rng.random() < 0.5 else -1.0
    s = person_walker(sc, *local(x, y, yaw, 0.0, side * 0.3), yaw)
    parked_bicycle(sc, *local(x, y, yaw, 0.1, -side * 0.15), yaw)
    for fx, z in ((0.55, 0.98), (-0.15, 0.92)):
        hand = (*local(x, y, yaw, fx, -side * 0.1), z)
        limb(sc, (*local(x, y, yaw, 0.0, side * (0.3 - 0.22 * s)), 1.35 * s), hand, 0.04 * s,
             jitter(rng, pick(rng, CLOTHES)))


@held_out(SET, MOVABLE, "hamper")
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


@held_out(SET, MOVABLE, "tray_stack")
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


@held_out(SET, MOVABLE, "tube_bundle")
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


@held_out(SET, CLEAR, "grandfather_clock")
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


@held_out(SET, CLEAR, "water_cooler")
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


@held_out(SET, CLEAR, "ironing_board")
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
