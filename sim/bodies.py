"""Creating pybullet bodies for the floor, world solids, people and robots in one BulletClient.

Every function takes the client explicitly (no global pybullet connection), so several simulations
can live in one process without interfering.
"""

from __future__ import annotations

import math
from typing import Any, Tuple

import pybullet

from flex_nav_sim.profiles import RobotProfile
from flex_nav_sim.world import Person, Rgba, Solid

FLOOR_FRICTION = 1.0  # [-] Bullet multiplies the two bodies' friction: a box's own value then rules
FLOOR_COLOR: Rgba = (0.8, 0.8, 0.78, 1.0)
ROBOT_COLORS: Tuple[Rgba, ...] = (
    (0.15, 0.15, 0.15, 1.0),
    (0.1, 0.3, 0.8, 1.0),
    (0.1, 0.6, 0.2, 1.0),
    (0.6, 0.1, 0.6, 1.0),
)


def yaw_quaternion(yaw: float) -> Tuple[float, float, float, float]:
    """Quaternion (x, y, z, w) of a rotation by ``yaw`` [rad] about z."""
    return 0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0)


def quaternion_yaw(q: Tuple[float, ...]) -> float:
    """Yaw [rad] of quaternion (x, y, z, w)."""
    x, y, z, w = q
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def create_floor(client: Any) -> int:
    """A static floor plane at z = 0, drawn flat grey.

    pybullet draws a plane with a checkerboard texture by default; the tiny renderer then spends
    about 2.5 times longer on every camera image, so the texture is removed.
    """
    shape = client.createCollisionShape(pybullet.GEOM_PLANE)
    body = int(client.createMultiBody(0.0, shape, -1, [0.0, 0.0, 0.0]))
    client.changeVisualShape(body, -1, textureUniqueId=-1, rgbaColor=FLOOR_COLOR)
    client.changeDynamics(body, -1, lateralFriction=FLOOR_FRICTION)
    return body


def create_solid(client: Any, solid: Solid) -> int:
    """A box or cylinder standing on the floor; static if ``solid.mass == 0``."""
    x, y, yaw = solid.pose
    h = solid.height
    if solid.shape == "box":
        half = [solid.size[0] / 2.0, solid.size[1] / 2.0, h / 2.0]
        shape = client.createCollisionShape(pybullet.GEOM_BOX, halfExtents=half)
        visual = client.createVisualShape(pybullet.GEOM_BOX, halfExtents=half, rgbaColor=solid.color)
    else:
        shape = client.createCollisionShape(pybullet.GEOM_CYLINDER, radius=solid.radius, height=h)
        visual = client.createVisualShape(pybullet.GEOM_CYLINDER, radius=solid.radius, length=h, rgbaColor=solid.color)
    body = int(client.createMultiBody(solid.mass, shape, visual, [x, y, h / 2.0], yaw_quaternion(yaw)))
    client.changeDynamics(body, -1, lateralFriction=solid.friction)
    return body


def person_z(person: Person) -> float:
    """Height [m] of a person's capsule centre (the capsule stands on the floor)."""
    return person.height / 2.0


def create_person(client: Any, person: Person, pose: Tuple[float, float, float]) -> int:
    """A kinematic capsule (mass 0: moved by resetting its pose, never pushed)."""
    cylinder = max(0.01, person.height - 2.0 * person.radius)  # capsule = cylinder + two half spheres
    shape = client.createCollisionShape(pybullet.GEOM_CAPSULE, radius=person.radius, height=cylinder)
    visual = client.createVisualShape(
        pybullet.GEOM_CAPSULE, radius=person.radius, length=cylinder, rgbaColor=person.color
    )
    x, y, yaw = pose
    return int(client.createMultiBody(0.0, shape, visual, [x, y, person_z(person)], yaw_quaternion(yaw)))


def create_robot(client: Any, profile: RobotProfile, pose: Tuple[float, float, float], color: Rgba) -> int:
    """The robot body: a cylinder whose link frame is base_footprint (on the floor, at the axle centre).

    The centre of mass sits ``com_height`` above the floor; pybullet reports and resets the base
    pose at the centre of mass, so base_footprint = CoM - (0, 0, com_height) while upright. Friction
    is zero: the drive model applies the wheel forces itself (see :mod:`flex_nav_sim.robot`).
    """
    b = profile.base
    shape = client.createCollisionShape(
        pybullet.GEOM_CYLINDER, radius=b.radius, height=b.height, collisionFramePosition=[0.0, 0.0, b.height / 2.0]
    )
    visual = client.createVisualShape(
        pybullet.GEOM_CYLINDER,
        radius=b.radius,
        length=b.height,
        visualFramePosition=[0.0, 0.0, b.height / 2.0],
        rgbaColor=color,
    )
    x, y, yaw = pose
    body = int(
        client.createMultiBody(
            b.mass,
            shape,
            visual,
            [x, y, 0.0],
            yaw_quaternion(yaw),
            baseInertialFramePosition=[0.0, 0.0, b.com_height],
        )
    )
    client.changeDynamics(
        body,
        -1,
        lateralFriction=0.0,
        spinningFriction=0.0,
        rollingFriction=0.0,
        linearDamping=0.0,
        angularDamping=0.0,
    )
    return body
