"""Private names of hosted components (no master): ``~x`` resolves to the component's namespace while it is built
inside ``hosted_as`` and to the node's own name outside; blocks nest and unwind; bad component names and a bad
``~components`` list of the navigation node are refused with the value and the valid choices."""

import threading
from typing import List, Optional

import pytest
import rospy

from flex_nav.exceptions import ConfigError
from flex_nav.nodes.navigation import COMPONENTS, DEFAULT_COMPONENTS, component_names
from flex_nav.ros.private_ns import hosted_as, private_name, private_namespace


def test_outside_a_component_tilde_is_left_to_rospy() -> None:
    assert private_namespace() == rospy.get_name()
    assert private_name("~plan") == "~plan"  # rospy resolves it against the node's name


def test_inside_a_component_tilde_is_its_namespace() -> None:
    with hosted_as("get_path_server") as namespace:
        assert namespace == rospy.get_namespace().rstrip("/") + "/get_path_server"
        assert private_namespace() == namespace
        assert private_name("~plan") == namespace + "/plan"
        assert private_name("~global_costmap/costmap") == namespace + "/global_costmap/costmap"
        assert private_name("~") == namespace
        assert private_name("scan") == "scan"  # relative names stay relative
        assert private_name("/map") == "/map"
    assert private_namespace() == rospy.get_name()


def test_blocks_nest_and_unwind_after_an_error() -> None:
    with hosted_as("pure_pursuit_path"):
        with hosted_as("pure_pursuit_topic"):
            assert private_namespace().endswith("/pure_pursuit_topic")
        assert private_namespace().endswith("/pure_pursuit_path")
    with pytest.raises(RuntimeError), hosted_as("twist_relay"):
        raise RuntimeError("component failed")
    assert private_namespace() == rospy.get_name()


def test_other_threads_do_not_see_the_building_threads_component() -> None:
    seen: List[Optional[str]] = []
    with hosted_as("follow_path_server"):
        worker = threading.Thread(target=lambda: seen.append(private_namespace()))
        worker.start()
        worker.join(5.0)
    assert seen == [rospy.get_name()]


@pytest.mark.parametrize("bad", ["", "a/b", "~x", "1st", "has space", None])
def test_a_bad_component_name_is_refused(bad: object) -> None:
    with pytest.raises(ConfigError, match="not a ROS base name"), hosted_as(bad):  # type: ignore[arg-type]
        pass


def test_components_list_valid_and_invalid() -> None:
    assert component_names(list(DEFAULT_COMPONENTS)) == list(DEFAULT_COMPONENTS)
    assert component_names(["twist_relay"]) == ["twist_relay"]
    with pytest.raises(ConfigError, match=r"'get_plan' is not valid \(valid: get_path_server, "):
        component_names(["get_plan"])
    with pytest.raises(ConfigError, match="twice"):
        component_names(["twist_relay", "twist_relay"])
    not_a_list: List[object] = [[], "get_path_server", None]
    for empty in not_a_list:
        with pytest.raises(ConfigError, match="non-empty list"):
            component_names(empty)
    assert set(DEFAULT_COMPONENTS) < set(COMPONENTS)
