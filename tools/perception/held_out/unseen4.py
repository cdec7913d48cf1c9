"""The fourth held-out set: the ``unseen4`` split only, defined before seated people were trained on.

Defined before any model was trained with seated people, castor poles or tall appliances (``ASSISTIVE``):
new instances of those families, and new pushable objects.
"""

from __future__ import annotations

import math

from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from tools.perception.held_out.registry import held_out
from tools.perception.scene_base import (
    METAL,
    UPHOLSTERY,
    Scene,
    jitter,
    local,
    person_walker,
    pick,
    seated_figure,
)

SET = "unseen4"


@held_out(SET, PERSON, "power_chair_user")
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


@held_out(SET, PERSON, "cart_pusher")
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


@held_out(SET, MOVABLE, "lidded_tub")
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


@held_out(SET, MOVABLE, "duffel_bag")
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


@held_out(SET, MOVABLE, "bottle_pack")
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


@held_out(SET, CLEAR, "floor_lamp")
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


@held_out(SET, CLEAR, "fridge")
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


@held_out(SET, CLEAR, "photocopier")
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
