"""config/*.yaml: every section names only parameters its node reads, values pass the algorithms' own
validation, and the navigation limits stay inside the simulated robot's physical profile."""

import dataclasses
import math
from pathlib import Path

import pytest
import yaml
from harness import REPO_ROOT

from flex_nav import validation
from flex_nav.localization import FilterParams
from flex_nav.mapping.occupancy import OccupancyParams
from flex_nav.mapping.slam import SlamParams
from flex_nav.nav.control.pure_pursuit import PurePursuitParams
from flex_nav.nav.costmap.inflation import InflationParams
from flex_nav.nav.planning.planner import PlannerParams
from flex_nav.nodes import follow_server, get_path_server, localizer, mapper, pure_pursuit_controller
from flex_nav.ros import costmap_ros
from flex_nav_sim.profiles import load_profile

PROFILES = {"create": "create2", "turtlebot2": "kobuki", "turtlebot4": "turtlebot4"}  # config -> sim profile
NODES = {
    "get_path_server": get_path_server.PARAMETERS,
    "follow_path_server": follow_server.PARAMETERS,
    "follow_topic_server": follow_server.PARAMETERS,
    "pure_pursuit_path": pure_pursuit_controller.PARAMETERS,
    "pure_pursuit_topic": pure_pursuit_controller.PARAMETERS,
    "twist_relay": ("timeout",),
}
PLANNER_NAMES = {f.name for f in dataclasses.fields(PlannerParams)}


def load(name: str) -> dict:
    config: dict = yaml.safe_load((REPO_ROOT / "config" / f"{name}.yaml").read_text())
    return config


def test_one_config_per_profile_the_localizer_and_the_mapper():
    assert sorted(p.stem for p in (REPO_ROOT / "config").glob("*.yaml")) == sorted([*PROFILES, "localizer", "mapper"])


def test_the_mapper_config_names_only_its_parameters():
    config = load("mapper")
    slam_values = {k: v for k, v in config.items() if k in mapper.SLAM_PARAMS}
    assert set(config) - set(slam_values) <= set(mapper.NODE_PARAMS), set(config) - set(slam_values)
    params = validation.dataclass_from_mapping(SlamParams, slam_values, owner="config/mapper.yaml")
    assert params.do_loop_closing
    OccupancyParams(resolution=config["resolution"], max_free_range=config["max_laser_range"])


def test_the_localizer_config_names_only_its_parameters():
    config = load("localizer")
    filter_values = {k: v for k, v in config.items() if k in localizer.FILTER_PARAMS}
    assert set(config) - set(filter_values) <= set(localizer.NODE_PARAMS), set(config) - set(filter_values)
    params = FilterParams.from_mapping(filter_values, owner="config/localizer.yaml")
    assert params.recovery_alpha_fast > 0.0  # a kidnapped robot must be noticed


@pytest.mark.parametrize("name", sorted(PROFILES))
def test_sections_name_only_known_parameters(name):
    config = load(name)
    assert set(NODES) <= set(config), f"missing node sections: {set(NODES) - set(config)}"
    for node, known in NODES.items():
        section = config[node]
        assert set(section) <= set(known), f"{name}: {node}: unknown {set(section) - set(known)}"
        for costmap in ("global_costmap", "local_costmap"):
            if costmap in section:
                unknown = set(section[costmap]) - set(costmap_ros.PARAMETERS)
                assert not unknown, f"{name}: {node}/{costmap}: unknown {unknown}"
        if "planner" in section:
            assert set(section["planner"]) <= PLANNER_NAMES, f"{name}: {node}/planner"


@pytest.mark.parametrize("name", sorted(PROFILES))
def test_values_pass_validation_and_fit_the_robot(name):
    config = load(name)
    profile = load_profile(PROFILES[name])
    radius = config["robot_radius"]
    assert radius == pytest.approx(profile.base.radius)
    for node in ("get_path_server", "follow_path_server", "pure_pursuit_path"):
        for costmap in ("global_costmap", "local_costmap"):
            if costmap in config[node]:
                cm = config[node][costmap]
                assert cm["robot_radius"] == pytest.approx(radius), f"{node}/{costmap}"
                InflationParams(cm["robot_radius"], cm["inflation_radius"], cm["cost_scaling_factor"])
        if "planner" in config[node]:
            PlannerParams(**config[node]["planner"])

    controller = config["pure_pursuit_path"]
    local = controller["local_costmap"]
    pp = PurePursuitParams.from_mapping({**controller["pure_pursuit"], "inscribed_radius": local["robot_radius"],
                                         "inflation_cost_scaling_factor": local["cost_scaling_factor"]})
    drive = profile.drive
    assert pp.desired_linear_vel <= drive.max_linear_velocity
    assert pp.max_angular_vel <= drive.max_angular_velocity
    assert pp.rotate_to_heading_angular_vel <= drive.max_angular_velocity
    assert pp.max_linear_accel <= drive.max_linear_acceleration
    assert pp.max_linear_decel <= drive.max_linear_acceleration
    assert pp.max_angular_accel <= drive.max_angular_acceleration
    # the sensor watchdog must tolerate at least two missed scans / odometry messages
    assert controller["sensor_timeout"] >= 2.0 / profile.lidar.rate
    assert controller["sensor_timeout"] >= 2.0 / profile.odometry.rate
    assert local["obstacle_range"] <= profile.lidar.range_max
    assert config["pure_pursuit_topic"] == controller

    follow = config["follow_path_server"]
    assert config["follow_topic_server"] == follow
    # the lookahead point must lie on the rolling costmap, and the controller must not reach the end of a
    # local plan before the next one arrives
    half_window = min(follow["local_costmap"]["width"], follow["local_costmap"]["height"]) / 2.0
    assert follow["lookahead_distance"] < half_window
    assert follow["lookahead_distance"] > 2.0 * pp.desired_linear_vel / follow["planner_frequency"]
    assert config["twist_relay"]["timeout"] > 1.0 / controller["controller_frequency"]
    assert math.isfinite(config["get_path_server"]["map_timeout"])


def test_launch_files_name_the_configs():
    text = (REPO_ROOT / "launch" / "navigation.launch").read_text()
    assert "$(find flex_nav)/config/$(arg robot).yaml" in text
    assert Path(REPO_ROOT / "launch" / "navigation_nodes.launch").is_file()
