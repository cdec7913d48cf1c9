"""The eleventh held-out set: the ``unseen11`` split only, defined before the extra8 data was written.

Defined, rendered and committed before the ``extra8`` training data was written, and measured only as a
whole until a model trained with it was: a patient lying on a stretcher trolley (back rest flat or raised), a
person carrying a large flat panel in front of them, a person on a knee scooter; a folding wet-floor sign, a
pedal bin, a rolling kick stool; an ultrasound cart, a lectern, a structural pillar.
(The seen ``pillar`` is a plain column, not this ``structural_pillar``.)
"""

from __future__ import annotations

import math

from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from tools.perception.held_out.registry import held_out
from tools.perception.scene_base import (
    FRAMES,
    FURNITURE,
    METAL,
    SKIN,
    WALLS,
    Scene,
    arms_forward,
    clothing_colors,
    furniture_color,
    jitter,
    limb,
    local,
    person_walker,
    pick,
    random_color,
)

SET = "unseen11"


@held_out(SET, PERSON, "stretcher_patient")
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


@held_out(SET, PERSON, "panel_carrier")
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


@held_out(SET, PERSON, "knee_scooter_rider")
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


@held_out(SET, MOVABLE, "wet_floor_sign")
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


@held_out(SET, MOVABLE, "pedal_bin")
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


@held_out(SET, MOVABLE, "kick_stool")
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


@held_out(SET, CLEAR, "ultrasound_cart")
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


@held_out(SET, CLEAR, "lectern")
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


@held_out(SET, CLEAR, "structural_pillar")
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
