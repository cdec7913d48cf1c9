"""flex_nav_states: the Flexible Navigation state library (FlexBE-style states for the flex_nav engine).

Every state is a :class:`flex_nav.behavior.State` documented in its class docstring (``--`` parameters,
``>#``/``#>`` userdata keys, ``<=`` outcomes; see :mod:`flex_nav.behavior.docstring`). States never import
rospy: all ROS I/O goes through the behavior's proxies (``self.context.require_proxies()``, obtained in
``on_start``; the interface is :mod:`flex_nav_states.proxy_types`) and time comes from the behavior's clock.

Modules (one state or one small family each):

- action clients (:mod:`~flex_nav_states.action_base`): :mod:`get_path_state` (GetPath),
  :mod:`replan_state` (GetPath every period, each plan published: move_base's replanning),
  :mod:`follow_path_state` (FollowPath: a controller, and FollowPlanner: a mid-level planner),
  :mod:`follow_topic_state` (FollowTopic), :mod:`clear_costmaps_state` (several ClearCostmap servers at once);
- goals: :mod:`get_pose_state` (a PoseStamped goal from a topic, stale messages dropped),
  :mod:`goal_list_state` (the goals of a fixed list in turn, e.g. the paper's intermediate goals);
- motion (:mod:`~flex_nav_states.motion_base`; TwistStamped out, zero twist on every exit; the parameter groups
  they share in :mod:`~flex_nav_states.motion_params`): :mod:`move_distance_state`, :mod:`rotate_angle_state`
  (closed loop on odometry), :mod:`timed_twist_state`, :mod:`timed_stop_state`, :mod:`pure_pursuit_state` (follows
  the ``plan`` in userdata);
- monitors: :mod:`bumper_monitor_state` (bumper/cliff, configured by robot profile),
  :mod:`stuck_monitor_state`, :mod:`sensor_freshness_state`;
- obstacles (push or avoid): :mod:`follow_until_blocked_state` (FollowPath with a ``blocked`` outcome),
  :mod:`obstacle_class_state` (person / movable / clear from the obstacle classifier), :mod:`obstacle_fusion_state`
  (camera class + lidar shape, bounded looks again), :mod:`remember_obstacle_state` (a heavy obstacle's footprint
  for the costmap's obstacle memory), :mod:`push_state`
  (push a distance, fails fast on a heavy object, never pushes a person), :mod:`detour_check_state` (after a
  push, the old plan kept once when the replan is a long detour), :mod:`wait_path_clear_state`;
- operator: :mod:`operator_decision_state`, :mod:`log_state`, :mod:`wait_state`;
- retries: :mod:`backoff_state` (a wait before the next try of a goal, doubling after each failed one);
- exploration: :mod:`robot_pose_state` (the robot's pose from a pose topic into userdata),
  :mod:`find_frontier_state` (the next reachable frontier of the mapper's map, and remembering goals that failed),
  :mod:`save_map_state` (the mapper's save service); slow work runs off the behavior's thread
  (:mod:`~flex_nav_states.background_work`).

:func:`state_classes` imports them all and lists the concrete states (for documentation checks and tools);
``EXAMPLE_PARAMS`` gives constructor arguments for the states that have required parameters (every other
state can be built with its defaults).
"""

from __future__ import annotations

import importlib
import inspect
from typing import Any, Dict, List

STATE_MODULES = (
    "get_pose_state",
    "goal_list_state",
    "get_path_state",
    "replan_state",
    "follow_path_state",
    "follow_topic_state",
    "follow_until_blocked_state",
    "clear_costmaps_state",
    "move_distance_state",
    "rotate_angle_state",
    "timed_twist_state",
    "timed_stop_state",
    "pure_pursuit_state",
    "bumper_monitor_state",
    "stuck_monitor_state",
    "sensor_freshness_state",
    "operator_decision_state",
    "log_state",
    "wait_state",
    "backoff_state",
    "obstacle_class_state",
    "obstacle_fusion_state",
    "remember_obstacle_state",
    "push_state",
    "detour_check_state",
    "wait_path_clear_state",
    "robot_pose_state",
    "find_frontier_state",
    "save_map_state",
)

# Constructor arguments for the states whose constructor has required parameters (for tools and checks).
EXAMPLE_PARAMS: Dict[str, Dict[str, Any]] = {
    "MoveDistanceState": {"distance_m": -0.25},
    "RotateAngleState": {"angle_rad": 1.57},
    "WaitState": {"wait_time_s": 1.0},
    "PushState": {"distance_m": 0.5},
}


def state_classes() -> List[type]:
    """The concrete state classes of this package, in module order (imports every state module)."""
    from flex_nav.behavior.state import State  # noqa: PLC0415 - keep `import flex_nav_states` light

    found: List[type] = []
    for name in STATE_MODULES:
        module = importlib.import_module(f"{__name__}.{name}")
        for _, obj in inspect.getmembers(module, inspect.isclass):
            if issubclass(obj, State) and obj.__module__ == module.__name__ and obj.__name__.endswith("State"):
                found.append(obj)
    return found
