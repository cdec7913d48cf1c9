"""Physics of the simulator: lidar geometry, odometry, pushing and stalling, bumpers, people, events,
bad commands and determinism. Pure: pybullet in DIRECT mode, no ROS; short simulated durations."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Dict, List, Sequence, Tuple, Type, TypeVar

import numpy as np
import pytest

from flex_nav.exceptions import ConfigError
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
from flex_nav_sim.simulation import LocalizationDrift, SensorOptions, Simulation
from flex_nav_sim.world import Spawn, WorldSpec, load_world

NO_CAMERA = SensorOptions(camera=False)


def make_world(tmp_path: Path, body: str = "", room: Tuple[float, float, float, float] = (-2, -2, 2, 2)) -> WorldSpec:
    """A square room (walls 0.1 m thick centred on the given rectangle) plus ``body`` YAML."""
    path = tmp_path / "test_world.yaml"
    x0, y0, x1, y1 = room
    path.write_text(
        "name: test_world\n"
        "defaults: {wall_height: 0.6, wall_thickness: 0.1}\n"
        f"rooms:\n  - {{name: room, min: [{x0}, {y0}], max: [{x1}, {y1}]}}\n" + body
    )
    return load_world(path)


def spawn(name: str = "r1", profile: str = "kobuki", pose: Sequence[float] = (0.0, 0.0, 0.0)) -> Spawn:
    return Spawn(name, profile, (pose[0], pose[1], math.radians(pose[2])))


def drive(sim: Simulation, robot: str, v: float, w: float, duration: float) -> List[object]:
    """Command (v, w) every 0.1 s for ``duration`` [s] (beats the command timeout); return all readings."""
    out: List[object] = []
    end = sim.time + duration - 1e-9
    while sim.time < end:
        sim.command(robot, v, w)
        out.extend(sim.run(min(0.1, end - sim.time + 1e-9)))
    return out


R = TypeVar("R")  # a kind of reading


def last(readings: Sequence[object], kind: Type[R]) -> R:
    found = [r for r in readings if isinstance(r, kind)]
    assert found, f"no {kind.__name__}"
    return found[-1]


def present(sim: Simulation, name: str) -> Pose2D:
    """The pose of solid or person ``name``, which must be in the world."""
    pose = sim.object_pose(name)
    assert pose is not None, f"{name} is not in the world"
    return pose


# -- lidar --------------------------------------------------------------------------------------------
def expected_room_ranges(origin: Tuple[float, float], angles: np.ndarray, inner: float) -> np.ndarray:
    """Distance from ``origin`` along each world bearing to the inner faces of a square room |x|,|y| = inner."""
    ox, oy = origin
    c, s = np.cos(angles), np.sin(angles)
    with np.errstate(divide="ignore"):
        tx = np.where(c > 0, (inner - ox) / c, np.where(c < 0, (-inner - ox) / c, np.inf))
        ty = np.where(s > 0, (inner - oy) / s, np.where(s < 0, (-inner - oy) / s, np.inf))
    return np.minimum(tx, ty)


@pytest.mark.parametrize(("profile", "yaw_deg"), [("kobuki", 0.0), ("kobuki", 30.0), ("turtlebot4", -70.0)])
def test_lidar_ranges_match_room_geometry(tmp_path: Path, profile: str, yaw_deg: float) -> None:
    world = make_world(tmp_path)
    with Simulation(world, [spawn(profile=profile, pose=(0.3, -0.2, yaw_deg))], seed=4, sensors=NO_CAMERA) as sim:
        scan = last(sim.step(), ScanReading)
        spec = sim.robot("r1").profile.lidar
        yaw = math.radians(yaw_deg)
        mx, my, _ = spec.mount
        origin = (0.3 + math.cos(yaw) * mx - math.sin(yaw) * my, -0.2 + math.sin(yaw) * mx + math.cos(yaw) * my)
        expected = expected_room_ranges(origin, spec.beam_angles() + yaw, inner=1.95)
        expected = np.where(expected > spec.range_max, np.inf, expected)
        ranges = scan.ranges.astype(np.float64)
        assert ranges.shape == (spec.beam_count,)
        finite = np.isfinite(expected)
        assert (np.isfinite(ranges) == finite).all()
        sigma = spec.noise_std + spec.noise_fraction * expected[finite]
        error = ranges[finite] - expected[finite]
        assert np.all(np.abs(error) < 5.0 * sigma + 0.002), f"worst error {np.abs(error).max():.4f} m"
        z = error / sigma
        assert abs(z.mean()) < 0.3  # unbiased
        assert 0.7 < z.std() < 1.3  # noise is there, with the profile's size


def test_lidar_sees_obstacles_people_and_robots_but_not_low_obstacles(tmp_path: Path) -> None:
    world = make_world(
        tmp_path,
        "obstacles:\n"
        "  - {name: low, shape: box, size: [0.3, 0.6, 0.05], pose: [0.7, 0.0]}\n"
        "  - {name: post, shape: cylinder, radius: 0.1, height: 0.5, pose: [0.0, 1.0]}\n"
        "people:\n  - {name: bob, pose: [-1.0, 0.0]}\n",
    )
    spawns = [spawn("r1", "turtlebot4", (0, 0, 0)), spawn("r2", "kobuki", (0.0, -1.2, 0))]
    with Simulation(world, spawns, seed=1, sensors=NO_CAMERA) as sim:
        scans = {r.robot: r for r in sim.step() if isinstance(r, ScanReading)}
        spec = sim.robot("r1").profile.lidar
        angles = spec.beam_angles()
        mount_x = spec.mount[0]  # -0.04

        def range_at(deg: float) -> float:
            return float(scans["r1"].ranges[int(np.argmin(np.abs(angles - math.radians(deg))))])

        assert range_at(0.0) == pytest.approx(1.95 - mount_x, abs=0.03)  # the low box is invisible
        assert range_at(90.0) == pytest.approx(1.0 - 0.1, abs=0.03)  # the post
        assert range_at(180.0) == pytest.approx(1.0 + mount_x - 0.2, abs=0.03)  # the person (radius 0.2)
        assert range_at(-90.0) == pytest.approx(1.2 - 0.177, abs=0.03)  # the other robot's body
        assert np.nanmin(scans["r1"].ranges) > sim.robot("r1").profile.base.radius  # never sees itself


# -- odometry and drive ---------------------------------------------------------------------------------
def test_odometry_integrates_commanded_motion(tmp_path: Path) -> None:
    world = make_world(tmp_path, room=(-3, -3, 3, 3))
    with Simulation(world, [spawn(pose=(-2.0, 0.0, 0.0))], seed=2, sensors=NO_CAMERA) as sim:
        out = drive(sim, "r1", 0.4, 0.0, 3.0)
        odom = last(out, OdometryReading)
        accel = sim.robot("r1").profile.drive.max_linear_acceleration
        travelled = 0.4 * 3.0 - 0.4**2 / (2.0 * accel)  # ramp-up at the acceleration limit
        assert odom.truth_pose.x - (-2.0) == pytest.approx(travelled, abs=0.02)
        assert odom.odom_pose.x == pytest.approx(travelled, rel=0.03)  # noisy, but close
        assert abs(odom.odom_pose.y) < 0.02
        assert odom.linear == pytest.approx(0.4, abs=0.02)
        out = drive(sim, "r1", 0.0, 1.0, 2.0)
        odom2 = last(out, OdometryReading)
        turned = odom2.truth_pose.yaw - odom.truth_pose.yaw
        alpha = sim.robot("r1").profile.drive.max_angular_acceleration
        assert turned == pytest.approx(2.0 - 1.0 / (2.0 * alpha), abs=0.06)  # ramp-up at the limit
        assert odom2.odom_pose.yaw - odom.odom_pose.yaw == pytest.approx(turned, abs=0.1)
        assert odom2.angular == pytest.approx(1.0, abs=0.05)
        # map -> odom * odom -> base = map -> base (ground-truth localization)
        m2o, o2b = odom2.map_to_odom, odom2.odom_pose
        c, s = math.cos(m2o.yaw), math.sin(m2o.yaw)
        composed = (m2o.x + c * o2b.x - s * o2b.y, m2o.y + s * o2b.x + c * o2b.y)
        assert composed == pytest.approx((odom2.truth_pose.x, odom2.truth_pose.y), abs=1e-9)


def test_sensor_rates_match_profile(tmp_path: Path) -> None:
    with Simulation(make_world(tmp_path), [spawn(profile="turtlebot4")], sensors=NO_CAMERA) as sim:
        out = [r for r in sim.run(3.0) if 1.0 < getattr(r, "stamp", 0.0) <= 3.0]  # two whole seconds
    assert sum(isinstance(r, OdometryReading) for r in out) == 2 * 20
    assert sum(isinstance(r, ScanReading) for r in out) == 11  # 5.5 Hz
    assert sum(isinstance(r, BumperReading) for r in out) in (2 * 62, 2 * 62 + 1)  # 62 Hz on a 240 Hz clock


@pytest.mark.parametrize("profile", ["kobuki", "create2", "turtlebot4"])
def test_light_box_is_pushed_heavy_box_stalls_the_robot(tmp_path: Path, profile: str) -> None:
    world = make_world(
        tmp_path,
        "boxes:\n"
        "  - {name: light, size: [0.3, 0.3, 0.3], mass: 0.5, friction: 0.5, pose: [-0.6, 1.0]}\n"
        "  - {name: heavy, size: [0.6, 0.6, 0.6], mass: 30.0, friction: 0.5, pose: [-0.4, -1.0]}\n",
        room=(-3, -3, 3, 3),
    )
    spawns = [spawn("pusher", profile, (-2.0, 1.0, 0)), spawn("staller", profile, (-2.0, -1.0, 0))]
    with Simulation(world, spawns, seed=3, sensors=NO_CAMERA) as sim:
        v = min(0.3, sim.robot("pusher").profile.drive.max_linear_velocity)
        sim2_out: List[object] = []
        while sim.time < 8.0 - 1e-9:  # drive both straight ahead for 8 s
            sim.command("pusher", v, 0.0)
            sim.command("staller", v, 0.0)
            sim2_out.extend(sim.run(0.1))
        light = sim.object_pose("light")
        heavy = sim.object_pose("heavy")
        assert light is not None and heavy is not None
        assert light.x - (-0.6) > 0.5, "the light box should have been pushed"
        assert abs(heavy.x - (-0.4)) < 0.01, "the heavy box must not move"
        staller = [r for r in sim2_out if isinstance(r, OdometryReading) and r.robot == "staller"]
        # the staller reached the heavy box (front face at x = -0.7) and stopped there
        assert staller[-1].truth_pose.x == pytest.approx(-0.7 - sim.robot("staller").profile.radius, abs=0.02)
        # odometry tells the truth: over the last 2 s (stalled, still commanded) it reports no motion
        recent = [r for r in staller if r.stamp >= sim.time - 2.0]
        assert abs(recent[-1].odom_pose.x - recent[0].odom_pose.x) < 0.005
        assert abs(recent[-1].linear) < 0.01
        assert sim.robot("staller").cmd_v == pytest.approx(v)  # it was still being commanded
        assert any(isinstance(r, ContactReading) and r.begin and r.other == "heavy" for r in sim2_out)


# -- bumpers ----------------------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("profile", "offset_y", "zones"),  # contact bearing asin(offset / (robot radius + 0.1 m post radius))
    [
        ("kobuki", 0.0, {"center"}),
        ("kobuki", 0.2, {"left"}),  # 46 deg
        ("kobuki", -0.2, {"right"}),
        ("create2", 0.0, {"left", "right"}),
        ("create2", 0.2, {"left"}),
        ("create2", -0.2, {"right"}),
        ("turtlebot4", 0.0, {"bump_front_center"}),
        ("turtlebot4", 0.13, {"bump_front_left"}),  # 29 deg
        ("turtlebot4", -0.13, {"bump_front_right"}),
        ("turtlebot4", 0.25, {"bump_left"}),  # 67 deg
    ],
)
def test_bumper_zone_of_a_contact(tmp_path: Path, profile: str, offset_y: float, zones: set) -> None:
    world = make_world(
        tmp_path,
        f"obstacles:\n  - {{name: post, shape: cylinder, radius: 0.1, height: 0.5, pose: [0.6, {offset_y}]}}\n",
    )
    with Simulation(world, [spawn(profile=profile)], seed=0, sensors=NO_CAMERA) as sim:
        out = drive(sim, "r1", 0.2, 0.0, 3.0)
    bumps = [r for r in out if isinstance(r, BumperReading)]
    pressed = {z for r in bumps for z, state in r.pressed.items() if state}
    assert pressed == zones
    first = next(r for r in bumps if any(r.pressed.values()))
    assert set(first.changed) == zones
    contact = next(r for r in out if isinstance(r, ContactReading) and r.begin)
    assert (contact.other, contact.other_kind, set(contact.zones)) == ("post", "obstacle", zones)


def test_low_obstacle_found_by_bumper_only(tmp_path: Path) -> None:
    world = make_world(tmp_path, "obstacles:\n  - {name: low, shape: box, size: [0.3, 0.8, 0.05], pose: [0.8, 0.0]}\n")
    with Simulation(world, [spawn()], seed=0, sensors=NO_CAMERA) as sim:
        out = drive(sim, "r1", 0.3, 0.0, 3.0)
    scans = [r for r in out if isinstance(r, ScanReading)]
    odoms = [r for r in out if isinstance(r, OdometryReading)]
    ahead = len(scans[0].ranges) // 2
    for scan in scans:  # the lidar never sees it: the beam ahead always reaches the far wall
        x = min(odoms, key=lambda o: abs(o.stamp - scan.stamp)).truth_pose.x
        assert scan.ranges[ahead] == pytest.approx(1.95 - (x + 0.05), abs=0.04)
    contact = next(r for r in out if isinstance(r, ContactReading) and r.begin)
    assert (contact.other, contact.zones) == ("low", ("center",))
    assert last(out, BumperReading).pressed["center"]


def test_bumper_released_after_backing_off(tmp_path: Path) -> None:
    world = make_world(
        tmp_path, "obstacles:\n  - {name: post, shape: cylinder, radius: 0.1, height: 0.5, pose: [0.5, 0.0]}\n"
    )
    with Simulation(world, [spawn()], seed=0, sensors=NO_CAMERA) as sim:
        drive(sim, "r1", 0.2, 0.0, 2.0)
        out = drive(sim, "r1", -0.1, 0.0, 1.0)
    released = [r for r in out if isinstance(r, BumperReading) and "center" in r.changed]
    assert released and not released[-1].pressed["center"]
    assert any(isinstance(r, ContactReading) and not r.begin and r.other == "post" for r in out)


# -- people and events ------------------------------------------------------------------------------------
def test_person_walks_along_waypoints(tmp_path: Path) -> None:
    world = make_world(
        tmp_path,
        "people:\n"
        "  - {name: ann, waypoints: [[-1.5, 1.5], [1.5, 1.5], [1.5, -1.5]], speed: 1.0, loop: false, start: 0.5}\n",
    )
    person = world.people[0]
    with Simulation(world, [spawn(pose=(-1.0, -1.0, 0))], seed=0, sensors=NO_CAMERA) as sim:
        sim.run(0.5)
        assert present(sim, "ann")[:2] == pytest.approx((-1.5, 1.5), abs=1e-6)  # not started yet
        sim.run(2.0)
        assert present(sim, "ann")[:2] == pytest.approx(person.pose_after(2.0)[:2], abs=0.01)
        assert present(sim, "ann")[:2] == pytest.approx((0.5, 1.5), abs=0.01)
        sim.run(5.0)
        assert present(sim, "ann")[:2] == pytest.approx((1.5, -1.5), abs=0.01)  # stopped at the end


def test_person_touching_robot_reported(tmp_path: Path) -> None:
    # ann walks at the robot from its front-left (bearing 60 deg) and stops 2 cm into it
    world = make_world(tmp_path, "people:\n  - {name: ann, waypoints: [[0.75, 1.3], [0.1785, 0.309]], loop: false}\n")
    with Simulation(world, [spawn(pose=(0.0, 0.0, 0.0))], seed=0, sensors=NO_CAMERA) as sim:
        out = sim.run(2.0)
    contact = next(r for r in out if isinstance(r, ContactReading) and r.begin)
    assert (contact.other, contact.other_kind, contact.zones) == ("ann", "person", ("left",))
    assert any(isinstance(r, BumperReading) and r.pressed["left"] for r in out)


def test_scripted_events_remove_and_start(tmp_path: Path) -> None:
    world = make_world(
        tmp_path,
        "obstacles:\n  - {name: wall_piece, shape: box, size: [0.2, 1.0, 0.5], pose: [1.0, 0.0]}\n"
        "people:\n  - {name: ann, waypoints: [[-1.5, 1.5], [1.5, 1.5]], speed: 1.0, start: null}\n"
        "events:\n"
        "  - {at: 0.5, action: remove, target: wall_piece}\n"
        "  - {at: 1.0, action: start_walking, target: ann}\n",
    )
    with Simulation(world, [spawn()], seed=0, sensors=NO_CAMERA) as sim:
        before = [r for r in sim.run(0.4) if isinstance(r, ScanReading)]
        out = sim.run(1.6)
        ahead = len(before[0].ranges) // 2
        assert before[-1].ranges[ahead] == pytest.approx(0.9 - 0.05, abs=0.03)
        after = [r for r in out if isinstance(r, ScanReading) and r.stamp > 0.6]
        assert after[-1].ranges[ahead] == pytest.approx(1.95 - 0.05, abs=0.03)
        events = [(e.stamp, e.action, e.target) for e in out if isinstance(e, WorldEventReading)]
        assert [e[1:] for e in events] == [("remove", "wall_piece"), ("start_walking", "ann")]
        assert events[0][0] == pytest.approx(0.5, abs=0.005)
        assert sim.object_pose("wall_piece") is None
        assert present(sim, "ann").x == pytest.approx(-1.5 + 1.0, abs=0.02)  # walked 1 s


def test_a_world_started_on_request_runs_its_script_from_then(tmp_path: Path) -> None:
    """With ``world_started=False`` nobody walks and no event happens until start_world; then the world's times
    count from the start, and a second start is refused."""
    world = make_world(
        tmp_path,
        "obstacles:\n  - {name: wall_piece, shape: box, size: [0.2, 1.0, 0.5], pose: [1.0, 0.0]}\n"
        "people:\n  - {name: ann, waypoints: [[-1.5, 1.5], [1.5, 1.5]], speed: 1.0, start: 0.5}\n"
        "  - {name: bob, waypoints: [[-1.5, -1.5], [1.5, -1.5]], speed: 1.0}\n"
        "events:\n  - {at: 0.5, action: remove, target: wall_piece}\n",
    )
    with Simulation(world, [spawn()], seed=0, sensors=NO_CAMERA, world_started=False) as sim:
        waited = sim.run(2.0)
        assert not any(isinstance(r, WorldEventReading) for r in waited)
        assert present(sim, "ann")[:2] == pytest.approx((-1.5, 1.5), abs=1e-6)
        assert present(sim, "bob")[:2] == pytest.approx((-1.5, -1.5), abs=1e-6)  # walks "from the start": not yet
        assert sim.object_pose("wall_piece") is not None
        sim.start_world()
        assert sim.world_start_s == pytest.approx(2.0)
        out = sim.run(1.5)
        events = [e for e in out if isinstance(e, WorldEventReading)]
        assert [(e.action, e.target) for e in events] == [("remove", "wall_piece")]
        assert events[0].stamp == pytest.approx(2.5, abs=0.005)
        assert present(sim, "ann").x == pytest.approx(-1.5 + 1.0, abs=0.02)  # walked from 2.5 s to 3.5 s
        assert present(sim, "bob").x == pytest.approx(-1.5 + 1.5, abs=0.02)  # from 2.0 s
        with pytest.raises(ConfigError, match="started already"):
            sim.start_world()


def _scans_after_start(world: WorldSpec, waited_steps: int) -> List[np.ndarray]:
    with Simulation(world, [spawn()], seed=3, sensors=NO_CAMERA, world_started=False) as sim:
        for _ in range(waited_steps):
            sim.step()
        sim.start_world()
        return [r.ranges for r in sim.run(1.0) if isinstance(r, ScanReading)]


def test_noise_starts_afresh_from_the_seed_when_the_world_starts(tmp_path: Path) -> None:
    """Two runs started after different waits draw the same lidar noise from the start on (a scan period of the
    kobuki's lidar apart, so the scans fall on the same steps after the start)."""
    world = make_world(tmp_path)
    with Simulation(world, [spawn()], sensors=NO_CAMERA) as sim:
        lidar = sim.lidar_spec_of("r1")
        step_hz = round(1.0 / sim.dt)
    assert lidar is not None and step_hz % round(lidar.rate) == 0, "the test needs a lidar rate dividing the steps'"
    period_steps = step_hz // round(lidar.rate)
    early = _scans_after_start(world, period_steps * 2)
    late = _scans_after_start(world, period_steps * 7)
    assert len(early) == len(late) > 2
    for a, b in zip(early, late):
        np.testing.assert_array_equal(a, b)


# -- bad commands -----------------------------------------------------------------------------------------
def test_non_finite_commands_ignored_and_robot_stops(tmp_path: Path) -> None:
    with Simulation(make_world(tmp_path), [spawn()], seed=0, sensors=NO_CAMERA) as sim:
        for v, w in ((math.nan, 0.0), (0.1, math.inf), (-math.inf, math.nan)):
            notice = sim.command("r1", v, w)
            assert notice is not None and notice.kind == "ignored"
        sim.run(1.0)
        assert sim.truth_pose("r1")[:2] == pytest.approx((0.0, 0.0), abs=1e-3)
        sim.command("r1", 0.3, 0.0)
        sim.run(0.3)
        notice = sim.command("r1", math.nan, 0.0)
        assert notice is not None and notice.kind == "ignored"  # previous command stays until the timeout
        out = sim.run(1.5)
        notices = [r for r in out if isinstance(r, CommandNotice)]
        assert [n.kind for n in notices] == ["timeout"]
        stopped = sim.truth_pose("r1").x
        sim.run(0.5)
        assert sim.truth_pose("r1").x == pytest.approx(stopped, abs=1e-3)


def test_commands_above_limits_clamped_no_explosion(tmp_path: Path) -> None:
    world = make_world(tmp_path, room=(-5, -5, 5, 5))
    with Simulation(world, [spawn(pose=(-4.0, 0.0, 0.0))], seed=0, sensors=NO_CAMERA) as sim:
        notice = sim.command("r1", 1e9, -1e9)
        assert notice is not None and notice.kind == "clamped" and "clamped to (0.700, -3.140)" in notice.detail
        out = drive(sim, "r1", 50.0, 0.0, 3.0)
        odom = [r for r in out if isinstance(r, OdometryReading)]
        assert max(r.truth_linear for r in odom) <= 0.7 + 0.01
        assert odom[-1].truth_linear == pytest.approx(0.7, abs=0.01)
        pos, orn = sim.client.getBasePositionAndOrientation(sim.robot("r1").body)
        assert abs(pos[2] - 0.08) < 0.005 and abs(orn[0]) < 0.01 and abs(orn[1]) < 0.01  # upright, on the floor


def test_unknown_robot_and_bad_physics_rate(tmp_path: Path) -> None:
    world = make_world(tmp_path)
    with pytest.raises(ConfigError, match=r"physics_rate must be 30..5000 Hz"):
        Simulation(world, [spawn()], physics_rate=1.0)
    with Simulation(world, [spawn()], sensors=NO_CAMERA) as sim, pytest.raises(
        ConfigError, match=r"robot 'r9' is not valid \(valid: r1\)"
    ):
        sim.command("r9", 0.1, 0.0)


def test_bad_spawn_rejected_before_physics_starts(tmp_path: Path) -> None:
    world = make_world(tmp_path)
    with pytest.raises(ConfigError, match="overlaps wall"):
        Simulation(world, [spawn(pose=(1.95, 0.0, 0.0))])
    with pytest.raises(ConfigError, match="two robots share the namespace 'r1'"):
        Simulation(world, [spawn(pose=(-1, 0, 0)), spawn(pose=(1, 0, 0))])


# -- determinism ------------------------------------------------------------------------------------------
def _trajectory(world: WorldSpec, seed: int) -> Tuple[np.ndarray, np.ndarray]:
    with Simulation(world, [spawn(pose=(-1.0, 0.0, 0.0))], seed=seed, sensors=NO_CAMERA) as sim:
        poses = []
        scans = []
        for i in range(30):
            sim.command("r1", 0.3, 0.8 * math.sin(i / 5.0))
            for r in sim.run(0.1):
                if isinstance(r, OdometryReading):
                    poses.append((*r.odom_pose, *r.truth_pose))
                elif isinstance(r, ScanReading):
                    scans.append(r.ranges)
        return np.array(poses), np.array(scans)


def test_same_seed_same_trajectory(tmp_path: Path) -> None:
    world = make_world(tmp_path, "boxes:\n  - {name: b, size: [0.3, 0.3, 0.3], mass: 0.5, pose: [0.2, 0.3]}\n")
    a_poses, a_scans = _trajectory(world, seed=7)
    b_poses, b_scans = _trajectory(world, seed=7)
    c_poses, c_scans = _trajectory(world, seed=8)
    assert a_poses.shape[0] >= 150
    assert np.array_equal(a_poses, b_poses)
    assert np.array_equal(a_scans, b_scans)
    assert not np.array_equal(a_poses[:, :3], c_poses[:, :3])  # odometry noise depends on the seed
    assert not np.array_equal(a_scans, c_scans)


def test_localization_drift_is_bounded_and_seeded(tmp_path: Path) -> None:
    drift = LocalizationDrift(sigma_xy=0.05, sigma_yaw=0.02, tau=2.0)
    with Simulation(make_world(tmp_path), [spawn()], seed=1, sensors=NO_CAMERA, drift=drift) as sim:
        odoms = [r for r in sim.run(10.0) if isinstance(r, OdometryReading)]
    offsets = np.array([(r.map_to_odom.x, r.map_to_odom.y) for r in odoms])
    assert 0.005 < offsets.std() < 0.15
    assert np.abs(offsets).max() < 0.3


# -- camera -----------------------------------------------------------------------------------------------
def test_camera_sees_a_person_ahead(tmp_path: Path) -> None:
    world = make_world(tmp_path, "people:\n  - {name: ann, pose: [1.2, 0.0], color: [1.0, 0.0, 0.0, 1.0]}\n")
    with Simulation(world, [spawn()], seed=0) as sim:
        image = last(sim.step(), ImageReading)
        spec = sim.robot("r1").profile.camera
        assert spec is not None
    assert image.rgb.shape == (spec.height, spec.width, 3) and image.rgb.dtype == np.uint8
    h, w = spec.height, spec.width
    centre = image.rgb[h // 2 - 5 : h // 2 + 5, w // 2 - 5 : w // 2 + 5].reshape(-1, 3).astype(int)
    assert (centre[:, 0] > centre[:, 1] + 60).all()  # red person in the middle
    side = image.rgb[h // 2, 5].astype(int)
    assert not side[0] > side[1] + 60  # not red at the edge
    # depth registered to the colour image: the person's near side in the middle, [m] along the optical axis
    assert image.depth.shape == (h, w) and image.depth.dtype == np.float32
    person_radius = sim.world.people[0].radius
    expected = 1.2 - spec.mount[0] - person_radius
    np.testing.assert_allclose(image.depth[h // 2 - 5 : h // 2 + 5, w // 2 - 5 : w // 2 + 5], expected, atol=0.03)
    assert image.depth[h // 2, 5] > expected + 0.3  # beside the person: farther
    assert np.isinf(image.depth[0]).any() or (image.depth[0] > 2.0).all()  # the top row looks past the walls


def test_a_camera_nobody_watches_renders_nothing_and_resumes_on_its_schedule(tmp_path: Path) -> None:
    with Simulation(make_world(tmp_path), [spawn()], seed=0) as sim:
        spec = sim.camera_spec_of("r1")
        assert spec is not None
        sim.set_camera_wanted("r1", False)
        unwatched = [r for r in sim.run(1.0) if isinstance(r, ImageReading)]
        sim.set_camera_wanted("r1", True)
        watched = [r for r in sim.run(1.0) if isinstance(r, ImageReading)]
        with pytest.raises(ConfigError):
            sim.set_camera_wanted("nobody", True)
    assert unwatched == []
    assert len(watched) == pytest.approx(spec.rate, abs=1)  # the schedule went on: a frame per period again
    assert watched[0].stamp == pytest.approx(1.0, abs=1.0 / spec.rate + 1e-6)


def test_shipped_worlds_run(tmp_path: Path) -> None:
    for name in ("lab", "two_rooms", "open_room", "corridor"):
        with Simulation(load_world(name), seed=0, sensors=NO_CAMERA) as sim:
            kinds: Dict[str, int] = {}
            for r in drive(sim, sim.robot_names[0], 0.2, 0.1, 0.5):
                kinds[type(r).__name__] = kinds.get(type(r).__name__, 0) + 1
            assert {"OdometryReading", "ScanReading", "BumperReading"} <= set(kinds)


def test_door_events_open_and_close(tmp_path: Path) -> None:
    world = make_world(
        tmp_path,
        "walls:\n  - {name: divider, from: [1.0, -2.0], to: [1.0, 2.0]}\n"
        "doors:\n  - {name: door, at: [1.0, 0.0], width: 0.9, state: closed}\n"
        "events:\n  - {at: 0.5, action: open, target: door}\n  - {at: 1.0, action: close, target: door}\n",
    )
    with Simulation(world, [spawn()], seed=0, sensors=NO_CAMERA) as sim:
        scans = [r for r in sim.run(1.5) if isinstance(r, ScanReading)]
        ahead = len(scans[0].ranges) // 2
        door_face = 1.0 - world.solid("door").size[1] / 2.0 - 0.05  # lidar 5 cm ahead of the centre
        by_time = {round(s.stamp, 1): float(s.ranges[ahead]) for s in scans}
        assert by_time[0.0] == pytest.approx(door_face, abs=0.03)  # closed: the panel
        assert by_time[0.7] == pytest.approx(1.95 - 0.05, abs=0.03)  # open: the far wall
        assert by_time[1.4] == pytest.approx(door_face, abs=0.03)  # closed again


# -- teleport (the kidnapped robot) ------------------------------------------------------------------------
def test_teleport_moves_the_robot_but_not_its_odometry(tmp_path: Path) -> None:
    with Simulation(make_world(tmp_path), [spawn()], seed=0, sensors=NO_CAMERA) as sim:
        sim.run(0.2)
        odom_before = [r for r in sim.run(0.1) if isinstance(r, OdometryReading)][-1].odom_pose
        message = sim.teleport("r1", Pose2D(1.0, -0.5, math.pi / 2))
        assert "teleported to (1.00, -0.50, 90 deg)" in message
        readings = [r for r in sim.run(0.3) if isinstance(r, OdometryReading)]
        truth = sim.truth_pose("r1")
        assert (truth.x, truth.y, truth.yaw) == pytest.approx((1.0, -0.5, math.pi / 2), abs=2e-3)
        # the wheels did not turn: odometry stays where it was, so map -> odom of an oracle jumps instead
        assert readings[-1].odom_pose[:2] == pytest.approx(odom_before[:2], abs=1e-3)


def test_teleport_refuses_solids_unknown_robots_and_nan(tmp_path: Path) -> None:
    world = make_world(tmp_path, "obstacles:\n  - {name: crate, shape: box, size: [0.4, 0.4, 0.5], pose: [1.0, 0.0]}\n")
    with Simulation(world, [spawn()], seed=0, sensors=NO_CAMERA) as sim:
        with pytest.raises(ConfigError, match="overlaps obstacle 'crate'"):
            sim.teleport("r1", Pose2D(1.0, 0.1, 0.0))
        with pytest.raises(ConfigError, match="r1"):
            sim.teleport("nobody", Pose2D(0.0, 0.0, 0.0))
        with pytest.raises(ConfigError, match="must be finite"):
            sim.teleport("r1", Pose2D(math.nan, 0.0, 0.0))
        assert sim.truth_pose("r1")[:2] == pytest.approx((0.0, 0.0), abs=1e-3)


def test_teleport_world_event(tmp_path: Path) -> None:
    world = make_world(tmp_path, "events:\n  - {at: 0.5, action: teleport, target: r1, pose: [-1.0, 1.0, 180]}\n")
    with Simulation(world, [spawn()], seed=0, sensors=NO_CAMERA) as sim:
        out = sim.run(0.7)
        events = [e for e in out if isinstance(e, WorldEventReading)]
        assert [(e.action, e.target) for e in events] == [("teleport", "r1")]
        assert "teleported to (-1.00, 1.00, 180 deg)" in events[0].detail
        assert sim.truth_pose("r1")[:2] == pytest.approx((-1.0, 1.0), abs=2e-3)
    bad = make_world(tmp_path, "events:\n  - {at: 0.5, action: teleport, target: r9, pose: [0, 1]}\n")
    with pytest.raises(ConfigError, match=r"teleport event target.*r9.*r1"):
        Simulation(bad, [spawn()], seed=0, sensors=NO_CAMERA)
