"""The eighth held-out set: the ``unseen8`` split only, defined before an extra6 model was measured.

Defined, rendered and measured with the shipped model while the models trained with ``extra6`` were training,
before any of them was measured: a person reaching up with both arms, a person walking a dog, a person lying on
a bench; a pet carrier, a bean bag, a toolbox; a step ladder, a pedestal fan, a ticket kiosk.
"""

from __future__ import annotations

import math

from flex_nav.perception.labels import CLEAR, MOVABLE, PERSON
from tools.perception.held_out.registry import held_out
from tools.perception.scene_base import (
    CLOTHES,
    LIGHT_BOXES,
    METAL,
    SHOES,
    SKIN,
    Scene,
    furniture_color,
    jitter,
    limb,
    local,
    person_walker,
    pick,
    random_color,
    ring,
)

SET = "unseen8"


@held_out(SET, PERSON, "reaching_up")
def person_reaching_up(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker-built person with both arms raised (reaching for a high shelf), sometimes on tiptoe."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw)
    sleeve = jitter(rng, pick(rng, CLOTHES))
    shoulder = 0.9 * s + 0.55 * s
    for side in (1.0, -1.0):
        ax, ay = local(x, y, yaw, rng.uniform(0.0, 0.15), side * 0.22 * s)
        sc.capsule((ax, ay, shoulder + 0.3 * s), 0.045 * s, 0.55 * s, sleeve, yaw=yaw, pitch=rng.uniform(-0.3, 0.1))
        hx, hy = local(x, y, yaw, 0.05, side * 0.22 * s)
        sc.sphere((hx, hy, shoulder + 0.62 * s), 0.045 * s, jitter(rng, pick(rng, SKIN), 0.03))


@held_out(SET, PERSON, "dog_walker")
def person_dog_walker(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A walker with a dog on a lead beside or ahead of them (the dog: body, legs, head, tail)."""
    rng = sc.rng
    s = person_walker(sc, x, y, yaw)
    side = 1.0 if rng.random() < 0.5 else -1.0
    dx, dy = local(x, y, yaw, rng.uniform(0.2, 0.7), side * rng.uniform(0.4, 0.7))
    size = rng.uniform(0.6, 1.2)
    fur = jitter(rng, pick(rng, ((0.1, 0.08, 0.06), (0.55, 0.4, 0.2), (0.85, 0.75, 0.55), (0.95, 0.95, 0.9),
                                 (0.4, 0.4, 0.42))))
    body_z, length = 0.35 * size, 0.5 * size
    sc.capsule((dx, dy, body_z), 0.1 * size, length, fur, yaw=yaw, pitch=math.pi / 2.0)
    for fx in (length / 2.0, -length / 2.0):
        for fy in (0.06 * size, -0.06 * size):
            lx, ly = local(dx, dy, yaw, fx, fy)
            sc.capsule((lx, ly, body_z / 2.0), 0.025 * size, body_z - 0.05, fur, yaw=yaw)
    hx, hy = local(dx, dy, yaw, length / 2.0 + 0.15 * size, 0.0)
    sc.sphere((hx, hy, body_z + 0.15 * size), 0.09 * size, fur)
    tx, ty = local(dx, dy, yaw, -length / 2.0 - 0.1 * size, 0.0)
    sc.capsule((tx, ty, body_z + 0.08 * size), 0.015 * size, 0.2 * size, fur, yaw=yaw, pitch=-0.6)
    hand_x, hand_y = local(x, y, yaw, 0.1, side * 0.25 * s)
    limb(sc, (hand_x, hand_y, 0.85 * s), (hx, hy, body_z + 0.15 * size), 0.006, jitter(rng, (0.7, 0.1, 0.1)))


@held_out(SET, PERSON, "bench_sleeper")
def person_bench_sleeper(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A person lying on their back or side along a bench, at least 1.3 m from the camera (at the origin, looking
    along +x: nearer, the camera sees only the bench's side below the person)."""
    rng = sc.rng
    far = math.hypot(x, y)
    if far < 1.3:
        x, y = x * 1.3 / far, y * 1.3 / far
    length, depth, h = rng.uniform(1.7, 2.0), rng.uniform(0.4, 0.5), rng.uniform(0.4, 0.48)
    seat = furniture_color(rng)
    sc.box((x, y, h), (depth / 2.0, length / 2.0, 0.03), seat, yaw)
    for fy in (length / 2.0 - 0.1, -length / 2.0 + 0.1):
        px, py = local(x, y, yaw, 0.0, fy)
        sc.box((px, py, h / 2.0), (depth / 2.0 - 0.03, 0.03, h / 2.0), seat, yaw)
    s = rng.uniform(0.9, 1.05)
    shirt, trousers = jitter(rng, pick(rng, CLOTHES)), jitter(rng, pick(rng, CLOTHES))
    skin, shoes = jitter(rng, pick(rng, SKIN), 0.03), jitter(rng, pick(rng, SHOES), 0.03)
    along = yaw + math.pi / 2.0  # the body lies along the bench
    top = h + 0.03
    thick = rng.uniform(0.2, 0.26) * s if rng.random() < 0.6 else rng.uniform(0.34, 0.4) * s  # back or side
    head_end = 1.0 if rng.random() < 0.5 else -1.0
    tx, ty = local(x, y, yaw, 0.0, head_end * 0.45 * s)
    sc.box((tx, ty, top + thick / 2.0), (0.19 * s, 0.28 * s, thick / 2.0), shirt, yaw)
    hx, hy = local(x, y, yaw, 0.0, head_end * 0.82 * s)
    sc.sphere((hx, hy, top + 0.1 * s), 0.1 * s, skin)
    for side in (1.0, -1.0):
        lx, ly = local(x, y, yaw, side * 0.09 * s, -head_end * 0.3 * s)
        sc.capsule((lx, ly, top + 0.07 * s), 0.07 * s, 0.75 * s, trousers, yaw=along, pitch=math.pi / 2.0)
        fx, fy = local(x, y, yaw, side * 0.09 * s, -head_end * 0.75 * s)
        sc.box((fx, fy, top + 0.1 * s), (0.045 * s, 0.04 * s, 0.1 * s), shoes, yaw)


@held_out(SET, MOVABLE, "pet_carrier")
def movable_pet_carrier(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A plastic pet carrier: a two-tone shell with a handle on top, a wire door at the front and side vents."""
    rng = sc.rng
    length, width, h = rng.uniform(0.45, 0.7), rng.uniform(0.3, 0.45), rng.uniform(0.3, 0.45)
    top = jitter(rng, pick(rng, ((0.85, 0.85, 0.82), (0.2, 0.35, 0.7), (0.6, 0.6, 0.62), (0.75, 0.3, 0.3))))
    base = jitter(rng, pick(rng, ((0.15, 0.15, 0.18), (0.5, 0.5, 0.52), (0.9, 0.9, 0.88))))
    sc.box((x, y, h * 0.25), (length / 2.0, width / 2.0, h * 0.25), base, yaw)
    sc.box((x, y, h * 0.72), (length / 2.0 - 0.01, width / 2.0 - 0.01, h * 0.22), top, yaw)
    sc.box((x, y, h + 0.03), (0.1, 0.02, 0.03), base, yaw)
    dx, dy = local(x, y, yaw, length / 2.0 + 0.003, 0.0)
    for k in range(5):
        gx, gy = local(dx, dy, yaw, 0.0, (k / 4.0 - 0.5) * width * 0.7)
        sc.box((gx, gy, h * 0.5), (0.003, 0.004, h * 0.3), (0.3, 0.3, 0.32, 1.0), yaw)
    for side in (1.0, -1.0):
        for k in range(3):
            vx, vy = local(x, y, yaw, (k - 1) * length * 0.2, side * (width / 2.0 - 0.005))
            sc.box((vx, vy, h * 0.72), (0.04, 0.003, 0.01), (0.1, 0.1, 0.1, 1.0), yaw)


@held_out(SET, MOVABLE, "bean_bag")
def movable_bean_bag(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A bean bag: a squashed round body of spheres with a dent where one sits, in fabric colours."""
    rng = sc.rng
    r = rng.uniform(0.3, 0.45)
    fabric = random_color(rng, 0.1, 0.9)
    for k in range(7):
        a = 2.0 * math.pi * k / 7.0 + yaw
        sc.sphere((x + 0.45 * r * math.cos(a), y + 0.45 * r * math.sin(a), 0.55 * r), 0.6 * r, fabric)
    bx, by = local(x, y, yaw, -0.3 * r, 0.0)
    sc.sphere((bx, by, 0.95 * r), 0.55 * r, fabric)


@held_out(SET, MOVABLE, "toolbox")
def movable_toolbox(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A toolbox or tackle box on the floor: a metal or plastic case with a lid line, latches and a carry handle,
    sometimes two stacked."""
    rng = sc.rng
    z = 0.0
    for _ in range(1 if rng.random() < 0.6 else 2):
        length, width, h = rng.uniform(0.4, 0.65), rng.uniform(0.2, 0.3), rng.uniform(0.18, 0.3)
        case = jitter(rng, pick(rng, ((0.8, 0.1, 0.1), (0.1, 0.2, 0.6), (0.95, 0.75, 0.1), (0.2, 0.2, 0.2),
                                      (0.6, 0.6, 0.62))))
        sc.box((x, y, z + h / 2.0), (length / 2.0, width / 2.0, h / 2.0), case, yaw)
        sc.box((x, y, z + h * 0.7), (length / 2.0 + 0.003, width / 2.0 + 0.003, 0.005), (0.1, 0.1, 0.1, 1.0), yaw)
        for fx in (-length * 0.3, length * 0.3):
            lx, ly = local(x, y, yaw, fx, width / 2.0 + 0.004)
            sc.box((lx, ly, z + h * 0.7), (0.02, 0.004, 0.025), (0.8, 0.8, 0.82, 1.0), yaw)
        z += h
    sc.box((x, y, z + 0.05), (length * 0.25, 0.015, 0.015), (0.1, 0.1, 0.1, 1.0), yaw)
    for fx in (-length * 0.25, length * 0.25):
        hx, hy = local(x, y, yaw, fx, 0.0)
        sc.box((hx, hy, z + 0.025), (0.012, 0.012, 0.025), (0.1, 0.1, 0.1, 1.0), yaw)


@held_out(SET, CLEAR, "step_ladder")
def clear_step_ladder(sc: Scene, x: float, y: float, yaw: float) -> None:
    """An A-frame step ladder standing open: two pairs of rails, steps on the front, a top platform."""
    rng = sc.rng
    h, width = rng.uniform(1.0, 1.8), rng.uniform(0.4, 0.55)
    spread = rng.uniform(0.3, 0.4) * h  # [m] between the feet of the front and back rails
    color = jitter(rng, pick(rng, (*METAL, (0.85, 0.65, 0.1), (0.55, 0.38, 0.22))))
    lean = math.atan2(spread / 2.0, h)
    for front in (1.0, -1.0):
        for side in (1.0, -1.0):
            rx, ry = local(x, y, yaw, front * spread / 4.0, side * width / 2.0)
            sc.box((rx, ry, h / 2.0), (0.02, 0.015, h / 2.0 / math.cos(lean)), color, yaw, -front * lean)
    steps = int(h / 0.28)
    for k in range(1, steps + 1):
        z = k * h / (steps + 1)
        fx, fy = local(x, y, yaw, spread / 2.0 * (1.0 - z / h), 0.0)
        sc.box((fx, fy, z), (0.06, width / 2.0, 0.012), color, yaw)
    sc.box((x, y, h), (0.1, width / 2.0 + 0.01, 0.02), color, yaw)


@held_out(SET, CLEAR, "pedestal_fan")
def clear_pedestal_fan(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A pedestal fan: a round or cross base, a telescopic pole and a round guard with the motor behind it."""
    rng = sc.rng
    h = rng.uniform(1.0, 1.4)
    body = jitter(rng, pick(rng, ((0.95, 0.95, 0.95), (0.1, 0.1, 0.1), (0.6, 0.6, 0.62))))
    if rng.random() < 0.5:
        sc.cylinder((x, y, 0.02), 0.2, 0.04, body)
    else:
        for k in range(2):
            sc.box((x, y, 0.02), (0.25, 0.025, 0.02), body, yaw + k * math.pi / 2.0)
    sc.cylinder((x, y, h / 2.0), 0.015, h, body)
    r = rng.uniform(0.2, 0.26)
    gx, gy = local(x, y, yaw, 0.08, 0.0)
    ring(sc, (gx, gy, h + r * 0.6), yaw + math.pi / 2.0, radius=r, tube=0.008, color=body, segments=14)
    sc.cylinder((gx, gy, h + r * 0.6), r * 0.25, 0.02, body, yaw=yaw, roll=math.pi / 2.0, pitch=0.0)
    mx, my = local(x, y, yaw, -0.05, 0.0)
    sc.cylinder((mx, my, h + r * 0.6), 0.08, 0.14, body, yaw=yaw + math.pi / 2.0, roll=math.pi / 2.0)


@held_out(SET, CLEAR, "kiosk")
def clear_kiosk(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A self-service kiosk (check-in, tickets): a tall slim cabinet with a tilted touch screen, a card slot and a
    printed header."""
    rng = sc.rng
    w, d, h = rng.uniform(0.45, 0.7), rng.uniform(0.35, 0.5), rng.uniform(1.4, 1.8)
    shell = jitter(rng, pick(rng, ((0.95, 0.95, 0.95), (0.15, 0.15, 0.18), (0.2, 0.4, 0.7), (0.7, 0.72, 0.75))))
    sc.box((x, y, h / 2.0), (d / 2.0, w / 2.0, h / 2.0), shell, yaw)
    sx_, sy_ = local(x, y, yaw, d / 2.0 + 0.01, 0.0)
    sc.box((sx_, sy_, h * 0.68), (0.01, w / 2.0 - 0.06, 0.2), jitter(rng, (0.1, 0.2, 0.35)), yaw, -0.25)
    cx, cy = local(x, y, yaw, d / 2.0 + 0.005, w * 0.2)
    sc.box((cx, cy, h * 0.45), (0.005, 0.05, 0.01), (0.05, 0.05, 0.05, 1.0), yaw)
    hx, hy = local(x, y, yaw, d / 2.0 + 0.003, 0.0)
    sc.box((hx, hy, h - 0.1), (0.003, w / 2.0 - 0.03, 0.07), jitter(rng, pick(rng, LIGHT_BOXES)), yaw)
