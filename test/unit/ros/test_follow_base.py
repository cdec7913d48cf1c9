"""The follow nodes' shared base without a master: a source that is not a GoalSource is refused naming the valid
ones (before any ROS call), each source serves its action, and a bad path's reason names where it came from.
The goal branch, results and feedback on the wire are tested in actions.test, nodes_io.test and
navigation_drive.test."""

import pytest

from flex_nav.exceptions import ConfigError
from flex_nav.nodes.follow_base import GoalSource, bad_path
from flex_nav.nodes.follow_server import FollowServer
from flex_nav.nodes.pure_pursuit_controller import PurePursuitController


@pytest.mark.parametrize("node", [FollowServer, PurePursuitController])
def test_a_source_that_is_not_a_goal_source_is_refused_naming_the_valid_ones(node):
    with pytest.raises(ConfigError, match=r"source 'path' is not valid \(valid: GoalSource.PATH, GoalSource.TOPIC\)"):
        node("path")


def test_each_source_serves_its_action():
    assert [source.action for source in GoalSource] == ["FollowPath", "FollowTopic"]


def test_a_bad_paths_reason_names_the_topic_it_came_on():
    class OnTopic:
        topic = "/robot/plan"

    assert bad_path(None, ValueError("empty")) == "bad path: empty"
    assert bad_path(OnTopic(), ValueError("empty")) == "bad path on /robot/plan: empty"  # type: ignore[arg-type]
