"""Parts of the classifier's dataset scenes that the training models (:mod:`tools.perception.scenes`) and the
held-out models (:mod:`tools.perception.held_out`) share: the visual-only :class:`Scene`, the colour
palettes, the rendered :class:`Sample`, and the figures and frames several models are built from (the walking
and the seated person, a wheelchair, castor stars, legs). Changing any of them changes the stored renders.
"""

from __future__ import annotations

import contextlib
import math
import os
import sys
from dataclasses import dataclass
from typing import Any, Callable, Dict, Iterator, Sequence, Tuple

import numpy as np
import pybullet
import pybullet_data

from flex_nav_sim.bodies import FLOOR_COLOR
from flex_nav_sim.world import DEFAULT_COLORS

Rgba = Tuple[float, float, float, float]
Vec3 = Tuple[float, float, float]
DATA = pybullet_data.getDataPath()

# -- colour palettes ----------------------------------------------------------------------------------
CLOTHES: Tuple[Vec3, ...] = (
    DEFAULT_COLORS["person"][:3], (0.1, 0.15, 0.35), (0.15, 0.15, 0.18), (0.25, 0.35, 0.6), (0.2, 0.5, 0.5),
    (0.55, 0.1, 0.1), (0.1, 0.4, 0.15), (0.45, 0.4, 0.3), (0.9, 0.9, 0.92), (0.5, 0.2, 0.45), (0.85, 0.55, 0.1),
    (0.3, 0.55, 0.75), (0.6, 0.75, 0.85), (0.35, 0.25, 0.2), (0.8, 0.25, 0.45),
)
SKIN: Tuple[Vec3, ...] = ((0.95, 0.8, 0.7), (0.85, 0.65, 0.5), (0.6, 0.42, 0.3), (0.4, 0.27, 0.18))
SHOES: Tuple[Vec3, ...] = ((0.05, 0.05, 0.05), (0.3, 0.2, 0.1), (0.9, 0.9, 0.9), (0.2, 0.2, 0.3))
BOXES: Tuple[Vec3, ...] = (
    DEFAULT_COLORS["box"][:3], (0.75, 0.58, 0.35), (0.65, 0.5, 0.3), (0.85, 0.7, 0.45), (0.9, 0.9, 0.88),
    (0.3, 0.45, 0.75), (0.75, 0.2, 0.2), (0.25, 0.55, 0.3), (0.9, 0.8, 0.2), (0.45, 0.45, 0.45),
    (0.8, 0.8, 0.8), (0.62, 0.62, 0.64), (0.97, 0.97, 0.97),  # grey and white plastic
)
FURNITURE: Tuple[Vec3, ...] = (
    DEFAULT_COLORS["obstacle"][:3], DEFAULT_COLORS["wall"][:3], DEFAULT_COLORS["door"][:3], (0.9, 0.9, 0.9),
    (0.6, 0.6, 0.62), (0.4, 0.4, 0.42), (0.55, 0.4, 0.25), (0.7, 0.55, 0.4), (0.8, 0.8, 0.75), (0.5, 0.55, 0.6),
)
WALLS: Tuple[Vec3, ...] = (
    DEFAULT_COLORS["wall"][:3], (0.85, 0.85, 0.8), (0.75, 0.8, 0.85), (0.9, 0.88, 0.8), (0.6, 0.65, 0.6),
    (0.8, 0.75, 0.7), (0.95, 0.95, 0.95),
)
FLOORS: Tuple[Vec3, ...] = (
    FLOOR_COLOR[:3], (0.7, 0.7, 0.68), (0.6, 0.55, 0.5), (0.5, 0.55, 0.6), (0.85, 0.85, 0.85), (0.55, 0.45, 0.35),
    (0.4, 0.42, 0.45),
)


def jitter(rng: np.random.Generator, color: Vec3, amount: float = 0.06) -> Rgba:
    r, g, b = (float(np.clip(v + rng.uniform(-amount, amount), 0.0, 1.0)) for v in color)
    return r, g, b, 1.0


def pick(rng: np.random.Generator, palette: Sequence[Vec3]) -> Vec3:
    return palette[int(rng.integers(len(palette)))]


def random_color(rng: np.random.Generator, lo: float, hi: float, amount: float = 0.0) -> Rgba:
    """Any colour: each channel uniform in [lo, hi], then :func:`jitter` by ``amount``."""
    r, g, b = (float(v) for v in rng.uniform(lo, hi, 3))
    return jitter(rng, (r, g, b), amount)


@dataclass(frozen=True)
class Sample:
    """One rendered sample: the image and what is in it."""

    rgb: np.ndarray  # uint8 (height, width, 3)
    depth: np.ndarray  # float32 (height, width) [m], registered to rgb; +inf where nothing was rendered
    label: str
    model: str
    profile: str
    distance: float  # [m] camera to target (0 for 'empty')


class Scene:
    """Visual-only primitives in one BulletClient (nothing is simulated, only rendered)."""

    def __init__(self, client: Any, rng: np.random.Generator) -> None:
        self.c = client
        self.rng = rng

    def _body(self, visual: int, pos: Vec3, orn: Sequence[float]) -> int:
        return int(self.c.createMultiBody(0.0, -1, visual, list(pos), list(orn)))

    def box(self, pos: Vec3, half: Vec3, color: Rgba, yaw: float = 0.0, pitch: float = 0.0) -> int:
        visual = self.c.createVisualShape(pybullet.GEOM_BOX, halfExtents=list(half), rgbaColor=list(color))
        return self._body(visual, pos, self.c.getQuaternionFromEuler([0.0, pitch, yaw]))

    def cylinder(self, pos: Vec3, radius: float, length: float, color: Rgba, *, yaw: float = 0.0,
                 pitch: float = 0.0, roll: float = 0.0) -> int:
        """Upright unless turned: ``roll`` = pi/2 lays it on its side across ``yaw`` (a wheel)."""
        visual = self.c.createVisualShape(pybullet.GEOM_CYLINDER, radius=radius, length=length, rgbaColor=list(color))
        upright = roll == 0.0 and pitch == 0.0 and yaw == 0.0
        orn = (0.0, 0.0, 0.0, 1.0) if upright else self.c.getQuaternionFromEuler([roll, pitch, yaw])
        return self._body(visual, pos, orn)

    def capsule(self, pos: Vec3, radius: float, length: float, color: Rgba, *, yaw: float = 0.0,
                pitch: float = 0.0, roll: float = 0.0) -> int:
        visual = self.c.createVisualShape(pybullet.GEOM_CAPSULE, radius=radius, length=length, rgbaColor=list(color))
        return self._body(visual, pos, self.c.getQuaternionFromEuler([roll, pitch, yaw]))

    def sphere(self, pos: Vec3, radius: float, color: Rgba) -> int:
        visual = self.c.createVisualShape(pybullet.GEOM_SPHERE, radius=radius, rgbaColor=list(color))
        return self._body(visual, pos, (0.0, 0.0, 0.0, 1.0))

    def floor(self, color: Rgba) -> None:
        visual = self.c.createVisualShape(pybullet.GEOM_BOX, halfExtents=[30.0, 30.0, 0.005], rgbaColor=list(color))
        self._body(visual, (0.0, 0.0, -0.005), (0.0, 0.0, 0.0, 1.0))

    def wall(self, centre: Tuple[float, float], length: float, height: float, yaw: float, color: Rgba, *,
             thickness: float = 0.1) -> None:
        """A wall segment whose long side runs along ``yaw`` [rad]."""
        self.box((centre[0], centre[1], height / 2.0), (length / 2.0, thickness / 2.0, height / 2.0), color, yaw)


def local(x: float, y: float, yaw: float, fx: float, fy: float) -> Tuple[float, float]:
    """A point (fx forward, fy left) [m] in the frame of an object at (x, y, yaw), in world coordinates."""
    c, s = math.cos(yaw), math.sin(yaw)
    return x + c * fx - s * fy, y + s * fx + c * fy


def limb(sc: Scene, a: Vec3, b: Vec3, radius: float, color: Rgba) -> None:
    """A capsule whose axis runs from point ``a`` to point ``b`` [m]."""
    dx, dy, dz = b[0] - a[0], b[1] - a[1], b[2] - a[2]
    sc.capsule(((a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0, (a[2] + b[2]) / 2.0), radius,
               max(math.sqrt(dx * dx + dy * dy + dz * dz), 1e-3), color, yaw=math.atan2(dy, dx),
               pitch=math.atan2(math.hypot(dx, dy), dz))


def person_walker(sc: Scene, x: float, y: float, yaw: float, *, dress: bool = False,
                  size: Tuple[float, float] = (0.9, 1.1)) -> float:
    """A figure of primitives: legs in a walking pose, shoes, torso, arms, head (``dress``: a skirt), scaled
    by a factor drawn from ``size``; returns that factor."""
    rng = sc.rng
    s = rng.uniform(*size)
    hip_h, hip_w = 0.9 * s, rng.uniform(0.08, 0.12) * s
    leg_r = rng.uniform(0.05, 0.08) * s
    stride = rng.uniform(-0.45, 0.45)  # [rad] leg swing
    trousers = jitter(rng, pick(rng, CLOTHES))
    shirt = jitter(rng, pick(rng, CLOTHES))
    skin = jitter(rng, pick(rng, SKIN), 0.03)
    shoes = jitter(rng, pick(rng, SHOES), 0.03)
    legs = skin if dress and rng.random() < 0.6 else trousers
    lower = rng.random()  # trousers, shorts (bare lower legs) or a long coat over the thighs
    for side, swing in ((1.0, stride), (-1.0, -stride)):
        hx, hy = local(x, y, yaw, 0.0, side * hip_w)
        length = hip_h / max(math.cos(swing), 0.5)
        fwd = 0.5 * length * math.sin(swing)
        cx, cy = local(hx, hy, yaw, fwd, 0.0)
        sc.capsule((cx, cy, hip_h - 0.5 * length * math.cos(swing) + 0.02), leg_r, length - 2 * leg_r, legs,
                   yaw=yaw, pitch=-swing)
        if not dress and 0.6 <= lower < 0.8:  # shorts: bare lower legs
            kx, ky = local(hx, hy, yaw, 0.75 * length * math.sin(swing), 0.0)
            sc.capsule((kx, ky, hip_h - 0.75 * length * math.cos(swing) + 0.02), leg_r * 1.02, 0.5 * length - 2 * leg_r,
                       skin, yaw=yaw, pitch=-swing)
        foot_fwd = length * math.sin(swing) + 0.06
        fx, fy = local(hx, hy, yaw, foot_fwd, 0.0)
        sc.box((fx, fy, 0.04), (0.13 * s, 0.05 * s, 0.04), shoes, yaw)
    torso_h = rng.uniform(0.5, 0.62) * s
    width, depth = rng.uniform(0.34, 0.44) * s, rng.uniform(0.2, 0.28) * s
    sc.box((x, y, hip_h + torso_h / 2.0), (depth / 2.0, width / 2.0, torso_h / 2.0), shirt, yaw)
    if not dress and lower >= 0.8:  # long coat (lab coat, scrubs gown) down to the knees
        coat = jitter(rng, (0.93, 0.93, 0.93)) if rng.random() < 0.5 else shirt
        half_h = (hip_h - 0.45 * s) / 2.0
        sc.box((x, y, 0.45 * s + half_h + 0.05), (depth / 2.0 + 0.03, width / 2.0 + 0.02, half_h), coat, yaw)
    if dress:
        skirt_bottom = rng.uniform(0.35, 0.6) * s
        sc.cylinder((x, y, (hip_h + 0.05 + skirt_bottom) / 2.0), rng.uniform(0.2, 0.3) * s,
                    hip_h + 0.05 - skirt_bottom, shirt if rng.random() < 0.5 else jitter(rng, pick(rng, CLOTHES)))
    else:
        sc.box((x, y, hip_h), (depth / 2.0 + 0.01, width / 2.0 - 0.02, 0.06), trousers, yaw)  # hips
    shoulder = hip_h + torso_h
    for side in (1.0, -1.0):
        swing = -side * stride * 0.8
        ax, ay = local(x, y, yaw, 0.5 * 0.6 * math.sin(swing), side * (width / 2.0 + 0.05))
        sc.capsule((ax, ay, shoulder - 0.3 * s), 0.045 * s, 0.5 * s, shirt, yaw=yaw, pitch=-swing)
    sc.sphere((x, y, shoulder + 0.15 * s), 0.1 * s, skin)
    return s


def arms_forward(sc: Scene, x: float, y: float, yaw: float, *, fx: float, z: float, scale: float,
                 length: float) -> None:
    """Two bare forearms held forward at height ``z`` [m] (hands on a handle), ``fx`` [m] ahead of a figure of
    ``scale`` at (x, y) facing ``yaw``, ``length`` [m] long."""
    rng = sc.rng
    for side in (1.0, -1.0):
        ax, ay = local(x, y, yaw, fx, side * 0.18 * scale)
        sc.capsule((ax, ay, z), 0.04 * scale, length, jitter(rng, pick(rng, SKIN), 0.03), yaw=yaw,
                   pitch=math.pi / 2.0)


@contextlib.contextmanager
def quiet_output() -> Iterator[None]:
    """Silence file descriptors 1 and 2 (pybullet's C code prints its warnings there, around sys.stdout)."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(1), os.dup(2)]
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 1)
        os.dup2(devnull, 2)
        yield
    finally:
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        for fd in (*saved, devnull):
            os.close(fd)


def color_links(sc: Scene, body: int, colors: Callable[[str], Rgba]) -> None:
    sc.c.changeVisualShape(body, -1, rgbaColor=list(colors("base")))
    for j in range(sc.c.getNumJoints(body)):
        name = sc.c.getJointInfo(body, j)[12].decode()
        sc.c.changeVisualShape(body, j, rgbaColor=list(colors(name)))


def stand_on_floor(sc: Scene, body: int, x: float, y: float, orn: Sequence[float]) -> None:
    """Move ``body`` so its lowest point touches the floor at (x, y)."""
    pos, _ = sc.c.getBasePositionAndOrientation(body)
    lo_z, lo_xy = math.inf, None
    ranges = [sc.c.getAABB(body, j) for j in range(-1, sc.c.getNumJoints(body))]
    lo = np.min([r[0] for r in ranges], axis=0)
    hi = np.max([r[1] for r in ranges], axis=0)
    lo_z = float(lo[2])
    lo_xy = (float(lo[0] + hi[0]) / 2.0, float(lo[1] + hi[1]) / 2.0)
    sc.c.resetBasePositionAndOrientation(
        body, [pos[0] + x - lo_xy[0], pos[1] + y - lo_xy[1], pos[2] - lo_z], list(orn)
    )


def clothing_colors(sc: Scene) -> Dict[str, Rgba]:
    rng = sc.rng
    return {
        "trousers": jitter(rng, pick(rng, CLOTHES)),
        "shirt": jitter(rng, pick(rng, CLOTHES)),
        "skin": jitter(rng, pick(rng, SKIN), 0.03),
        "shoes": jitter(rng, pick(rng, SHOES), 0.03),
    }


# -- parts shared by the training and the held-out models ----------------------------------------------
def box_color(rng: np.random.Generator) -> Rgba:
    return jitter(rng, BOXES[0] if rng.random() < 0.35 else pick(rng, BOXES))


def furniture_color(rng: np.random.Generator) -> Rgba:
    return jitter(rng, pick(rng, FURNITURE))


METAL: Tuple[Vec3, ...] = ((0.75, 0.75, 0.78), (0.55, 0.56, 0.6), (0.35, 0.36, 0.4), (0.92, 0.92, 0.92),
                           (0.3, 0.45, 0.7))
LIGHT_BOXES: Tuple[Vec3, ...] = (
    (0.97, 0.97, 0.97), (0.9, 0.9, 0.88), (0.8, 0.8, 0.8), (0.68, 0.68, 0.7), (0.55, 0.55, 0.57),
    (0.85, 0.9, 0.95), (0.95, 0.9, 0.8), (0.8, 0.85, 0.8), (0.78, 0.72, 0.65),
)


def legs4(sc: Scene, x: float, y: float, yaw: float, *, dx: float, dy: float, height: float, half: float,
          color: Rgba) -> None:
    """Four square legs of ``height`` [m] at (+-dx, +-dy) in the object's frame."""
    for fx in (dx, -dx):
        for fy in (dy, -dy):
            px, py = local(x, y, yaw, fx, fy)
            sc.box((px, py, height / 2.0), (half, half, height / 2.0), color, yaw)


def round_or_square_top(sc: Scene, x: float, y: float, yaw: float, *, z: float, radius: float, thickness: float,
                        color: Rgba, round_chance: float) -> None:
    """A seat or table top centred at height ``z`` [m]: a disc of ``radius`` [m] (with ``round_chance``) or a
    square of the same half-width."""
    if sc.rng.random() < round_chance:
        sc.cylinder((x, y, z), radius, thickness, color)
    else:
        sc.box((x, y, z), (radius, radius, thickness / 2.0), color, yaw)


# -- seated people (the fourth held-out set and the ``extra4`` training splits share the figure) ------------
def seated_figure(sc: Scene, x: float, y: float, yaw: float, *, seat_h: float, foot_z: float = 0.0,
                  hip_fx: float = 0.0, lean: float = 0.0, armrest_h: float | None = None) -> float:
    """A person seated with the hips ``hip_fx`` [m] ahead of (x, y) on a seat ``seat_h`` [m] high: thighs
    forward, shins down to the feet at ``foot_z`` [m], the torso leaning back by ``lean`` [rad], the forearms
    on armrests ``armrest_h`` [m] high (None: on the lap). Returns the figure's scale."""
    rng = sc.rng
    s = rng.uniform(0.85, 1.1)
    trousers, shirt = jitter(rng, pick(rng, CLOTHES)), jitter(rng, pick(rng, CLOTHES))
    skin, shoes = jitter(rng, pick(rng, SKIN), 0.03), jitter(rng, pick(rng, SHOES), 0.03)
    legs = skin if rng.random() < 0.15 else trousers  # a skirt or shorts: bare shins
    thigh_r, thigh_len = rng.uniform(0.06, 0.08) * s, 0.4 * s
    hip_w = rng.uniform(0.09, 0.13) * s
    knee_fx, knee_z = hip_fx + thigh_len, seat_h + thigh_r
    ankle_z = foot_z + 0.08
    for side in (1.0, -1.0):
        tx, ty = local(x, y, yaw, hip_fx + thigh_len / 2.0, side * hip_w)
        sc.capsule((tx, ty, knee_z), thigh_r, thigh_len - thigh_r, trousers, yaw=yaw, pitch=math.pi / 2.0)
        ahead = rng.uniform(-0.08, 0.15)  # [m] feet tucked back or stretched out
        tilt = math.atan2(-ahead, knee_z - ankle_z)
        shin = math.hypot(ahead, knee_z - ankle_z)
        sx_, sy_ = local(x, y, yaw, knee_fx + ahead / 2.0, side * hip_w)
        sc.capsule((sx_, sy_, (knee_z + ankle_z) / 2.0), thigh_r * 0.8, max(shin - thigh_r, 0.05),
                   legs, yaw=yaw, pitch=tilt)
        fx, fy = local(x, y, yaw, knee_fx + ahead + 0.06 * s, side * hip_w)
        sc.box((fx, fy, foot_z + 0.04), (0.12 * s, 0.05 * s, 0.04), shoes, yaw)
    torso_h = rng.uniform(0.5, 0.6) * s
    width, depth = rng.uniform(0.34, 0.42) * s, rng.uniform(0.2, 0.26) * s
    up = (-math.sin(lean), math.cos(lean))  # (forward, up) along the spine
    base_fx, base_z = hip_fx - 0.04, seat_h + 0.04
    cx, cy = local(x, y, yaw, base_fx + up[0] * torso_h / 2.0, 0.0)
    sc.box((cx, cy, base_z + up[1] * torso_h / 2.0), (depth / 2.0, width / 2.0, torso_h / 2.0), shirt, yaw, -lean)
    hx, hy = local(x, y, yaw, base_fx + up[0] * (torso_h + 0.14 * s), 0.0)
    sc.sphere((hx, hy, base_z + up[1] * (torso_h + 0.14 * s)), 0.1 * s, skin)
    shoulder_fx, shoulder_z = base_fx + up[0] * (torso_h - 0.06), base_z + up[1] * (torso_h - 0.06)
    elbow_z = armrest_h + 0.05 if armrest_h is not None else seat_h + 0.16
    for side in (1.0, -1.0):
        arm_y = side * (width / 2.0 + 0.05 * s)
        ux, uy = local(x, y, yaw, shoulder_fx, arm_y)
        sc.capsule((ux, uy, (shoulder_z + elbow_z) / 2.0), 0.045 * s, max(shoulder_z - elbow_z - 0.05, 0.05), shirt,
                   yaw=yaw)
        fore_y = arm_y if armrest_h is not None else side * (hip_w + 0.04)
        ex, ey = local(x, y, yaw, shoulder_fx + 0.14 * s, fore_y)
        sc.capsule((ex, ey, elbow_z), 0.04 * s, 0.22 * s, skin if rng.random() < 0.3 else shirt, yaw=yaw,
                   pitch=math.pi / 2.0)
    return s


UPHOLSTERY: Tuple[Vec3, ...] = ((0.1, 0.1, 0.1), (0.2, 0.25, 0.45), (0.35, 0.2, 0.15), (0.4, 0.4, 0.42),
                                (0.15, 0.35, 0.3))


FRAMES: Tuple[Vec3, ...] = (*METAL, (0.1, 0.1, 0.1), (0.7, 0.1, 0.1), (0.1, 0.45, 0.25), (0.15, 0.2, 0.55))


def ring(sc: Scene, centre: Tuple[float, float, float], yaw: float, *, radius: float, tube: float, color: Rgba,
         segments: int = 12) -> None:
    """A wheel's tyre seen from the side: ``segments`` capsules round a circle of ``radius`` [m] in the vertical
    plane across ``yaw`` (the hub and the spokes stay see-through)."""
    chord = 2.0 * radius * math.sin(math.pi / segments)
    for k in range(segments):
        a = 2.0 * math.pi * (k + 0.5) / segments
        px, py = local(centre[0], centre[1], yaw, radius * math.cos(a), 0.0)
        sc.capsule((px, py, centre[2] + radius * math.sin(a)), tube, chord, color, yaw=yaw, pitch=-a)


def wheelchair(sc: Scene, x: float, y: float, yaw: float) -> Tuple[float, float, float]:
    """A manual wheelchair of random build facing +x: rear wheels (self-propelling, spoked or solid) or small
    transit wheels, castors, a sling seat and back, push handles, maybe armrests, footplates.
    Returns (seat height, footplate height, armrest height or 0) [m]."""
    rng = sc.rng
    frame = jitter(rng, pick(rng, FRAMES))
    cloth = jitter(rng, pick(rng, UPHOLSTERY))
    tyre = jitter(rng, (0.07, 0.07, 0.07), 0.02)
    seat_h, half_w = rng.uniform(0.44, 0.52), rng.uniform(0.2, 0.27)
    rear_r = rng.uniform(0.24, 0.33) if rng.random() < 0.75 else rng.uniform(0.1, 0.16)
    spoked = rng.random() < 0.6
    for side in (1.0, -1.0):
        wx, wy = local(x, y, yaw, -0.12, side * (half_w + 0.05))
        if spoked and rear_r > 0.2:
            ring(sc, (wx, wy, rear_r), yaw, radius=rear_r - 0.015, tube=0.015, color=tyre)
            ring(sc, (wx, wy, rear_r), yaw, radius=rear_r - 0.05, tube=0.006, color=jitter(rng, pick(rng, METAL)))
            sc.cylinder((wx, wy, rear_r), 0.04, 0.05, frame, yaw=yaw, roll=math.pi / 2.0)
        else:
            sc.cylinder((wx, wy, rear_r), rear_r, 0.03, tyre, yaw=yaw, roll=math.pi / 2.0)
            sc.cylinder((wx, wy, rear_r), rear_r * 0.8, 0.035, frame, yaw=yaw, roll=math.pi / 2.0)
        castor_r = rng.uniform(0.05, 0.1)
        cx, cy = local(x, y, yaw, 0.28, side * (half_w - 0.02))
        sc.cylinder((cx, cy, castor_r), castor_r, 0.03, tyre, yaw=yaw, roll=math.pi / 2.0)
        sc.box((cx, cy, (castor_r + seat_h) / 2.0), (0.012, 0.012, (seat_h - castor_r) / 2.0), frame, yaw)
        rx, ry = local(x, y, yaw, 0.0, side * half_w)
        sc.box((rx, ry, seat_h), (0.25, 0.012, 0.012), frame, yaw)  # seat rail
        px, py = local(x, y, yaw, -0.22, side * half_w)
        top = seat_h + rng.uniform(0.42, 0.52)
        sc.box((px, py, (seat_h - 0.1 + top) / 2.0), (0.012, 0.012, (top - seat_h + 0.1) / 2.0), frame, yaw, -0.1)
        hx, hy = local(x, y, yaw, -0.3, side * half_w)
        sc.box((hx, hy, top), (0.07, 0.018, 0.018), (0.1, 0.1, 0.1, 1.0), yaw)
        fx, fy = local(x, y, yaw, 0.4, side * (half_w * 0.5))
        sc.box((fx, fy, 0.12), (0.07, half_w * 0.45, 0.01), frame, yaw)
    sc.box((x, y, seat_h), (0.23, half_w, 0.02), cloth, yaw)
    bx, by = local(x, y, yaw, -0.23, 0.0)
    sc.box((bx, by, seat_h + 0.24), (0.015, half_w, 0.2), cloth, yaw, -0.1)
    armrest_h = 0.0
    if rng.random() < 0.6:
        armrest_h = seat_h + rng.uniform(0.18, 0.25)
        for side in (1.0, -1.0):
            ax, ay = local(x, y, yaw, -0.02, side * (half_w + 0.01))
            sc.box((ax, ay, armrest_h), (0.17, 0.025, 0.02), cloth, yaw)
    return seat_h, 0.13, armrest_h


def castor_star(sc: Scene, x: float, y: float, yaw: float, *, feet: int, reach: float, arm_z: float,
                arm_half: Tuple[float, float], color: Rgba) -> None:
    """A star base: ``feet`` arms ``reach`` [m] long from (x, y) at height ``arm_z`` [m] (half width and
    height ``arm_half`` [m]), a castor at the end of each."""
    for k in range(feet):
        a = yaw + 2.0 * math.pi * k / feet
        sc.box((x + reach / 2.0 * math.cos(a), y + reach / 2.0 * math.sin(a), arm_z), (reach / 2.0, *arm_half), color,
               a)
        sc.sphere((x + reach * math.cos(a), y + reach * math.sin(a), 0.03), 0.03, (0.1, 0.1, 0.1, 1.0))


Builder = Callable[[Scene, float, float, float], object]  # what a builder returns is not used
