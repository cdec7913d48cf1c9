"""The simulation: one BulletClient, one seeded RNG, a world, robots, and a fixed-step loop.

Pure Python + pybullet, no ROS: :meth:`Simulation.step` advances the physics by one fixed step and
returns the readings that fell due (odometry, scans, bumpers, images, contacts, world events,
command notices). The ROS bridge (``flex_nav.nodes.sim_bridge``) and the tests drive it the same way.

Determinism: the same world, spawns, seed, physics rate and command sequence (by step) give the
same trajectory, because all randomness comes from generators spawned from the one seeded
``numpy.random.Generator`` and pybullet runs single-threaded with deterministic overlapping pairs.

Not thread-safe: call every method from one thread (the bridge queues ROS commands for it).
"""

from __future__ import annotations

import contextlib
import math
import os
import time
from dataclasses import dataclass, replace
from typing import Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import pybullet
from pybullet_utils import bullet_client

from flex_nav.exceptions import ConfigError, choices_message
from flex_nav_sim.bodies import (
    ROBOT_COLORS,
    create_floor,
    create_person,
    create_robot,
    create_solid,
    person_z,
    yaw_quaternion,
)
from flex_nav_sim.odometry import inverse, multiply
from flex_nav_sim.profiles import CameraSpec, LidarSpec, RobotProfile, load_profile
from flex_nav_sim.readings import (
    BumperReading,
    CommandNotice,
    ContactReading,
    ImageReading,
    OdometryReading,
    Pose2D,
    ScanReading,
    WorldEventReading,
)
from flex_nav_sim.robot import Contact, SimRobot
from flex_nav_sim.sensors import Camera, Lidar
from flex_nav_sim.world import SPAWN_CLEARANCE, Person, Solid, Spawn, WorldEvent, WorldSpec, check_spawns

Reading = Union[
    OdometryReading, ScanReading, BumperReading, ImageReading, ContactReading, WorldEventReading, CommandNotice
]
COST_KEYS = ("physics", "lidar", "camera", "other_sensors")  # parts of Simulation.costs
DEFAULT_PHYSICS_RATE = 240.0  # [Hz] fixed physics step (pybullet's default time step is 1/240 s)
_EPS = 1e-9  # [s] scheduling tolerance


@dataclass(frozen=True)
class SensorOptions:
    """Which sensors to simulate (a disabled sensor costs nothing)."""

    odometry: bool = True
    lidar: bool = True
    bumpers: bool = True
    camera: bool = True


@dataclass(frozen=True)
class LocalizationDrift:
    """Optional slowly wandering localization error (map -> odom), an Ornstein-Uhlenbeck process."""

    sigma_xy: float  # [m] stationary standard deviation of the x and y error
    sigma_yaw: float  # [rad] stationary standard deviation of the heading error
    tau: float  # [s] correlation time

    def __post_init__(self) -> None:
        if not (self.sigma_xy >= 0.0 and self.sigma_yaw >= 0.0 and self.tau > 0.0):
            raise ConfigError(f"localization drift needs sigma_xy >= 0, sigma_yaw >= 0, tau > 0; got {self}")


class _RobotSlot:
    """A robot with its sensors and their schedules."""

    def __init__(
        self, robot: SimRobot, lidar: Optional[Lidar], camera: Optional[Camera], drift_rng: np.random.Generator
    ) -> None:
        self.robot = robot
        self.drift_rng = drift_rng
        self.lidar = lidar
        self.camera = camera
        self.next_odom = 0.0  # [s] next due times
        self.next_scan = 0.0
        self.next_bumper = 0.0
        self.next_image = 0.0
        self.camera_wanted = True  # False: nobody looks, its frames are not rendered (set_camera_wanted)
        self.drift = np.zeros(3)  # localization error (x [m], y [m], yaw [rad])


class _PersonState:
    def __init__(self, person: Person, body: int) -> None:
        self.person = person
        self.body = body
        self.walking = person.walks and person.start_time is not None and person.start_time <= 0.0
        self.walked = 0.0  # [s] time spent walking


class Simulation:
    """A world with robots in its own DIRECT (or GUI) BulletClient; see the module docstring."""

    def __init__(
        self,
        world: WorldSpec,
        spawns: Optional[Sequence[Spawn]] = None,
        *,
        seed: int = 0,
        physics_rate: float = DEFAULT_PHYSICS_RATE,
        profiles: Optional[Mapping[str, RobotProfile]] = None,
        sensors: SensorOptions = SensorOptions(),
        drift: Optional[LocalizationDrift] = None,
        gui: bool = False,
        world_started: bool = True,
    ) -> None:
        if not (math.isfinite(physics_rate) and 30.0 <= physics_rate <= 5000.0):
            raise ConfigError(f"physics_rate must be 30..5000 Hz, got {physics_rate!r}")
        spawn_list = list(world.spawns if spawns is None else spawns)
        resolved = self._profiles(spawn_list, profiles or {})
        check_spawns(world, spawn_list, {s.name: resolved[s.name].radius for s in spawn_list})
        robots = sorted(s.name for s in spawn_list)
        for event in world.events:
            if event.action == "teleport" and event.target not in robots:
                raise ConfigError(choices_message(f"{world.source}: teleport event target", event.target, robots))

        self.world = world
        self.dt = 1.0 / physics_rate  # [s]
        self.time = 0.0  # [s] simulated time
        self.steps = 0
        self.seed = seed
        self.rng = np.random.default_rng(seed)
        # [s] when the world's script (people's walks, world events) started; None: not yet (start_world)
        self.world_start_s: Optional[float] = 0.0 if world_started else None
        self.sensors = sensors
        self.drift = drift
        self.costs: Dict[str, float] = dict.fromkeys(COST_KEYS, 0.0)  # [s] wall time spent, by part
        self.gui_active = bool(gui and os.environ.get("DISPLAY"))
        mode = pybullet.GUI if self.gui_active else pybullet.DIRECT
        self.client = bullet_client.BulletClient(connection_mode=mode)
        try:
            self._build(spawn_list, resolved)
        except BaseException:
            self.close()
            raise

    # -- construction -----------------------------------------------------------------------------
    @staticmethod
    def _profiles(spawns: Sequence[Spawn], given: Mapping[str, RobotProfile]) -> Dict[str, RobotProfile]:
        unknown = sorted(set(given) - {s.name for s in spawns})
        if unknown:
            raise ConfigError(choices_message("profile override for robot", unknown[0], [s.name for s in spawns]))
        cache: Dict[str, RobotProfile] = {}
        out = {}
        for s in spawns:
            if s.name in given:
                out[s.name] = given[s.name]
            else:
                if s.profile not in cache:
                    cache[s.profile] = load_profile(s.profile)
                out[s.name] = cache[s.profile]
        return out

    def _build(self, spawns: Sequence[Spawn], profiles: Mapping[str, RobotProfile]) -> None:
        c = self.client
        c.setGravity(0.0, 0.0, -9.81)
        c.setTimeStep(self.dt)
        c.setPhysicsEngineParameter(deterministicOverlappingPairs=1)
        if self.gui_active:
            c.configureDebugVisualizer(pybullet.COV_ENABLE_GUI, 0)
        self.floor = create_floor(c)
        self._names: Dict[int, Tuple[str, str]] = {}  # body -> (name, kind)
        self._solid_bodies: Dict[str, int] = {}
        self._solids: Dict[str, Solid] = {s.name: s for s in self.world.solids}
        for solid in self.world.solids:
            if solid.present:
                self._add_solid(solid)
        self._people: Dict[str, _PersonState] = {}
        for person in self.world.people:
            body = create_person(c, person, person.pose_after(0.0))
            state = _PersonState(person, body)
            state.walking = state.walking and self.world_start_s is not None  # else from start_world on
            self._people[person.name] = state
            self._names[body] = (person.name, "person")
        self._slots: Dict[str, _RobotSlot] = {}
        for i, spawn in enumerate(spawns):
            profile = profiles[spawn.name]
            body = create_robot(c, profile, spawn.pose, ROBOT_COLORS[i % len(ROBOT_COLORS)])
            rngs = self.rng.spawn(3)  # odometry, lidar, localization drift
            robot = SimRobot(
                c, spawn.name, profile, body=body, spawn=Pose2D(*spawn.pose), rng=rngs[0], floor=self.floor
            )
            lidar = Lidar(c, profile.lidar, profile.base.radius, rngs[1]) if self.sensors.lidar else None
            camera = Camera(c, profile.camera) if (self.sensors.camera and profile.camera is not None) else None
            self._slots[spawn.name] = _RobotSlot(robot, lidar, camera, rngs[2])
            self._names[body] = (spawn.name, "robot")
        self._event_index = 0

    def _add_solid(self, solid: Solid) -> None:
        body = create_solid(self.client, solid)
        self._solid_bodies[solid.name] = body
        self._names[body] = (solid.name, solid.kind)

    # -- public API -------------------------------------------------------------------------------
    def lidar_spec_of(self, robot: str) -> Optional[LidarSpec]:
        """The lidar actually simulated for ``robot`` (None if lidars are off)."""
        self.robot(robot)  # ConfigError for an unknown name
        lidar = self._slots[robot].lidar
        return lidar.spec if lidar is not None else None

    def camera_spec_of(self, robot: str) -> Optional[CameraSpec]:
        """The camera actually simulated for ``robot`` (None if off or the profile has none)."""
        self.robot(robot)
        camera = self._slots[robot].camera
        return camera.spec if camera is not None else None

    def set_camera_wanted(self, robot: str, wanted: bool) -> None:
        """Render ``robot``'s camera frames (at their rate) only while ``wanted``: rendering is most of the
        simulator's cost, and a frame nobody receives is wasted. Frames are due on the same schedule either way."""
        self.robot(robot)
        self._slots[robot].camera_wanted = bool(wanted)

    @property
    def robot_names(self) -> List[str]:
        return list(self._slots)

    def robot(self, name: str) -> SimRobot:
        """The named robot; ConfigError lists the valid names."""
        if name not in self._slots:
            raise ConfigError(choices_message("robot", name, list(self._slots)))
        return self._slots[name].robot

    def command(self, robot: str, linear: float, angular: float) -> Optional[CommandNotice]:
        """Set a robot's velocity command [m/s, rad/s]; returns a notice if it was ignored or clamped."""
        return self.robot(robot).command(linear, angular, self.time)

    def truth_pose(self, robot: str) -> Pose2D:
        """Exact pose of a robot's base_footprint in the map frame."""
        return self.robot(robot).truth()[0]

    def object_pose(self, name: str) -> Optional[Pose2D]:
        """Pose of a solid or person (None if the solid is absent)."""
        if name in self._people:
            body = self._people[name].body
        elif name in self._solid_bodies:
            body = self._solid_bodies[name]
        elif name in self._solids:
            return None
        else:
            raise ConfigError(choices_message("object", name, sorted([*self._solids, *self._people])))
        pos, orn = self.client.getBasePositionAndOrientation(body)
        return Pose2D(pos[0], pos[1], pybullet.getEulerFromQuaternion(orn)[2])

    def step(self) -> List[Reading]:
        """Advance one physics step; return the readings due at the new time."""
        out: List[Reading] = []
        start = time.perf_counter()
        self._apply_events(out)
        self._move_people()
        for slot in self._slots.values():
            notice = slot.robot.check_timeout(self.time)
            if notice is not None:
                out.append(notice)
            slot.robot.apply_drive(self.dt)
        self.client.stepSimulation()
        self.steps += 1
        self.time = self.steps * self.dt
        for slot in self._slots.values():
            slot.robot.latch_contacts()
        self.costs["physics"] += time.perf_counter() - start
        for slot in self._slots.values():
            self._sample(slot, out)
        return out

    def run(self, duration: float) -> List[Reading]:
        """Step for ``duration`` [s] of simulated time; return every reading."""
        out: List[Reading] = []
        end = self.time + duration - _EPS
        while self.time < end:
            out.extend(self.step())
        return out

    def close(self) -> None:
        """Disconnect the physics server (idempotent)."""
        client = getattr(self, "client", None)
        if client is not None:
            with contextlib.suppress(pybullet.error):
                client.disconnect()
            self.client = None

    def __enter__(self) -> Simulation:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def start_world(self) -> None:
        """Start the world's script now: people start walking and world events happen that many seconds after
        this step, and every noise generator starts afresh from the seed. A run that begins here is the same
        run whenever it begins (a simulation built with ``world_started=False`` waits for this)."""
        if self.world_start_s is not None:
            raise ConfigError(f"the world's script started already, at t = {self.world_start_s:.3f} s")
        self.world_start_s = self.time
        fresh = np.random.default_rng(self.seed)
        for slot in self._slots.values():
            odometry, lidar, drift = fresh.spawn(3)
            slot.robot.rng = slot.robot.odometry.rng = odometry
            if slot.lidar is not None:
                slot.lidar.rng = lidar
            slot.drift_rng = drift

    # -- internals --------------------------------------------------------------------------------
    def _apply_events(self, out: List[Reading]) -> None:
        if self.world_start_s is None:
            return
        events = self.world.events
        while (self._event_index < len(events)
               and events[self._event_index].time + self.world_start_s <= self.time + _EPS):
            ev = events[self._event_index]
            self._event_index += 1
            out.append(WorldEventReading(self.time, ev.action, ev.target, self._apply(ev)))

    def teleport(self, robot: str, pose: Pose2D) -> str:
        """Move ``robot`` to ``pose`` (map frame) at once and at rest; its odometry does not see the jump (the
        kidnapped robot). ConfigError for an unknown robot, a non-finite pose or one overlapping a present solid."""
        sim_robot = self.robot(robot)
        if not all(math.isfinite(v) for v in pose):
            raise ConfigError(f"teleport pose of robot {robot!r} must be finite, got {tuple(pose)}")
        clearance = sim_robot.profile.base.radius + SPAWN_CLEARANCE
        for name in self._solid_bodies:
            solid = self._solids[name]
            if solid.footprint().distance_to(pose.x, pose.y) < clearance:
                raise ConfigError(
                    f"teleport of robot {robot!r} to ({pose.x:.2f}, {pose.y:.2f}) overlaps {solid.kind} {name!r}; "
                    "choose free space"
                )
        client = self.client
        (_, _, z), _ = client.getBasePositionAndOrientation(sim_robot.body)
        client.resetBasePositionAndOrientation(sim_robot.body, [pose.x, pose.y, z], yaw_quaternion(pose.yaw))
        client.resetBaseVelocity(sim_robot.body, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0])
        sim_robot.set_v = sim_robot.set_w = 0.0
        sim_robot.last_truth = Pose2D(pose.x, pose.y, pose.yaw)  # odometry integrates from here: no jump in it
        return (f"robot {robot or '(unnamed)'} teleported to ({pose.x:.2f}, {pose.y:.2f}, "
                f"{math.degrees(pose.yaw):.0f} deg)")

    def _apply(self, event: WorldEvent) -> str:
        action, target = event.action, event.target
        if action == "teleport":
            assert event.pose is not None  # the world loader gives every teleport a pose
            return self.teleport(target, Pose2D(*event.pose))
        if action in ("start_walking", "stop_walking"):
            state = self._people[target]
            state.walking = action == "start_walking"
            return f"person {target} {'starts' if state.walking else 'stops'} walking"
        present = target in self._solid_bodies
        want = action in ("add", "close")
        if present == want:
            return f"{target} already {'present' if present else 'absent'}; nothing to do"
        if want:
            self._add_solid(self._solids[target])
            return f"{target} added"
        body = self._solid_bodies.pop(target)
        self._names.pop(body, None)
        self.client.removeBody(body)
        for slot in self._slots.values():
            slot.robot.touching.discard(body)
        return f"{target} removed"

    def _move_people(self) -> None:
        for state in self._people.values():
            person = state.person
            if not state.walking:
                if (
                    person.walks
                    and person.start_time is not None
                    and self.world_start_s is not None
                    and not state.walked
                    and self.time - self.world_start_s >= person.start_time
                ):
                    state.walking = True
                else:
                    continue
            state.walked += self.dt
            x, y, yaw = person.pose_after(state.walked)
            self.client.resetBasePositionAndOrientation(state.body, [x, y, person_z(person)], yaw_quaternion(yaw))

    def _sample(self, slot: _RobotSlot, out: List[Reading]) -> None:
        robot = slot.robot
        profile = robot.profile
        t = self.time
        pose: Optional[Pose2D] = None
        costs = self.costs
        start = time.perf_counter()
        if self.sensors.odometry and t >= slot.next_odom - _EPS:
            slot.next_odom += 1.0 / profile.odometry.rate
            pose, v, w = robot.truth()
            odom = robot.odometry.update(robot.last_truth, pose, t - robot.last_odom_stamp)
            robot.last_truth, robot.last_odom_stamp = pose, t
            estimate = self._localization(slot, pose, 1.0 / profile.odometry.rate)
            out.append(
                OdometryReading(
                    robot.name,
                    t,
                    odom,
                    robot.odometry.linear,
                    robot.odometry.angular,
                    pose,
                    v,
                    w,
                    multiply(estimate, inverse(odom)),
                )
            )
        if self.sensors.bumpers and t >= slot.next_bumper - _EPS:
            slot.next_bumper += 1.0 / profile.bumper.rate
            pressed, changed, contacts = robot.sample_bumpers()
            out.append(BumperReading(robot.name, t, pressed, tuple(changed)))
            self._contact_events(robot, contacts, out)
        mid = time.perf_counter()
        costs["other_sensors"] += mid - start
        if slot.lidar is not None and t >= slot.next_scan - _EPS:
            slot.next_scan += 1.0 / profile.lidar.rate
            if pose is None:
                pose = robot.truth()[0]
            out.append(ScanReading(robot.name, t, slot.lidar.scan(pose)))
            end = time.perf_counter()
            costs["lidar"] += end - mid
            mid = end
        if slot.camera is not None and t >= slot.next_image - _EPS:
            slot.next_image += 1.0 / slot.camera.spec.rate
            if slot.camera_wanted:
                if pose is None:
                    pose = robot.truth()[0]
                out.append(ImageReading(robot.name, t, *slot.camera.render(pose)))
            costs["camera"] += time.perf_counter() - mid

    def _contact_events(self, robot: SimRobot, contacts: Mapping[int, Contact], out: List[Reading]) -> None:
        now = set(contacts)
        for body in sorted(now - robot.touching):
            name, kind = self._names.get(body, (f"body{body}", "unknown"))
            contact = contacts[body]
            zones = tuple(robot.profile.bumper.zones_at(contact.bearing))
            out.append(ContactReading(robot.name, self.time, True, name, kind, zones, contact.point))
        for body in sorted(robot.touching - now):
            name, kind = self._names.get(body, (f"body{body}", "unknown"))
            out.append(ContactReading(robot.name, self.time, False, name, kind, (), (math.nan, math.nan, math.nan)))
        robot.touching = now

    def _localization(self, slot: _RobotSlot, truth: Pose2D, dt: float) -> Pose2D:
        """Ground truth, plus the optional Ornstein-Uhlenbeck drift."""
        if self.drift is None:
            return truth
        d = self.drift
        decay = math.exp(-dt / d.tau)
        gain = math.sqrt(max(0.0, 1.0 - decay * decay))
        noise = slot.drift_rng.standard_normal(3)
        slot.drift = slot.drift * decay + gain * noise * np.array([d.sigma_xy, d.sigma_xy, d.sigma_yaw])
        return Pose2D(truth.x + slot.drift[0], truth.y + slot.drift[1], truth.yaw + slot.drift[2])


def with_lidar(profile: RobotProfile, **changes: float) -> RobotProfile:
    """A copy of ``profile`` with lidar fields changed (e.g. for benchmarks: ``angle_increment``, ``rate``)."""
    return replace(profile, lidar=replace(profile.lidar, **changes))  # type: ignore[arg-type]
