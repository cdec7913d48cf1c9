"""The ninth held-out set: the ``unseen9`` split only, defined before the extra7 data was written.

Defined, rendered and measured with the shipped model before the procedural people and objects (``extra7``)
were written: a person bent over picking something up, a person sitting on a cardboard box, a person in an
ankle-length hooded coat; a stack of nested buckets, a plastic drawer unit on castors, a parcel on a flat dolly;
a washing machine, a treadmill, a painter's easel.
"""

from __future__ import annotations

import math

from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from tools.perception.held_out.registry import held_out
from tools.perception.scene_base import (
    SHOES,
    SKIN,
    Scene,
    box_color,
    clothing_colors,
    jitter,
    limb,
    local,
    pick,
    random_color,
    seated_figure,
)

SET = "unseen9"


@held_out(SET, PERSON, "bending_picker")
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


@held_out(SET, PERSON, "box_sitter")
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


@held_out(SET, PERSON, "hooded_coat")
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


@held_out(SET, MOVABLE, "bucket_stack")
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


@held_out(SET, MOVABLE, "drawer_unit")
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


@held_out(SET, MOVABLE, "dolly_parcel")
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


@held_out(SET, CLEAR, "washing_machine")
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


@held_out(SET, CLEAR, "treadmill")
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


@held_out(SET, CLEAR, "easel")
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
