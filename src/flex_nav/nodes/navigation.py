"""`rosrun flex_nav navigation`: one robot's navigation servers and controllers hosted in one process.

Each component keeps the name, action, services, topics and private parameters it has as a node of its own:
get_path_server serves GetPath on ``<ns>/get_path_server`` and reads ``<ns>/get_path_server/...``, and so on
(:mod:`flex_nav.ros.private_ns`). What they share is what one process can share: one tf buffer and listener, one
connection per subscribed topic (the map, the scan and odometry arrive once and are handed to every component
that subscribed), one Python interpreter and its imported libraries and compiled kernels.

Parameters:

- ``~components`` (list of str; default: get_path_server, follow_path_server, follow_topic_server,
  pure_pursuit_path, pure_pursuit_topic): which to host, from :data:`COMPONENTS` (those and twist_relay,
  bumper_relay, localizer); each at most once.

The shared tf buffer keeps 30 s of transforms, the localizer's need. Components run their callbacks on rospy's
threads of the one process; the compiled kernels of the planner and the localizer release the GIL.

A component's bad parameter stops the node with its reason (exit status 2), as it would stop that node alone.
"""

from __future__ import annotations

from typing import Callable, Dict, List, Optional, Sequence

import rospy
import tf2_ros

from flex_nav.exceptions import ConfigError, choices_message
from flex_nav.ros.frames import TfSource
from flex_nav.ros.params import reject_unknown
from flex_nav.ros.private_ns import hosted_as, private_name

TF_CACHE_S = 30.0  # [s] the shared buffer's: the localizer's (flex_nav.nodes.localizer.TF_CACHE_S)
ComponentFactory = Callable[[tf2_ros.Buffer], object]


def _get_path(tf_buffer: tf2_ros.Buffer) -> object:
    from flex_nav.nodes.get_path_server import GetPathServer  # noqa: PLC0415 - only the hosted components

    return GetPathServer(tf_buffer)


def _follow_server(path: bool) -> ComponentFactory:
    def build(tf_buffer: tf2_ros.Buffer) -> object:
        from flex_nav.nodes.follow_base import GoalSource  # noqa: PLC0415 - only the hosted components
        from flex_nav.nodes.follow_server import FollowServer  # noqa: PLC0415 - only the hosted components

        return FollowServer(GoalSource.PATH if path else GoalSource.TOPIC, tf_buffer)

    return build


def _controller(path: bool) -> ComponentFactory:
    def build(tf_buffer: tf2_ros.Buffer) -> object:
        from flex_nav.nodes.follow_base import GoalSource  # noqa: PLC0415 - only the hosted components
        from flex_nav.nodes.pure_pursuit_controller import PurePursuitController  # noqa: PLC0415 - only the hosted components

        return PurePursuitController(GoalSource.PATH if path else GoalSource.TOPIC, tf_buffer)

    return build


def _twist_relay(_tf_buffer: tf2_ros.Buffer) -> object:
    from flex_nav.nodes.twist_relay import TwistRelay  # noqa: PLC0415 - only the hosted components

    return TwistRelay()


def _bumper_relay(_tf_buffer: tf2_ros.Buffer) -> object:
    from flex_nav.nodes.bumper_relay import BumperRelay  # noqa: PLC0415 - only the hosted components

    return BumperRelay()


def _localizer(tf_buffer: tf2_ros.Buffer) -> object:
    from flex_nav.nodes.localizer import LocalizerNode  # noqa: PLC0415 - only the hosted components

    return LocalizerNode(tf_buffer)


# Component name (its namespace, as the node of that name has) -> how to build it; modules are imported only for
# the components asked for.
COMPONENTS: Dict[str, ComponentFactory] = {
    "get_path_server": _get_path,
    "follow_path_server": _follow_server(path=True),
    "follow_topic_server": _follow_server(path=False),
    "pure_pursuit_path": _controller(path=True),
    "pure_pursuit_topic": _controller(path=False),
    "twist_relay": _twist_relay,
    "bumper_relay": _bumper_relay,
    "localizer": _localizer,
}
DEFAULT_COMPONENTS = (
    "get_path_server", "follow_path_server", "follow_topic_server", "pure_pursuit_path", "pure_pursuit_topic",
)


def component_names(raw: object) -> List[str]:
    """The validated ``~components`` list: known names, each once, at least one (ConfigError naming the bad
    entry and the valid names)."""
    if not isinstance(raw, (list, tuple)) or not raw:
        raise ConfigError(f"parameter {private_name('~components')} = {raw!r} must be a non-empty list of "
                          f"component names ({', '.join(COMPONENTS)})")
    names: List[str] = []
    for name in raw:
        if name not in COMPONENTS:
            raise ConfigError(choices_message(f"{private_name('~components')} entry", name, list(COMPONENTS)))
        if name in names:
            raise ConfigError(f"parameter {private_name('~components')} names {name!r} twice")
        names.append(str(name))
    return names


class NavigationHost:
    """Builds the asked-for components, each in its own private namespace, on one shared tf buffer."""

    def __init__(self, components: Optional[Sequence[str]] = None) -> None:
        reject_unknown("~", ("components",))
        names = component_names(components if components is not None
                                 else rospy.get_param(private_name("~components"), list(DEFAULT_COMPONENTS)))
        self.tf = TfSource(cache_s=TF_CACHE_S)
        self.components: Dict[str, object] = {}
        for name in names:
            with hosted_as(name):
                self.components[name] = COMPONENTS[name](self.tf.buffer)
        rospy.loginfo(f"{rospy.get_name()}: hosting {', '.join(names)} in one process")
