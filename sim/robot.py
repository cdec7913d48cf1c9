"""One simulated differential-drive robot: command handling, force-limited drive, bumper contacts.

Drive model. Wheels are not simulated as bodies; instead, each physics step the drive computes the
forces the two wheels would exert on the chassis:

1. the commanded (v, w) is ramped towards the target at the profile's acceleration limits;
2. a proportional velocity loop asks for the forward force and yaw torque that would reach the
   ramped velocity within ``DRIVE_TIME_CONSTANT``;
3. force and torque are split onto the left and right wheel and each wheel force is clipped to
   ``max_wheel_force`` (the motor/traction limit);
4. a lateral force (up to ``LATERAL_GRIP`` x weight) removes sideways slip: wheels do not skid sideways.

The chassis has zero friction with everything, so these forces are the only propulsion: a robot
pushes a light box (needs a few newtons) and stalls against a heavy one (needs more than its wheels
can give), and because its pose then does not change, its odometry reports no motion.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Optional, Set, Tuple

import numpy as np
import pybullet

from flex_nav_sim.bodies import quaternion_yaw
from flex_nav_sim.odometry import OdometryIntegrator
from flex_nav_sim.profiles import RobotProfile
from flex_nav_sim.readings import CommandNotice, Pose2D

GRAVITY = 9.81  # [m/s^2]
DRIVE_TIME_CONSTANT = 0.02  # [s] velocity loop: reach the setpoint in about this time (if force allows)
LATERAL_GRIP = 1.0  # [-] wheels resist sideways slip up to this fraction of the robot's weight
CONTACT_SLOP = 0.001  # [m] contact points farther apart than this are not touching


class Contact:
    """A touching pair seen at one physics step: the other body and the bearing/point of contact."""

    __slots__ = ("bearing", "body", "point")

    def __init__(self, body: int, bearing: float, point: Tuple[float, float, float]) -> None:
        self.body = body
        self.bearing = bearing  # [rad] in the robot frame, 0 = ahead, CCW positive
        self.point = point  # [m] world


class SimRobot:
    """A robot body in a BulletClient with its drive, command state, odometry and contact latch."""

    def __init__(
        self,
        client: Any,
        name: str,
        profile: RobotProfile,
        *,
        body: int,
        spawn: Pose2D,
        rng: np.random.Generator,
        floor: int,
    ) -> None:
        self.client = client
        self.name = name
        self.profile = profile
        self.body = body
        self.floor = floor
        self.rng = rng
        info = client.getDynamicsInfo(body, -1)
        self.mass: float = float(info[0])
        self.inertia_z: float = float(info[2][2])  # [kg m^2] about the vertical axis
        drive = profile.drive
        self._half_track = drive.wheel_separation / 2.0
        # command state
        self.cmd_v = 0.0  # [m/s] last accepted command (clamped)
        self.cmd_w = 0.0  # [rad/s]
        self.cmd_time = -math.inf  # [s] when it arrived (sim time)
        self.set_v = 0.0  # [m/s] acceleration-limited setpoint
        self.set_w = 0.0  # [rad/s]
        self.timed_out = True
        # odometry and pose bookkeeping
        self.spawn = spawn
        self.odometry = OdometryIntegrator(profile.odometry, rng)
        self.last_truth = spawn
        self.last_odom_stamp = 0.0
        # contacts latched between bumper readings
        self.latched: Dict[int, Contact] = {}
        self.pressed: Dict[str, bool] = {z.name: False for z in profile.bumper.zones}
        self.touching: Set[int] = set()
        self.applied_force = (0.0, 0.0)  # [N] last (forward, torque/half-track) for diagnostics

    # -- commands ---------------------------------------------------------------------------------
    def command(self, v: float, w: float, now: float) -> Optional[CommandNotice]:
        """Accept a velocity command [m/s, rad/s]: non-finite -> ignored; beyond the limits -> clamped."""
        if not (math.isfinite(v) and math.isfinite(w)):
            return CommandNotice(
                self.name, now, "ignored", f"cmd_vel not finite (linear.x={v}, angular.z={w}); ignored"
            )
        drive = self.profile.drive
        cv = min(max(v, -drive.max_linear_velocity), drive.max_linear_velocity)
        cw = min(max(w, -drive.max_angular_velocity), drive.max_angular_velocity)
        self.cmd_v, self.cmd_w, self.cmd_time = cv, cw, now
        self.timed_out = False
        if cv != v or cw != w:
            return CommandNotice(
                self.name,
                now,
                "clamped",
                f"cmd_vel ({v:.3f} m/s, {w:.3f} rad/s) beyond the {self.profile.name} limits "
                f"({drive.max_linear_velocity} m/s, {drive.max_angular_velocity} rad/s); "
                f"clamped to ({cv:.3f}, {cw:.3f})",
            )
        return None

    def check_timeout(self, now: float) -> Optional[CommandNotice]:
        """Stop (target zero) when no command arrived within the profile's cmd_vel_timeout."""
        if not self.timed_out and now - self.cmd_time > self.profile.drive.cmd_vel_timeout:
            self.timed_out = True
            self.cmd_v = self.cmd_w = 0.0
            return CommandNotice(
                self.name, now, "timeout", f"no cmd_vel for {self.profile.drive.cmd_vel_timeout} s; stopping"
            )
        return None

    # -- physics ----------------------------------------------------------------------------------
    def truth(self) -> Tuple[Pose2D, float, float]:
        """Exact (pose of base_footprint, forward velocity [m/s], yaw rate [rad/s])."""
        pos, orn = self.client.getBasePositionAndOrientation(self.body)
        lin, ang = self.client.getBaseVelocity(self.body)
        yaw = quaternion_yaw(orn)
        c, s = math.cos(yaw), math.sin(yaw)
        return Pose2D(pos[0], pos[1], yaw), c * lin[0] + s * lin[1], ang[2]

    def apply_drive(self, dt: float) -> None:
        """Apply this step's wheel forces (see the module docstring). Call once before each stepSimulation."""
        drive = self.profile.drive
        dv = drive.max_linear_acceleration * dt
        dw = drive.max_angular_acceleration * dt
        self.set_v += min(max(self.cmd_v - self.set_v, -dv), dv)
        self.set_w += min(max(self.cmd_w - self.set_w, -dw), dw)

        client = self.client
        pos, orn = client.getBasePositionAndOrientation(self.body)
        lin, ang = client.getBaseVelocity(self.body)
        yaw = quaternion_yaw(orn)
        c, s = math.cos(yaw), math.sin(yaw)
        forward = c * lin[0] + s * lin[1]
        lateral = -s * lin[0] + c * lin[1]

        force = self.mass * (self.set_v - forward) / DRIVE_TIME_CONSTANT
        torque = self.inertia_z * (self.set_w - ang[2]) / DRIVE_TIME_CONSTANT
        limit = drive.max_wheel_force
        right = min(max(force / 2.0 + torque / (2.0 * self._half_track), -limit), limit)
        left = min(max(force / 2.0 - torque / (2.0 * self._half_track), -limit), limit)
        force = right + left
        torque = (right - left) * self._half_track
        grip = LATERAL_GRIP * self.mass * GRAVITY
        side = min(max(-self.mass * lateral / dt, -grip), grip)
        self.applied_force = (force, torque)
        client.applyExternalForce(
            self.body, -1, [c * force - s * side, s * force + c * side, 0.0], pos, pybullet.WORLD_FRAME
        )
        client.applyExternalTorque(self.body, -1, [0.0, 0.0, torque], pybullet.WORLD_FRAME)

    def latch_contacts(self) -> None:
        """Record what touches the robot this step (kept until the next bumper reading)."""
        points = self.client.getContactPoints(bodyA=self.body)
        if not points:
            return
        pos, orn = self.client.getBasePositionAndOrientation(self.body)
        yaw = quaternion_yaw(orn)
        for pt in points:
            other = pt[2]
            if other == self.floor or pt[8] > CONTACT_SLOP:
                continue
            if other in self.latched:
                continue
            on_a = pt[5]
            bearing = math.atan2(on_a[1] - pos[1], on_a[0] - pos[0]) - yaw
            self.latched[other] = Contact(other, math.atan2(math.sin(bearing), math.cos(bearing)), tuple(on_a))

    def sample_bumpers(self) -> Tuple[Dict[str, bool], List[str], Dict[int, Contact]]:
        """Zone states from the latched contacts; returns (pressed, changed zones, contacts) and clears the latch."""
        bumper = self.profile.bumper
        now_pressed = {z.name: False for z in bumper.zones}
        for contact in self.latched.values():
            for zone in bumper.zones_at(contact.bearing):
                now_pressed[zone] = True
        changed = [name for name, state in now_pressed.items() if state != self.pressed[name]]
        self.pressed = now_pressed
        contacts = self.latched
        self.latched = {}
        return now_pressed, changed, contacts
