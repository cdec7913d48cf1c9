"""A URDF of a robot profile, for ``robot_description`` (RViz's RobotModel display); pure, no ROS.

The links and fixed joints are those of the simulator's static transforms (``base_footprint`` -> ``base_link``
at the wheel axle height, ``laser`` at the lidar's mount, ``camera_rgb_frame`` at the camera's mount, pitched
down), so the model drawn sits where the sensors' frames are. Shapes: the body is a cylinder of the profile's
radius and height standing on the floor, the lidar a small cylinder, the camera a small box. Frame names are
unprefixed: a namespaced robot's model is drawn with RViz's TF prefix (e.g. ``robot1``).
"""

from __future__ import annotations

from typing import List, Tuple

from flex_nav_sim.profiles import RobotProfile

LIDAR_RADIUS_M = 0.025  # [m] drawn size of the lidar head
LIDAR_HEIGHT_M = 0.04  # [m]
CAMERA_BOX_M = (0.04, 0.12, 0.04)  # [m] drawn size of the camera (depth along x, width, height)


def _f(value: float) -> str:
    return f"{value:.4f}".rstrip("0").rstrip(".") if value != 0.0 else "0"


def _xyz(values: Tuple[float, float, float]) -> str:
    return " ".join(_f(v) for v in values)


def _link(name: str, geometry: str = "", z_m: float = 0.0, colour: str = "") -> List[str]:
    if not geometry:
        return [f'  <link name="{name}"/>']
    return [
        f'  <link name="{name}">',
        "    <visual>",
        f'      <origin xyz="0 0 {_f(z_m)}" rpy="0 0 0"/>',
        f"      <geometry>{geometry}</geometry>",
        f'      <material name="{name}_colour"><color rgba="{colour}"/></material>',
        "    </visual>",
        "  </link>",
    ]


def _joint(child: str, xyz: Tuple[float, float, float], pitch_rad: float = 0.0) -> List[str]:
    return [
        f'  <joint name="{child}_joint" type="fixed">',
        '    <parent link="base_footprint"/>',
        f'    <child link="{child}"/>',
        f'    <origin xyz="{_xyz(xyz)}" rpy="0 {_f(pitch_rad)} 0"/>',
        "  </joint>",
    ]


def robot_urdf(profile: RobotProfile) -> str:
    """The URDF text of ``profile`` (deterministic: the same profile gives the same bytes)."""
    base, axle_m = profile.base, profile.drive.wheel_radius
    lines = [
        '<?xml version="1.0"?>',
        f"<!-- Generated from sim/robots/{profile.name}.yaml by tools/gen_urdf.py; do not edit. -->",
        f'<robot name="{profile.name}">',
        *_link("base_footprint"),
        *_link("base_link", f'<cylinder radius="{_f(base.radius)}" length="{_f(base.height)}"/>',
               z_m=base.height / 2.0 - axle_m, colour="0.25 0.25 0.25 0.7"),
        *_joint("base_link", (0.0, 0.0, axle_m)),
        *_link("laser", f'<cylinder radius="{_f(LIDAR_RADIUS_M)}" length="{_f(LIDAR_HEIGHT_M)}"/>',
               colour="0.1 0.1 0.1 1"),
        *_joint("laser", profile.lidar.mount),
    ]
    if profile.camera is not None:
        lines += [
            *_link("camera_rgb_frame", f'<box size="{_xyz(CAMERA_BOX_M)}"/>', colour="0.1 0.1 0.6 1"),
            *_joint("camera_rgb_frame", profile.camera.mount, profile.camera.pitch),
        ]
    lines.append("</robot>")
    return "\n".join(lines) + "\n"
