"""Robot profiles: the shipped files load with the manufacturers' numbers; bad files fail naming the field."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from flex_nav.exceptions import ConfigError
from flex_nav_sim.profiles import PROFILE_DIR, available_profiles, load_profile


def test_shipped_profiles() -> None:
    assert available_profiles() == ["create2", "kobuki", "turtlebot4"]


@pytest.mark.parametrize(
    ("name", "separation", "radius", "v_max", "zones", "style"),
    [
        ("create2", 0.235, 0.036, 0.5, ["left", "right"], "create"),
        ("kobuki", 0.230, 0.035, 0.7, ["left", "center", "right"], "kobuki"),
        (
            "turtlebot4",
            0.233,
            0.036,
            0.306,
            ["bump_left", "bump_front_left", "bump_front_center", "bump_front_right", "bump_right"],
            "zones",
        ),
    ],
)
def test_profile_values(name: str, separation: float, radius: float, v_max: float, zones: list, style: str) -> None:
    p = load_profile(name)
    assert p.name == name
    assert p.drive.wheel_separation == separation
    assert p.drive.wheel_radius == radius
    assert p.drive.max_linear_velocity == v_max
    assert [z.name for z in p.bumper.zones] == zones
    assert p.bumper.driver_style == style
    assert p.camera is not None and p.camera.width > 0


def test_turtlebot4_limits_and_rplidar() -> None:
    p = load_profile("turtlebot4")
    assert p.drive.max_angular_velocity == pytest.approx(1.9)
    lidar = p.lidar
    assert (lidar.range_min, lidar.range_max, lidar.rate) == (0.15, 12.0, 5.5)
    assert lidar.beam_count == 360
    assert lidar.angle_increment == pytest.approx(math.radians(1.0))


def test_kobuki_hokuyo() -> None:
    lidar = load_profile("kobuki").lidar
    assert (lidar.range_min, lidar.range_max, lidar.rate) == (0.02, 5.6, 10.0)
    assert math.degrees(lidar.angle_max - lidar.angle_min) == pytest.approx(239.06, abs=0.01)
    assert math.degrees(lidar.angle_increment) == pytest.approx(0.352, abs=0.001)
    angles = lidar.beam_angles()
    assert angles[0] == pytest.approx(lidar.angle_min) and angles[-1] == pytest.approx(lidar.angle_max)


def test_bumper_zone_lookup() -> None:
    kobuki = load_profile("kobuki").bumper
    assert kobuki.zones_at(0.0) == ["center"]
    assert kobuki.zones_at(math.radians(60)) == ["left"]
    assert kobuki.zones_at(math.radians(-60)) == ["right"]
    assert kobuki.zones_at(math.pi) == []  # behind: no bumper
    create = load_profile("create2").bumper
    assert create.zones_at(0.0) == ["left", "right"]  # head-on presses both


def test_footprint_polygon_on_circle() -> None:
    base = load_profile("kobuki").base
    pts = base.footprint(12)
    assert len(pts) == 12
    assert all(math.hypot(x, y) == pytest.approx(base.radius) for x, y in pts)


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "bad.yaml"
    path.write_text(text)
    return path


def _kobuki_text() -> str:
    return (PROFILE_DIR / "kobuki.yaml").read_text()


def test_unknown_profile_lists_valid_names() -> None:
    with pytest.raises(
        ConfigError, match=r"robot profile 'roomba' is not valid \(valid: create2, kobuki, turtlebot4\)"
    ):
        load_profile("roomba")


def test_missing_profile_file() -> None:
    with pytest.raises(ConfigError, match="does not exist"):
        load_profile("/nonexistent/robot.yaml")


def test_malformed_yaml(tmp_path: Path) -> None:
    path = _write(tmp_path, "name: [unclosed\n")
    with pytest.raises(ConfigError, match="malformed YAML") as err:
        load_profile(path)
    assert str(path) in str(err.value)


def test_bad_field_named(tmp_path: Path) -> None:
    path = _write(tmp_path, _kobuki_text().replace("wheel_radius: 0.035", "wheel_radius: -0.035"))
    with pytest.raises(ConfigError, match=r"drive\.wheel_radius must be > 0"):
        load_profile(path)


def test_unknown_field_rejected(tmp_path: Path) -> None:
    path = _write(tmp_path, _kobuki_text().replace("wheel_radius: 0.035", "wheel_radius: 0.035\n  wheel_radios: 1"))
    with pytest.raises(ConfigError, match=r"drive\.wheel_radios: unknown field"):
        load_profile(path)


def test_bad_bumper_style_lists_choices(tmp_path: Path) -> None:
    path = _write(tmp_path, _kobuki_text().replace("driver_style: kobuki", "driver_style: roomba"))
    with pytest.raises(
        ConfigError, match=r"bumper\.driver_style 'roomba' is not valid \(valid: kobuki, create, zones\)"
    ):
        load_profile(path)


def test_kobuki_style_needs_three_zones(tmp_path: Path) -> None:
    path = _write(tmp_path, _kobuki_text().replace("{name: center,", "{name: middle,"))
    with pytest.raises(ConfigError, match="needs zones named center, left, right"):
        load_profile(path)


def test_camera_inside_body_rejected(tmp_path: Path) -> None:
    path = _write(tmp_path, _kobuki_text().replace("mount: [0.18, 0.0, 0.30]", "mount: [0.0, 0.0, 0.30]"))
    with pytest.raises(ConfigError, match="inside the body cylinder"):
        load_profile(path)
