"""Procedural models for the classifier's ``extra7`` and ``extra8`` training splits: a person in a pose drawn from
a continuous space, a pushable object composed of random primitives, and a non-pushable structure composed of
random primitives (``extra8`` adds people pushing random wheeled things, machines, appliances and legged frames).

Why: eight held-out sets in a row showed that every hand-written family of people and objects helps the held-out
sets that resemble it and no other (every new set held a shape with no family in training). These builders do
not describe any one thing; they sample the space the labels are defined over:

- a *person* is an articulated figure (torso, head, two-segment arms and legs, shoes, hands) of any size from a
  child to a tall adult and any build, posed by joint angles (spine, hips, knees, shoulders, elbows) in one of
  nine stances (standing, walking, bending, squatting, kneeling on one or both knees, sitting on a support,
  sitting on the floor, lying on the floor or on a support, on all fours), the whole figure rested on the floor
  or on the support; dressed at random (trousers, shorts, skirt, long coat, hat or hood, bag), sometimes holding
  a thing or partly hidden behind one;
- a *movable* object is a compact cluster of one to three primitives (box, upright or lying cylinder, capsule,
  blob of spheres, soft bag), the main part at most 0.7 m across, the whole at most ~1.1 m across and 0.9 m
  high with its handle, with random handles, wheels, bands and markings;
- a *clear* structure is something the robot must not push and need not avoid as a person, at least 0.8 m high:
  a tall body (1-2 m), a stand on thin legs or a pole carrying a head, or an open rack or frame, in random
  proportions and colours (a tall body's front panels may reach below the floor, where they are not seen).

The builders never name a held-out model and share no code with :mod:`tools.perception.held_out`.
"""

from __future__ import annotations

import math
from typing import Callable, List, Sequence, Tuple

import numpy as np

from tools.perception.scene_base import (
    CLOTHES,
    METAL,
    SHOES,
    SKIN,
    Rgba,
    Scene,
    Vec3,
    box_color,
    furniture_color,
    jitter,
    legs4,
    limb,
    local,
    pick,
    random_color,
)

STANCES = ("standing", "walking", "bending", "squatting", "kneeling", "sitting_on", "sitting_floor", "lying",
           "all_fours")
Point = np.ndarray  # (3,) [m] in the figure's frame: x forward, y left, z up


def _direction(flex: float, side: float) -> Point:
    """A unit vector that points straight down turned ``flex`` [rad] forward (about the lateral axis), then
    ``side`` [rad] outwards (positive: to +y)."""
    return np.array([math.sin(flex) * math.cos(side), math.sin(side), -math.cos(flex) * math.cos(side)])


def _pitch(v: Point, angle: float) -> Point:
    """``v`` turned by ``angle`` [rad] about the lateral (y) axis, +z towards +x (as a pybullet pitch)."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([c * v[0] + s * v[2], v[1], -s * v[0] + c * v[2]])


class _Pose:
    """Joint angles [rad] of a figure in its own upright frame, and the pitch of the whole figure."""

    def __init__(self, rng: np.random.Generator, stance: str) -> None:
        u = rng.uniform
        self.body_pitch = 0.0  # [rad] the whole figure turned forward about its hips (lying, all fours)
        self.spine = u(-0.1, 0.25)  # [rad] torso leaning forward from the pelvis
        self.hip = [u(-0.15, 0.15), u(-0.15, 0.15)]  # [rad] thigh swung forward, left and right
        self.knee = [u(0.0, 0.2), u(0.0, 0.2)]  # [rad] shin bent back from the thigh
        self.splay = [u(0.0, 0.15), u(0.0, 0.15)]  # [rad] leg outwards
        self.support = False  # rests on something (a seat, a bed), not on the floor
        if stance == "walking":
            stride = u(0.2, 0.5)
            self.hip = [stride, -stride * u(0.6, 1.0)]
            self.knee = [u(0.0, 0.5), u(0.0, 0.4)]
        elif stance == "bending":
            self.spine = u(0.6, 1.7)
            self.knee = [u(0.0, 0.6)] * 2
            self.hip = [k / 2.0 for k in self.knee]
        elif stance == "squatting":
            bend = u(1.6, 2.4)
            self.hip, self.knee = [bend * u(0.8, 1.0), bend * u(0.8, 1.0)], [bend, bend * u(0.9, 1.0)]
            self.spine = u(0.2, 0.8)
            self.splay = [u(0.1, 0.45), u(0.1, 0.45)]
        elif stance == "kneeling":
            both = rng.random() < 0.5
            self.hip = [u(-0.1, 0.4), u(1.3, 1.7)] if not both else [u(-0.1, 0.4)] * 2
            self.knee = [math.pi / 2.0 + u(-0.1, 0.3), u(1.3, 1.7)] if not both else [math.pi / 2.0 + u(-0.1, 0.3)] * 2
            if rng.random() < 0.3:  # sitting back on the heels
                self.hip, self.knee = [u(0.8, 1.3)] * 2, [u(2.4, 2.8)] * 2
        elif stance == "sitting_on":
            self.support = True
            self.hip = [u(1.2, 1.8), u(1.2, 1.8)]
            self.knee = [h + u(-0.5, 0.1) for h in self.hip]
            self.spine = u(-0.35, 0.4)
        elif stance == "sitting_floor":  # the thighs level or rising, the feet on the floor (legs out .. knees up)
            self.hip = [u(1.45, 2.3)] * 2 if rng.random() < 0.6 else [u(1.45, 2.3), u(1.45, 2.3)]
            self.knee = [h - math.acos(max(-1.0, min(1.0, -0.45 * math.cos(h) / 0.43))) for h in self.hip]
            self.splay = [u(0.0, 0.5), u(0.0, 0.5)]
            self.spine = u(-0.5, 0.4)
        elif stance == "lying":
            self.support = rng.random() < 0.4
            self.body_pitch = -math.pi / 2.0 if rng.random() < 0.7 else math.pi / 2.0  # on the back or the front
            self.spine = u(-0.1, 0.3) if self.body_pitch < 0.0 else 0.0
            knees_up = rng.random() < 0.35 and self.body_pitch < 0.0
            self.hip = [u(0.6, 1.1)] * 2 if knees_up else [u(-0.05, 0.15), u(-0.05, 0.15)]
            self.knee = [h * 2.0 for h in self.hip] if knees_up else [u(0.0, 0.2), u(0.0, 0.2)]
        elif stance == "all_fours":
            self.body_pitch = math.pi / 2.0 + u(-0.3, 0.1)
            self.hip = [math.pi / 2.0 + u(-0.2, 0.2)] * 2
            self.knee = [math.pi / 2.0 + u(-0.1, 0.1)] * 2
        self._arms(rng, stance)

    def _arms(self, rng: np.random.Generator, stance: str) -> None:
        u = rng.uniform
        self.shoulder = [u(-0.7, 3.0), u(-0.7, 3.0)]  # [rad] arm swung forward (pi: straight up)
        self.abduct = [u(0.0, 1.4), u(0.0, 1.4)]  # [rad] arm outwards
        self.elbow = [u(0.0, 2.2), u(0.0, 2.2)]  # [rad] forearm bent forward
        if stance == "all_fours":  # on the hands
            self.shoulder, self.abduct, self.elbow = [u(1.3, 1.8)] * 2, [u(0.05, 0.2)] * 2, [u(0.0, 0.2)] * 2
        elif stance == "lying":  # along the body, out to the side or above the head, not into the floor
            front = self.body_pitch > 0.0
            self.shoulder = [u(2.9, 3.1) if rng.random() < 0.25 else u(-0.2, 0.1) if front else u(-0.1, 1.6)
                             for _ in range(2)]
            self.elbow = [u(0.0, 0.3) if front else u(0.0, 1.5) for _ in range(2)]

    def reach_forward(self, rng: np.random.Generator) -> None:
        """Both arms held forward at about hand-rail height (the hands on a handle)."""
        grip = rng.uniform(0.9, 1.5)  # [rad] both upper arms forward ...
        self.shoulder, self.abduct = [grip, grip], [rng.uniform(0.0, 0.25)] * 2
        self.elbow = [rng.uniform(0.0, 0.6)] * 2  # ... the forearms a little more


CONTACTS = {  # the points a stance rests on (the lowest of them is put on the floor or the support)
    "standing": ("ankle", "toe"), "walking": ("ankle", "toe"), "bending": ("ankle", "toe"),
    "squatting": ("ankle", "toe"), "kneeling": ("knee", "ankle", "toe"), "sitting_on": ("ankle", "toe"),
    "sitting_floor": ("pelvis", "ankle", "toe"), "lying": ("pelvis", "neck", "head", "knee", "ankle"),
    "all_fours": ("knee", "wrist", "toe"),
}


def person_random_pose(sc: Scene, x: float, y: float, yaw: float, *, stances: Sequence[str] | None = None,
                       reach: bool = False) -> List[Vec3]:
    """A figure of random size, build and clothes in a random stance of ``stances`` (default :data:`STANCES`;
    see the module); ``reach``: both arms held forward at about hand-rail height (the hands on a handle).
    Returns the hands' positions [m]."""
    rng = sc.rng
    choices = STANCES if stances is None else tuple(stances)
    stance = choices[int(rng.integers(len(choices)))]
    pose = _Pose(rng, stance)
    if reach:
        pose.reach_forward(rng)
    s = rng.uniform(0.55, 0.75) if rng.random() < 0.2 else rng.uniform(0.85, 1.15)  # child or adult
    build = rng.uniform(0.8, 1.35)  # thin .. heavy
    thigh, shin = 0.45 * s * rng.uniform(0.92, 1.08), 0.43 * s * rng.uniform(0.92, 1.08)  # [m]
    upper, fore = 0.3 * s, 0.27 * s  # [m]
    torso_h, width, depth = rng.uniform(0.5, 0.6) * s, 0.36 * s * build, 0.22 * s * build
    leg_r, arm_r, head_r = 0.065 * s * build, 0.045 * s * build, rng.uniform(0.09, 0.11) * s
    colours = _clothes(rng)
    # joints in the figure's frame, the pelvis at the origin, the whole figure turned by the body pitch
    turn, lean = pose.body_pitch, pose.body_pitch + pose.spine
    spine = _pitch(np.array([0.0, 0.0, 1.0]), lean)
    neck = spine * torso_h
    head = neck + spine * (head_r + 0.05 * s)
    parts: List[Tuple[Point, Point, float, Rgba]] = []  # (from, to, radius [m], colour)
    points: List[Tuple[str, Point, float]] = [("pelvis", np.zeros(3), depth / 2.0), ("neck", neck, depth / 2.0),
                                              ("head", head, head_r)]
    feet, hands = [], []
    for i, side in enumerate((1.0, -1.0)):
        hip = _pitch(np.array([0.0, side * 0.1 * s * build, 0.0]), turn)
        knee = hip + _pitch(_direction(pose.hip[i], side * pose.splay[i]), turn) * thigh
        ankle = knee + _pitch(_direction(pose.hip[i] - pose.knee[i], side * pose.splay[i]), turn) * shin
        toe = ankle + _pitch(_direction(pose.hip[i] - pose.knee[i] + math.pi / 2.0, 0.0), turn) * 0.16 * s
        parts += [(hip, knee, leg_r, colours["thighs"]), (knee, ankle, leg_r * 0.85, colours["shins"])]
        feet.append((ankle, toe))
        shoulder = neck + _pitch(np.array([0.0, side * (width / 2.0 + arm_r), -0.04 * s]), lean)
        elbow = shoulder + _pitch(_direction(pose.shoulder[i], side * pose.abduct[i]), lean) * upper
        wrist = elbow + _pitch(_direction(pose.shoulder[i] + pose.elbow[i], side * pose.abduct[i]), lean) * fore
        parts += [(shoulder, elbow, arm_r, colours["sleeves"]), (elbow, wrist, arm_r * 0.9, colours["forearms"])]
        hands.append((wrist, arm_r))
        points += [("knee", knee, leg_r), ("ankle", ankle, leg_r), ("toe", toe, 0.045 * s), ("wrist", wrist, arm_r)]
    contact_z = min(float(p[2]) - r for name, p, r in points if name in CONTACTS[stance])
    rest = rng.uniform(0.3, 0.7) if pose.support and stance == "lying" else 0.0  # [m] a bed's or bench's top
    lift = np.array([0.0, 0.0, rest - contact_z])

    def world(p: Point) -> Vec3:
        q = p + lift
        return (*local(x, y, yaw, float(q[0]), float(q[1])), max(float(q[2]), 0.0))

    if pose.support:
        xs = [float(p[0]) for _, p, _ in points]
        _support(sc, x, y, yaw, stance, seat_z=float(lift[2]) - leg_r, rest=rest, span=(min(xs), max(xs)))
    for a, b, r, colour in parts:
        limb(sc, world(a), world(b), r, colour)
    for ankle, toe in feet:
        limb(sc, world(ankle), world(toe), 0.045 * s, colours["shoes"])
    for wrist, r in hands:
        sc.sphere(world(wrist), r * 1.05, colours["skin"])
    sc.box(world(neck / 2.0), (depth / 2.0, width / 2.0, torso_h / 2.0 + 0.03), colours["shirt"], yaw, lean)
    sc.sphere(world(head), head_r, colours["skin"])
    sc.sphere(world(head + spine * head_r * 0.35), head_r * 0.95, colours["hat"])  # hair or a hat
    hand_points = [world(w) for w, _ in hands]
    _extras(sc, x, y, yaw, stance, world=world, neck=neck, lean=lean, hands=hand_points, size=(s, width, depth),
            shirt=colours["shirt"])
    return hand_points


def _extras(sc: Scene, x: float, y: float, yaw: float, stance: str, *, world: Callable[[Point], Vec3], neck: Point,
            lean: float, hands: List[Vec3], size: Tuple[float, float, float], shirt: Rgba) -> None:
    """A skirt or a coat, a backpack, a thing in a hand, a thing in front (for upright figures) of a figure of
    ``size`` (scale, shoulder width [m], chest depth [m])."""
    rng = sc.rng
    s, width, depth = size
    if stance in ("standing", "walking") and rng.random() < 0.35:  # a skirt or a coat from the waist down
        hem, waist = rng.uniform(0.25, 0.6) * s, world(np.zeros(3))
        sc.cylinder((waist[0], waist[1], (waist[2] + 0.05 + hem) / 2.0), rng.uniform(0.2, 0.3) * s,
                    max(waist[2] + 0.05 - hem, 0.05), shirt if rng.random() < 0.5 else
                    random_color(rng, 0.05, 0.95))
    if rng.random() < 0.2:  # a backpack
        back = world(neck * 0.55 + _pitch(np.array([-depth / 2.0 - 0.08 * s, 0.0, 0.0]), lean))
        sc.box(back, (0.08 * s, width * 0.4, 0.2 * s), random_color(rng, 0.05, 0.9), yaw, lean)
    if rng.random() < 0.25:  # a thing held in a hand
        hand = hands[int(rng.integers(2))]
        half = rng.uniform(0.05, 0.2, 3)
        sc.box((hand[0], hand[1], max(hand[2] - float(half[2]), float(half[2]))), (float(half[0]), float(half[1]),
               float(half[2])), random_color(rng, 0.05, 0.95), yaw + rng.uniform(-0.5, 0.5))
    if stance in ("standing", "walking", "bending") and rng.random() < 0.3 and math.hypot(x, y) > 1.2:  # partly
        # hidden behind a thing nearer the camera
        bearing = math.atan2(y, x)
        near = math.hypot(x, y) - rng.uniform(0.4, 0.7)
        movable_random_object(sc, *local(0.0, 0.0, bearing, near, rng.uniform(-0.3, 0.3)), rng.uniform(-3.0, 3.0))


def _clothes(rng: np.random.Generator) -> dict[str, Rgba]:
    def cloth() -> Rgba:
        return jitter(rng, pick(rng, CLOTHES)) if rng.random() < 0.7 else random_color(rng, 0.03, 0.97)

    skin = jitter(rng, pick(rng, SKIN), 0.03)
    shirt, trousers = cloth(), cloth()
    lower = rng.random()
    return {
        "shirt": shirt, "skin": skin, "shoes": jitter(rng, pick(rng, SHOES), 0.03),
        "thighs": trousers, "shins": skin if lower < 0.2 else trousers,  # shorts or a skirt: bare shins
        "sleeves": shirt, "forearms": skin if rng.random() < 0.4 else shirt,
        "hat": cloth() if rng.random() < 0.3 else skin,
    }


def _support(sc: Scene, x: float, y: float, yaw: float, stance: str, *, seat_z: float, rest: float,
             span: Tuple[float, float]) -> None:
    """What a figure sits or lies on: a seat under the pelvis (``seat_z`` [m] its top: a box, a stool, a crate, a
    bench) or a bed, bench or trolley top at ``rest`` [m] under the lying body, which spans ``span`` [m] along the
    figure's x axis."""
    rng = sc.rng
    colour = box_color(rng) if rng.random() < 0.3 else furniture_color(rng) if rng.random() < 0.6 else \
        random_color(rng, 0.05, 0.95)
    if stance == "sitting_on":
        top = max(seat_z, 0.15)
        half = (rng.uniform(0.17, 0.3), rng.uniform(0.17, 0.6))
        cx, cy = local(x, y, yaw, -0.05, 0.0)
        if rng.random() < 0.5:  # solid: a box, an ottoman, a crate
            sc.box((cx, cy, top / 2.0), (half[0], half[1], top / 2.0), colour, yaw)
        else:  # a top on legs
            sc.box((cx, cy, top - 0.02), (half[0], half[1], 0.02), colour, yaw)
            legs4(sc, cx, cy, yaw, dx=half[0] - 0.03, dy=half[1] - 0.03, height=top, half=0.02, color=colour)
        return
    length = (span[1] - span[0]) + 0.2  # [m]
    cx, cy = local(x, y, yaw, (span[0] + span[1]) / 2.0, 0.0)
    sc.box((cx, cy, rest - 0.04), (length / 2.0, rng.uniform(0.3, 0.45), 0.04), colour, yaw)
    if rng.random() < 0.5:
        sc.box((cx, cy, (rest - 0.08) / 2.0), (length / 2.0 - 0.1, rng.uniform(0.1, 0.3), (rest - 0.08) / 2.0),
               colour, yaw)
    else:
        for fx in (length / 2.0 - 0.05, -length / 2.0 + 0.05):
            lx, ly = local(cx, cy, yaw, fx, 0.0)
            sc.box((lx, ly, (rest - 0.08) / 2.0), (0.03, 0.3, (rest - 0.08) / 2.0), colour, yaw)


# -- objects ------------------------------------------------------------------------------------------------
def _primitive(sc: Scene, x: float, y: float, yaw: float, *, z0: float, size: Tuple[float, float, float],
               colour: Rgba) -> float:
    """One random primitive of about ``size`` (length, width, height) [m] standing on height ``z0`` [m]; returns
    its top [m]."""
    rng = sc.rng
    a, b, h = size
    kind = rng.random()
    if kind < 0.45:
        sc.box((x, y, z0 + h / 2.0), (a / 2.0, b / 2.0, h / 2.0), colour, yaw)
        return z0 + h
    if kind < 0.65:  # upright cylinder
        sc.cylinder((x, y, z0 + h / 2.0), min(a, b) / 2.0, h, colour)
        return z0 + h
    if kind < 0.8:  # a cylinder or a capsule on its side
        r = min(b, h) / 2.0
        if rng.random() < 0.5:
            sc.cylinder((x, y, z0 + r), r, a, colour, yaw=yaw + math.pi / 2.0, roll=math.pi / 2.0)
        else:
            sc.capsule((x, y, z0 + r), r, max(a - 2.0 * r, 0.01), colour, yaw=yaw, pitch=math.pi / 2.0)
        return z0 + 2.0 * r
    if kind < 0.9:  # a sphere or a squashed blob of spheres
        r = min(a, b, h * 1.5) / 2.0
        for _ in range(int(rng.integers(1, 5))):
            ox, oy = local(x, y, yaw, rng.uniform(-0.3, 0.3) * a, rng.uniform(-0.3, 0.3) * b)
            sc.sphere((ox, oy, z0 + r * 0.8), r * rng.uniform(0.7, 1.0), colour)
        return z0 + r * 1.8
    for k in range(2):  # a soft bag: two overlapping rounded boxes
        ox, oy = local(x, y, yaw, (k - 0.5) * a * 0.2, 0.0)
        sc.capsule((ox, oy, z0 + h * 0.45), h * 0.45, max(b - h * 0.9, 0.01), colour, yaw=yaw + math.pi / 2.0,
                   pitch=math.pi / 2.0)
    return z0 + h * 0.9


def _object_colour(rng: np.random.Generator) -> Rgba:
    roll = rng.random()
    if roll < 0.45:
        return random_color(rng, 0.03, 0.97)
    if roll < 0.75:
        return box_color(rng)
    return jitter(rng, pick(rng, CLOTHES))


def movable_random_object(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A compact cluster of primitives a robot could push (see the module)."""
    rng = sc.rng
    colour = _object_colour(rng)
    a, b = rng.uniform(0.15, 0.7), rng.uniform(0.15, 0.7)
    h = rng.uniform(0.1, 0.6)
    z0 = 0.0
    if rng.random() < 0.25:  # on wheels or feet
        z0 = rng.uniform(0.03, 0.08)
        for fx in (a / 2.0 - 0.04, -a / 2.0 + 0.04):
            for fy in (b / 2.0 - 0.04, -b / 2.0 + 0.04):
                wx, wy = local(x, y, yaw, fx, fy)
                sc.sphere((wx, wy, z0 / 2.0 + 0.005), z0 / 2.0 + 0.005, (0.1, 0.1, 0.1, 1.0))
    top = _primitive(sc, x, y, yaw, z0=z0, size=(a, b, h), colour=colour)
    if rng.random() < 0.35 and top < 0.55:  # a second part on top
        size = (a * rng.uniform(0.5, 1.0), b * rng.uniform(0.5, 1.0), rng.uniform(0.08, 0.75 - top))
        ox, oy = local(x, y, yaw, rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1))
        top = _primitive(sc, ox, oy, yaw + rng.uniform(-0.4, 0.4), z0=top, size=size,
                         colour=colour if rng.random() < 0.4 else _object_colour(rng))
    if rng.random() < 0.3:  # a part beside
        side = 1.0 if rng.random() < 0.5 else -1.0
        size = (rng.uniform(0.12, 0.4), rng.uniform(0.12, 0.3), rng.uniform(0.1, 0.45))
        ox, oy = local(x, y, yaw, rng.uniform(-0.2, 0.2), side * (b / 2.0 + size[1] / 2.0 + 0.01))
        _primitive(sc, ox, oy, yaw + rng.uniform(-0.6, 0.6), z0=0.0, size=size, colour=_object_colour(rng))
    if rng.random() < 0.3:  # a carry handle over the top
        grip = jitter(rng, pick(rng, ((0.1, 0.1, 0.1), (0.5, 0.5, 0.52), colour[:3])))
        span = min(a, 0.3) / 2.0
        p0, p1 = local(x, y, yaw, -span, 0.0), local(x, y, yaw, span, 0.0)
        rise = rng.uniform(0.03, 0.12)
        limb(sc, (*p0, top), (*p0, top + rise), 0.012, grip)
        limb(sc, (*p1, top), (*p1, top + rise), 0.012, grip)
        limb(sc, (*p0, top + rise), (*p1, top + rise), 0.012, grip)
    for _ in range(int(rng.integers(0, 4))):  # bands, labels, lids, straps on the main part
        face = 1.0 if rng.random() < 0.5 else -1.0
        px, py = local(x, y, yaw, face * (a / 2.0 + 0.004), rng.uniform(-0.3, 0.3) * b)
        sc.box((px, py, z0 + rng.uniform(0.2, 0.8) * h), (0.004, rng.uniform(0.03, 0.45) * b,
                                                          rng.uniform(0.01, 0.3) * h), random_color(rng, 0.0, 1.0), yaw)


# -- structures -----------------------------------------------------------------------------------------------
def _structure_colour(rng: np.random.Generator) -> Rgba:
    roll = rng.random()
    if roll < 0.4:
        return furniture_color(rng)
    if roll < 0.7:
        return jitter(rng, pick(rng, METAL))
    return random_color(rng, 0.03, 0.97)


def clear_random_structure(sc: Scene, x: float, y: float, yaw: float) -> None:
    """Something not to push (see the module): a tall body, a stand carrying a head, or an open rack or frame."""
    rng = sc.rng
    colour, trim = _structure_colour(rng), _structure_colour(rng)
    kind = rng.random()
    build = _tall_body if kind < 0.35 else _stand if kind < 0.7 else _rack
    build(sc, x, y, yaw, colour=colour, trim=trim)


def _tall_body(sc: Scene, x: float, y: float, yaw: float, *, colour: Rgba, trim: Rgba) -> None:
    """A tall body on a plinth, legs, castors or the floor, with panels."""
    rng = sc.rng
    w, d, h = rng.uniform(0.35, 1.2), rng.uniform(0.3, 0.8), rng.uniform(1.0, 2.0)
    z0 = (0.0, rng.uniform(0.05, 0.12), rng.uniform(0.1, 0.35))[int(rng.integers(3))]
    if rng.random() < 0.7:
        sc.box((x, y, z0 + (h - z0) / 2.0), (d / 2.0, w / 2.0, (h - z0) / 2.0), colour, yaw)
    else:
        sc.cylinder((x, y, z0 + (h - z0) / 2.0), min(w, d) / 2.0, h - z0, colour)
    if z0 > 0.0:
        legs4(sc, x, y, yaw, dx=d / 2.0 - 0.04, dy=w / 2.0 - 0.04, height=z0, half=0.025, color=trim)
    for _ in range(int(rng.integers(0, 5))):  # doors, screens, grilles, labels on the front
        px, py = local(x, y, yaw, d / 2.0 + 0.005, rng.uniform(-0.3, 0.3) * w)
        sc.box((px, py, rng.uniform(z0 + 0.1, h - 0.05)), (0.005, rng.uniform(0.05, 0.45) * w,
                                                          rng.uniform(0.02, 0.25) * h),
               random_color(rng, 0.0, 1.0) if rng.random() < 0.5 else trim, yaw)


def _stand(sc: Scene, x: float, y: float, yaw: float, *, colour: Rgba, trim: Rgba) -> None:
    """A pole or three or four splayed legs carrying a head."""
    rng = sc.rng
    h = rng.uniform(0.8, 1.9)
    apex = (x, y, h)
    if rng.random() < 0.5:
        sc.cylinder((x, y, h / 2.0), rng.uniform(0.012, 0.04), h, trim)
        base_r = rng.uniform(0.15, 0.35)
        if rng.random() < 0.5:
            sc.cylinder((x, y, 0.02), base_r, 0.04, trim)
        else:
            feet = int(rng.integers(3, 6))
            for k in range(feet):
                ang = yaw + 2.0 * math.pi * k / feet
                limb(sc, (x, y, 0.08), (x + base_r * math.cos(ang), y + base_r * math.sin(ang), 0.02), 0.015, trim)
    else:
        feet, spread = int(rng.integers(3, 5)), rng.uniform(0.25, 0.5)
        for k in range(feet):
            ang = yaw + 2.0 * math.pi * k / feet + 0.3
            limb(sc, (x + spread * math.cos(ang), y + spread * math.sin(ang), 0.0), apex,
                 rng.uniform(0.01, 0.025), trim)
    head = rng.random()
    size = rng.uniform(0.15, 0.5)
    if head < 0.3:
        sc.box((x, y, h + size / 2.0), (rng.uniform(0.02, 0.3), size, size / 2.0), colour, yaw)
    elif head < 0.55:
        sc.cylinder((x, y, h), size, 0.03, colour, yaw=yaw, roll=math.pi / 2.0 if rng.random() < 0.5 else 0.0)
    elif head < 0.8:
        sc.sphere((x, y, h + size / 3.0), size / 3.0, colour)
    else:  # hooks or arms
        for k in range(int(rng.integers(2, 6))):
            ang = yaw + 2.0 * math.pi * k / 5.0
            limb(sc, (x, y, h - 0.05), (x + 0.2 * math.cos(ang), y + 0.2 * math.sin(ang), h + 0.05), 0.012,
                 trim)


def _rack(sc: Scene, x: float, y: float, yaw: float, *, colour: Rgba, trim: Rgba) -> None:
    """An open rack or frame: posts with shelves or rails."""
    rng = sc.rng
    w, d, h = rng.uniform(0.5, 1.6), rng.uniform(0.3, 0.7), rng.uniform(0.8, 2.0)
    post = rng.uniform(0.012, 0.035)
    legs4(sc, x, y, yaw, dx=d / 2.0, dy=w / 2.0, height=h, half=post, color=trim)
    levels = int(rng.integers(1, 6))
    solid = rng.random() < 0.6
    for k in range(levels):
        z = max(h * (k + 1) / levels - 0.02, 0.1)
        if solid:
            sc.box((x, y, z), (d / 2.0, w / 2.0, 0.015), colour, yaw)
        else:
            for fx in (d / 2.0, -d / 2.0):
                px, py = local(x, y, yaw, fx, 0.0)
                sc.box((px, py, z), (post, w / 2.0, post), trim, yaw)
        if solid and rng.random() < 0.4:  # things on the shelf
            ox, oy = local(x, y, yaw, 0.0, rng.uniform(-0.3, 0.3) * w)
            tall = rng.uniform(0.05, min(0.3, h / levels - 0.05)) if h / levels > 0.12 else 0.05
            sc.box((ox, oy, z + tall / 2.0 + 0.015), (d * 0.35, rng.uniform(0.05, 0.3) * w, tall / 2.0),
                   random_color(rng, 0.05, 0.95), yaw)
    if rng.random() < 0.3:  # castors
        for fx in (d / 2.0, -d / 2.0):
            for fy in (w / 2.0, -w / 2.0):
                px, py = local(x, y, yaw, fx, fy)
                sc.sphere((px, py, 0.03), 0.03, (0.1, 0.1, 0.1, 1.0))


# -- the ``extra8`` additions: designed from the errors on the ninth and tenth held-out sets (a person pushing a
# cart, a treadmill, a washing machine, an easel, an ironing board), written after ``unseen11`` was defined and
# without any of its kinds (no stretcher, panel, scooter, sign, bin, step stool, medical cart, lectern, pillar).
def person_pushing_thing(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A standing, walking or bending figure with both hands on the handle of a random wheeled thing ahead of it
    (a cart, a trolley, a pram, a frame): a body of random shape and size between the figure and its front, on
    wheels or feet, reached by a bar between the hands. The thing may hide the figure's legs from the front."""
    rng = sc.rng
    hands = person_random_pose(sc, x, y, yaw, stances=("standing", "walking", "bending"), reach=True)
    (ax, ay, az), (bx, by, bz) = hands
    grip = ((ax + bx) / 2.0, (ay + by) / 2.0, (az + bz) / 2.0)
    colour, trim = _object_colour(rng), jitter(rng, pick(rng, METAL))
    limb(sc, (ax, ay, az), (bx, by, bz), 0.015, trim)  # the handle bar
    fwd = (grip[0] - x) * math.cos(yaw) + (grip[1] - y) * math.sin(yaw)  # [m] the handle ahead of the figure
    length, width = rng.uniform(0.4, 1.1), rng.uniform(0.35, 0.7)
    top = rng.uniform(0.3, max(0.35, grip[2] - 0.05))
    bottom = rng.uniform(0.08, max(0.1, top - 0.15))
    cx, cy = local(x, y, yaw, fwd + 0.05 + length / 2.0, 0.0)
    if rng.random() < 0.6:  # a solid body (a bin, a box on a chassis, a pram)
        sc.box((cx, cy, (top + bottom) / 2.0), (length / 2.0, width / 2.0, (top - bottom) / 2.0), colour, yaw)
    else:  # an open frame with shelves
        legs4(sc, cx, cy, yaw, dx=length / 2.0, dy=width / 2.0, height=top, half=0.012, color=trim)
        for z in (bottom, top):
            sc.box((cx, cy, z), (length / 2.0, width / 2.0, 0.012), colour, yaw)
    for side in (1.0, -1.0):  # the handle's uprights down to the body
        hx, hy = local(x, y, yaw, fwd, side * width * 0.4)
        limb(sc, (hx, hy, grip[2]), (*local(x, y, yaw, fwd + 0.08, side * width * 0.4), top), 0.012, trim)
    wheel = rng.uniform(0.04, min(0.15, bottom))
    for fx in (0.1, length - 0.1):
        for side in (1.0, -1.0):
            wx, wy = local(x, y, yaw, fwd + 0.05 + fx, side * (width / 2.0 - 0.03))
            sc.cylinder((wx, wy, wheel), wheel, 0.03, (0.1, 0.1, 0.1, 1.0), yaw=yaw + math.pi / 2.0,
                        roll=math.pi / 2.0)


def clear_random_machine(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A long low base (1-2 m, 0.08-0.45 m high) on the floor, feet or castors with one or two uprights at one
    end rising to 0.9-1.6 m, joined by a bar, a console or handles, maybe a seat on the base: exercise machines,
    hoists, floor machines."""
    rng = sc.rng
    colour, trim = _structure_colour(rng), _structure_colour(rng)
    length, width, h = rng.uniform(1.0, 2.0), rng.uniform(0.45, 0.9), rng.uniform(0.08, 0.45)
    z0 = (0.0, rng.uniform(0.04, 0.1))[int(rng.integers(2))]
    sc.box((x, y, z0 + h / 2.0), (length / 2.0, width / 2.0, h / 2.0), colour, yaw)
    if z0 > 0.0:
        legs4(sc, x, y, yaw, dx=length / 2.0 - 0.05, dy=width / 2.0 - 0.05, height=z0, half=0.02, color=trim)
    if rng.random() < 0.5:  # a belt, a pad or a rail along the top
        sc.box((x, y, z0 + h + 0.01), (length / 2.0 - 0.05, width / 2.0 - 0.08, 0.01), _structure_colour(rng), yaw)
    end = 1.0 if rng.random() < 0.5 else -1.0
    rise = rng.uniform(0.9, 1.6)
    posts = (1.0, -1.0) if rng.random() < 0.6 else (0.0,)
    ux = end * (length / 2.0 - rng.uniform(0.05, 0.3))
    lean = rng.uniform(-0.25, 0.25)
    for side in posts:
        foot = (*local(x, y, yaw, ux, side * (width / 2.0 - 0.03)), z0 + h)
        head = (*local(x, y, yaw, ux + lean * rise, side * (width / 2.0 - 0.03)), rise)
        limb(sc, foot, head, rng.uniform(0.015, 0.05), trim)
    hx, hy = local(x, y, yaw, ux + lean * rise, 0.0)
    kind = rng.random()
    if kind < 0.4:  # a console
        sc.box((hx, hy, rise + 0.05), (rng.uniform(0.05, 0.2), width / 2.0, rng.uniform(0.04, 0.15)), colour, yaw,
               rng.uniform(-0.6, 0.6))
    elif kind < 0.7:  # a bar across
        sc.cylinder((hx, hy, rise), 0.02, width, trim, yaw=yaw, roll=math.pi / 2.0)
    else:  # handles reaching back along the base
        for side in (1.0, -1.0):
            limb(sc, (*local(x, y, yaw, ux + lean * rise, side * (width / 2.0 - 0.03)), rise),
                 (*local(x, y, yaw, ux - end * rng.uniform(0.2, 0.5), side * (width / 2.0 - 0.03)), rise - 0.1),
                 0.02, trim)
    if rng.random() < 0.35:  # a seat on a post
        sx_, sy_ = local(x, y, yaw, -end * length * 0.25, 0.0)
        seat_z = z0 + h + rng.uniform(0.15, 0.5)
        limb(sc, (sx_, sy_, z0 + h), (sx_, sy_, seat_z), 0.03, trim)
        sc.box((sx_, sy_, seat_z + 0.04), (0.15, 0.13, 0.04), _structure_colour(rng), yaw)


def clear_random_appliance(sc: Scene, x: float, y: float, yaw: float) -> None:
    """An appliance-sized body 0.85-1.3 m high and 0.5-0.9 m wide on the floor or feet, with random fronts: a
    round window, a control strip, taps, grilles, a door line, maybe a thing on top."""
    rng = sc.rng
    colour = jitter(rng, pick(rng, ((0.95, 0.95, 0.95), (0.85, 0.85, 0.83), (0.7, 0.7, 0.72), (0.2, 0.2, 0.22),
                                    (0.6, 0.62, 0.66)))) if rng.random() < 0.6 else _structure_colour(rng)
    w, d, h = rng.uniform(0.5, 0.9), rng.uniform(0.45, 0.8), rng.uniform(0.85, 1.3)
    z0 = (0.0, rng.uniform(0.02, 0.08))[int(rng.integers(2))]
    sc.box((x, y, z0 + (h - z0) / 2.0), (d / 2.0, w / 2.0, (h - z0) / 2.0), colour, yaw)
    if z0 > 0.0:
        legs4(sc, x, y, yaw, dx=d / 2.0 - 0.04, dy=w / 2.0 - 0.04, height=z0, half=0.02, color=(0.1, 0.1, 0.1, 1.0))
    fx, fy = local(x, y, yaw, d / 2.0 + 0.006, 0.0)
    for _ in range(int(rng.integers(1, 4))):
        detail = rng.random()
        z = rng.uniform(z0 + 0.15, h - 0.1)
        if detail < 0.3:  # a round window or a dial
            r = rng.uniform(0.05, min(0.25, w / 2.0 - 0.05))
            wx, wy = local(x, y, yaw, d / 2.0 + 0.01, rng.uniform(-0.2, 0.2) * w)
            sc.cylinder((wx, wy, min(z, h - r - 0.02)), r, 0.02, random_color(rng, 0.05, 0.9),
                        yaw=yaw + math.pi / 2.0, roll=math.pi / 2.0)
        elif detail < 0.55:  # a control strip
            sc.box((fx, fy, h - rng.uniform(0.04, 0.12)), (0.006, w / 2.0 - 0.02, rng.uniform(0.02, 0.06)),
                   random_color(rng, 0.0, 1.0), yaw)
        elif detail < 0.75:  # taps or knobs
            for k in range(int(rng.integers(1, 4))):
                kx, ky = local(x, y, yaw, d / 2.0 + 0.02, (k - 1) * 0.08)
                sc.box((kx, ky, z), (0.02, 0.015, 0.02), random_color(rng, 0.0, 1.0), yaw)
        else:  # a door line or a grille
            sc.box((fx, fy, z), (0.004, w / 2.0 - rng.uniform(0.02, 0.1), rng.uniform(0.005, 0.2)),
                   jitter(rng, pick(rng, METAL)), yaw)
    if rng.random() < 0.3:  # a bottle or a box on top
        if rng.random() < 0.5:
            sc.cylinder((x, y, h + 0.18), rng.uniform(0.1, 0.15), 0.36, random_color(rng, 0.3, 0.95))
        else:
            half = rng.uniform(0.08, 0.25, 3)
            sc.box((x, y, h + float(half[2])), (float(half[0]), float(half[1]), float(half[2])),
                   random_color(rng, 0.05, 0.95), yaw + rng.uniform(-0.5, 0.5))


def clear_legged_frame(sc: Scene, x: float, y: float, yaw: float) -> None:
    """A board or a flat body held 0.8-1.6 m up on two to four thin legs, straight, splayed or crossed, the board
    level or tilted up to 1.2 rad: high tables, stands, boards on trestles or tripods."""
    rng = sc.rng
    colour, trim = _structure_colour(rng), _structure_colour(rng)
    top = rng.uniform(0.8, 1.6)
    length, depth = rng.uniform(0.4, 1.4), rng.uniform(0.05, 0.5)
    tilt = 0.0 if rng.random() < 0.4 else rng.uniform(0.2, 1.2)
    thick = rng.uniform(0.015, 0.05)
    along = yaw + (math.pi / 2.0 if rng.random() < 0.5 else 0.0)
    board_h = depth * math.sin(tilt) + thick
    sc.box((x, y, top + board_h / 2.0), (depth / 2.0, length / 2.0, thick / 2.0), colour, along, tilt)
    if tilt > 0.0 and rng.random() < 0.5:  # a sheet, a picture or a lip on the board
        px, py = local(x, y, along, math.cos(tilt) * 0.02, 0.0)
        sc.box((px, py, top + board_h / 2.0 + 0.01), (depth * 0.4, length * 0.4, 0.004),
               random_color(rng, 0.0, 1.0), along, tilt)
    legs = int(rng.integers(2, 5))
    radius = rng.uniform(0.01, 0.03)
    style = rng.random()
    for k in range(legs):
        fy = (k / (legs - 1) - 0.5) * length * 0.8  # legs >= 2
        if style < 0.4:  # straight
            foot = (*local(x, y, along, 0.0, fy), 0.0)
            head = (*local(x, y, along, 0.0, fy), top)
        elif style < 0.75:  # splayed front and back in turn
            out = (1.0 if k % 2 == 0 else -1.0) * rng.uniform(0.15, 0.45)
            foot = (*local(x, y, along, out, fy * 1.2), 0.0)
            head = (*local(x, y, along, 0.0, fy * 0.7), top)
        else:  # crossed along the board
            foot = (*local(x, y, along, (1.0 if k % 2 == 0 else -1.0) * 0.1, fy), 0.0)
            head = (*local(x, y, along, (1.0 if k % 2 == 0 else -1.0) * 0.1, -fy), top)
        limb(sc, foot, head, radius, trim)
    if rng.random() < 0.4:  # a rail between the legs
        z = rng.uniform(0.1, top * 0.6)
        sc.cylinder((x, y, z), 0.012, length * 0.7, trim, yaw=along + math.pi / 2.0, roll=math.pi / 2.0)
