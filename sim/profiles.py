"""Robot profiles: one YAML file per robot model in ``sim/robots/``, loaded into frozen dataclasses.

The same files are the single source of truth for the simulator (body, drive, sensors, noise) and for
the navigation configuration (robot radius, footprint, velocity/acceleration limits, bumper zones).
Use :func:`load_profile` with a name (``kobuki``, ``create2``, ``turtlebot4``) or a path.

Conventions: angles in the YAML are in degrees (field names end in ``_deg``) and are stored in
radians here; lengths in metres, times in seconds, rates in hertz, masses in kilograms, forces in
newtons. Bumper zone angles are measured in the robot frame (x forward, y left), counter-clockwise
positive, 0 = straight ahead.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import List, Optional, Tuple

import numpy as np

from flex_nav.exceptions import ConfigError
from flex_nav_sim.yaml_fields import Fields, PathLike, available_names, read_yaml_mapping, resolve_named_file

PROFILE_DIR = Path(__file__).resolve().parent / "robots"
BUMPER_STYLES = ("kobuki", "create", "zones")  # which driver-style bumper message the bridge publishes


@dataclass(frozen=True)
class BaseSpec:
    """The robot body: a vertical cylinder standing on the floor (collision, visibility to other robots)."""

    radius: float  # [m] body radius (circular footprint)
    height: float  # [m] body height (what other robots' lidars and cameras see)
    mass: float  # [kg]
    com_height: float  # [m] centre of mass above the floor

    def footprint(self, sides: int = 16) -> List[Tuple[float, float]]:
        """A polygon [m] around the circular footprint (vertices on the circle), for costmap footprints."""
        return [
            (self.radius * math.cos(2.0 * math.pi * i / sides), self.radius * math.sin(2.0 * math.pi * i / sides))
            for i in range(sides)
        ]


@dataclass(frozen=True)
class DriveSpec:
    """Differential drive: geometry, limits and the motor force limit that makes a robot stall."""

    wheel_separation: float  # [m] distance between the wheel contact points
    wheel_radius: float  # [m]
    max_linear_velocity: float  # [m/s]
    max_angular_velocity: float  # [rad/s]
    max_linear_acceleration: float  # [m/s^2]
    max_angular_acceleration: float  # [rad/s^2]
    max_wheel_force: float  # [N] traction/motor force limit per wheel
    cmd_vel_timeout: float  # [s] the base stops when no command arrived for this long


@dataclass(frozen=True)
class BumperZone:
    """One bumper switch: pressed by a contact whose bearing lies in [min_angle, max_angle]."""

    name: str
    min_angle: float  # [rad] robot frame, CCW positive, 0 = ahead
    max_angle: float  # [rad]

    @property
    def center(self) -> float:
        """Bearing [rad] of the zone's middle."""
        return 0.5 * (self.min_angle + self.max_angle)

    def contains(self, bearing: float) -> bool:
        """True if ``bearing`` [rad] (any wrap) lies in this zone."""
        wrapped = math.atan2(math.sin(bearing), math.cos(bearing))
        return self.min_angle <= wrapped <= self.max_angle


@dataclass(frozen=True)
class BumperSpec:
    """Bumper zones and how the real driver reports them (see ``BUMPER_STYLES``)."""

    driver_style: str  # kobuki: BumperEvent (bumper 0/1/2 + state); create: left/right flags; zones: generic only
    zones: Tuple[BumperZone, ...]
    rate: float  # [Hz] sampling rate of the bumper switches

    def zones_at(self, bearing: float) -> List[str]:
        """Names of the zones a contact at ``bearing`` [rad] presses (zones may overlap)."""
        return [z.name for z in self.zones if z.contains(bearing)]


@dataclass(frozen=True)
class LidarSpec:
    """A planar scanning lidar (sensor_msgs/LaserScan conventions: CCW from angle_min to angle_max)."""

    model: str
    mount: Tuple[float, float, float]  # [m] x, y, z of the scan centre in base_footprint
    range_min: float  # [m]
    range_max: float  # [m]
    angle_min: float  # [rad] first beam, relative to the robot's heading
    angle_max: float  # [rad] last beam
    angle_increment: float  # [rad]
    rate: float  # [Hz] scans per second
    noise_std: float  # [m] range noise standard deviation, absolute part
    noise_fraction: float  # [-] range noise standard deviation as a fraction of the range

    @property
    def beam_count(self) -> int:
        return round((self.angle_max - self.angle_min) / self.angle_increment) + 1

    def beam_angles(self) -> np.ndarray:
        """Beam bearings [rad] in the robot frame, float64 (beam_count,)."""
        return self.angle_min + self.angle_increment * np.arange(self.beam_count, dtype=np.float64)


@dataclass(frozen=True)
class CameraSpec:
    """A forward-looking RGB camera rendered offscreen (ER_TINY_RENDERER)."""

    model: str
    width: int  # [px] rendered image width
    height: int  # [px]
    hfov: float  # [rad] horizontal field of view
    mount: Tuple[float, float, float]  # [m] x, y, z of the optical centre in base_footprint
    pitch: float  # [rad] downward tilt (positive looks down)
    rate: float  # [Hz]
    near: float  # [m] clipping planes
    far: float  # [m]

    @property
    def vfov(self) -> float:
        """Vertical field of view [rad] implied by hfov and the aspect ratio."""
        return 2.0 * math.atan(math.tan(self.hfov / 2.0) * self.height / self.width)

    @property
    def focal_px(self) -> float:
        """Focal length [px] (square pixels)."""
        return (self.width / 2.0) / math.tan(self.hfov / 2.0)


@dataclass(frozen=True)
class OdometrySpec:
    """Wheel odometry: publication rate and error model (variance grows with the motion, not with time)."""

    rate: float  # [Hz]
    trans_var_per_m: float  # [m^2/m] variance of the distance error per metre driven
    trans_var_per_rad: float  # [m^2/rad] variance of the distance error per radian turned
    rot_var_per_rad: float  # [rad^2/rad] variance of the heading error per radian turned
    rot_var_per_m: float  # [rad^2/m] variance of the heading error per metre driven
    scale_error_std: float  # [-] per-run systematic scale error (wheel radius/separation calibration)


@dataclass(frozen=True)
class RobotProfile:
    """Everything the simulator and the navigation configuration need to know about one robot model."""

    name: str
    description: str
    base: BaseSpec
    drive: DriveSpec
    bumper: BumperSpec
    lidar: LidarSpec
    camera: Optional[CameraSpec]
    odometry: OdometrySpec
    source: str  # file the profile was loaded from

    @property
    def radius(self) -> float:
        """Robot radius [m] (for costmap inflation and collision checks)."""
        return self.base.radius


def available_profiles() -> List[str]:
    """Names of the shipped profiles (``sim/robots/*.yaml``)."""
    return available_names(PROFILE_DIR)


def load_profile(name_or_path: PathLike) -> RobotProfile:
    """Load and validate a robot profile by name or path; ConfigError names the file, field and valid values."""
    path = resolve_named_file(name_or_path, PROFILE_DIR, "robot profile")
    top = Fields(read_yaml_mapping(path, "robot profile"), str(path))
    profile = RobotProfile(
        name=top.string("name"),
        description=top.string("description", ""),
        base=_base(top.sub("base")),
        drive=_drive(top.sub("drive")),
        bumper=_bumper(top.sub("bumper")),
        lidar=_lidar(top.sub("lidar")),
        camera=_camera(top.sub("camera")) if top.raw("camera", None) is not None else None,
        odometry=_odometry(top.sub("odometry")),
        source=str(path),
    )
    top.done()
    cam = profile.camera
    if (
        cam is not None
        and math.hypot(cam.mount[0], cam.mount[1]) < profile.base.radius
        and cam.mount[2] < profile.base.height
    ):
        raise ConfigError(
            f"{path}: camera.mount {list(cam.mount)} lies inside the body cylinder (radius {profile.base.radius} m, "
            f"height {profile.base.height} m); the camera would see the body from inside: mount it at or beyond "
            "the body edge or above the body"
        )
    return profile


def _base(f: Fields) -> BaseSpec:
    radius = f.positive("radius", unit="[m]")
    height = f.positive("height", unit="[m]")
    spec = BaseSpec(
        radius=radius,
        height=height,
        mass=f.positive("mass", unit="[kg]"),
        com_height=f.number("com_height", positive=True, maximum=height, unit="[m]"),
    )
    f.done()
    return spec


def _drive(f: Fields) -> DriveSpec:
    spec = DriveSpec(
        wheel_separation=f.positive("wheel_separation", unit="[m]"),
        wheel_radius=f.positive("wheel_radius", unit="[m]"),
        max_linear_velocity=f.positive("max_linear_velocity", unit="[m/s]"),
        max_angular_velocity=f.positive("max_angular_velocity", unit="[rad/s]"),
        max_linear_acceleration=f.positive("max_linear_acceleration", unit="[m/s^2]"),
        max_angular_acceleration=f.positive("max_angular_acceleration", unit="[rad/s^2]"),
        max_wheel_force=f.positive("max_wheel_force", unit="[N]"),
        cmd_vel_timeout=f.positive("cmd_vel_timeout", unit="[s]"),
    )
    f.done()
    return spec


def _bumper(f: Fields) -> BumperSpec:
    style = f.choice("driver_style", BUMPER_STYLES)
    zones = []
    seen = set()
    for z in f.sub_list("zones"):
        name = z.string("name")
        if not name or name in seen:
            raise ConfigError(f"{z.where('name')} must be a unique non-empty name, got {name!r}")
        seen.add(name)
        lo = math.radians(z.number("min_angle_deg", minimum=-180.0, maximum=180.0, unit="[deg]"))
        hi = math.radians(z.number("max_angle_deg", minimum=-180.0, maximum=180.0, unit="[deg]"))
        if hi <= lo:
            raise ConfigError(f"{z.where('max_angle_deg')} must be above min_angle_deg")
        zones.append(BumperZone(name, lo, hi))
        z.done()
    if not zones:
        raise ConfigError(f"{f.where('zones')} must list at least one zone")
    names = {z.name for z in zones}
    needed = {"kobuki": {"left", "center", "right"}, "create": {"left", "right"}, "zones": set()}[style]
    if not needed <= names:
        raise ConfigError(
            f"{f.where('zones')}: driver_style {style} needs zones named {', '.join(sorted(needed))}, "
            f"got {', '.join(sorted(names))}"
        )
    spec = BumperSpec(driver_style=style, zones=tuple(zones), rate=f.positive("rate", unit="[Hz]"))
    f.done()
    return spec


def _lidar(f: Fields) -> LidarSpec:
    range_min = f.positive("range_min", unit="[m]")
    range_max = f.positive("range_max", unit="[m]")
    if range_max <= range_min:
        raise ConfigError(f"{f.where('range_max')} ({range_max}) must exceed range_min ({range_min})")
    angle_min = math.radians(f.number("angle_min_deg", minimum=-180.0, maximum=180.0, unit="[deg]"))
    angle_max = math.radians(f.number("angle_max_deg", minimum=-180.0, maximum=180.0, unit="[deg]"))
    increment = math.radians(f.number("angle_increment_deg", minimum=0.01, maximum=90.0, unit="[deg]"))
    if angle_max <= angle_min:
        raise ConfigError(f"{f.where('angle_max_deg')} must exceed angle_min_deg")
    spec = LidarSpec(
        model=f.string("model"),
        mount=_mount(f),
        range_min=range_min,
        range_max=range_max,
        angle_min=angle_min,
        angle_max=angle_max,
        angle_increment=increment,
        rate=f.positive("rate", unit="[Hz]"),
        noise_std=f.number("noise_std", minimum=0.0, unit="[m]"),
        noise_fraction=f.number("noise_fraction", minimum=0.0, maximum=0.5),
    )
    f.done()
    return spec


def _camera(f: Fields) -> CameraSpec:
    near = f.positive("near", unit="[m]")
    far = f.positive("far", unit="[m]")
    if far <= near:
        raise ConfigError(f"{f.where('far')} ({far}) must exceed near ({near})")
    spec = CameraSpec(
        model=f.string("model"),
        width=f.integer("width", minimum=8),
        height=f.integer("height", minimum=8),
        hfov=math.radians(f.number("hfov_deg", minimum=1.0, maximum=170.0, unit="[deg]")),
        mount=_mount(f),
        pitch=math.radians(f.number("pitch_deg", minimum=-89.0, maximum=89.0, unit="[deg]")),
        rate=f.positive("rate", unit="[Hz]"),
        near=near,
        far=far,
    )
    f.done()
    return spec


def _odometry(f: Fields) -> OdometrySpec:
    spec = OdometrySpec(
        rate=f.positive("rate", unit="[Hz]"),
        trans_var_per_m=f.number("trans_var_per_m", minimum=0.0),
        trans_var_per_rad=f.number("trans_var_per_rad", minimum=0.0),
        rot_var_per_rad=f.number("rot_var_per_rad", minimum=0.0),
        rot_var_per_m=f.number("rot_var_per_m", minimum=0.0),
        scale_error_std=f.number("scale_error_std", minimum=0.0, maximum=0.2),
    )
    f.done()
    return spec


def _mount(f: Fields) -> Tuple[float, float, float]:
    x, y, z = f.vector("mount", 3, unit="[m] (x, y, z in base_footprint)")
    if z <= 0.0:
        raise ConfigError(f"{f.where('mount')} z must be above the floor, got {z}")
    return x, y, z
