"""flex_nav: Flexible Navigation for ROS 1.

The subpackages are the layers (checked by the import-linter contracts in ``pyproject.toml``):

- ``flex_nav.behavior``    the FlexBE-style behavior engine (no rospy)
- ``flex_nav.nav``         navigation algorithms: ``costmap``, ``planning``, ``control`` (no rospy)
- ``flex_nav.localization`` adaptive Monte Carlo localization on a known map (no rospy)
- ``flex_nav.perception``  obstacle classifier and laser tracking of moving people (no rospy)
- ``flex_nav.compat``      the ``smach`` and ``flexbe_core`` APIs on the engine
- ``flex_nav.ros``         ROS adapters: proxies, parameters, frames, conversions, goal server, clocks
- ``flex_nav.nodes``       one module per ROS node (``scripts/`` holds their launchers)
- ``flex_nav.apps``        the demo, scenario runs and evaluation, run pictures, the operator CLI
- ``flex_nav.testing``     the test harness: private master, process management, network namespaces
- ``flex_nav.msg``         message and action classes generated from ``msg/`` and ``action/`` (by
  ``tools/gen_actions.py`` or catkin); ``flex_nav.srv`` the service classes from ``srv/``
- ``flex_nav.exceptions``  the typed exceptions every part raises
- ``flex_nav.validation``  the parameter checks every part uses (numbers with bounds and units, integers,
  booleans, names, choices)
- ``flex_nav.resources``   where the data folders (behaviors, models, config, launch) are
- ``flex_nav.action_types`` the four actions' classes and result codes by name

The state library is the sibling package ``flex_nav_states`` (``states/``) and the simulator ``flex_nav_sim``
(``sim/``).
"""

__version__ = "0.1.0"
