"""What more than one held-out set builds: a parked bicycle (``unseen6``'s ``bicycle``, pushed along by
``unseen10``'s ``bike_walker``). Frozen like the sets: a change here changes both sets' renders."""

from __future__ import annotations

import math

from tools.perception.scene_base import METAL, Scene, jitter, local, pick, random_color, ring


def parked_bicycle(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A parked bicycle on its kickstand: two spoked wheels, a diamond frame, a saddle and handlebars."""
    rng = sc.rng
    frame = random_color(rng, 0.05, 0.9)
    r, base = rng.uniform(0.3, 0.35), rng.uniform(0.5, 0.55)  # [m] wheel radius, half wheelbase
    for fx in (-base, base):
        cx, cy = local(x, y, yaw, fx, 0.0)
        ring(sc, (cx, cy, r), yaw + math.pi / 2.0, radius=r - 0.015, tube=0.015, color=(0.06, 0.06, 0.06, 1.0))
        sc.cylinder((cx, cy, r), 0.03, 0.06, jitter(rng, pick(rng, METAL)), yaw=yaw + math.pi / 2.0, roll=math.pi / 2.0)
    crank = (0.0, 0.3)
    seat = (-0.15, r + 0.55)
    head = (base - 0.12, r + 0.5)
    rear, front = (-base, r), (base, r)
    for (ax, az), (bx, bz) in ((rear, crank), (crank, seat), (seat, head), (crank, head), (rear, seat), (head, front)):
        mx, my = local(x, y, yaw, (ax + bx) / 2.0, 0.0)
        length = math.hypot(bx - ax, bz - az)
        sc.capsule((mx, my, (az + bz) / 2.0), 0.017, length, frame, yaw=yaw,
                   pitch=math.pi / 2.0 - math.atan2(bz - az, bx - ax))
    sx_, sy_ = local(x, y, yaw, seat[0] - 0.02, 0.0)
    sc.box((sx_, sy_, seat[1] + 0.05), (0.12, 0.07, 0.03), (0.08, 0.08, 0.08, 1.0), yaw)
    hx, hy = local(x, y, yaw, head[0] - 0.03, 0.0)
    sc.cylinder((hx, hy, head[1] + 0.12), 0.014, 0.5, (0.1, 0.1, 0.1, 1.0), yaw=yaw + math.pi / 2.0, roll=math.pi / 2.0)
